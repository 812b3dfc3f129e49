// The mask editor's histograms (editor/world/terrain_histogram.h): at level 0 they
// count exactly what world_sample reads at the samples, heights over their own range
// and slopes by central differences; a wide area is read at a coarser level; a
// bounded world clamps the area to its extent, and an area outside it is an error.
#include "editor/world/terrain_histogram.h"

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
        cmocka_unit_test(test_wide_areas_and_edges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
