// The mask editor's histograms (editor/world/terrain_histogram.h): at level 0 they
// count exactly what world_sample reads at the samples, heights over their own range
// and slopes by central differences; a wide area is read at a coarser level; a
// bounded world clamps the area to its extent, and an area outside it is an error.
#include "editor/world/terrain_histogram.h"

#include "editor/layers/layer_mask.h"
#include "editor/params/world_grid.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static void silent(void *user, const char *message) {
    (void)user, (void)message;
}

static world *open_world(void) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.generator = GEN_FBM;
    p.seed = 77;
    p.octaves = 5;
    p.size = 512;
    p.spacing = 1.0;
    p.feature_size = 128.0;
    p.max_height = 200;
    world_settings s = {.cache_budget_bytes = (size_t)128 << 20, .workers = 2, .warn = silent};
    og_error err;
    world *w = world_create(&p, &s, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    return w;
}

static void test_level_zero_counts_every_sample(void **state) {
    (void)state;
    world *w = open_world();
    terrain_histogram h;
    og_error err;
    assert_int_equal(terrain_histogram_compute(w, 0, 200, 300, 40, &h, &err), 0);
    assert_true(h.spacing == 1.0 && h.x0 == 160 && h.x1 == 240 && h.z0 == 260 && h.z1 == 340);
    enum { N = 81 };
    static double v[N][N];
    double lo = INFINITY, hi = -INFINITY;
    for (int z = 0; z < N; z++)
        for (int x = 0; x < N; x++) {
            assert_int_equal(world_sample(w, 0, 160 + x, 260 + z, &v[z][x], &err), 0);
            lo = fmin(lo, v[z][x]), hi = fmax(hi, v[z][x]);
        }
    assert_true(h.samples == N * N && h.height_min == lo && h.height_max == hi);
    const int bins = TERRAIN_HISTOGRAM_BINS;
    double height[TERRAIN_HISTOGRAM_BINS] = {0}, slope[TERRAIN_HISTOGRAM_BINS] = {0};
    for (int z = 0; z < N; z++)
        for (int x = 0; x < N; x++) {
            int b = (int)(((float)v[z][x] - h.height_min) / (hi - lo) * bins);
            height[b < bins ? b : bins - 1] += 1.0 / (N * N);
            if (x == 0 || z == 0 || x == N - 1 || z == N - 1) continue;
            double dx = ((float)v[z][x + 1] - (float)v[z][x - 1]) / 2;
            double dz = ((float)v[z + 1][x] - (float)v[z - 1][x]) / 2;
            int s = (int)(atan(sqrt(dx * dx + dz * dz)) * 180 / M_PI / 90 * bins);
            slope[s < bins ? s : bins - 1] += 1.0 / ((N - 2) * (N - 2));
        }
    double sum = 0;
    for (int b = 0; b < bins; b++) {
        if (fabs(height[b] - h.height[b]) > 1e-6 || fabs(slope[b] - h.slope[b]) > 1e-6)
            fail_msg("bin %d: height %g (want %g), slope %g (want %g)", b, h.height[b], height[b],
                     h.slope[b], slope[b]);
        sum += h.slope[b];
    }
    assert_true(fabs(sum - 1) < 1e-5);
    world_close(w);
}

// Curvature and flow: the mask's own terms (layer_mask_curvature over the inner samples,
// layer_mask_flow_area over the area) binned; the flow field is those areas.
static void test_curvature_and_flow(void **state) {
    (void)state;
    world *w = open_world();
    terrain_histogram h;
    terrain_flow_field f = {0};
    og_error err;
    assert_int_equal(terrain_histogram_compute_flow(w, 0, 200, 300, 40, &h, &f, &err), 0);
    enum { N = 81 };
    static float v[N * N], k[(N - 2) * (N - 2)], area[N * N];
    for (int z = 0; z < N; z++)
        for (int x = 0; x < N; x++) {
            double d;
            assert_int_equal(world_sample(w, 0, 160 + x, 260 + z, &d, &err), 0);
            v[z * N + x] = (float)d;
        }
    assert_true(f.w == N && f.h == N && f.x0 == 160 && f.z0 == 260 && f.spacing == 1.0);
    layer_mask_curvature(v, N - 2, N - 2, 1, 1.0, k);
    assert_int_equal(layer_mask_flow_area(v, N, N, 0, 1.0, area), 0);
    assert_memory_equal(area, f.area, sizeof area);
    const int bins = TERRAIN_HISTOGRAM_BINS;
    double kb[TERRAIN_HISTOGRAM_BINS] = {0}, fb[TERRAIN_HISTOGRAM_BINS] = {0}, most = 0;
    int below = 0;
    for (int i = 0; i < (N - 2) * (N - 2); i++) {
        double at = (k[i] - h.curvature_min) / (h.curvature_max - h.curvature_min) * bins;
        kb[at < 0 ? 0 : at >= bins ? bins - 1 : (int)at] += 1.0 / ((N - 2) * (N - 2));
        below += k[i] < h.curvature_min;
    }
    for (int i = 0; i < N * N; i++)
        most = fmax(most, area[i]);
    assert_true(h.flow_min == 1.0 && h.flow_max == most && most > 100);
    for (int i = 0; i < N * N; i++) {
        double at = (double)(float)log10(fmax(area[i], 1.0)) / log10(most) * bins;
        fb[at >= bins ? bins - 1 : (int)at] += 1.0 / (N * N);
    }
    for (int b = 0; b < bins; b++)
        if (fabs(kb[b] - h.curvature[b]) > 1e-5 || fabs(fb[b] - h.flow[b]) > 1e-5)
            fail_msg("bin %d: curvature %g (want %g), flow %g (want %g)", b, h.curvature[b], kb[b],
                     h.flow[b], fb[b]);
    // The curvatures' range leaves 1% out at each end.
    assert_true(below == (N - 2) * (N - 2) / 100 || below == (N - 2) * (N - 2) / 100 - 1);
    terrain_flow_field_free(&f);
    assert_null(f.area);
    world_close(w);
}

// On a planet: face-local metres of the face asked for, clamped to the face.
static void test_planet_face(void **state) {
    (void)state;
    world_params p;
    world_params_default(&p, WORLD_PLANET);
    world_settings s = {.cache_budget_bytes = (size_t)128 << 20, .workers = 2, .warn = silent};
    og_error err;
    world *w = world_create(&p, &s, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    const double sp = world_grid_sample_metres(world_get_params(w));
    const int64_t n = world_grid_face_samples(world_get_params(w));
    terrain_histogram h;
    const double c = (double)(n / 2) * sp;
    assert_int_equal(terrain_histogram_compute(w, 3, c, c, 20 * sp, &h, &err), 0);
    assert_true(h.spacing == sp && h.samples == 41 * 41);
    double lo = INFINITY, hi = -INFINITY;
    for (int z = 0; z <= 40; z++)
        for (int x = 0; x <= 40; x++) {
            double v;
            assert_int_equal(world_sample(w, 3, h.x0 + x * sp, h.z0 + z * sp, &v, &err), 0);
            lo = fmin(lo, (float)v), hi = fmax(hi, (float)v);
        }
    assert_true(h.height_min == lo && (h.height_max == hi || hi == lo));
    // By the face's corner: clamped to its samples.
    assert_int_equal(terrain_histogram_compute(w, 3, 0, (double)(n - 1) * sp, 20 * sp, &h, &err),
                     0);
    assert_true(h.x0 == 0 && h.z1 == (double)(n - 1) * sp && h.samples == 21 * 21);
    world_close(w);
}

static void test_wide_areas_and_edges(void **state) {
    (void)state;
    world *w = open_world();
    terrain_histogram h;
    og_error err;
    // 1,000 m across is read at level 2 (4 m apart), within the world's 511 m.
    assert_int_equal(terrain_histogram_compute(w, 0, 256, 256, 500, &h, &err), 0);
    assert_true(h.spacing == 4.0 && h.x0 == 0 && h.z0 == 0 && h.x1 == 508 && h.z1 == 508);
    assert_int_equal(h.samples, 128 * 128);
    // Near a corner the area is clamped to the world.
    assert_int_equal(terrain_histogram_compute(w, 0, 5, 5, 40, &h, &err), 0);
    assert_true(h.x0 == 0 && h.z0 == 0 && h.x1 == 45 && h.spacing == 1.0);
    // Outside it: an error saying so; nonsense sizes too.
    assert_int_equal(terrain_histogram_compute(w, 0, -900, 100, 40, &h, &err), -1);
    assert_non_null(strstr(err.msg, "outside the world"));
    assert_int_equal(terrain_histogram_compute(w, 0, 100, 100, NAN, &h, &err), -1);
    world_close(w);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_level_zero_counts_every_sample),
        cmocka_unit_test(test_curvature_and_flow),
        cmocka_unit_test(test_planet_face),
        cmocka_unit_test(test_wide_areas_and_edges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
