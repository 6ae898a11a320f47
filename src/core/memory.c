/* madvise and MADV_HUGEPAGE, which C11 alone hides */
#define _DEFAULT_SOURCE
#include "core/memory.h"

#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

/* Large blocks in 2 MiB pages where the kernel makes them on request
 * (Linux's transparent huge pages in their "madvise" mode; in "always"
 * mode it does so anyway): a page fault costs about as much as filling a
 * 4 KiB page, and the dragon's load, layouts and BVH took 28 000 of them,
 * half of its whole process (README, "Loading a large mesh"). Only whole
 * huge pages inside the block are asked for, so none is another's. */
void gli_advise_huge(void *p, size_t bytes) {
#ifdef MADV_HUGEPAGE
  uintptr_t mask = (uintptr_t)GLI_HUGE_PAGE - 1;
  uintptr_t start = ((uintptr_t)p + mask) & ~mask;
  uintptr_t end = ((uintptr_t)p + bytes) & ~mask;
  if (end > start)
    (void)madvise((void *)start, end - start, MADV_HUGEPAGE);
#else
  (void)p, (void)bytes;
#endif
}

/* calloc, aligned by hand: glibc hands a large block straight from mmap,
 * whose pages are zero already, so calloc writes none of it and each page
 * is first touched by the code that fills it (aligned_alloc and a memset
 * wrote every page twice). A large block is aligned to a huge page, so
 * that all of it but its last page may be made of huge pages: the extra
 * room is address space, never touched. The block's own start is kept in
 * the word before the aligned pointer; malloc's 16-byte alignment leaves
 * at least that much room. */
void *gli_aligned_calloc(size_t count, size_t size) {
  if (size != 0 && count > SIZE_MAX / size)
    return NULL;
  size_t bytes = count * size;
  size_t align = bytes >= GLI_HUGE_PAGE ? GLI_HUGE_PAGE : GLI_ALIGN;
  /* room for the word, the alignment and p's last huge page's end */
  size_t room = GLI_ALIGN + 2 * align;
  if (bytes > SIZE_MAX - room)
    return NULL;
  char *block = calloc(1, bytes + room);
  if (!block)
    return NULL;
  uintptr_t mask = (uintptr_t)align - 1;
  char *p = (char *)(((uintptr_t)block + GLI_ALIGN + mask) & ~mask);
  ((void **)p)[-1] = block;
  /* up to the end of p's last huge page, which lies inside the block */
  gli_advise_huge(p, (bytes + mask) & ~(size_t)mask);
  return p;
}

void gli_aligned_free(void *p) {
  if (p)
    free(((void **)p)[-1]);
}

int gli_grow(void **items, size_t *capacity, size_t needed, size_t size) {
  if (needed <= *capacity)
    return 0;
  size_t cap = *capacity ? *capacity : 8;
  while (cap < needed) {
    if (cap > SIZE_MAX / 2)
      return -1;
    cap *= 2;
  }
  if (cap > SIZE_MAX / size)
    return -1;
  void *p = realloc(*items, cap * size);
  if (!p)
    return -1;
  gli_advise_huge(p, cap * size);
  *items = p;
  *capacity = cap;
  return 0;
}
