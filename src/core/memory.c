/* mmap, madvise and sysconf, which C11 alone hides */
#define _DEFAULT_SOURCE
#include "core/memory.h"

#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

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

#if !GLI_PLAIN_BLOCKS
/* What gli_aligned_free needs, in the 16 bytes before a block: where it
 * was allocated, and the length of its mapping (0: a malloc block). */
typedef struct block_head {
  void *base;
  size_t mapped;
} block_head;

/* A block of a huge page or more, mapped where it starts on a huge page:
 * the kernel hands out zero pages, so nothing is written before the code
 * that fills the block touches it (aligned_alloc and a memset wrote every
 * page twice), and all of it but its last page may be made of huge pages.
 * The mapping keeps one small page before the block for its head and
 * gives the rest of the alignment's room back, so that nothing but the
 * block shares its huge pages, and a freed block's pages go back at once
 * (glibc reuses large blocks freed, clearing them whole on calloc). */
static void *map_block(size_t bytes) {
  long page_size = sysconf(_SC_PAGESIZE);
  size_t head_page = page_size > 0 ? (size_t)page_size : 4096;
  size_t whole = (bytes + GLI_HUGE_PAGE - 1) & ~(GLI_HUGE_PAGE - 1);
  if (whole < bytes || whole > SIZE_MAX - GLI_HUGE_PAGE - head_page)
    return NULL;
  size_t len = whole + GLI_HUGE_PAGE + head_page;
  char *base = mmap(NULL, len, PROT_READ | PROT_WRITE,
                    MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (base == MAP_FAILED)
    return NULL;
  uintptr_t mask = (uintptr_t)GLI_HUGE_PAGE - 1;
  char *p = (char *)(((uintptr_t)base + head_page + mask) & ~mask);
  char *head = p - head_page, *end = p + whole;
  if (head > base)
    munmap(base, (size_t)(head - base));
  if (base + len > end)
    munmap(end, (size_t)(base + len - end));
  ((block_head *)p)[-1] = (block_head){head, head_page + whole};
  gli_advise_huge(p, whole);
  return p;
}

#endif

void *gli_aligned_calloc(size_t count, size_t size) {
  if (size != 0 && count > SIZE_MAX / size)
    return NULL;
  size_t bytes = count * size;
  /* aligned_alloc wants a multiple of the alignment */
  size_t rounded = (bytes + GLI_ALIGN - 1) & ~(size_t)(GLI_ALIGN - 1);
  if (rounded < bytes || rounded > SIZE_MAX - GLI_ALIGN)
    return NULL;
#if GLI_PLAIN_BLOCKS
  void *plain = aligned_alloc(GLI_ALIGN, rounded ? rounded : GLI_ALIGN);
  if (plain)
    memset(plain, 0, rounded);
  return plain;
#else
  if (bytes >= GLI_HUGE_PAGE)
    return map_block(bytes);
  /* the head in a cache line of its own before the block */
  char *base = aligned_alloc(GLI_ALIGN, GLI_ALIGN + rounded);
  if (!base)
    return NULL;
  char *p = base + GLI_ALIGN;
  memset(p, 0, rounded);
  ((block_head *)p)[-1] = (block_head){base, 0};
  return p;
#endif
}

void gli_aligned_free(void *p) {
  if (!p)
    return;
#if GLI_PLAIN_BLOCKS
  free(p);
#else
  block_head head = ((const block_head *)p)[-1];
  if (head.mapped)
    munmap(head.base, head.mapped);
  else
    free(head.base);
#endif
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
