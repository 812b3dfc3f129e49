#include "editor/tools/raise_row.h"

#include <math.h>

// One sample, as the vector paths compute each lane.
static inline float raise_sample(float h, float dx2, float dz2, float inv_r, float strength,
                                 float amount, float limit) {
    float t = sqrtf(dx2 + dz2) * inv_r;
    t = t < 1.0f ? t : 1.0f;
    float w = (1.0f - t * t * (3.0f - 2.0f * t)) * strength;
    float v = h + w * amount;
    v = v == v ? v : h;
    v = limit < v ? limit : v;
    return -limit > v ? -limit : v;
}

static void raise_row_plain(float *row, const float *dx2, float dz2, float inv_r, float strength,
                            float amount, float limit, int n) {
    for (int i = 0; i < n; i++)
        row[i] = raise_sample(row[i], dx2[i], dz2, inv_r, strength, amount, limit);
}

// Written with intrinsics: the compiler's own vectorisation of the loop above spent as
// much again on the clamps' compares and blends and on scalar tails (a row is ~100
// samples, a dab ~130 rows). The squares of the columns' distances come from a table
// made once per dab (they were four operations per vector: a conversion, two additions
// and a multiplication). 2t is t + t (exact, as 2 * t). min/max are the selects above
// exactly (the first operand when the comparison holds, else the second, NaN
// included); whole vectors load and store without masks (a masked access takes an
// arithmetic port too), the last partial one with them. Not under ThreadSanitizer or
// other compilers (as HOT_LOOP: no ifunc), where the plain loop runs.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
#include <immintrin.h>

#define AVX2 __attribute__((target("avx2"), always_inline)) static inline

// New heights of 8 samples (h) from their squared column distances (d2).
AVX2 __m256 raise8(__m256 h, __m256 d2, __m256 vdz2, __m256 vinv, __m256 vstr, __m256 vamt,
                   __m256 hi, __m256 lo) {
    const __m256 one = _mm256_set1_ps(1.0f), three = _mm256_set1_ps(3.0f);
    __m256 t = _mm256_mul_ps(_mm256_sqrt_ps(_mm256_add_ps(d2, vdz2)), vinv);
    t = _mm256_min_ps(t, one);
    __m256 p = _mm256_mul_ps(_mm256_mul_ps(t, t), _mm256_sub_ps(three, _mm256_add_ps(t, t)));
    __m256 w = _mm256_mul_ps(_mm256_sub_ps(one, p), vstr);
    __m256 v = _mm256_add_ps(h, _mm256_mul_ps(w, vamt));
    v = _mm256_blendv_ps(h, v, _mm256_cmp_ps(v, v, _CMP_EQ_OQ));
    return _mm256_max_ps(lo, _mm256_min_ps(hi, v));
}

__attribute__((target("avx2"))) static void raise_row_avx2(float *row, const float *dx2, float dz2,
                                                           float inv_r, float strength,
                                                           float amount, float limit, int n) {
    const __m256 vdz2 = _mm256_set1_ps(dz2), vinv = _mm256_set1_ps(inv_r),
                 vstr = _mm256_set1_ps(strength), vamt = _mm256_set1_ps(amount),
                 hi = _mm256_set1_ps(limit), lo = _mm256_set1_ps(-limit);
    int i = 0;
    for (; i + 8 <= n; i += 8)
        _mm256_storeu_ps(row + i, raise8(_mm256_loadu_ps(row + i), _mm256_loadu_ps(dx2 + i), vdz2,
                                         vinv, vstr, vamt, hi, lo));
    if (i < n) {
        const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
        __m256i mask = _mm256_cmpgt_epi32(_mm256_set1_epi32(n - i), lane);
        __m256 v = raise8(_mm256_maskload_ps(row + i, mask), _mm256_maskload_ps(dx2 + i, mask),
                          vdz2, vinv, vstr, vamt, hi, lo);
        _mm256_maskstore_ps(row + i, mask, v);
    }
}

#define AVX512 __attribute__((target("avx512f"), always_inline)) static inline

// The same with 16 lanes. A NaN result comes only from a NaN height (w * amount is
// finite): the addition is masked to the heights that are numbers, a NaN keeping its
// bits through min/max (their second operand), so no compare and blend of the result.
AVX512 __m512 raise16(__m512 h, __m512 d2, __m512 vdz2, __m512 vinv, __m512 vstr, __m512 vamt,
                      __m512 hi, __m512 lo) {
    const __m512 one = _mm512_set1_ps(1.0f), three = _mm512_set1_ps(3.0f);
    __m512 t = _mm512_mul_ps(_mm512_sqrt_ps(_mm512_add_ps(d2, vdz2)), vinv);
    t = _mm512_min_ps(t, one);
    __m512 p = _mm512_mul_ps(_mm512_mul_ps(t, t), _mm512_sub_ps(three, _mm512_add_ps(t, t)));
    __m512 w = _mm512_mul_ps(_mm512_sub_ps(one, p), vstr);
    __mmask16 number = _mm512_cmp_ps_mask(h, h, _CMP_ORD_Q);
    __m512 v = _mm512_mask_add_ps(h, number, h, _mm512_mul_ps(w, vamt));
    return _mm512_max_ps(lo, _mm512_min_ps(hi, v));
}

__attribute__((target("avx512f"))) static void raise_row_avx512(float *row, const float *dx2,
                                                                float dz2, float inv_r,
                                                                float strength, float amount,
                                                                float limit, int n) {
    const __m512 vdz2 = _mm512_set1_ps(dz2), vinv = _mm512_set1_ps(inv_r),
                 vstr = _mm512_set1_ps(strength), vamt = _mm512_set1_ps(amount),
                 hi = _mm512_set1_ps(limit), lo = _mm512_set1_ps(-limit);
    int i = 0;
    for (; i + 16 <= n; i += 16)
        _mm512_storeu_ps(row + i, raise16(_mm512_loadu_ps(row + i), _mm512_loadu_ps(dx2 + i), vdz2,
                                          vinv, vstr, vamt, hi, lo));
    if (i < n) {
        __mmask16 m = (__mmask16)((1u << (n - i)) - 1u);
        __m512 v = raise16(_mm512_maskz_loadu_ps(m, row + i), _mm512_maskz_loadu_ps(m, dx2 + i),
                           vdz2, vinv, vstr, vamt, hi, lo);
        _mm512_mask_storeu_ps(row + i, m, v);
    }
}

// 0: plain C, 1: AVX2, 2: AVX-512 (as far as the processor has them).
int raise_row_paths(void) {
    return __builtin_cpu_supports("avx512f") ? 3 : __builtin_cpu_supports("avx2") ? 2 : 1;
}

void raise_row_smooth_path(int path, float *row, const float *dx2, float dz2, float inv_r,
                           float strength, float amount, float limit, int n) {
    if (path == 2)
        raise_row_avx512(row, dx2, dz2, inv_r, strength, amount, limit, n);
    else if (path == 1)
        raise_row_avx2(row, dx2, dz2, inv_r, strength, amount, limit, n);
    else
        raise_row_plain(row, dx2, dz2, inv_r, strength, amount, limit, n);
}
#else
int raise_row_paths(void) {
    return 1;
}

void raise_row_smooth_path(int path, float *row, const float *dx2, float dz2, float inv_r,
                           float strength, float amount, float limit, int n) {
    (void)path;
    raise_row_plain(row, dx2, dz2, inv_r, strength, amount, limit, n);
}
#endif

void raise_row_smooth(float *row, const float *dx2, float dz2, float inv_r, float strength,
                      float amount, float limit, int n) {
    raise_row_smooth_path(raise_row_paths() - 1, row, dx2, dz2, inv_r, strength, amount, limit, n);
}
