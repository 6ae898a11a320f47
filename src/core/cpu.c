/* sched_getaffinity and CPU_COUNT are GNU extensions of <sched.h>. */
#define _GNU_SOURCE
#include "core/cpu.h"

#include "core/error.h"
#include "glint.h"

#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* GLINT_ISA=none|sse|avx2|avx512 caps what detection reports, to test
 * fallbacks and to compare instruction sets on one machine. It can only
 * take features away, never claim ones the CPU lacks. */
static void apply_cap(gli_cpu_features *f) {
  const char *cap = getenv("GLINT_ISA");
  if (!cap || !*cap)
    return; /* an unknown value caps nothing; glint_isa_cap_check says so */
  if (strcmp(cap, "none") == 0)
    f->sse41 = f->avx2 = f->avx512 = 0;
  else if (strcmp(cap, "sse") == 0)
    f->avx2 = f->avx512 = 0;
  else if (strcmp(cap, "avx2") == 0)
    f->avx512 = 0;
}

glint_status glint_isa_cap_check(glint_error *error) {
  static const char *const known[] = {"none", "sse", "avx2", "avx512"};
  const char *cap = getenv("GLINT_ISA");
  if (!cap || !*cap)
    return GLINT_OK;
  for (size_t i = 0; i < sizeof known / sizeof *known; i++)
    if (strcmp(cap, known[i]) == 0)
      return GLINT_OK;
  char shown[48];
  snprintf(shown, sizeof shown, "%.40s%s", cap, strlen(cap) > 40 ? "..." : "");
  for (char *p = shown; *p; p++)
    if ((unsigned char)*p < 0x20 || (unsigned char)*p >= 0x7f)
      *p = '?';
  return gli_fail(error, GLINT_E_ARGUMENT,
                  "GLINT_ISA='%s' is not none, sse, avx2 or avx512", shown);
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

/* The CPUs this process may run on (taskset, cgroups' cpusets), not all
 * that are online: threads beyond them would only take turns. */
int glint_cpu_count(void) {
  long n = sysconf(_SC_NPROCESSORS_ONLN);
#ifdef CPU_COUNT
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0)
    n = CPU_COUNT(&set);
#endif
  if (n < 1)
    return 1;
  if (n > GLINT_MAX_THREADS)
    return GLINT_MAX_THREADS;
  return (int)n;
}
