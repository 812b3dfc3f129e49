// The "craters" generator (the moon preset's): impact craters over fBm. The crater field
// alone (a flat generator under it) must hold bowls with raised rims at several sizes,
// be the same on both sides of a face edge (one field over the sphere), be band limited
// (a coarse level holds no craters narrower than its samples), and leave seed 004's
// generators as they were (their tiles do not change with it).
#include "editor/gen/gen.h"
#include "editor/gen/gen_craters.h"
#include "editor/params/planet_presets.h"
#include "editor/params/world_grid.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

static world_params moon(void) {
    world_params p;
    og_error err;
    world_params_default(&p, WORLD_PLANET);
    assert_int_equal(planet_preset_apply(&p, "moon", &err), 0);
    assert_int_equal(p.generator, GEN_CRATERS);
    return p;
}

// The craters alone on a tile: heights over zero.
static void field(const world_params *p, tile_key key, float *out) {
    memset(out, 0, sizeof(float) * TILE_SAMPLES);
    gen_craters_add(p, key, out);
}

static void test_bowls_and_rims(void **state) {
    (void)state;
    const world_params p = moon();
    static float h[TILE_SAMPLES];
    // A level-4 tile (1.6 km samples, 410 km across): craters from kilometres up.
    field(&p, (tile_key){TILE_LAYER_COARSE, 4, 4, 10, 10}, h);
    int below = 0, above = 0;
    float lowest = 0;
    for (size_t k = 0; k < TILE_SAMPLES; k++) {
        below += h[k]<-1.0f, above += h[k]> 1.0f;
        lowest = fminf(lowest, h[k]);
    }
    printf("level 4: %.1f%% in bowls, %.1f%% on rims, deepest %.0f m\n",
           100.0 * below / TILE_SAMPLES, 100.0 * above / TILE_SAMPLES, lowest);
    assert_true(below > TILE_SAMPLES / 20 && below < TILE_SAMPLES * 3 / 4);
    assert_true(above > TILE_SAMPLES / 50);
    assert_true(lowest < -300.0f && lowest >= -p.max_height);
    // Around the deepest sample the ground rises on every side to a rim above the
    // surroundings' zero before falling back.
    size_t at = 0;
    for (size_t k = 0; k < TILE_SAMPLES; k++)
        if (h[k] < h[at]) at = k;
    const int ci = (int)(at % TILE_SIZE), cj = (int)(at / TILE_SIZE);
    static const int dirs[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    int rims = 0;
    for (int d = 0; d < 4; d++) {
        float peak = -INFINITY;
        for (int r = 1; r < 60; r++) {
            const int i = ci + dirs[d][0] * r, j = cj + dirs[d][1] * r;
            if (i < 0 || j < 0 || i >= TILE_SIZE || j >= TILE_SIZE) break;
            peak = fmaxf(peak, h[j * TILE_SIZE + i]);
        }
        rims += peak > 0.0f;
    }
    assert_true(rims >= 3);
}

static void test_one_field_across_edges(void **state) {
    (void)state;
    const world_params p = moon();
    // The samples on either side of face 4's +s edge and face 0's -s edge at the same
    // height t lie side by side on the sphere: their craters' heights differ no more
    // than neighbouring samples on one face do.
    const int level = 3;
    const int64_t m = world_grid_face_samples(&p) >> level;
    const int64_t last = m - 1;
    static float a[TILE_SAMPLES], b[TILE_SAMPLES];
    const int32_t ty = (int32_t)((m / 2) / TILE_SIZE);
    field(&p, (tile_key){TILE_LAYER_COARSE, 4, level, (int32_t)(last / TILE_SIZE), ty}, a);
    field(&p, (tile_key){TILE_LAYER_COARSE, 0, level, 0, ty}, b);
    double across = 0, within = 0;
    for (int j = 0; j < TILE_SIZE; j++) {
        const float *ra = a + (size_t)j * TILE_SIZE, *rb = b + (size_t)j * TILE_SIZE;
        const int ia = (int)(last % TILE_SIZE);
        across += fabs(ra[ia] - rb[0]);
        within += fabs(ra[ia] - ra[ia - 1]) + fabs(rb[1] - rb[0]);
    }
    printf("across the edge %.1f m, beside it %.1f m (mean steps)\n", across / TILE_SIZE,
           within / (2 * TILE_SIZE));
    assert_true(across / TILE_SIZE <= 2.0 * within / (2 * TILE_SIZE) + 1.0);
}

static void test_band_limited(void **state) {
    (void)state;
    const world_params p = moon();
    static float h[TILE_SAMPLES];
    // At the coarsest levels a sample is wider than any crater scale kept: nothing.
    field(&p, (tile_key){TILE_LAYER_COARSE, 2, 12, 0, 0}, h);
    for (size_t k = 0; k < TILE_SAMPLES; k++)
        assert_true(h[k] == 0.0f);
}

static void test_other_generators_unchanged(void **state) {
    (void)state;
    world_params p = moon();
    static float with[TILE_SAMPLES], without[TILE_SAMPLES];
    const tile_key key = {TILE_LAYER_COARSE, 1, 5, 3, 4};
    p.generator = GEN_FBM_ADVANCED;
    assert_int_equal(gen_tile(&p, key, without), 0);
    p.generator = GEN_CRATERS;
    assert_int_equal(gen_tile(&p, key, with), 0);
    static float craters[TILE_SAMPLES];
    field(&p, key, craters);
    int differ = 0;
    for (size_t k = 0; k < TILE_SAMPLES; k++) {
        const float expect =
            fminf(fmaxf(without[k] + craters[k], (float)-p.max_height), (float)p.max_height);
        assert_true(fabsf(with[k] - expect) <= 1e-3f * (float)p.max_height);
        differ += with[k] != without[k];
    }
    assert_true(differ > 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bowls_and_rims),
        cmocka_unit_test(test_one_field_across_edges),
        cmocka_unit_test(test_band_limited),
        cmocka_unit_test(test_other_generators_unchanged),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
