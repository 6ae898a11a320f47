/* Run-time instruction-set detection (CPUID plus the OS's XSAVE state). */
#ifndef GLINT_CORE_CPU_H
#define GLINT_CORE_CPU_H

typedef struct gli_cpu_features {
  int sse41;  /* SSE4.1 (and SSE2 beneath it) */
  int avx2;   /* AVX2 + FMA, with the OS saving YMM state */
  int avx512; /* AVX-512F (+DQ, VL, BW, CD), with the OS saving ZMM state */
} gli_cpu_features;

void gli_cpu_detect(gli_cpu_features *features);

#endif
