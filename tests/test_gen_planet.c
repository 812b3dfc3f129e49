// The planet generator (editor/gen/gen_planet.c) on the Earth-like preset reads as a
// planet: a sea over most of the surface and continents, mountain ranges that cover a
// small share of the land and reach up toward max_height, and ridges and valleys
// hundreds of metres deep within 10 km on land, where seed 004's fBm (the preset's
// old generator) stays within tens of metres.
#include "editor/gen/gen.h"
#include "editor/params/planet_presets.h"
#include "editor/params/world_grid.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

static world_params earth(void) {
    world_params p;
    og_error err;
    world_params_default(&p, WORLD_PLANET);
    assert_int_equal(planet_preset_apply(&p, "earth", &err), 0);
    assert_int_equal(p.generator, GEN_PLANET);
    return p;
}

static float *tile(const world_params *p, int face, int level, int tx, int ty) {
    float *t = malloc(sizeof(float) * TILE_SAMPLES);
    assert_int_equal(gen_tile(p, (tile_key){TILE_LAYER_COARSE, face, level, tx, ty}, t), 0);
    return t;
}

// The level whose single tile covers a whole face.
static int whole_face_level(const world_params *p) {
    int level = 0;
    while ((world_grid_face_samples(p) >> level) > TILE_SIZE)
        level++;
    return level;
}

static void test_sea_continents_and_ranges(void **state) {
    (void)state;
    const world_params p = earth();
    const int level = whole_face_level(&p);
    const double sea = world_params_ocean_height(&p);
    long n = 0, land = 0, high = 0;
    double top = -INFINITY;
    for (int f = 0; f < 6; f++) {
        float *t = tile(&p, f, level, 0, 0);
        for (size_t k = 0; k < TILE_SAMPLES; k++) {
            n++;
            if (t[k] > sea) land++;
            if (t[k] > sea + 0.4 * p.max_height) high++;
            top = fmax(top, t[k]);
        }
        free(t);
    }
    const double land_share = (double)land / n, high_share = (double)high / land;
    print_message("land %.1f%%, of it above 40%% of the relief %.1f%%, highest %.0f m\n",
                  100 * land_share, 100 * high_share, top);
    assert_true(land_share > 0.2 && land_share < 0.6);
    assert_true(high_share > 0.01 && high_share < 0.3); // ranges, not a plateau
    assert_true(top > 0.7 * p.max_height);
}

// The mean over land windows of 10 km of (highest - lowest): ridges and valleys.
static double relief_10km(const world_params *p) {
    const int window = (int)(10000.0 / p->spacing); // level-0 samples
    double sum = 0;
    int windows = 0;
    const double sea = world_params_ocean_height(p);
    for (int f = 0; f < 6; f++)
        for (int k = 0; k < 6; k++) {
            // Tiles spread over the face (level 0: 256 samples of 100 m).
            const int tiles = (int)(world_grid_face_samples(p) / TILE_SIZE);
            float *t = tile(p, f, 0, (k * 37 + f * 11) % tiles, (k * 53 + f * 7) % tiles);
            for (int wy = 0; wy + window <= TILE_SIZE; wy += window)
                for (int wx = 0; wx + window <= TILE_SIZE; wx += window) {
                    double lo = INFINITY, hi = -INFINITY;
                    for (int j = wy; j < wy + window; j++)
                        for (int i = wx; i < wx + window; i++)
                            lo = fmin(lo, t[j * TILE_SIZE + i]),
                            hi = fmax(hi, t[j * TILE_SIZE + i]);
                    if (lo <= sea) continue;
                    sum += hi - lo;
                    windows++;
                }
            free(t);
        }
    assert_true(windows > 20);
    return sum / windows;
}

static void test_ridges_and_valleys_within_10km(void **state) {
    (void)state;
    world_params p = earth();
    const double planet = relief_10km(&p);
    p.generator = GEN_FBM_ADVANCED; // the preset's generator before
    const double fbm = relief_10km(&p);
    print_message("relief within 10 km on land: %.0f m (fBm: %.0f m)\n", planet, fbm);
    assert_true(planet > 150.0);
    assert_true(planet > 2.0 * fbm);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sea_continents_and_ranges),
        cmocka_unit_test(test_ridges_and_valleys_within_10km),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
