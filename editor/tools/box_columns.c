#include "editor/tools/box_columns.h"

#include "editor/tools/hot_loop.h"

// The compiler's loop (it gets AVX2 and AVX-512 clones) converted each group of 16
// floats to doubles through extracts and inserts: with the conversions those were
// most of the step. The ring keeps the first box's rows as doubles, so `old` needs
// no conversion either.
HOT_LOOP_WIDE static void step_loop(double *restrict sum1, double *restrict sum2,
                                    double *restrict m, const double *restrict old,
                                    const float *restrict a, const float *restrict r, double inv,
                                    float *restrict row, int64_t c0, int64_t c1) {
    for (int64_t x = c0; x < c1; x++) {
        double mid = (double)(float)(sum1[x] * inv);
        m[x] = mid;
        double s = sum2[x] + (mid - old[x]);
        sum2[x] = s;
        row[x] = (float)(s * inv);
        sum1[x] += (double)a[x] - (double)r[x];
    }
}

// Not under ThreadSanitizer or other compilers (as HOT_LOOP): the loop runs there.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
#include <immintrin.h>

// Eight columns at a time; the last group through masks (loads of the floats as 16
// lanes, the upper 8 masked off, so only AVX-512F is needed).
__attribute__((target("avx512f"))) static void
step_avx512(double *restrict sum1, double *restrict sum2, double *restrict m,
            const double *restrict old, const float *restrict a, const float *restrict r,
            double inv, float *restrict row, int64_t c0, int64_t c1) {
    const __m512d vinv = _mm512_set1_pd(inv);
    int64_t x = c0;
    for (; x + 8 <= c1; x += 8) {
        __m512d s1 = _mm512_loadu_pd(sum1 + x);
        __m512d mid = _mm512_cvtps_pd(_mm512_cvtpd_ps(_mm512_mul_pd(s1, vinv)));
        _mm512_storeu_pd(m + x, mid);
        __m512d s =
            _mm512_add_pd(_mm512_loadu_pd(sum2 + x), _mm512_sub_pd(mid, _mm512_loadu_pd(old + x)));
        _mm512_storeu_pd(sum2 + x, s);
        _mm256_storeu_ps(row + x, _mm512_cvtpd_ps(_mm512_mul_pd(s, vinv)));
        s1 = _mm512_add_pd(s1, _mm512_sub_pd(_mm512_cvtps_pd(_mm256_loadu_ps(a + x)),
                                             _mm512_cvtps_pd(_mm256_loadu_ps(r + x))));
        _mm512_storeu_pd(sum1 + x, s1);
    }
    step_loop(sum1, sum2, m, old, a, r, inv, row, x, c1); // the last few columns
}

int box_column_paths(void) {
    return __builtin_cpu_supports("avx512f") ? 2 : 1;
}

void box_column_step_path(int path, double *sum1, double *sum2, double *m, const double *old,
                          const float *a, const float *r, double inv, float *row, int64_t c0,
                          int64_t c1) {
    if (path == 1)
        step_avx512(sum1, sum2, m, old, a, r, inv, row, c0, c1);
    else
        step_loop(sum1, sum2, m, old, a, r, inv, row, c0, c1);
}
#else
int box_column_paths(void) {
    return 1;
}

void box_column_step_path(int path, double *sum1, double *sum2, double *m, const double *old,
                          const float *a, const float *r, double inv, float *row, int64_t c0,
                          int64_t c1) {
    (void)path;
    step_loop(sum1, sum2, m, old, a, r, inv, row, c0, c1);
}
#endif

void box_column_step(double *sum1, double *sum2, double *m, const double *old, const float *a,
                     const float *r, double inv, float *row, int64_t c0, int64_t c1) {
    box_column_step_path(box_column_paths() - 1, sum1, sum2, m, old, a, r, inv, row, c0, c1);
}
