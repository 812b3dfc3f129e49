// Gradient noise and fractals: batch paths bit-identical to the reference (with and
// without AVX2), range, continuity across cells and the 2^32 wrap, fractional
// octaves (Kahoun 2010), decorrelated octaves and seeds, determinism across threads.
#include "editor/gen/gen_noise.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

// Test hook in gen_noise.c (not part of the public header).
void gen_noise_allow_avx2(int allow);

static uint64_t rng_state = 0x243F6A8885A308D3ull;
static uint64_t rng_next(void) {
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    uint64_t x = rng_state;
    x ^= x >> 33;
    x *= 0xFF51AFD7ED558CCDull;
    x ^= x >> 33;
    return x;
}
// Uniform in [lo, hi).
static double rng_range(double lo, double hi) {
    return lo + (hi - lo) * (double)(rng_next() >> 11) * (1.0 / 9007199254740992.0);
}
// A test coordinate: mostly moderate, some negative, some near +-2^32 and +-2^40.
static double rng_coord(void) {
    switch (rng_next() % 6) {
    case 0:
        return rng_range(-4.0, 4.0);
    case 1:
        return rng_range(-1e4, 1e4);
    case 2:
        return rng_range(-1.0, 1.0) * 1099511627776.0; // +-2^40
    case 3:
        return 4294967296.0 + rng_range(-3.0, 3.0);
    case 4:
        return -4294967296.0 + rng_range(-3.0, 3.0);
    default:
        return (double)(int64_t)(rng_next() % 2001) - 1000.0 + rng_range(-1e-6, 1e-6);
    }
}

static const gen_fractal FRACTALS[] = {
    {GEN_FRACTAL_FBM, 1, 8.0, 0.5, 2.0, 1.0},          {GEN_FRACTAL_FBM, 77, 3.5, 0.62, 1.93, 1.0},
    {GEN_FRACTAL_FBM, 0xDEADBEEF, 0.4, 0.5, 2.0, 1.0}, {GEN_FRACTAL_FBM, 5, 12.25, 0.45, 2.2, 1.0},
    {GEN_FRACTAL_RIDGED, 2, 8.0, 0.5, 2.0, 1.0},       {GEN_FRACTAL_RIDGED, 3, 5.7, 0.55, 2.1, 0.9},
};
#define NFRACTALS (sizeof FRACTALS / sizeof FRACTALS[0])

static int same_bits(float a, float b) {
    return memcmp(&a, &b, sizeof a) == 0;
}

static void check_grid2(const gen_fractal *f, int nx, int ny) {
    double *xs = malloc(sizeof(double) * (size_t)nx);
    double *ys = malloc(sizeof(double) * (size_t)ny);
    float *out = malloc(sizeof(float) * (size_t)nx * (size_t)ny);
    for (int i = 0; i < nx; i++)
        xs[i] = rng_coord();
    for (int j = 0; j < ny; j++)
        ys[j] = rng_coord();
    gen_fractal_grid2(f, xs, nx, ys, ny, out);
    for (int j = 0; j < ny; j++) {
        for (int i = 0; i < nx; i++) {
            float ref = gen_fractal2(f, xs[i], ys[j]);
            float got = out[(size_t)j * nx + i];
            if (!same_bits(ref, got)) {
                fail_msg("grid2 kind %d at (%.17g, %.17g): %.9g != reference %.9g", f->kind, xs[i],
                         ys[j], got, ref);
            }
        }
    }
    free(xs), free(ys), free(out);
}

static void check_points3(const gen_fractal *f, size_t n) {
    double *xyz = malloc(sizeof(double) * 3 * n);
    float *out = malloc(sizeof(float) * n);
    for (size_t k = 0; k < 3 * n; k++)
        xyz[k] = rng_coord();
    gen_fractal_points3(f, xyz, n, out);
    for (size_t i = 0; i < n; i++) {
        float ref = gen_fractal3(f, xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
        if (!same_bits(ref, out[i])) {
            fail_msg("points3 kind %d at (%.17g, %.17g, %.17g): %.9g != reference %.9g", f->kind,
                     xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2], out[i], ref);
        }
    }
    free(xyz), free(out);
}

static void grid2_matches_reference(int avx2) {
    gen_noise_allow_avx2(avx2);
    for (size_t k = 0; k < NFRACTALS; k++) {
        check_grid2(&FRACTALS[k], 203, 37); // not a multiple of any vector or chunk width
        check_grid2(&FRACTALS[k], 1, 5);
        check_grid2(&FRACTALS[k], 64, 1);
    }
    gen_noise_allow_avx2(1);
}

static void points3_matches_reference(int avx2) {
    gen_noise_allow_avx2(avx2);
    for (size_t k = 0; k < NFRACTALS; k++) {
        check_points3(&FRACTALS[k], 5001);
        check_points3(&FRACTALS[k], 3);
    }
    gen_noise_allow_avx2(1);
}

static void test_grid2_matches_reference(void **state) {
    (void)state;
    grid2_matches_reference(1);
}
static void test_grid2_baseline_matches_reference(void **state) {
    (void)state;
    grid2_matches_reference(0);
}
static void test_points3_matches_reference(void **state) {
    (void)state;
    points3_matches_reference(1);
}
static void test_points3_baseline_matches_reference(void **state) {
    (void)state;
    points3_matches_reference(0);
}

// A batch's results do not depend on where the batch starts or ends.
static void test_batch_boundaries(void **state) {
    (void)state;
    const gen_fractal *f = &FRACTALS[0];
    enum { N = 300 };
    double xs[N], ys[3], xyz[3 * N];
    float whole[3 * N], part[3 * N];
    for (int i = 0; i < N; i++)
        xs[i] = rng_coord();
    for (int j = 0; j < 3; j++)
        ys[j] = rng_coord();
    for (int k = 0; k < 3 * N; k++)
        xyz[k] = rng_coord();
    gen_fractal_grid2(f, xs, N, ys, 3, whole);
    for (int i0 = 0; i0 < N; i0 += 37) {
        int m = N - i0 < 37 ? N - i0 : 37;
        gen_fractal_grid2(f, xs + i0, m, ys + 1, 1, part);
        assert_memory_equal(part, whole + N + i0, sizeof(float) * (size_t)m);
    }
    gen_fractal_points3(f, xyz, N, whole);
    for (int i0 = 0; i0 < N; i0 += 29) {
        int m = N - i0 < 29 ? N - i0 : 29;
        gen_fractal_points3(f, xyz + 3 * i0, (size_t)m, part);
        assert_memory_equal(part, whole + i0, sizeof(float) * (size_t)m);
    }
}

static void test_noise_range(void **state) {
    (void)state;
    double sum2 = 0, sq2 = 0, sum3 = 0, sq3 = 0, max2 = 0, max3 = 0;
    const int n = 400000;
    for (int i = 0; i < n; i++) {
        double x = rng_coord(), y = rng_coord(), z = rng_coord();
        float a = gen_noise2(9, x, y), b = gen_noise3(9, x, y, z);
        sum2 += a, sq2 += (double)a * a, sum3 += b, sq3 += (double)b * b;
        if (fabsf(a) > max2) max2 = fabsf(a);
        if (fabsf(b) > max3) max3 = fabsf(b);
    }
    double sd2 = sqrt(sq2 / n - (sum2 / n) * (sum2 / n));
    double sd3 = sqrt(sq3 / n - (sum3 / n) * (sum3 / n));
    assert_true(max2 <= 1.01 && max3 <= 1.01);
    assert_true(max2 > 0.6 && max3 > 0.6); // uses most of the range
    assert_true(sd2 > 0.1 && sd3 > 0.1);
    assert_true(fabs(sum2 / n) < 0.01 && fabs(sum3 / n) < 0.01);

    // Cell centres with aligned gradients are where the peaks are.
    for (int i = 0; i < 100000; i++) {
        double x = floor(rng_range(-1e6, 1e6)) + 0.5, y = floor(rng_range(-1e6, 1e6)) + 0.5;
        assert_true(fabsf(gen_noise2(3, x, y)) <= 1.01f);
        assert_true(fabsf(gen_noise3(3, x, y, 0.5 + rng_range(0.3, 0.4))) <= 1.01f);
    }

    // Ridged output is normalised to [-1, 1].
    double rmin = 1, rmax = -1, rs = 0, rq = 0;
    for (int i = 0; i < 20000; i++) {
        float r = gen_fractal2(&FRACTALS[4], rng_range(-100, 100), rng_range(-100, 100));
        rmin = r < rmin ? r : rmin, rmax = r > rmax ? r : rmax;
        rs += r, rq += (double)r * r;
    }
    assert_true(rmin >= -1.0001 && rmax <= 1.0001);
    assert_true(sqrt(rq / 20000 - (rs / 20000) * (rs / 20000)) > 0.05);
}

// |f(p + h) - f(p)| <= k * h along each axis, h = 1e-4.
static void check_continuity2(float (*fn)(const void *, double, double), const void *ctx, double x,
                              double y, double k) {
    const double h = 1e-4;
    float v = fn(ctx, x, y);
    double dx = fabs((double)fn(ctx, x + h, y) - v), dy = fabs((double)fn(ctx, x, y + h) - v);
    if (dx > k * h || dy > k * h) fail_msg("jump at (%.17g, %.17g): %g %g", x, y, dx, dy);
}
static void check_continuity3(float (*fn)(const void *, double, double, double), const void *ctx,
                              double x, double y, double z, double k) {
    const double h = 1e-4;
    float v = fn(ctx, x, y, z);
    double d = fabs((double)fn(ctx, x + h, y, z) - v);
    d = fmax(d, fabs((double)fn(ctx, x, y + h, z) - v));
    d = fmax(d, fabs((double)fn(ctx, x, y, z + h) - v));
    if (d > k * h) fail_msg("jump at (%.17g, %.17g, %.17g): %g", x, y, z, d);
}
static float noise2_fn(const void *ctx, double x, double y) {
    return gen_noise2(*(const uint32_t *)ctx, x, y);
}
static float noise3_fn(const void *ctx, double x, double y, double z) {
    return gen_noise3(*(const uint32_t *)ctx, x, y, z);
}
static float fractal2_fn(const void *ctx, double x, double y) {
    return gen_fractal2(ctx, x, y);
}
static float fractal3_fn(const void *ctx, double x, double y, double z) {
    return gen_fractal3(ctx, x, y, z);
}

static void test_continuity(void **state) {
    (void)state;
    uint32_t seed = 4;
    // Single noise: slope bound ~3 per unit; fractals: sum over octaves of amp*freq.
    for (int i = 0; i < 20000; i++) {
        // Half the samples straddle a lattice boundary (integer +- a fraction of h).
        double x = rng_range(-1e5, 1e5), y = rng_range(-1e5, 1e5), z = rng_range(-1e5, 1e5);
        if (i & 1) x = floor(x) - rng_range(0, 1e-4), y = floor(y) - rng_range(0, 1e-4);
        check_continuity2(noise2_fn, &seed, x, y, 4.0);
        check_continuity3(noise3_fn, &seed, x, y, z, 4.0);
        check_continuity2(fractal2_fn, &FRACTALS[0], x / 64, y / 64, 8 * 4.0);
        check_continuity3(fractal3_fn, &FRACTALS[0], x / 64, y / 64, z / 64, 8 * 4.0);
        check_continuity2(fractal2_fn, &FRACTALS[4], x / 64, y / 64, 8 * 8.0);
    }
    // Across the 2^32 wrap of the lattice, in both directions, and across 0.
    const double wraps[] = {4294967296.0, -4294967296.0, 0.0, 2147483648.0, -2147483648.0};
    for (size_t w = 0; w < sizeof wraps / sizeof wraps[0]; w++) {
        for (int i = 0; i < 200; i++) {
            double x = wraps[w] - rng_range(0, 1e-4), y = rng_range(-10, 10);
            check_continuity2(noise2_fn, &seed, x, y, 4.0);
            check_continuity2(noise2_fn, &seed, y, x, 4.0);
            check_continuity3(noise3_fn, &seed, x, y, x, 4.0);
        }
    }
    // The lattice is periodic with 2^32 cells: exactly representable shifts repeat it.
    for (int i = 0; i < 1000; i++) {
        double x = floor(rng_range(-1e3, 1e3) * 256) / 256, y = rng_range(-10, 10);
        assert_true(same_bits(gen_noise2(seed, x, y), gen_noise2(seed, x + 4294967296.0, y)));
        assert_true(same_bits(gen_noise3(seed, y, x, y), gen_noise3(seed, y, x - 4294967296.0, y)));
    }
}

// Seed 004 3.2.2: floor(k) full octaves, then (k - floor(k)) * w * noise(p * n).
static void test_fractional_octaves(void **state) {
    (void)state;
    gen_fractal f = {GEN_FRACTAL_FBM, 11, 3.0, 0.5, 2.0, 1.0};
    gen_fractal g = f, h = f, q = f;
    g.octaves = 3.5, h.octaves = 4.0, q.octaves = 3.25;
    int differ = 0;
    for (int i = 0; i < 20000; i++) {
        double x = rng_range(-1e3, 1e3), y = rng_range(-1e3, 1e3), z = rng_range(-1e3, 1e3);
        float a = gen_fractal2(&f, x, y), b = gen_fractal2(&g, x, y), c = gen_fractal2(&h, x, y);
        float d = gen_fractal2(&q, x, y);
        assert_true(fabs((b - a) - 0.5 * (c - a)) <= 4e-7);
        assert_true(fabs((d - a) - 0.25 * (c - a)) <= 4e-7);
        differ += b != a;
        a = gen_fractal3(&f, x, y, z), b = gen_fractal3(&g, x, y, z), c = gen_fractal3(&h, x, y, z);
        assert_true(fabs((b - a) - 0.5 * (c - a)) <= 4e-7);
    }
    assert_true(differ > 19000);
    // The octave count is continuous for ridged output too.
    gen_fractal r = FRACTALS[4], r2 = r;
    r.octaves = 3.0, r2.octaves = 3.0 + 1e-6;
    for (int i = 0; i < 1000; i++) {
        double x = rng_range(-1e3, 1e3), y = rng_range(-1e3, 1e3);
        assert_true(fabsf(gen_fractal2(&r, x, y) - gen_fractal2(&r2, x, y)) < 1e-5f);
    }
}

static double correlation(const float *a, const float *b, int n) {
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    for (int i = 0; i < n; i++) {
        sa += a[i], sb += b[i], saa += (double)a[i] * a[i], sbb += (double)b[i] * b[i];
        sab += (double)a[i] * b[i];
    }
    double cov = sab / n - (sa / n) * (sb / n);
    return cov / sqrt((saa / n - (sa / n) * (sa / n)) * (sbb / n - (sb / n) * (sb / n)));
}

// Octave o is not octave o-1 rescaled (same seed, aligned lattice): the octave-1
// field at p, recovered as (fbm2 - fbm1) / gain at p / lacunarity, is uncorrelated
// with the octave-0 field at p. Nor is the fBm pinned to 0 at integer points.
static void test_octaves_decorrelated(void **state) {
    (void)state;
    enum { N = 20000 };
    static float o0[N], o1[N], o0z[N], o1z[N];
    gen_fractal one = {GEN_FRACTAL_FBM, 21, 1.0, 0.5, 2.0, 1.0}, two = one;
    two.octaves = 2.0;
    for (int i = 0; i < N; i++) {
        double x = rng_range(-500, 500), y = rng_range(-500, 500), z = rng_range(-500, 500);
        o0[i] = gen_fractal2(&one, x, y);
        o1[i] = (gen_fractal2(&two, x / 2, y / 2) - gen_fractal2(&one, x / 2, y / 2)) / 0.5f;
        o0z[i] = gen_fractal3(&one, x, y, z);
        o1z[i] =
            (gen_fractal3(&two, x / 2, y / 2, z / 2) - gen_fractal3(&one, x / 2, y / 2, z / 2)) /
            0.5f;
    }
    assert_true(fabs(correlation(o0, o1, N)) < 0.05);
    assert_true(fabs(correlation(o0z, o1z, N)) < 0.05);

    int nonzero = 0;
    for (int x = -5; x < 5; x++) {
        for (int y = -5; y < 5; y++) {
            nonzero += fabsf(gen_fractal2(&FRACTALS[0], x, y)) > 1e-3f;
            nonzero += fabsf(gen_fractal3(&FRACTALS[0], x, y, 0)) > 1e-3f;
        }
    }
    assert_true(nonzero > 180);
}

static void test_seeds_differ(void **state) {
    (void)state;
    enum { N = 20000 };
    static float a[N], b[N], c[N], d[N];
    gen_fractal f = FRACTALS[0], g = f;
    g.seed = f.seed + 1;
    for (int i = 0; i < N; i++) {
        double x = rng_range(-500, 500), y = rng_range(-500, 500), z = rng_range(-500, 500);
        a[i] = gen_fractal2(&f, x, y), b[i] = gen_fractal2(&g, x, y);
        c[i] = gen_noise3(100, x, y, z), d[i] = gen_noise3(101, x, y, z);
    }
    assert_true(fabs(correlation(a, b, N)) < 0.05);
    assert_true(fabs(correlation(c, d, N)) < 0.05);
}

typedef struct thread_job {
    const double *xs, *ys, *xyz;
    const float *grid_ref, *points_ref;
    int ok;
} thread_job;

enum { TNX = 150, TNY = 40, TNP = 3000 };

static void *thread_main(void *arg) {
    thread_job *job = arg;
    float *grid = malloc(sizeof(float) * TNX * TNY), *pts = malloc(sizeof(float) * TNP);
    job->ok = 1;
    for (int rep = 0; rep < 20; rep++) {
        const gen_fractal *f = &FRACTALS[rep % NFRACTALS];
        gen_fractal_grid2(f, job->xs, TNX, job->ys, TNY, grid);
        gen_fractal_points3(f, job->xyz, TNP, pts);
        if (memcmp(grid, job->grid_ref + (size_t)(rep % NFRACTALS) * TNX * TNY,
                   sizeof(float) * TNX * TNY) ||
            memcmp(pts, job->points_ref + (size_t)(rep % NFRACTALS) * TNP, sizeof(float) * TNP))
            job->ok = 0;
    }
    free(grid), free(pts);
    return NULL;
}

static void test_threads_deterministic(void **state) {
    (void)state;
    static double xs[TNX], ys[TNY], xyz[3 * TNP];
    static float grid_ref[NFRACTALS * TNX * TNY], points_ref[NFRACTALS * TNP];
    for (int i = 0; i < TNX; i++)
        xs[i] = rng_coord();
    for (int j = 0; j < TNY; j++)
        ys[j] = rng_coord();
    for (int k = 0; k < 3 * TNP; k++)
        xyz[k] = rng_coord();
    for (size_t k = 0; k < NFRACTALS; k++) {
        gen_fractal_grid2(&FRACTALS[k], xs, TNX, ys, TNY, grid_ref + k * TNX * TNY);
        gen_fractal_points3(&FRACTALS[k], xyz, TNP, points_ref + k * TNP);
    }
    thread_job jobs[2];
    pthread_t th[2];
    for (int t = 0; t < 2; t++) {
        jobs[t] = (thread_job){xs, ys, xyz, grid_ref, points_ref, 0};
        assert_int_equal(pthread_create(&th[t], NULL, thread_main, &jobs[t]), 0);
    }
    for (int t = 0; t < 2; t++) {
        assert_int_equal(pthread_join(th[t], NULL), 0);
        assert_true(jobs[t].ok);
    }
}

static void test_edge_inputs(void **state) {
    (void)state;
    gen_fractal none = FRACTALS[0];
    none.octaves = 0.0;
    assert_true(gen_fractal2(&none, 1.5, 2.5) == 0.0f);
    float out[4] = {7, 7, 7, 7};
    double xs[2] = {0.5, 1.5}, ys[2] = {0.5, 1.5};
    gen_fractal_grid2(&FRACTALS[0], xs, 0, ys, 2, out);
    gen_fractal_points3(&FRACTALS[0], xs, 0, out);
    assert_true(out[0] == 7.0f);
    // Non-finite input gives NaN, not a crash (and no undefined conversion).
    assert_true(isnan(gen_noise2(1, NAN, 0.5)));
    assert_true(isnan(gen_noise3(1, 0.5, INFINITY, 0.5)));
    double bad[6] = {NAN, 0.5, 0.5, -INFINITY, 1e308, -1e308};
    gen_fractal_points3(&FRACTALS[0], bad, 2, out);
    assert_true(isnan(out[0]) && isnan(out[1]));
    // Huge finite coordinates still give finite noise.
    assert_true(isfinite(gen_fractal2(&FRACTALS[0], 1e300, -1e300)));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grid2_matches_reference),
        cmocka_unit_test(test_grid2_baseline_matches_reference),
        cmocka_unit_test(test_points3_matches_reference),
        cmocka_unit_test(test_points3_baseline_matches_reference),
        cmocka_unit_test(test_batch_boundaries),
        cmocka_unit_test(test_noise_range),
        cmocka_unit_test(test_continuity),
        cmocka_unit_test(test_fractional_octaves),
        cmocka_unit_test(test_octaves_decorrelated),
        cmocka_unit_test(test_seeds_differ),
        cmocka_unit_test(test_threads_deterministic),
        cmocka_unit_test(test_edge_inputs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
