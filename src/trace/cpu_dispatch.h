// Function multi-versioning for the tracer's per-hit code (surface reconstruction, texture
// filtering, BSDF evaluation, the path loop): each marked function is compiled for AVX2 and for
// baseline x86-64, and the dynamic loader picks the version the CPU runs (an ifunc resolved
// once). AVX2 without FMA: GCC contracts nothing into fused multiply-adds unless FMA is enabled,
// and it reorders no float arithmetic without -ffast-math, so both versions give the same bits
// and the traced results do not depend on the machine. GCC on x86-64 Linux only (the sanitizer
// build included, whose ASan runs the clones too); elsewhere (Clang's fuzz builds, other CPUs)
// the macro is empty and the baseline is all there is.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define DDISH_CPU_DISPATCH __attribute__((target_clones("avx2", "default")))
#else
#define DDISH_CPU_DISPATCH
#endif
