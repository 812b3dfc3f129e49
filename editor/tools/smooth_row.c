#include "editor/tools/smooth_row.h"

#include <math.h>

void smooth_row_squares(float *dx2, float fdx0, int n) {
    for (int i = 0; i < n; i++) {
        float dx = fdx0 + (float)i;
        dx2[i] = dx * dx;
    }
}

// One sample, as the vector paths compute each lane.
static inline float blend_sample(float h, float s, float dx2, float dz2, float inv_r,
                                 float strength, int invert, float limit) {
    float t = sqrtf(dx2 + dz2) * inv_r;
    t = t < 1.0f ? t : 1.0f;
    float w = (1.0f - t * t * (3.0f - 2.0f * t)) * strength;
    float v = h + (invert ? -w : w) * (s - h);
    v = v == v ? v : h;
    v = limit < v ? limit : v;
    v = -limit > v ? -limit : v;
    return w > 0.0f ? v : h;
}

static void smooth_row_plain(float *row, const float *smoothed, const float *dx2, float dz2,
                             float inv_r, float strength, int invert, float limit, int n) {
    for (int i = 0; i < n; i++)
        row[i] = blend_sample(row[i], smoothed[i], dx2[i], dz2, inv_r, strength, invert, limit);
}

// Written with intrinsics (as raise_row.c): the weights never leave the registers, and
// the last partial group goes through masked loads and stores. min/max are the selects
// above exactly (the first operand when the comparison holds, else the second). Not
// under ThreadSanitizer or other compilers (as HOT_LOOP: no ifunc): the plain loop.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
#include <immintrin.h>

__attribute__((target("avx2"))) static void smooth_row_avx2(float *row, const float *smoothed,
                                                            const float *dx2, float dz2,
                                                            float inv_r, float strength, int invert,
                                                            float limit, int n) {
    const __m256 one = _mm256_set1_ps(1.0f), two = _mm256_set1_ps(2.0f),
                 three = _mm256_set1_ps(3.0f), vdz2 = _mm256_set1_ps(dz2),
                 vinv = _mm256_set1_ps(inv_r), vstr = _mm256_set1_ps(strength),
                 hi = _mm256_set1_ps(limit), lo = _mm256_set1_ps(-limit),
                 zero = _mm256_setzero_ps(), sign = _mm256_set1_ps(invert ? -0.0f : 0.0f);
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    for (int i = 0; i < n; i += 8) {
        __m256i mask = _mm256_setzero_si256();
        int full = n - i >= 8;
        if (!full) mask = _mm256_cmpgt_epi32(_mm256_set1_epi32(n - i), lane);
        __m256 d2 = full ? _mm256_loadu_ps(dx2 + i) : _mm256_maskload_ps(dx2 + i, mask);
        __m256 t = _mm256_mul_ps(_mm256_sqrt_ps(_mm256_add_ps(d2, vdz2)), vinv);
        t = _mm256_min_ps(t, one);
        __m256 p = _mm256_mul_ps(_mm256_mul_ps(t, t), _mm256_sub_ps(three, _mm256_mul_ps(two, t)));
        __m256 w = _mm256_mul_ps(_mm256_sub_ps(one, p), vstr);
        __m256 h = full ? _mm256_loadu_ps(row + i) : _mm256_maskload_ps(row + i, mask);
        __m256 s = full ? _mm256_loadu_ps(smoothed + i) : _mm256_maskload_ps(smoothed + i, mask);
        __m256 v = _mm256_add_ps(h, _mm256_mul_ps(_mm256_xor_ps(w, sign), _mm256_sub_ps(s, h)));
        v = _mm256_blendv_ps(h, v, _mm256_cmp_ps(v, v, _CMP_EQ_OQ));
        v = _mm256_max_ps(lo, _mm256_min_ps(hi, v));
        v = _mm256_blendv_ps(h, v, _mm256_cmp_ps(w, zero, _CMP_GT_OQ));
        if (full)
            _mm256_storeu_ps(row + i, v);
        else
            _mm256_maskstore_ps(row + i, mask, v);
    }
}

// The same with 16 lanes and mask registers where the processor has AVX-512.
__attribute__((target("avx512f"))) static void smooth_row_avx512(float *row, const float *smoothed,
                                                                 const float *dx2, float dz2,
                                                                 float inv_r, float strength,
                                                                 int invert, float limit, int n) {
    const __m512 one = _mm512_set1_ps(1.0f), two = _mm512_set1_ps(2.0f),
                 three = _mm512_set1_ps(3.0f), vdz2 = _mm512_set1_ps(dz2),
                 vinv = _mm512_set1_ps(inv_r), vstr = _mm512_set1_ps(strength),
                 hi = _mm512_set1_ps(limit), lo = _mm512_set1_ps(-limit),
                 zero = _mm512_setzero_ps();
    const __m512i sign = _mm512_set1_epi32(invert ? (int)0x80000000u : 0);
    for (int i = 0; i < n; i += 16) {
        __mmask16 m = n - i >= 16 ? (__mmask16)0xffff : (__mmask16)((1u << (n - i)) - 1u);
        // Whole vectors load without masks (a masked load takes an arithmetic port too).
        int full = m == (__mmask16)0xffff;
        __m512 d2 = full ? _mm512_loadu_ps(dx2 + i) : _mm512_maskz_loadu_ps(m, dx2 + i);
        __m512 t = _mm512_mul_ps(_mm512_sqrt_ps(_mm512_add_ps(d2, vdz2)), vinv);
        t = _mm512_min_ps(t, one);
        __m512 p = _mm512_mul_ps(_mm512_mul_ps(t, t), _mm512_sub_ps(three, _mm512_mul_ps(two, t)));
        __m512 w = _mm512_mul_ps(_mm512_sub_ps(one, p), vstr);
        __m512 ws = _mm512_castsi512_ps(_mm512_xor_epi32(_mm512_castps_si512(w), sign));
        __m512 h = full ? _mm512_loadu_ps(row + i) : _mm512_maskz_loadu_ps(m, row + i);
        __m512 s = full ? _mm512_loadu_ps(smoothed + i) : _mm512_maskz_loadu_ps(m, smoothed + i);
        __m512 v = _mm512_add_ps(h, _mm512_mul_ps(ws, _mm512_sub_ps(s, h)));
        v = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(v, v, _CMP_EQ_OQ), h, v);
        v = _mm512_max_ps(lo, _mm512_min_ps(hi, v));
        __mmask16 write = m & _mm512_cmp_ps_mask(w, zero, _CMP_GT_OQ);
        _mm512_mask_storeu_ps(row + i, write, v);
    }
}

// 0: plain C, 1: AVX2, 2: AVX-512 (as far as the processor has them).
int smooth_row_paths(void) {
    return __builtin_cpu_supports("avx512f") ? 3 : __builtin_cpu_supports("avx2") ? 2 : 1;
}

void smooth_row_blend_path(int path, float *row, const float *smoothed, const float *dx2, float dz2,
                           float inv_r, float strength, int invert, float limit, int n) {
    if (path == 2)
        smooth_row_avx512(row, smoothed, dx2, dz2, inv_r, strength, invert, limit, n);
    else if (path == 1)
        smooth_row_avx2(row, smoothed, dx2, dz2, inv_r, strength, invert, limit, n);
    else
        smooth_row_plain(row, smoothed, dx2, dz2, inv_r, strength, invert, limit, n);
}
#else
int smooth_row_paths(void) {
    return 1;
}

void smooth_row_blend_path(int path, float *row, const float *smoothed, const float *dx2, float dz2,
                           float inv_r, float strength, int invert, float limit, int n) {
    (void)path;
    smooth_row_plain(row, smoothed, dx2, dz2, inv_r, strength, invert, limit, n);
}
#endif

void smooth_row_blend(float *row, const float *smoothed, const float *dx2, float dz2, float inv_r,
                      float strength, int invert, float limit, int n) {
    smooth_row_blend_path(smooth_row_paths() - 1, row, smoothed, dx2, dz2, inv_r, strength, invert,
                          limit, n);
}
