#include "core/memory.h"

#include <stdlib.h>
#include <string.h>

/* calloc, not aligned_alloc and memset: a large block comes from the
 * kernel already zero, a page at a time as it is first touched, so a
 * 16384 x 16384 film costs nothing until it is rendered into (the memset
 * wrote its 3 GiB first, for seconds in which nothing could stop it). The
 * block's own address is kept just before the aligned one, which has a
 * whole number of alignments after it. */
void *gli_aligned_calloc(size_t count, size_t size) {
  if (size != 0 && count > SIZE_MAX / size)
    return NULL;
  size_t bytes = count * size;
  size_t rounded = (bytes + GLI_ALIGN - 1) & ~(size_t)(GLI_ALIGN - 1);
  size_t extra = GLI_ALIGN + sizeof(void *);
  if (rounded < bytes || rounded > SIZE_MAX - extra)
    return NULL;
  char *block = calloc(1, (rounded ? rounded : GLI_ALIGN) + extra);
  if (!block)
    return NULL;
  uintptr_t at = ((uintptr_t)(block + sizeof(void *)) + GLI_ALIGN - 1) &
                 ~(uintptr_t)(GLI_ALIGN - 1);
  ((void **)at)[-1] = block;
  return (void *)at;
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
  *items = p;
  *capacity = cap;
  return 0;
}
