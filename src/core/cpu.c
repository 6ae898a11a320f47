#include "core/cpu.h"

#include "glint.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* GLINT_ISA=none|sse|avx2|avx512 caps what detection reports, to test
 * fallbacks and to compare instruction sets on one machine. It can only
 * take features away, never claim ones the CPU lacks. */
static void apply_cap(gli_cpu_features *f) {
  const char *cap = getenv("GLINT_ISA");
  if (!cap || !*cap)
    return;
  if (strcmp(cap, "none") == 0 || strcmp(cap, "scalar") == 0)
    f->sse41 = f->avx2 = f->avx512 = 0;
  else if (strcmp(cap, "sse") == 0)
    f->avx2 = f->avx512 = 0;
  else if (strcmp(cap, "avx2") == 0)
    f->avx512 = 0;
}

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>

static unsigned long long xgetbv0(void) {
  unsigned int eax, edx;
  __asm__ volatile("xgetbv" : "=a"(eax), "=d"(edx) : "c"(0));
  return ((unsigned long long)edx << 32) | eax;
}

void gli_cpu_detect(gli_cpu_features *f) {
  unsigned int a, b, c, d;
  f->sse41 = f->avx2 = f->avx512 = 0;
  if (!__get_cpuid(1, &a, &b, &c, &d))
    return;
  f->sse41 = (c >> 19) & 1;
  int fma = (c >> 12) & 1, osxsave = (c >> 27) & 1, avx = (c >> 28) & 1;
  int popcnt = (c >> 23) & 1;
  if (!osxsave || !avx)
    return;
  unsigned long long xcr0 = xgetbv0();
  int ymm_saved = (xcr0 & 0x6) == 0x6;
  int zmm_saved = (xcr0 & 0xe6) == 0xe6;
  if (__get_cpuid_max(0, 0) < 7)
    return;
  __cpuid_count(7, 0, a, b, c, d);
  int avx2 = (b >> 5) & 1;
  int avx512f = (b >> 16) & 1, avx512dq = (b >> 17) & 1;
  int avx512bw = (b >> 30) & 1, avx512vl = (b >> 31) & 1;
  int avx512cd = (b >> 28) & 1;
  f->avx2 = avx2 && fma && popcnt && ymm_saved;
  f->avx512 = f->avx2 && avx512f && avx512dq && avx512bw && avx512vl &&
              avx512cd && zmm_saved;
  apply_cap(f);
}
#else
void gli_cpu_detect(gli_cpu_features *f) { f->sse41 = f->avx2 = f->avx512 = 0; }
#endif

int glint_cpu_count(void) {
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  if (n < 1)
    return 1;
  if (n > GLINT_MAX_THREADS)
    return GLINT_MAX_THREADS;
  return (int)n;
}
