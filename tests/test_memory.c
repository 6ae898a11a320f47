/* Aligned blocks and growable arrays (core/memory.h): zero-filled, aligned
 * for the widest SIMD load, a large block aligned to a huge page and
 * marked for huge pages (its mapping's "hg" flag in /proc/self/smaps) and
 * unmapped when freed, every size overflow refused. */
/* mmap and madvise, which C11 alone hides */
#define _DEFAULT_SOURCE
#include "test_util.h"

#include "core/memory.h"

#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

static void expect_zero_and_writable(unsigned char *p, size_t bytes) {
  for (size_t i = 0; i < bytes; i++)
    if (p[i] != 0)
      fail_msg("byte %zu of %zu is %d, not 0", i, bytes, p[i]);
  memset(p, 0xa5, bytes); /* the whole block is the caller's (ASan) */
}

static void blocks_are_aligned_and_zero(void **state) {
  (void)state;
  const size_t sizes[] = {0,
                          1,
                          63,
                          64,
                          4097,
                          GLI_HUGE_PAGE - 1,
                          GLI_HUGE_PAGE,
                          3 * GLI_HUGE_PAGE + 5};
  for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) {
    unsigned char *p = gli_aligned_calloc(sizes[k], 1);
    assert_non_null(p);
    assert_int_equal((uintptr_t)p % GLI_ALIGN, 0);
    if (sizes[k] >= GLI_HUGE_PAGE && !GLI_PLAIN_BLOCKS)
      assert_int_equal((uintptr_t)p % GLI_HUGE_PAGE, 0);
    expect_zero_and_writable(p, sizes[k]);
    gli_aligned_free(p);
  }
  /* count * size, not count alone */
  double *d = gli_aligned_calloc(1000, sizeof *d);
  assert_non_null(d);
  expect_zero_and_writable((unsigned char *)d, 1000 * sizeof *d);
  gli_aligned_free(d);
  gli_aligned_free(NULL);
}

static void overflow_is_refused(void **state) {
  (void)state;
  assert_null(gli_aligned_calloc(SIZE_MAX / 2 + 1, 2));
  assert_null(gli_aligned_calloc(SIZE_MAX - 10, 1)); /* no room to align */
  void *items = NULL;
  size_t cap = 0;
  assert_int_equal(gli_grow(&items, &cap, SIZE_MAX / 4, 8), -1);
  assert_null(items);
  assert_int_equal(cap, 0);
}

static void arrays_grow_by_doubling(void **state) {
  (void)state;
  int *items = NULL;
  size_t cap = 0;
  assert_int_equal(gli_grow((void **)&items, &cap, 1, sizeof *items), 0);
  assert_int_equal(cap, 8);
  items[0] = 7;
  assert_int_equal(gli_grow((void **)&items, &cap, 8, sizeof *items), 0);
  assert_int_equal(cap, 8); /* room already */
  assert_int_equal(gli_grow((void **)&items, &cap, 9, sizeof *items), 0);
  assert_int_equal(cap, 16);
  assert_int_equal(gli_grow((void **)&items, &cap, 100, sizeof *items), 0);
  assert_int_equal(cap, 128);
  assert_int_equal(items[0], 7); /* kept */
  free(items);
}

/* The VmFlags of the mapping that holds p, from /proc/self/smaps; 0 when
 * there is no such file. */
static int mapping_flags(const void *p, char *flags, size_t size) {
  FILE *f = fopen("/proc/self/smaps", "r");
  if (!f)
    return 0;
  char line[512];
  int inside = 0, found = 0;
  while (fgets(line, sizeof line, f)) {
    unsigned long lo, hi;
    if (sscanf(line, "%lx-%lx ", &lo, &hi) == 2 && strchr(line, '-') &&
        line[0] != 'V')
      inside = (uintptr_t)p >= lo && (uintptr_t)p < hi;
    else if (inside && strncmp(line, "VmFlags:", 8) == 0) {
      snprintf(flags, size, "%s", line + 8);
      found = 1;
      break;
    }
  }
  fclose(f);
  return found;
}

/* Whether this kernel marks memory given MADV_HUGEPAGE (it does in every
 * THP mode, "never" included, where it has THP at all): a page-aligned
 * probe of our own. */
static int kernel_marks_huge_pages(void) {
#ifdef MADV_HUGEPAGE
  size_t len = 2 * GLI_HUGE_PAGE;
  char *probe = mmap(NULL, len, PROT_READ | PROT_WRITE,
                     MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (probe == MAP_FAILED)
    return 0;
  char flags[512];
  int marked = madvise(probe, len, MADV_HUGEPAGE) == 0 &&
               mapping_flags(probe, flags, sizeof flags) &&
               strstr(flags, " hg") != NULL;
  munmap(probe, len);
  return marked;
#else
  return 0;
#endif
}

static void large_blocks_ask_for_huge_pages(void **state) {
  (void)state;
  if (GLI_PLAIN_BLOCKS || !kernel_marks_huge_pages()) {
    printf("no huge pages here (AddressSanitizer, or a kernel that does not "
           "mark them in /proc/self/smaps): SKIPPED\n");
    skip();
  }
  size_t bytes = 3 * GLI_HUGE_PAGE;
  unsigned char *p = gli_aligned_calloc(bytes, 1);
  assert_non_null(p);
  char flags[512];
  /* both ends of the block, and a page in the middle */
  const unsigned char *probe[] = {p, p + bytes / 2, p + bytes - 1};
  for (int i = 0; i < 3; i++) {
    assert_true(mapping_flags(probe[i], flags, sizeof flags));
    if (!strstr(flags, " hg"))
      fail_msg("byte %td of the block: VmFlags%s without hg", probe[i] - p,
               flags);
  }
  /* freed, its pages go back (glibc would keep a freed large block for
   * reuse, and clear it whole on the next calloc) */
  gli_aligned_free(p);
  assert_false(mapping_flags(p, flags, sizeof flags));
  assert_false(mapping_flags(p + bytes - 1, flags, sizeof flags));
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(blocks_are_aligned_and_zero),
      cmocka_unit_test(overflow_is_refused),
      cmocka_unit_test(arrays_grow_by_doubling),
      cmocka_unit_test(large_blocks_ask_for_huge_pages),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
