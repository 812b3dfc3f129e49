#ifndef OROGEN_IO_AVX2_CLONE_H
#define OROGEN_IO_AVX2_CLONE_H

// AVX2_CLONE gives a loop an AVX2 clone picked at run time (the same results: the build
// turns off FMA contraction), for the editing layers below editor/tools (which has
// hot_loop.h). Not under ThreadSanitizer: its instrumented ifunc resolver runs before
// the sanitizer starts and crashes the program at load.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
#define AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#else
#define AVX2_CLONE
#endif

#endif
