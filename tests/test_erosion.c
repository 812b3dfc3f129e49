// Erosion kernels: thermal reaches the angle of repose and conserves mass; hydraulic
// conserves mass within the stated tolerance, smooths the surface and is
// deterministic; neither touches a zero-weight cell; both scale exactly with the
// grid; parameters are validated by name; tiny and unweighted grids are no-ops.
#include "editor/tools/erosion.h"

#include <math.h>
#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

// Test hook in erosion.c (not part of the public header).
void erosion_allow_avx2(int allow);
void erosion_allow_threads(int allow);

static uint32_t hash2(uint32_t i, uint32_t j, uint32_t seed) {
    uint32_t x = i * 0x9E3779B1u ^ (j + 0x7F4A7C15u) * 0x85EBCA77u ^ seed * 0xC2B2AE3Du;
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}
// Uniform in [-0.5, 0.5).
static float hash_noise(int i, int j, uint32_t seed) {
    return (float)(hash2((uint32_t)i, (uint32_t)j, seed) >> 8) * (1.0f / 16777216.0f) - 0.5f;
}

typedef struct grid {
    float *h, *w;
    erosion_grid g;
} grid;

static grid grid_new(int width, int height, float spacing) {
    grid t;
    size_t n = (size_t)width * height;
    t.h = calloc(n ? n : 1, sizeof(float));
    t.w = calloc(n ? n : 1, sizeof(float));
    assert_non_null(t.h);
    assert_non_null(t.w);
    t.g = (erosion_grid){t.h, t.w, width, height, spacing, NULL};
    return t;
}
static void grid_free(grid *t) {
    free(t->h), free(t->w);
}
static size_t cells(const grid *t) {
    return (size_t)t->g.width * t->g.height;
}
static float *copy_heights(const grid *t) {
    float *c = malloc(cells(t) * sizeof(float));
    memcpy(c, t->h, cells(t) * sizeof(float));
    return c;
}

// A slope with sine hills and hash noise, in metres (about 0.3 m/m plus +-20 m hills
// and +-amp/2 noise).
static void noisy_slope(grid *t, float amp, uint32_t seed) {
    for (int j = 0; j < t->g.height; j++)
        for (int i = 0; i < t->g.width; i++) {
            float x = (float)i * t->g.spacing, y = (float)j * t->g.spacing;
            t->h[(size_t)j * t->g.width + i] = 0.3f * x +
                                               20.0f * sinf(x * 0.05f) * cosf(y * 0.043f) +
                                               amp * hash_noise(i, j, seed);
        }
}

// Weight 1 everywhere but a zero halo `halo` cells wide.
static void box_weights(grid *t, int halo) {
    for (int j = 0; j < t->g.height; j++)
        for (int i = 0; i < t->g.width; i++)
            t->w[(size_t)j * t->g.width + i] =
                (i >= halo && j >= halo && i < t->g.width - halo && j < t->g.height - halo) ? 1.0f
                                                                                            : 0.0f;
}

// A brush: cone falloff x 0.8 inside a disc, zero outside, plus zero-weight holes, a
// negative and a NaN weight (both must count as 0). Some holes hold -0 m, whose sign
// bit must survive.
static void brush_weights(grid *t, uint32_t seed) {
    const float cx = 0.5f * (float)(t->g.width - 1), cy = 0.5f * (float)(t->g.height - 1);
    const float r = 0.45f * (float)(t->g.width < t->g.height ? t->g.width : t->g.height);
    for (int j = 0; j < t->g.height; j++)
        for (int i = 0; i < t->g.width; i++) {
            float d = hypotf((float)i - cx, (float)j - cy) / r;
            float w = d < 1.0f ? 0.8f * (1.0f - d) : 0.0f;
            if (hash2((uint32_t)i, (uint32_t)j, seed) % 23 == 0) {
                w = 0.0f;
                if (hash2((uint32_t)i, (uint32_t)j, seed + 1) % 3 == 0)
                    t->h[(size_t)j * t->g.width + i] = -0.0f;
            }
            t->w[(size_t)j * t->g.width + i] = w;
        }
    t->w[(size_t)(t->g.height / 2) * t->g.width + t->g.width / 2 + 3] = -0.5f;
    t->w[(size_t)(t->g.height / 2 + 2) * t->g.width + t->g.width / 2] = NAN;
}

static double height_sum(const grid *t) {
    double s = 0.0;
    for (size_t k = 0; k < cells(t); k++)
        s += t->h[k];
    return s;
}

static double abs_change(const grid *t, const float *before) {
    double s = 0.0;
    for (size_t k = 0; k < cells(t); k++)
        s += fabs((double)t->h[k] - before[k]);
    return s;
}

static int weighted(const grid *t, size_t k) {
    return t->w[k] > 0.0f;
}

// Every cell with weight <= 0 (or NaN) kept its bits; returns how many weighted cells changed.
static size_t check_halo_bits(const grid *t, const float *before) {
    size_t changed = 0;
    for (size_t k = 0; k < cells(t); k++) {
        if (weighted(t, k)) {
            changed += memcmp(&t->h[k], &before[k], sizeof(float)) != 0;
        } else if (memcmp(&t->h[k], &before[k], sizeof(float)) != 0) {
            fail_msg("zero-weight cell %zu changed: %.9g -> %.9g", k, before[k], t->h[k]);
        }
    }
    return changed;
}

static void check_finite(const grid *t) {
    for (size_t k = 0; k < cells(t); k++)
        if (!isfinite(t->h[k])) fail_msg("cell %zu is %g", k, t->h[k]);
}

// Sum of |discrete Laplacian| over cells whose 3x3 block is weighted.
static double roughness(const grid *t) {
    const int W = t->g.width;
    double s = 0.0;
    for (int j = 1; j < t->g.height - 1; j++)
        for (int i = 1; i < W - 1; i++) {
            size_t c = (size_t)j * W + i;
            int all = 1;
            for (int dj = -1; dj <= 1; dj++)
                for (int di = -1; di <= 1; di++)
                    all &= weighted(t, c + (size_t)((ptrdiff_t)dj * W + di));
            if (!all) continue;
            s +=
                fabs((double)t->h[c - 1] + t->h[c + 1] + t->h[c - W] + t->h[c + W] - 4.0 * t->h[c]);
        }
    return s;
}

// ---------------------------------------------------------------------------------
// Thermal

// The steepest slope (drop / distance) between two weighted 8-neighbours.
static double steepest_weighted_slope(const grid *t) {
    const int W = t->g.width, H = t->g.height;
    double worst = 0.0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            size_t c = (size_t)j * W + i;
            if (!weighted(t, c)) continue;
            for (int dj = -1; dj <= 1; dj++)
                for (int di = -1; di <= 1; di++) {
                    int ni = i + di, nj = j + dj;
                    if ((di == 0 && dj == 0) || ni < 0 || nj < 0 || ni >= W || nj >= H) continue;
                    size_t n = (size_t)nj * W + ni;
                    if (!weighted(t, n)) continue;
                    double dist = t->g.spacing * ((di && dj) ? sqrt(2.0) : 1.0);
                    double s = ((double)t->h[c] - t->h[n]) / dist;
                    if (s > worst) worst = s;
                }
        }
    return worst;
}

// Spiky terrain: noise, a few tall columns and a deep pit.
static void spiky(grid *t, uint32_t seed) {
    for (int j = 0; j < t->g.height; j++)
        for (int i = 0; i < t->g.width; i++)
            t->h[(size_t)j * t->g.width + i] = 40.0f * hash_noise(i, j, seed) + 100.0f;
    t->h[(size_t)10 * t->g.width + 12] += 300.0f;
    t->h[(size_t)25 * t->g.width + 30] += 150.0f;
    t->h[(size_t)20 * t->g.width + 20] -= 200.0f;
}

static void thermal_reaches_repose(float talus, float rate, int iterations) {
    grid t = grid_new(48, 40, 2.0f);
    spiky(&t, 7);
    box_weights(&t, 1);
    float *before = copy_heights(&t);
    const double sum0 = height_sum(&t), limit = tan(talus * M_PI / 180.0);
    assert_true(steepest_weighted_slope(&t) > 10.0 * limit);

    thermal_params p = {.talus_deg = talus, .iterations = iterations, .rate = rate};
    erosion_thermal(&t.g, &p);
    check_finite(&t);
    const double steepest = steepest_weighted_slope(&t);
    if (steepest > limit + 1e-4)
        fail_msg("talus %g rate %g: steepest slope %.6f exceeds tan(talus) = %.6f + 1e-4", talus,
                 rate, steepest, limit);
    const double rel = fabs(height_sum(&t) - sum0) / fabs(sum0);
    if (rel > 1e-5) fail_msg("mass changed by %.3g relative", rel);
    assert_true(check_halo_bits(&t, before) > cells(&t) / 2);
    free(before);
    grid_free(&t);
}

static void test_thermal_talus_and_mass(void **state) {
    (void)state;
    thermal_reaches_repose(35.0f, 1.0f, 500);
    thermal_reaches_repose(35.0f, 0.5f, 1000);
    thermal_reaches_repose(60.0f, 1.0f, 500);
}

// A pile on a flat plate spreads alike in all directions: mirroring the input mirrors
// the output (an in-place, scan-order pass would skew it).
static void test_thermal_order_independent(void **state) {
    (void)state;
    const int n = 33;
    grid a = grid_new(n, n, 1.0f), b = grid_new(n, n, 1.0f);
    box_weights(&a, 1);
    box_weights(&b, 1);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            float h = (i == 9 && j == 14) ? 60.0f : (i == 20 && j == 20 ? 35.0f : 0.0f);
            a.h[(size_t)j * n + i] = h;
            b.h[(size_t)j * n + (n - 1 - i)] = h;
        }
    thermal_params p = {.talus_deg = 30.0f, .iterations = 5, .rate = 1.0f};
    erosion_thermal(&a.g, &p);
    erosion_thermal(&b.g, &p);
    double worst = 0.0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double d = fabs((double)a.h[(size_t)j * n + i] - b.h[(size_t)j * n + (n - 1 - i)]);
            if (d > worst) worst = d;
        }
    if (worst > 1e-4) fail_msg("mirrored runs differ by %g m", worst);
    assert_true(a.h[(size_t)14 * n + 9] < 60.0f); // it did spread
    grid_free(&a), grid_free(&b);
}

static void test_thermal_never_touches_zero_weight(void **state) {
    (void)state;
    grid t = grid_new(70, 57, 1.5f);
    noisy_slope(&t, 30.0f, 3);
    brush_weights(&t, 11);
    t.h[0] = -0.0f; // a -0 in the halo must stay -0
    t.h[5] = -0.0f;
    float *before = copy_heights(&t);
    thermal_params p = {.talus_deg = 20.0f, .iterations = 50, .rate = 1.0f};
    erosion_thermal(&t.g, &p);
    check_finite(&t);
    assert_true(check_halo_bits(&t, before) > 100);
    free(before);
    grid_free(&t);
}

static void test_thermal_simd_matches_baseline(void **state) {
    (void)state;
    grid a = grid_new(203, 37, 1.0f), b = grid_new(203, 37, 1.0f);
    noisy_slope(&a, 8.0f, 5);
    brush_weights(&a, 2);
    memcpy(b.h, a.h, cells(&a) * sizeof(float));
    memcpy(b.w, a.w, cells(&a) * sizeof(float));
    thermal_params p = {.talus_deg = 25.0f, .iterations = 7, .rate = 0.7f};
    erosion_allow_avx2(0);
    erosion_thermal(&a.g, &p);
    erosion_allow_avx2(1);
    erosion_thermal(&b.g, &p);
    assert_memory_equal(a.h, b.h, cells(&a) * sizeof(float));
    grid_free(&a), grid_free(&b);
}

// ---------------------------------------------------------------------------------
// Hydraulic

static hydraulic_params hydraulic(uint64_t seed, int droplets) {
    hydraulic_params p;
    hydraulic_params_default(&p);
    p.seed = seed;
    p.droplets = droplets;
    return p;
}

// |sum after - sum before| <= 1e-4 x sum |change| (the contract), and within one float
// step of the highest cell plus 1e-9 x sum |change| (what the carry achieves); the
// report agrees with the grid.
static void check_mass(const grid *t, const float *before, double sum0, const hydraulic_report *r) {
    const double net = height_sum(t) - sum0, moved = abs_change(t, before);
    float top = 0.0f;
    for (size_t k = 0; k < cells(t); k++)
        top = fabsf(t->h[k]) > top ? fabsf(t->h[k]) : top;
    const double step = (double)nextafterf(top, INFINITY) - top;
    if (!(fabs(net) <= 1e-4 * moved))
        fail_msg("net change %.6g exceeds 1e-4 x sum |change| = %.6g", net, 1e-4 * moved);
    if (!(fabs(net) <= step + 1e-9 * moved))
        fail_msg("net change %.6g exceeds one float step %.3g + 1e-9 x %.6g", net, step, moved);
    const double books = r->deposited + r->dropped - r->eroded;
    if (!(fabs(books - net) <= step + 1e-9 * moved))
        fail_msg("report says %.6g net, grid says %.6g", books, net);
    assert_true(r->eroded >= 0.0 && r->deposited >= 0.0 && r->dropped >= 0.0);
}

static void test_hydraulic_mass(void **state) {
    (void)state;
    grid t = grid_new(160, 128, 1.0f);
    noisy_slope(&t, 3.0f, 1);
    box_weights(&t, 2);
    float *before = copy_heights(&t);
    const double sum0 = height_sum(&t);
    hydraulic_params p = hydraulic(42, 20000);
    hydraulic_report r;
    erosion_hydraulic(&t.g, &p, &r);
    check_finite(&t);
    assert_int_equal(r.droplets, 20000);
    assert_true(r.eroded > 100.0); // it moved a real amount of material
    assert_true(abs_change(&t, before) > 100.0);
    check_mass(&t, before, sum0, &r);

    // High terrain (coarse float steps) with few, light droplets.
    grid m = grid_new(64, 64, 1.0f);
    noisy_slope(&m, 2.0f, 4);
    for (size_t k = 0; k < cells(&m); k++)
        m.h[k] += 3000.0f;
    box_weights(&m, 2);
    float *m0 = copy_heights(&m);
    const double msum0 = height_sum(&m);
    hydraulic_params light = hydraulic(9, 300);
    light.erosion = 0.01f, light.deposition = 0.01f;
    erosion_hydraulic(&m.g, &light, &r);
    assert_true(r.eroded > 0.0);
    check_mass(&m, m0, msum0, &r);
    free(m0);
    grid_free(&m);

    // The same on a soft brush with holes, and with harsh parameters.
    grid b = grid_new(90, 77, 4.0f);
    noisy_slope(&b, 10.0f, 9);
    brush_weights(&b, 4);
    float *b0 = copy_heights(&b);
    const double bsum0 = height_sum(&b);
    hydraulic_params q = hydraulic(7, 5000);
    q.capacity = 1000.0f, q.gravity = 1000.0f, q.erosion = 1.0f, q.deposition = 1.0f;
    q.evaporation = 0.0f, q.inertia = 1.0f, q.radius_cells = 32.0f, q.max_lifetime = 10000;
    q.min_capacity = 1000.0f, q.initial_speed = 1000.0f, q.initial_water = 1000.0f;
    erosion_hydraulic(&b.g, &q, &r);
    check_finite(&b);
    assert_true(r.eroded > 0.0);
    check_mass(&b, b0, bsum0, &r);
    free(b0), free(before);
    grid_free(&b), grid_free(&t);
}

static void test_hydraulic_never_touches_zero_weight(void **state) {
    (void)state;
    grid t = grid_new(96, 80, 2.0f);
    noisy_slope(&t, 5.0f, 2);
    brush_weights(&t, 3);
    t.h[0] = -0.0f;
    t.h[(size_t)40 * 96 + 3] = -0.0f;
    float *before = copy_heights(&t);
    hydraulic_params p = hydraulic(3, 20000);
    hydraulic_report r;
    erosion_hydraulic(&t.g, &p, &r);
    check_finite(&t);
    assert_true(check_halo_bits(&t, before) > 500);
    free(before);
    grid_free(&t);
}

static void test_hydraulic_deterministic(void **state) {
    (void)state;
    grid a = grid_new(120, 100, 1.0f), b = grid_new(120, 100, 1.0f), c = grid_new(120, 100, 1.0f);
    noisy_slope(&a, 3.0f, 6);
    brush_weights(&a, 5);
    memcpy(b.h, a.h, cells(&a) * sizeof(float));
    memcpy(b.w, a.w, cells(&a) * sizeof(float));
    memcpy(c.h, a.h, cells(&a) * sizeof(float));
    memcpy(c.w, a.w, cells(&a) * sizeof(float));
    hydraulic_params p = hydraulic(0x5EEDull, 8000), q = hydraulic(0x5EEEull, 8000);
    hydraulic_report ra, rb, rc;
    erosion_hydraulic(&a.g, &p, &ra);
    erosion_hydraulic(&b.g, &p, &rb);
    erosion_hydraulic(&c.g, &q, &rc);
    assert_memory_equal(a.h, b.h, cells(&a) * sizeof(float));
    assert_true(ra.eroded == rb.eroded && ra.deposited == rb.deposited &&
                ra.dropped == rb.dropped && ra.droplets == rb.droplets && ra.steps == rb.steps);
    assert_true(ra.steps > ra.droplets && ra.steps <= (int64_t)ra.droplets * p.max_lifetime);
    size_t differ = 0;
    for (size_t k = 0; k < cells(&a); k++)
        differ += a.h[k] != c.h[k];
    if (differ < cells(&a) / 10)
        fail_msg("seeds 0x5EED and 0x5EEE differ in %zu cells only", differ);
    grid_free(&a), grid_free(&b), grid_free(&c);
}

// Droplets run in bands of columns on every core: on one thread, the same bits. Wide
// enough for five bands (three of them at once).
static void test_hydraulic_threads_change_nothing(void **state) {
    (void)state;
    grid a = grid_new(360, 90, 1.0f), b = grid_new(360, 90, 1.0f);
    noisy_slope(&a, 3.0f, 12);
    brush_weights(&a, 5);
    memcpy(b.h, a.h, cells(&a) * sizeof(float));
    memcpy(b.w, a.w, cells(&a) * sizeof(float));
    hydraulic_params p = hydraulic(0xBA5Dull, 30000);
    hydraulic_report ra, rb;
    erosion_hydraulic(&a.g, &p, &ra);
    erosion_allow_threads(0);
    erosion_hydraulic(&b.g, &p, &rb);
    erosion_allow_threads(1);
    assert_memory_equal(a.h, b.h, cells(&a) * sizeof(float));
    assert_true(ra.eroded == rb.eroded && ra.deposited == rb.deposited &&
                ra.dropped == rb.dropped && ra.droplets == rb.droplets && ra.steps == rb.steps);
    assert_true(ra.eroded > 10.0);
    grid_free(&a), grid_free(&b);
}

static void test_hydraulic_smooths(void **state) {
    (void)state;
    grid t = grid_new(128, 128, 1.0f);
    noisy_slope(&t, 3.0f, 8);
    box_weights(&t, 2);
    float hi0 = -INFINITY;
    for (size_t k = 0; k < cells(&t); k++)
        if (weighted(&t, k) && t.h[k] > hi0) hi0 = t.h[k];
    const double rough0 = roughness(&t);
    hydraulic_params p = hydraulic(11, 30000);
    hydraulic_report r;
    erosion_hydraulic(&t.g, &p, &r);
    const double rough1 = roughness(&t);
    float hi1 = -INFINITY;
    for (size_t k = 0; k < cells(&t); k++)
        if (weighted(&t, k) && t.h[k] > hi1) hi1 = t.h[k];
    if (!(rough1 < 0.8 * rough0)) fail_msg("roughness %.1f -> %.1f: not smoother", rough0, rough1);
    assert_true(hi1 < hi0);
    assert_true(r.eroded > 0.0 && r.deposited > 0.0);
    grid_free(&t);
}

// ---------------------------------------------------------------------------------
// Both

// Doubling heights and spacing doubles the result exactly: heights enter only as slopes.
static void test_scale_invariant(void **state) {
    (void)state;
    grid a = grid_new(64, 50, 1.5f), b = grid_new(64, 50, 3.0f);
    noisy_slope(&a, 6.0f, 12);
    brush_weights(&a, 13);
    for (size_t k = 0; k < cells(&a); k++)
        b.h[k] = 2.0f * a.h[k], b.w[k] = a.w[k];
    thermal_params tp = {.talus_deg = 20.0f, .iterations = 20, .rate = 0.9f};
    erosion_thermal(&a.g, &tp);
    erosion_thermal(&b.g, &tp);
    hydraulic_params hp = hydraulic(5, 3000);
    erosion_hydraulic(&a.g, &hp, NULL);
    erosion_hydraulic(&b.g, &hp, NULL);
    for (size_t k = 0; k < cells(&a); k++)
        if (!(b.h[k] == 2.0f * a.h[k])) fail_msg("cell %zu: %.9g != 2 x %.9g", k, b.h[k], a.h[k]);
    grid_free(&a), grid_free(&b);
}

static void expect_error(int rc, const og_error *err, const char *field) {
    assert_int_equal(rc, -1);
    if (!strstr(err->msg, field)) fail_msg("message '%s' does not name '%s'", err->msg, field);
}

static void test_validation(void **state) {
    (void)state;
    og_error err;
    thermal_params tp = {.talus_deg = 30.0f, .iterations = 10, .rate = 0.5f};
    assert_int_equal(erosion_thermal_validate(&tp, &err), 0);
    const float bad_talus[] = {NAN, 0.0f, -5.0f, 89.5f, INFINITY};
    for (size_t k = 0; k < sizeof bad_talus / sizeof bad_talus[0]; k++) {
        thermal_params q = tp;
        q.talus_deg = bad_talus[k];
        expect_error(erosion_thermal_validate(&q, &err), &err, "talus_deg");
    }
    const float bad_rate[] = {NAN, 0.0f, -0.1f, 1.01f};
    for (size_t k = 0; k < sizeof bad_rate / sizeof bad_rate[0]; k++) {
        thermal_params q = tp;
        q.rate = bad_rate[k];
        expect_error(erosion_thermal_validate(&q, &err), &err, "rate");
    }
    thermal_params q = tp;
    q.iterations = -1;
    expect_error(erosion_thermal_validate(&q, &err), &err, "iterations");
    expect_error(erosion_thermal_validate(NULL, &err), &err, "thermal");

    hydraulic_params hp;
    hydraulic_params_default(&hp);
    assert_int_equal(erosion_hydraulic_validate(&hp, &err), 0);
    static const struct {
        const char *field;
        size_t offset;
        float bad[3];
    } F[] = {
        {"inertia", offsetof(hydraulic_params, inertia), {NAN, -0.1f, 1.5f}},
        {"capacity", offsetof(hydraulic_params, capacity), {NAN, -1.0f, INFINITY}},
        {"min_capacity", offsetof(hydraulic_params, min_capacity), {NAN, -0.01f, 1e6f}},
        {"erosion", offsetof(hydraulic_params, erosion), {NAN, -0.3f, 2.0f}},
        {"deposition", offsetof(hydraulic_params, deposition), {NAN, -0.3f, 1.1f}},
        {"evaporation", offsetof(hydraulic_params, evaporation), {NAN, -0.01f, 1.5f}},
        {"gravity", offsetof(hydraulic_params, gravity), {NAN, -4.0f, INFINITY}},
        {"radius_cells", offsetof(hydraulic_params, radius_cells), {NAN, 0.0f, 33.0f}},
        {"initial_water", offsetof(hydraulic_params, initial_water), {NAN, 0.0f, -1.0f}},
        {"initial_speed", offsetof(hydraulic_params, initial_speed), {NAN, -1.0f, 1e9f}},
    };
    for (size_t f = 0; f < sizeof F / sizeof F[0]; f++)
        for (int k = 0; k < 3; k++) {
            hydraulic_params q2 = hp;
            memcpy((char *)&q2 + F[f].offset, &F[f].bad[k], sizeof(float));
            expect_error(erosion_hydraulic_validate(&q2, &err), &err, F[f].field);
        }
    hydraulic_params q2 = hp;
    q2.droplets = -1;
    expect_error(erosion_hydraulic_validate(&q2, &err), &err, "droplets");
    q2 = hp;
    q2.max_lifetime = 0;
    expect_error(erosion_hydraulic_validate(&q2, &err), &err, "max_lifetime");

    // Invalid parameters or grids leave the grid alone.
    grid t = grid_new(20, 20, 1.0f);
    noisy_slope(&t, 5.0f, 1);
    box_weights(&t, 0);
    float *before = copy_heights(&t);
    q2 = hp;
    q2.erosion = NAN;
    hydraulic_report r = {.eroded = 99.0};
    erosion_hydraulic(&t.g, &q2, &r);
    assert_true(r.eroded == 0.0 && r.droplets == 0);
    q = tp;
    q.rate = NAN;
    erosion_thermal(&t.g, &q);
    assert_memory_equal(t.h, before, cells(&t) * sizeof(float));

    erosion_grid g = t.g;
    assert_int_equal(erosion_grid_validate(&g, &err), 0);
    g.spacing = 0.0f;
    expect_error(erosion_grid_validate(&g, &err), &err, "spacing");
    erosion_thermal(&g, &tp);
    erosion_hydraulic(&g, &hp, NULL);
    g.spacing = NAN;
    expect_error(erosion_grid_validate(&g, &err), &err, "spacing");
    g.spacing = 5e-5f;
    expect_error(erosion_grid_validate(&g, &err), &err, "spacing");
    g.spacing = 2e7f;
    expect_error(erosion_grid_validate(&g, &err), &err, "spacing");
    g = t.g;
    g.width = 0;
    expect_error(erosion_grid_validate(&g, &err), &err, "width");
    g = t.g;
    g.weight = NULL;
    expect_error(erosion_grid_validate(&g, &err), &err, "weight");
    erosion_thermal(&g, &tp);
    erosion_hydraulic(&g, &hp, NULL);
    g = t.g;
    g.heights = NULL;
    expect_error(erosion_grid_validate(&g, &err), &err, "heights");
    g = t.g;
    g.width = 1 << 16, g.height = 1 << 16;
    expect_error(erosion_grid_validate(&g, &err), &err, "width x height");
    assert_memory_equal(t.h, before, cells(&t) * sizeof(float));
    free(before);
    grid_free(&t);
}

static void test_tiny_and_unweighted(void **state) {
    (void)state;
    thermal_params tp = {.talus_deg = 10.0f, .iterations = 20, .rate = 1.0f};
    hydraulic_params hp = hydraulic(1, 500);
    hydraulic_report r;
    const int sizes[][2] = {{1, 1}, {1, 7}, {7, 1}, {2, 2}, {3, 2}};
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        grid t = grid_new(sizes[s][0], sizes[s][1], 1.0f);
        for (size_t k = 0; k < cells(&t); k++)
            t.h[k] = (float)(k * 37 % 11) * 5.0f, t.w[k] = 1.0f;
        float *before = copy_heights(&t);
        const double sum0 = height_sum(&t);
        erosion_thermal(&t.g, &tp);
        erosion_hydraulic(&t.g, &hp, &r);
        check_finite(&t);
        if (cells(&t) == 1) {
            assert_memory_equal(t.h, before, sizeof(float));
            assert_int_equal(r.droplets, 0);
        }
        assert_true(fabs(height_sum(&t) - sum0) <= 1e-4 * (abs_change(&t, before) + 1e-30));
        free(before);
        grid_free(&t);
    }

    grid t = grid_new(50, 40, 1.0f);
    noisy_slope(&t, 10.0f, 3);
    float *before = copy_heights(&t);
    erosion_thermal(&t.g, &tp);
    erosion_hydraulic(&t.g, &hp, &r); // weights all 0
    assert_int_equal(r.droplets, 0);
    assert_true(r.eroded == 0.0 && r.deposited == 0.0 && r.dropped == 0.0 && r.steps == 0);
    assert_memory_equal(t.h, before, cells(&t) * sizeof(float));
    // One weighted cell: no bilinear cell has four weighted corners, so no droplets;
    // thermal has no weighted pair to move material between.
    t.w[(size_t)20 * 50 + 25] = 1.0f;
    erosion_thermal(&t.g, &tp);
    erosion_hydraulic(&t.g, &hp, &r);
    assert_int_equal(r.droplets, 0);
    assert_memory_equal(t.h, before, cells(&t) * sizeof(float));
    // Zero droplets and zero iterations do nothing.
    box_weights(&t, 0);
    hp.droplets = 0;
    tp.iterations = 0;
    erosion_thermal(&t.g, &tp);
    erosion_hydraulic(&t.g, &hp, &r);
    assert_memory_equal(t.h, before, cells(&t) * sizeof(float));
    free(before);
    grid_free(&t);
}

// The most extreme inputs the header allows stay finite: heights up to 1e9 m at the
// smallest and largest spacing, with the harshest parameters.
static void test_extremes_stay_finite(void **state) {
    (void)state;
    const float spacings[] = {1e-4f, 1e7f};
    for (int s = 0; s < 2; s++) {
        grid t = grid_new(40, 36, spacings[s]);
        for (int j = 0; j < 36; j++)
            for (int i = 0; i < 40; i++)
                t.h[j * 40 + i] = 2e9f * hash_noise(i, j, 77);
        box_weights(&t, 1);
        thermal_params steep = {.talus_deg = 89.0f, .iterations = 30, .rate = 1.0f};
        thermal_params flat = {.talus_deg = 1e-6f, .iterations = 30, .rate = 1.0f};
        erosion_thermal(&t.g, &steep);
        check_finite(&t);
        hydraulic_params q = hydraulic(3, 60);
        q.capacity = 1000.0f, q.gravity = 1000.0f, q.erosion = 1.0f, q.deposition = 0.0f;
        q.evaporation = 0.0f, q.inertia = 0.0f, q.radius_cells = 32.0f, q.max_lifetime = 2000;
        q.min_capacity = 1000.0f, q.initial_speed = 1000.0f, q.initial_water = 1000.0f;
        erosion_hydraulic(&t.g, &q, NULL);
        check_finite(&t);
        erosion_thermal(&t.g, &flat);
        check_finite(&t);
        grid_free(&t);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_thermal_talus_and_mass),
        cmocka_unit_test(test_thermal_order_independent),
        cmocka_unit_test(test_thermal_never_touches_zero_weight),
        cmocka_unit_test(test_thermal_simd_matches_baseline),
        cmocka_unit_test(test_hydraulic_mass),
        cmocka_unit_test(test_hydraulic_never_touches_zero_weight),
        cmocka_unit_test(test_hydraulic_deterministic),
        cmocka_unit_test(test_hydraulic_threads_change_nothing),
        cmocka_unit_test(test_hydraulic_smooths),
        cmocka_unit_test(test_scale_invariant),
        cmocka_unit_test(test_extremes_stay_finite),
        cmocka_unit_test(test_validation),
        cmocka_unit_test(test_tiny_and_unweighted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
