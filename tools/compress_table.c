/* Writes src/simd/compress8.inc: for each 8-bit lane mask, the indices of
 * its set lanes packed 3 bits apiece, lowest first, which the AVX2
 * vf_compress_store (src/simd/simd_avx2.h) turns into a permutation.
 * ctest's compress_table_current checks the committed file against it. */
#include <stdio.h>

int main(void) {
  printf("/* Generated: for each 8-bit mask, the indices of its set bits "
         "packed 3\n"
         " * bits apiece, lowest first (see vf_compress_store in "
         "simd_avx2.h). */\n");
  for (unsigned mask = 0; mask < 256; mask++) {
    unsigned packed = 0, n = 0;
    for (unsigned lane = 0; lane < 8; lane++)
      if (mask >> lane & 1)
        packed |= lane << (3 * n++);
    printf("COMPRESS_ENTRY(0x%06xu)%c", packed, mask % 4 == 3 ? '\n' : ' ');
  }
  return 0;
}
