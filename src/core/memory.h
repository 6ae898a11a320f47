/* Aligned allocation and growable arrays. SIMD data is aligned to 64 bytes,
 * the widest vector (AVX-512) and a cache line. */
#ifndef GLINT_CORE_MEMORY_H
#define GLINT_CORE_MEMORY_H

#include <stddef.h>
#include <stdint.h>

#define GLI_ALIGN 64

/* AddressSanitizer checks the bounds of malloc's blocks, not of blocks
 * with a head before them or mapped by hand: under it every block is
 * aligned_alloc's, without huge pages. */
#if defined(__SANITIZE_ADDRESS__)
#define GLI_PLAIN_BLOCKS 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GLI_PLAIN_BLOCKS 1
#endif
#endif
#ifndef GLI_PLAIN_BLOCKS
#define GLI_PLAIN_BLOCKS 0
#endif

/* NULL on failure or on size overflow; zero-filled. A block of a huge
 * page or more is mapped on its own, starting on a huge page (see
 * gli_advise_huge), and unmapped when freed. */
void *gli_aligned_calloc(size_t count, size_t size);
void gli_aligned_free(void *p);

/* Asks the kernel for huge pages (x86-64's 2 MiB) for the whole ones among
 * the `bytes` at p, a block of the caller's own: large arrays filled once
 * fault 512 times less. */
#define GLI_HUGE_PAGE ((size_t)2 << 20)
void gli_advise_huge(void *p, size_t bytes);

/* Grows *items (of `size`-byte elements) so that `needed` fit; doubles the
 * capacity. Returns 0 on success, -1 on allocation failure or overflow. */
int gli_grow(void **items, size_t *capacity, size_t needed, size_t size);

/* Appends one element: GLI_PUSH(array, count, capacity, value) evaluates to
 * 0 on success, -1 when out of memory. */
#define GLI_PUSH(arr, count, cap, value)                                       \
  (gli_grow((void **)&(arr), &(cap), (count) + 1, sizeof *(arr)) == 0          \
       ? ((arr)[(count)++] = (value), 0)                                       \
       : -1)

#endif
