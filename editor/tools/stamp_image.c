#include "editor/tools/stamp_image.h"

#include "editor/tools/hot_loop.h"

#include <math.h>
#include <stddef.h>

// Where |slope * dx + offset| < 1 along dx, widened by `pad` (metres): [*lo, *hi].
static void band(double slope, double offset, double pad, double *lo, double *hi) {
    if (fabs(slope) < 1e-300) {
        *lo = fabs(offset) < 1.0 ? -INFINITY : INFINITY;
        *hi = fabs(offset) < 1.0 ? INFINITY : -INFINITY;
        return;
    }
    double a = (-1.0 - offset) / slope, b = (1.0 - offset) / slope;
    *lo = fmin(a, b) - pad;
    *hi = fmax(a, b) + pad;
}

void stamp_image_span(const stamp_image_map *m, int64_t z, int64_t x0, int64_t x1, int64_t *a,
                      int64_t *b) {
    double dz = (double)z * m->spacing - m->z, pad = 2.0 * m->spacing;
    double ulo, uhi, vlo, vhi;
    band(m->cos_r / m->half_w, m->sin_r * dz / m->half_w, pad, &ulo, &uhi);
    band(-m->sin_r / m->half_h, m->cos_r * dz / m->half_h, pad, &vlo, &vhi);
    double lo = fmax(ulo, vlo) + m->x, hi = fmin(uhi, vhi) + m->x; // metres
    if (m->support > 0.0) { // the support's chord on this row, padded alike
        double c = m->support * m->support - dz * dz;
        c = c > 0.0 ? sqrt(c) : 0.0;
        lo = fmax(lo, m->x - c - pad), hi = fmin(hi, m->x + c + pad);
        if (fabs(dz) > m->support + pad) hi = lo - 1.0;
    }
    *a = x0, *b = x1;
    if (!(lo <= hi)) {
        *b = *a;
        return;
    }
    double s0 = floor(lo / m->spacing), s1 = ceil(hi / m->spacing) + 1.0;
    if (s0 > (double)*a) *a = s0 < (double)x1 ? (int64_t)s0 : x1;
    if (s1 < (double)*b) *b = s1 > (double)x0 ? (int64_t)s1 : x0;
    if (*b < *a) *b = *a;
}

// The constants of one row.
typedef struct row_consts {
    double xd0, cu, su, cv, sv, hw, hh, sp, mx, fu, fv, w, h, wm1, hm1;
    // Both half sizes powers of two (a 512-pixel stamp at scale 1 on a 1 m grid: 256):
    // dividing by one is multiplying by its inverse, exactly (both round the same real
    // number once), and the vector paths multiply (a divide of 8 lanes is 16 cycles).
    int pow2;
    double ihw, ihh;
    int iw, iwm1, ihm1;
    const float *im;
} row_consts;

static int power_of_two(double v) {
    int e;
    return v > 0.0 && isfinite(v) && frexp(v, &e) == 0.5 && e > -1000 && e < 1000;
}

static row_consts consts_of(const stamp_image_map *m, int64_t z, int64_t x0) {
    double dz = (double)z * m->spacing - m->z;
    return (row_consts){.xd0 = (double)x0,
                        .pow2 = power_of_two(m->half_w) && power_of_two(m->half_h),
                        .ihw = 1.0 / m->half_w,
                        .ihh = 1.0 / m->half_h,
                        .cu = m->cos_r,
                        .su = m->sin_r * dz,
                        .cv = -m->sin_r,
                        .sv = m->cos_r * dz,
                        .hw = m->half_w,
                        .hh = m->half_h,
                        .sp = m->spacing,
                        .mx = m->x,
                        .fu = m->mirror_x ? -1.0 : 1.0,
                        .fv = m->mirror_z ? -1.0 : 1.0,
                        .w = m->width,
                        .h = m->height,
                        .wm1 = m->width - 1.0,
                        .hm1 = m->height - 1.0,
                        .iw = m->width,
                        .iwm1 = m->width - 1,
                        .ihm1 = m->height - 1,
                        .im = m->pixels};
}

// stamp_value's arithmetic for a flat image stamp at sample x0 + i: fmax/fmin become
// selects (the same for the finite values met here), (double)x is x0's value plus i,
// and -sin_r * dx is (-sin_r) * dx (negation is exact). The vector paths below compute
// each lane the same way.
static inline void value_at(const row_consts *c, int i, float *value, double *edge) {
    double dx = (c->xd0 + (double)i) * c->sp - c->mx;
    double u = (c->cu * dx + c->su) / c->hw, v = (c->cv * dx + c->sv) / c->hh;
    double au = fabs(u), av = fabs(v);
    *edge = au > av ? au : av;
    u *= c->fu, v *= c->fv;
    double px = (u + 1.0) * 0.5 * c->w - 0.5, py = (v + 1.0) * 0.5 * c->h - 0.5;
    px = px > 0.0 ? px : 0.0;
    py = py > 0.0 ? py : 0.0;
    px = px < c->wm1 ? px : c->wm1;
    py = py < c->hm1 ? py : c->hm1;
    int ix = (int)px, iy = (int)py;
    int jx = ix < c->iwm1 ? ix + 1 : ix, jy = iy < c->ihm1 ? iy + 1 : iy;
    double ax = px - ix, ay = py - iy;
    const float *r0 = c->im + (size_t)iy * c->iw, *r1 = c->im + (size_t)jy * c->iw;
    double top = r0[ix] * (1 - ax) + r0[jx] * ax;
    double bot = r1[ix] * (1 - ax) + r1[jx] * ax;
    *value = (float)(top * (1 - ay) + bot * ay);
}

static void values_plain(const row_consts *c, int i, int n, float *value, double *edge) {
    for (; i < n; i++)
        value_at(c, i, &value[i], &edge[i]);
}

// Written with intrinsics: the compiler vectorised the coordinates but read the image
// and blended sample by sample. Not under ThreadSanitizer or other compilers (as
// HOT_LOOP: no ifunc), where the plain loop runs.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
#include <immintrin.h>

__attribute__((target("avx2"))) static int values_avx2(const row_consts *c, int n, float *value,
                                                       double *edge) {
    const __m256d lane = _mm256_setr_pd(0, 1, 2, 3), cu = _mm256_set1_pd(c->cu),
                  su = _mm256_set1_pd(c->su), cv = _mm256_set1_pd(c->cv),
                  sv = _mm256_set1_pd(c->sv), hw = _mm256_set1_pd(c->hw),
                  hh = _mm256_set1_pd(c->hh), sp = _mm256_set1_pd(c->sp),
                  ihw = _mm256_set1_pd(c->ihw), ihh = _mm256_set1_pd(c->ihh),
                  mx = _mm256_set1_pd(c->mx), fu = _mm256_set1_pd(c->fu),
                  fv = _mm256_set1_pd(c->fv), w = _mm256_set1_pd(c->w), h = _mm256_set1_pd(c->h),
                  wm1 = _mm256_set1_pd(c->wm1), hm1 = _mm256_set1_pd(c->hm1),
                  one = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5), zero = _mm256_setzero_pd(),
                  sign = _mm256_set1_pd(-0.0);
    const __m128i iw = _mm_set1_epi32(c->iw), iwm1 = _mm_set1_epi32(c->iwm1),
                  ihm1 = _mm_set1_epi32(c->ihm1), ione = _mm_set1_epi32(1);
    int i = 0;
    for (; i + 4 <= n; i += 4) {
        __m256d xd = _mm256_add_pd(_mm256_set1_pd(c->xd0 + (double)i), lane);
        __m256d dx = _mm256_sub_pd(_mm256_mul_pd(xd, sp), mx);
        __m256d u = _mm256_add_pd(_mm256_mul_pd(cu, dx), su);
        __m256d v = _mm256_add_pd(_mm256_mul_pd(cv, dx), sv);
        u = c->pow2 ? _mm256_mul_pd(u, ihw) : _mm256_div_pd(u, hw);
        v = c->pow2 ? _mm256_mul_pd(v, ihh) : _mm256_div_pd(v, hh);
        __m256d e = _mm256_max_pd(_mm256_andnot_pd(sign, u), _mm256_andnot_pd(sign, v));
        _mm256_storeu_pd(edge + i, e);
        u = _mm256_mul_pd(u, fu), v = _mm256_mul_pd(v, fv);
        __m256d px =
            _mm256_sub_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_add_pd(u, one), half), w), half);
        __m256d py =
            _mm256_sub_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_add_pd(v, one), half), h), half);
        px = _mm256_min_pd(_mm256_max_pd(px, zero), wm1);
        py = _mm256_min_pd(_mm256_max_pd(py, zero), hm1);
        __m128i ix = _mm256_cvttpd_epi32(px), iy = _mm256_cvttpd_epi32(py);
        __m128i jx = _mm_min_epi32(_mm_add_epi32(ix, ione), iwm1);
        __m128i jy = _mm_min_epi32(_mm_add_epi32(iy, ione), ihm1);
        __m256d ax = _mm256_sub_pd(px, _mm256_cvtepi32_pd(ix));
        __m256d ay = _mm256_sub_pd(py, _mm256_cvtepi32_pd(iy));
        __m128i r0 = _mm_mullo_epi32(iy, iw), r1 = _mm_mullo_epi32(jy, iw);
        __m256d g00 = _mm256_cvtps_pd(_mm_i32gather_ps(c->im, _mm_add_epi32(r0, ix), 4));
        __m256d g01 = _mm256_cvtps_pd(_mm_i32gather_ps(c->im, _mm_add_epi32(r0, jx), 4));
        __m256d g10 = _mm256_cvtps_pd(_mm_i32gather_ps(c->im, _mm_add_epi32(r1, ix), 4));
        __m256d g11 = _mm256_cvtps_pd(_mm_i32gather_ps(c->im, _mm_add_epi32(r1, jx), 4));
        __m256d bx = _mm256_sub_pd(one, ax), by = _mm256_sub_pd(one, ay);
        __m256d top = _mm256_add_pd(_mm256_mul_pd(g00, bx), _mm256_mul_pd(g01, ax));
        __m256d bot = _mm256_add_pd(_mm256_mul_pd(g10, bx), _mm256_mul_pd(g11, ax));
        __m256d val = _mm256_add_pd(_mm256_mul_pd(top, by), _mm256_mul_pd(bot, ay));
        _mm_storeu_ps(value + i, _mm256_cvtpd_ps(val));
    }
    return i;
}

// The same with 8 lanes where the processor has AVX-512 (gathers stay AVX2's).
__attribute__((target("avx512f,avx2"))) static int values_avx512(const row_consts *c, int n,
                                                                 float *value, double *edge) {
    const __m512d lane = _mm512_setr_pd(0, 1, 2, 3, 4, 5, 6, 7), cu = _mm512_set1_pd(c->cu),
                  su = _mm512_set1_pd(c->su), cv = _mm512_set1_pd(c->cv),
                  sv = _mm512_set1_pd(c->sv), hw = _mm512_set1_pd(c->hw),
                  hh = _mm512_set1_pd(c->hh), sp = _mm512_set1_pd(c->sp),
                  ihw = _mm512_set1_pd(c->ihw), ihh = _mm512_set1_pd(c->ihh),
                  mx = _mm512_set1_pd(c->mx), fu = _mm512_set1_pd(c->fu),
                  fv = _mm512_set1_pd(c->fv), w = _mm512_set1_pd(c->w), h = _mm512_set1_pd(c->h),
                  wm1 = _mm512_set1_pd(c->wm1), hm1 = _mm512_set1_pd(c->hm1),
                  one = _mm512_set1_pd(1.0), half = _mm512_set1_pd(0.5), zero = _mm512_setzero_pd();
    const __m256i iw = _mm256_set1_epi32(c->iw), iwm1 = _mm256_set1_epi32(c->iwm1),
                  ihm1 = _mm256_set1_epi32(c->ihm1), ione = _mm256_set1_epi32(1);
    int i = 0;
    for (; i + 8 <= n; i += 8) {
        __m512d xd = _mm512_add_pd(_mm512_set1_pd(c->xd0 + (double)i), lane);
        __m512d dx = _mm512_sub_pd(_mm512_mul_pd(xd, sp), mx);
        __m512d u = _mm512_add_pd(_mm512_mul_pd(cu, dx), su);
        __m512d v = _mm512_add_pd(_mm512_mul_pd(cv, dx), sv);
        u = c->pow2 ? _mm512_mul_pd(u, ihw) : _mm512_div_pd(u, hw);
        v = c->pow2 ? _mm512_mul_pd(v, ihh) : _mm512_div_pd(v, hh);
        _mm512_storeu_pd(edge + i, _mm512_max_pd(_mm512_abs_pd(u), _mm512_abs_pd(v)));
        u = _mm512_mul_pd(u, fu), v = _mm512_mul_pd(v, fv);
        __m512d px =
            _mm512_sub_pd(_mm512_mul_pd(_mm512_mul_pd(_mm512_add_pd(u, one), half), w), half);
        __m512d py =
            _mm512_sub_pd(_mm512_mul_pd(_mm512_mul_pd(_mm512_add_pd(v, one), half), h), half);
        px = _mm512_min_pd(_mm512_max_pd(px, zero), wm1);
        py = _mm512_min_pd(_mm512_max_pd(py, zero), hm1);
        __m256i ix = _mm512_cvttpd_epi32(px), iy = _mm512_cvttpd_epi32(py);
        __m256i jx = _mm256_min_epi32(_mm256_add_epi32(ix, ione), iwm1);
        __m256i jy = _mm256_min_epi32(_mm256_add_epi32(iy, ione), ihm1);
        __m512d ax = _mm512_sub_pd(px, _mm512_cvtepi32_pd(ix));
        __m512d ay = _mm512_sub_pd(py, _mm512_cvtepi32_pd(iy));
        __m256i r0 = _mm256_mullo_epi32(iy, iw), r1 = _mm256_mullo_epi32(jy, iw);
        __m512d g00 = _mm512_cvtps_pd(_mm256_i32gather_ps(c->im, _mm256_add_epi32(r0, ix), 4));
        __m512d g01 = _mm512_cvtps_pd(_mm256_i32gather_ps(c->im, _mm256_add_epi32(r0, jx), 4));
        __m512d g10 = _mm512_cvtps_pd(_mm256_i32gather_ps(c->im, _mm256_add_epi32(r1, ix), 4));
        __m512d g11 = _mm512_cvtps_pd(_mm256_i32gather_ps(c->im, _mm256_add_epi32(r1, jx), 4));
        __m512d bx = _mm512_sub_pd(one, ax), by = _mm512_sub_pd(one, ay);
        __m512d top = _mm512_add_pd(_mm512_mul_pd(g00, bx), _mm512_mul_pd(g01, ax));
        __m512d bot = _mm512_add_pd(_mm512_mul_pd(g10, bx), _mm512_mul_pd(g11, ax));
        __m512d val = _mm512_add_pd(_mm512_mul_pd(top, by), _mm512_mul_pd(bot, ay));
        _mm256_storeu_ps(value + i, _mm512_cvtpd_ps(val));
    }
    return i;
}

int stamp_image_paths(void) {
    return __builtin_cpu_supports("avx512f") ? 3 : __builtin_cpu_supports("avx2") ? 2 : 1;
}

static int values_vector(int path, const row_consts *c, int n, float *value, double *edge) {
    return path == 2   ? values_avx512(c, n, value, edge)
           : path == 1 ? values_avx2(c, n, value, edge)
                       : 0;
}
#else
int stamp_image_paths(void) {
    return 1;
}

static int values_vector(int path, const row_consts *c, int n, float *value, double *edge) {
    (void)path, (void)c, (void)n, (void)value, (void)edge;
    return 0;
}
#endif

void stamp_image_values_path(int path, const stamp_image_map *m, int64_t z, int64_t x0, int n,
                             float *value, double *edge) {
    row_consts c = consts_of(m, z, x0);
    values_plain(&c, values_vector(path, &c, n, value, edge), n, value, edge);
}

void stamp_image_values(const stamp_image_map *m, int64_t z, int64_t x0, int n, float *value,
                        double *edge) {
    stamp_image_values_path(stamp_image_paths() - 1, m, z, x0, n, value, edge);
}

double stamp_image_support(const float *pixels, int width, int height) {
    double cx = 0.5 * (width - 1), cy = 0.5 * (height - 1), far = 0.0;
    for (int y = 0; y < height; y++) {
        const float *row = pixels + (size_t)y * (size_t)width;
        int a = 0, b = width - 1;
        while (a < width && row[a] == 0.0f)
            a++;
        if (a == width) continue; // all 0
        while (row[b] == 0.0f)
            b--;
        // The row's farthest non-zero pixels are its outermost ones.
        double dy = y - cy, dx = fmax(fabs(a - cx), fabs(b - cx));
        far = fmax(far, sqrt(dx * dx + dy * dy));
    }
    // A sample reads the 4 pixels around its point (within sqrt(2)), after clamping the
    // point into the image (at most half a pixel each way): 2.5 holds both.
    return far + 2.5;
}

// fmaxf/fminf as selects: the same for the sum, which is not NaN by then.
HOT_LOOP_WIDE void stamp_image_add(float *restrict row, const float *restrict value,
                                   const double *restrict edge, float k, float limit, int n) {
    for (int i = 0; i < n; i++) {
        float old = row[i], v = old + value[i] * k;
        v = v == v ? v : old;
        v = v > -limit ? v : -limit;
        v = v < limit ? v : limit;
        row[i] = edge[i] < 1.0 ? v : old;
    }
}
