#include "editor/tools/box_rows.h"

#include "editor/tools/hot_loop.h"

// dst[i] = a[i] + a[i + shift]: the sums of 2p samples from those of p.
HOT_LOOP_WIDE static void add_shifted(float *dst, const float *a, int64_t shift, int64_t n) {
    for (int64_t i = 0; i < n; i++)
        dst[i] = a[i] + a[i + shift];
}

HOT_LOOP_WIDE static void add_arrays(float *dst, const float *a, const float *b, int64_t n) {
    for (int64_t i = 0; i < n; i++)
        dst[i] = a[i] + b[i];
}

HOT_LOOP_WIDE static void add_scaled(float *dst, const float *a, const float *b, float k,
                                     int64_t n) {
    for (int64_t i = 0; i < n; i++)
        dst[i] = (a[i] + b[i]) * k;
}

// The plain pass: each doubling a loop over the array (vectorised by the compiler).
void box_rows_plain(const float *src, float *dst, int64_t n, int length, float scale,
                    float *scratch) {
    int64_t windows = n - (length - 1), k = (length - 1) / 2;
    const float *run[BOX_ROWS_LEVELS] = {src}; // run[l]: sums of 2^l samples from each start
    int top = 0;
    while ((int64_t)2 << top <= length && top + 1 < BOX_ROWS_LEVELS) {
        float *next = scratch + (int64_t)top * n;
        add_shifted(next, run[top], (int64_t)1 << top, n - (((int64_t)2 << top) - 1));
        run[++top] = next;
    }
    float *acc = scratch + (int64_t)top * n;
    const float *sum = run[top];
    int64_t covered = (int64_t)1 << top;
    for (int l = top - 1; l >= 0; l--) {
        if (!(length & (1 << l))) continue;
        if (covered + ((int64_t)1 << l) == length) { // the last (l = 0: length is odd)
            if (scale == 1.0f)
                add_arrays(dst + k, sum, run[l] + covered, windows);
            else
                add_scaled(dst + k, sum, run[l] + covered, scale, windows);
            return;
        }
        add_arrays(acc, sum, run[l] + covered, windows);
        sum = acc;
        covered += (int64_t)1 << l;
    }
}

void box_rows(const float *src, float *dst, int64_t n, int length, float scale, float *scratch) {
    if (box_rows_wide(src, dst, n, length, scale) != 0)
        box_rows_plain(src, dst, n, length, scale, scratch);
}

// The plain pass stores every doubling (runs of 2, 4, 8, 16) and reads
// it back shifted: ten sweeps over the array for the two boxes, each bound by its
// loads and stores. Here each doubling is one shuffle and one add on registers per 16
// samples: the 16 sums of runs of 2p starting at 16j are those of p at 16j plus those
// of p at 16j + p, lanes p.. of the two vectors of runs of p at 16j and 16(j + 1).
// Runs of 2 add the samples loaded one on instead (a load, not a shuffle), and the
// window's highest run needs no shuffle (it starts at 16j), nor one that starts 16
// on (the next vector): a box of 17 takes two shuffles, not five.
// Not under ThreadSanitizer or other compilers (as HOT_LOOP): the plain pass runs.
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

// 16 samples from src + at (zeros past n).
WIDE static inline __m512 block_at(const float *src, int64_t n, int64_t at) {
    int64_t left = n - at;
    if (left >= 16) return _mm512_loadu_ps(src + at);
    if (left <= 0) return _mm512_setzero_ps();
    return _mm512_maskz_loadu_ps((__mmask16)((1u << left) - 1u), src + at);
}

// Inlined for each length (a constant there): the choice of runs and shuffles folds away.
__attribute__((target("avx512f"), always_inline)) static inline void
box_rows_length(const float *src, float *dst, int64_t n, const int length, float scale,
                const int scaled) {
    const int64_t windows = n - (length - 1), k = (length - 1) / 2;
    const __m512 times = _mm512_set1_ps(scale);
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m512i by2 = _mm512_add_epi32(lane, _mm512_set1_epi32(2)),
                  by4 = _mm512_add_epi32(lane, _mm512_set1_epi32(4)),
                  by8 = _mm512_add_epi32(lane, _mm512_set1_epi32(8));
    // The runs of 16, 8, 4, 2 and 1 that length's bits add to the window's sum, high
    // bit first, each at the samples it starts after those before it (from[l]: 16
    // takes the next vector as it is, no shuffle; past 16, lanes of the next two).
    int use[5], top = -1;
    int64_t from[5];
    __m512i at[5];
    int64_t covered = 0;
    // Unrolled so that all of these fold to constants: left as a loop, GCC kept use[] and
    // from[] in the steps as tests and branches (a third of the pass's time).
#pragma GCC unroll 5
    for (int l = 4; l >= 0; l--) {
        use[l] = (length & (1 << l)) != 0;
        from[l] = covered;
        at[l] = _mm512_add_epi32(lane, _mm512_set1_epi32((int)(covered & 15)));
        if (use[l]) covered += 1 << l, top = top < 0 ? l : top;
    }
    // Vectors j .. of the samples (a), and of the runs of 2 (r2: the samples plus
    // those one on, loaded), 4, 8, 16 from them: output vector j reads each at j and
    // j + 1.
    __m512 a0 = block(src, n, 0), a1 = block(src, n, 1), a2 = block(src, n, 2),
           a3 = block(src, n, 3), a4 = block(src, n, 4);
    __m512 r2_0 = _mm512_add_ps(a0, block_at(src, n, 1)),
           r2_1 = _mm512_add_ps(a1, block_at(src, n, 17)),
           r2_2 = _mm512_add_ps(a2, block_at(src, n, 33)),
           r2_3 = _mm512_add_ps(a3, block_at(src, n, 49)),
           r2_4 = _mm512_add_ps(a4, block_at(src, n, 65));
    __m512 r4_0 = _mm512_add_ps(r2_0, shifted(r2_0, r2_1, by2)),
           r4_1 = _mm512_add_ps(r2_1, shifted(r2_1, r2_2, by2)),
           r4_2 = _mm512_add_ps(r2_2, shifted(r2_2, r2_3, by2)),
           r4_3 = _mm512_add_ps(r2_3, shifted(r2_3, r2_4, by2));
    __m512 r8_0 = _mm512_add_ps(r4_0, shifted(r4_0, r4_1, by4)),
           r8_1 = _mm512_add_ps(r4_1, shifted(r4_1, r4_2, by4)),
           r8_2 = _mm512_add_ps(r4_2, shifted(r4_2, r4_3, by4));
    __m512 r16_0 = _mm512_add_ps(r8_0, shifted(r8_0, r8_1, by8)),
           r16_1 = _mm512_add_ps(r8_1, shifted(r8_1, r8_2, by8));
    // Steps whose loads and store lie wholly inside the array run without the tail's
    // checks (a few instructions each, a third of a step's).
#define STEP(store, next_a, next_r2)                                                               \
    do {                                                                                           \
        const __m512 v0[5] = {a0, r2_0, r4_0, r8_0, r16_0}, v1[5] = {a1, r2_1, r4_1, r8_1, r16_1}, \
                     v2[5] = {a2, r2_2, r4_2, r8_2, r16_1};                                        \
        __m512 sum = v0[top];                                                                      \
        _Pragma("GCC unroll 5") for (int l = 4; l >= 0; l--) {                                     \
            if (l >= top || !use[l]) continue;                                                     \
            __m512 run = from[l] == 16  ? v1[l]                                                    \
                         : from[l] < 16 ? shifted(v0[l], v1[l], at[l])                             \
                                        : shifted(v1[l], v2[l], at[l]);                            \
            sum = _mm512_add_ps(sum, run);                                                         \
        }                                                                                          \
        __m512 out = scaled ? _mm512_mul_ps(sum, times) : sum;                                     \
        store;                                                                                     \
        a0 = a1, a1 = a2, a2 = a3, a3 = a4, a4 = next_a;                                           \
        r2_0 = r2_1, r2_1 = r2_2, r2_2 = r2_3, r2_3 = r2_4;                                        \
        r2_4 = _mm512_add_ps(a4, next_r2);                                                         \
        r4_0 = r4_1, r4_1 = r4_2, r4_2 = r4_3;                                                     \
        r4_3 = _mm512_add_ps(r2_3, shifted(r2_3, r2_4, by2));                                      \
        r8_0 = r8_1, r8_1 = r8_2;                                                                  \
        r8_2 = _mm512_add_ps(r4_2, shifted(r4_2, r4_3, by4));                                      \
        r16_0 = r16_1;                                                                             \
        r16_1 = _mm512_add_ps(r8_1, shifted(r8_1, r8_2, by8));                                     \
    } while (0)
    int64_t j = 0;
    // Each level at vectors j, j + 1 and j + 2 (runs past 16 on start in j + 1); one
    // vector on, each level's newest from the one below.
    for (; 16 * (j + 1) <= windows && 16 * (j + 6) + 1 <= n; j++)
        STEP(_mm512_storeu_ps(dst + k + 16 * j, out), _mm512_loadu_ps(src + 16 * (j + 5)),
             _mm512_loadu_ps(src + 16 * (j + 5) + 1));
    for (; 16 * j < windows; j++) {
        int64_t left = windows - 16 * j;
        __mmask16 m = left >= 16 ? (__mmask16)0xffff : (__mmask16)((1u << left) - 1u);
        STEP(_mm512_mask_storeu_ps(dst + k + 16 * j, m, out), block(src, n, j + 5),
             block_at(src, n, 16 * (j + 5) + 1));
    }
#undef STEP
}

// Each length (and whether it scales) inlined on its own.
#define LENGTH(length)                                                                             \
    case length:                                                                                   \
        if (scale == 1.0f)                                                                         \
            box_rows_length(src, dst, n, length, scale, 0);                                        \
        else                                                                                       \
            box_rows_length(src, dst, n, length, scale, 1);                                        \
        break;

WIDE static void box_rows_avx512(const float *src, float *dst, int64_t n, int length, float scale) {
    switch (length) {
        LENGTH(3)
        LENGTH(5)
        LENGTH(7)
        LENGTH(9)
        LENGTH(11)
        LENGTH(13)
        LENGTH(15)
        LENGTH(17)
        LENGTH(19)
        LENGTH(21)
        LENGTH(23)
        LENGTH(25)
        LENGTH(27)
        LENGTH(29)
        LENGTH(31)
    }
}
#undef LENGTH

int box_rows_wide(const float *src, float *dst, int64_t n, int length, float scale) {
    if (length < 3 || length > 31 || n < length || !__builtin_cpu_supports("avx512f")) return -1;
    box_rows_avx512(src, dst, n, length, scale);
    return 0;
}
#else
int box_rows_wide(const float *src, float *dst, int64_t n, int length, float scale) {
    (void)src, (void)dst, (void)n, (void)length, (void)scale;
    return -1;
}
#endif
