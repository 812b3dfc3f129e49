#include "editor/tools/box_rows.h"

// The pass of runs (box_blur.c) stores every doubling (runs of 2, 4, 8, 16) and reads
// it back shifted: ten sweeps over the array for the two boxes, each bound by its
// loads and stores. Here each doubling is one shuffle and one add on registers per 16
// samples: the 16 sums of runs of 2p starting at 16j are those of p at 16j plus those
// of p at 16j + p, lanes p.. of the two vectors of runs of p at 16j and 16(j + 1).
// Not under ThreadSanitizer or other compilers (as HOT_LOOP): the caller's pass runs.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
#include <immintrin.h>

#define WIDE __attribute__((target("avx512f")))

// Lanes [s, s + 16) of lo followed by hi, s = idx's first lane.
WIDE static inline __m512 shifted(__m512 lo, __m512 hi, __m512i idx) {
    return _mm512_permutex2var_ps(lo, idx, hi);
}

// Vector j of src (zeros past n: they reach only windows past the last).
WIDE static inline __m512 block(const float *src, int64_t n, int64_t j) {
    int64_t left = n - 16 * j;
    if (left >= 16) return _mm512_loadu_ps(src + 16 * j);
    if (left <= 0) return _mm512_setzero_ps();
    return _mm512_maskz_loadu_ps((__mmask16)((1u << left) - 1u), src + 16 * j);
}

WIDE static void box_rows_avx512(const float *src, float *dst, int64_t n, int length) {
    const int64_t windows = n - (length - 1), k = (length - 1) / 2;
    const __m512 inv = _mm512_set1_ps((float)(1.0 / length));
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m512i by1 = _mm512_add_epi32(lane, _mm512_set1_epi32(1)),
                  by2 = _mm512_add_epi32(lane, _mm512_set1_epi32(2)),
                  by4 = _mm512_add_epi32(lane, _mm512_set1_epi32(4)),
                  by8 = _mm512_add_epi32(lane, _mm512_set1_epi32(8));
    // The runs of 2, 4, 8 and 16 that length's bits add to the window's sum, low bit
    // first, each at the samples it starts after those before it (covered).
    int use[4], last = 0;
    __m512i at[4];
    int covered = 1;
    for (int l = 0; l < 4; l++) {
        use[l] = (length & (2 << l)) != 0;
        at[l] = _mm512_add_epi32(lane, _mm512_set1_epi32(covered));
        if (use[l]) covered += 2 << l, last = l;
    }
    // Vectors j .. of the samples (a), and of the runs of 2 (r2), 4, 8, 16 from them:
    // output vector j reads each at j and j + 1.
    __m512 a0 = block(src, n, 0), a1 = block(src, n, 1), a2 = block(src, n, 2),
           a3 = block(src, n, 3), a4 = block(src, n, 4), a5 = block(src, n, 5);
    __m512 r2_0 = _mm512_add_ps(a0, shifted(a0, a1, by1)),
           r2_1 = _mm512_add_ps(a1, shifted(a1, a2, by1)),
           r2_2 = _mm512_add_ps(a2, shifted(a2, a3, by1)),
           r2_3 = _mm512_add_ps(a3, shifted(a3, a4, by1)),
           r2_4 = _mm512_add_ps(a4, shifted(a4, a5, by1));
    __m512 r4_0 = _mm512_add_ps(r2_0, shifted(r2_0, r2_1, by2)),
           r4_1 = _mm512_add_ps(r2_1, shifted(r2_1, r2_2, by2)),
           r4_2 = _mm512_add_ps(r2_2, shifted(r2_2, r2_3, by2)),
           r4_3 = _mm512_add_ps(r2_3, shifted(r2_3, r2_4, by2));
    __m512 r8_0 = _mm512_add_ps(r4_0, shifted(r4_0, r4_1, by4)),
           r8_1 = _mm512_add_ps(r4_1, shifted(r4_1, r4_2, by4)),
           r8_2 = _mm512_add_ps(r4_2, shifted(r4_2, r4_3, by4));
    __m512 r16_0 = _mm512_add_ps(r8_0, shifted(r8_0, r8_1, by8)),
           r16_1 = _mm512_add_ps(r8_1, shifted(r8_1, r8_2, by8));
    for (int64_t j = 0; 16 * j < windows; j++) {
        __m512 sum = a0, out = a0;
        const __m512 lo[4] = {r2_0, r4_0, r8_0, r16_0}, hi[4] = {r2_1, r4_1, r8_1, r16_1};
        for (int l = 0; l < 4; l++) {
            if (!use[l]) continue;
            __m512 run = shifted(lo[l], hi[l], at[l]);
            if (l == last) {
                out = _mm512_mul_ps(_mm512_add_ps(sum, run), inv);
                break;
            }
            sum = _mm512_add_ps(sum, run);
        }
        int64_t left = windows - 16 * j;
        if (left >= 16)
            _mm512_storeu_ps(dst + k + 16 * j, out);
        else
            _mm512_mask_storeu_ps(dst + k + 16 * j, (__mmask16)((1u << left) - 1u), out);
        // One vector on: each level's newest from the one below.
        a0 = a1, a1 = a2, a2 = a3, a3 = a4, a4 = a5, a5 = block(src, n, j + 6);
        r2_0 = r2_1, r2_1 = r2_2, r2_2 = r2_3, r2_3 = r2_4;
        r2_4 = _mm512_add_ps(a4, shifted(a4, a5, by1));
        r4_0 = r4_1, r4_1 = r4_2, r4_2 = r4_3;
        r4_3 = _mm512_add_ps(r2_3, shifted(r2_3, r2_4, by2));
        r8_0 = r8_1, r8_1 = r8_2;
        r8_2 = _mm512_add_ps(r4_2, shifted(r4_2, r4_3, by4));
        r16_0 = r16_1;
        r16_1 = _mm512_add_ps(r8_1, shifted(r8_1, r8_2, by8));
    }
}

int box_rows_wide(const float *src, float *dst, int64_t n, int length) {
    if (length < 3 || length > 31 || n < length || !__builtin_cpu_supports("avx512f")) return -1;
    box_rows_avx512(src, dst, n, length);
    return 0;
}
#else
int box_rows_wide(const float *src, float *dst, int64_t n, int length) {
    (void)src, (void)dst, (void)n, (void)length;
    return -1;
}
#endif
