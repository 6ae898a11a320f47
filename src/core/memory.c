#include "core/memory.h"

#include <stdlib.h>
#include <string.h>

void *gli_aligned_calloc(size_t count, size_t size) {
  if (size != 0 && count > SIZE_MAX / size)
    return NULL;
  size_t bytes = count * size;
  /* aligned_alloc wants a multiple of the alignment. */
  size_t rounded = (bytes + GLI_ALIGN - 1) & ~(size_t)(GLI_ALIGN - 1);
  if (rounded < bytes)
    return NULL;
  if (rounded == 0)
    rounded = GLI_ALIGN;
  void *p = aligned_alloc(GLI_ALIGN, rounded);
  if (p)
    memset(p, 0, rounded);
  return p;
}

void gli_aligned_free(void *p) { free(p); }

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
