#include "editor/tools/box_columns.h"

// Row by row across all columns (box_blur.c's sweep), every step loads and stores each
// column's two sums and its ring entry, with conversions through extracts and inserts.
// A strip of 16 columns swept from top to bottom keeps both sums in registers and its
// ring in a few kilobytes; each column's operations and their order are unchanged.
// Not under ThreadSanitizer or other compilers (as HOT_LOOP): the caller's sweep runs.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
#include <immintrin.h>

#define WIDE __attribute__((target("avx512f")))

// The 16 floats of row at x (lanes past the mask read as 0) as two vectors of doubles.
WIDE static inline void load16(const float *row, __mmask16 m, __m512d *lo, __m512d *hi) {
    __m512 v = _mm512_maskz_loadu_ps(m, row);
    *lo = _mm512_cvtps_pd(_mm512_castps512_ps256(v));
    *hi = _mm512_cvtps_pd(_mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(v), 1)));
}

// (double)(float)v: the first box's row as box_blur.c keeps it.
WIDE static inline __m512d to_float(__m512d v) {
    return _mm512_cvtps_pd(_mm512_cvtpd_ps(v));
}

// Rows [y0, y1) of the source (rows[y] + x: row y at column x) as rows 0.. below.
WIDE static void strip(const float *const *rows, float *out, int64_t w, int k, double *ring,
                       int64_t x, __mmask16 m, int64_t y0, int64_t y1) {
    const float *const *src = rows + y0;
    const int64_t h = y1 - y0;
    out += y0 * w;
    const __m512d inv = _mm512_set1_pd(1.0 / (2 * k + 1)), zero = _mm512_setzero_pd();
    const int64_t slots = 2 * k + 2;
    // The first box's sum of rows [0, 2k] (0.0 plus each row in turn), the second's 0.
    __m512d s1lo = zero, s1hi = zero, s2lo = zero, s2hi = zero;
    for (int64_t i = 0; i <= 2 * k; i++) {
        __m512d lo, hi;
        load16(src[i] + x, m, &lo, &hi);
        s1lo = _mm512_add_pd(s1lo, lo), s1hi = _mm512_add_pd(s1hi, hi);
    }
    // The ring slot of the first box's row i (i mod slots), counted on.
    for (int64_t i = k, at = k % slots; i < h - k; i++, at = at + 1 == slots ? 0 : at + 1) {
        __m512d mlo = to_float(_mm512_mul_pd(s1lo, inv)), mhi = to_float(_mm512_mul_pd(s1hi, inv));
        double *slot = ring + at * 16;
        _mm512_storeu_pd(slot, mlo);
        _mm512_storeu_pd(slot + 8, mhi);
        __m512d olo = zero, ohi = zero; // nothing dropped while the first 2k + 1 rows come
        if (i - k > 2 * k) {            // row i - 2k - 1: the slot after this one
            const double *old = ring + (at + 1 == slots ? 0 : at + 1) * 16;
            olo = _mm512_loadu_pd(old), ohi = _mm512_loadu_pd(old + 8);
        }
        s2lo = _mm512_add_pd(s2lo, _mm512_sub_pd(mlo, olo));
        s2hi = _mm512_add_pd(s2hi, _mm512_sub_pd(mhi, ohi));
        if (i >= 3 * k) {
            __m256 lo = _mm512_cvtpd_ps(_mm512_mul_pd(s2lo, inv));
            __m256 hi = _mm512_cvtpd_ps(_mm512_mul_pd(s2hi, inv));
            __m512 row = _mm512_castpd_ps(_mm512_insertf64x4(
                _mm512_castpd256_pd512(_mm256_castps_pd(lo)), _mm256_castps_pd(hi), 1));
            _mm512_mask_storeu_ps(out + (i - k) * w + x, m, row);
        }
        // The sum of rows [i - k, i + k] moves on a row (after the last: a - a).
        const float *r = src[i - k] + x, *a = i + 1 < h - k ? src[i + k + 1] + x : r;
        __m512d alo, ahi, rlo, rhi;
        load16(a, m, &alo, &ahi);
        load16(r, m, &rlo, &rhi);
        s1lo = _mm512_add_pd(s1lo, _mm512_sub_pd(alo, rlo));
        s1hi = _mm512_add_pd(s1hi, _mm512_sub_pd(ahi, rhi));
    }
}

int box_columns_have_wide(void) {
    return __builtin_cpu_supports("avx512f");
}

int box_columns_wide(const float *const *rows, float *out, int64_t w, int k, double *ring,
                     int64_t c0, int64_t c1, int64_t y0, int64_t y1) {
    if (!box_columns_have_wide()) return -1;
    if (y1 - y0 <= 4 * k) return 0; // no result row
    for (int64_t x = c0; x < c1; x += 16) {
        int64_t left = c1 - x;
        strip(rows, out, w, k, ring, x,
              left >= 16 ? (__mmask16)0xffff : (__mmask16)((1u << left) - 1u), y0, y1);
    }
    return 0;
}
#else
int box_columns_have_wide(void) {
    return 0;
}

int box_columns_wide(const float *const *rows, float *out, int64_t w, int k, double *ring,
                     int64_t c0, int64_t c1, int64_t y0, int64_t y1) {
    (void)rows, (void)out, (void)w, (void)k, (void)ring, (void)c0, (void)c1, (void)y0, (void)y1;
    return -1;
}
#endif
