#ifndef OROGEN_HOT_LOOP_H
#define OROGEN_HOT_LOOP_H

// The hot loops get an AVX2 clone picked at run time (same results: no FMA, and
// sqrt is exact in both). Not under ThreadSanitizer: its instrumented ifunc resolver
// runs before the sanitizer starts and crashes the program at load.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
#define HOT_LOOP __attribute__((target_clones("avx2", "default")))
// HOT_LOOP_WIDE adds an AVX-512 clone (the same results: the build turns off FMA
// contraction) for loops that gain from 16 float lanes.
#define HOT_LOOP_WIDE __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define HOT_LOOP
#define HOT_LOOP_WIDE
#endif

#endif
