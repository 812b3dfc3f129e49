// Generators: determinism across thread counts and request orders, seamless tile
// borders, fractional octaves, and mip levels close to the filtered finer level.
#include "editor/gen/gen.h"
#include "editor/world/world.h"
#include "editor/params/world_grid.h"

#include <math.h>
#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

static const gen_kind all_generators[] = {
    GEN_FBM, GEN_FBM_ADVANCED, GEN_RIDGED, GEN_DIAMOND_SQUARE, GEN_FAULTS, GEN_PLANET};
#define GENERATOR_COUNT (sizeof all_generators / sizeof all_generators[0])

static world_params flat_params(gen_kind g) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.generator = g;
    p.seed = 4242;
    p.spacing = 8.0;
    p.fault_count = 24;
    return p;
}

static float *tile(const world_params *p, int face, int level, int tx, int ty) {
    float *t = malloc(sizeof(float) * TILE_SAMPLES);
    tile_key k = {TILE_LAYER_COARSE, face, level, tx, ty};
    assert_int_equal(gen_tile(p, k, t), 0);
    return t;
}

static void silent(void *user, const char *m) {
    (void)user, (void)m;
}

static uint64_t area_hash(const world_params *p, int workers, int reverse_prefetch) {
    world_settings s = {.cache_budget_bytes = 64u << 20, .workers = workers, .warn = silent};
    og_error err;
    world *w = world_create(p, &s, &err);
    assert_non_null(w);
    if (reverse_prefetch) {
        // Ask for the tiles in the opposite order first, without waiting.
        for (int ty = 2; ty >= -2; ty--)
            for (int tx = 2; tx >= -2; tx--) {
                tile_view v;
                tile_cache_request(world_cache(w), (tile_key){0, 0, 0, tx, ty}, &v);
                tile_cache_release(world_cache(w), &v);
            }
    }
    uint64_t digest, count;
    double lo = -2.0 * TILE_SIZE * p->spacing, hi = 3.0 * TILE_SIZE * p->spacing - p->spacing;
    assert_int_equal(world_hash(w, 0, lo, lo, hi, hi, &digest, &count, &err), 0);
    assert_int_equal(count, (uint64_t)(5 * TILE_SIZE) * (5 * TILE_SIZE));
    world_close(w);
    return digest;
}

static void test_determinism_threads_and_order(void **state) {
    (void)state;
    for (size_t g = 0; g < GENERATOR_COUNT; g++) {
        world_params p = flat_params(all_generators[g]);
        uint64_t one = area_hash(&p, 1, 0);
        uint64_t two = area_hash(&p, 2, 0);
        uint64_t four_rev = area_hash(&p, 4, 1);
        assert_true(one == two);
        assert_true(one == four_rev);
        p.seed++;
        assert_true(area_hash(&p, 2, 0) != one); // the seed matters
    }
}

// The same tile generated twice, and in the middle of other work, is bit-identical.
static void test_repeatable(void **state) {
    (void)state;
    for (size_t g = 0; g < GENERATOR_COUNT; g++) {
        world_params p = flat_params(all_generators[g]);
        float *a = tile(&p, 0, 0, -3, 7);
        float *other = tile(&p, 0, 2, 100, -100);
        float *b = tile(&p, 0, 0, -3, 7);
        assert_memory_equal(a, b, sizeof(float) * TILE_SAMPLES);
        free(a), free(b), free(other);
    }
}

// Largest step between neighbouring samples across the border of two adjacent tiles
// must look like the steps inside them: no seam.
static void check_border(const float *left, const float *right, int horizontal) {
    double border = 0, inside = 0;
    for (int k = 0; k < TILE_SIZE; k++) {
        double a, b;
        if (horizontal) {
            a = left[k * TILE_SIZE + TILE_SIZE - 1], b = right[k * TILE_SIZE];
            for (int i = 1; i < TILE_SIZE; i++) {
                double d = fabs(left[k * TILE_SIZE + i] - left[k * TILE_SIZE + i - 1]);
                inside = d > inside ? d : inside;
            }
        } else {
            a = left[(TILE_SIZE - 1) * TILE_SIZE + k], b = right[k];
            for (int j = 1; j < TILE_SIZE; j++) {
                double d = fabs(left[j * TILE_SIZE + k] - left[(j - 1) * TILE_SIZE + k]);
                inside = d > inside ? d : inside;
            }
        }
        border = fabs(a - b) > border ? fabs(a - b) : border;
    }
    assert_true(inside > 0.0);
    if (!(border <= inside * 1.05 + 1e-6)) print_message("border %g inside %g\n", border, inside);
    assert_true(border <= inside * 1.05 + 1e-6);
}

static void test_seamless(void **state) {
    (void)state;
    for (size_t g = 0; g < GENERATOR_COUNT; g++) {
        // Diamond-square has its creases along coarse grid lines (tile borders are
        // such lines), so it is checked exactly against one big array below instead.
        if (all_generators[g] == GEN_DIAMOND_SQUARE) continue;
        world_params p = flat_params(all_generators[g]);
        int coords[][2] = {{0, 0}, {-1, -1}, {12345, -6789}, {-2147483647, 2147483646}};
        for (size_t c = 0; c < 4; c++) {
            int tx = coords[c][0], ty = coords[c][1];
            for (int level = 0; level <= 3; level += 3) {
                float *a = tile(&p, 0, level, tx, ty);
                float *right = tile(&p, 0, level, tx + 1, ty);
                float *below = tile(&p, 0, level, tx, ty + 1);
                check_border(a, right, 1);
                check_border(a, below, 0);
                free(a), free(right), free(below);
            }
        }
    }
}

// Planet faces: tiles meet without steps inside a face, and face edges meet too.
static void test_planet_seamless(void **state) {
    (void)state;
    world_params p;
    world_params_default(&p, WORLD_PLANET);
    p.radius = 200000.0;
    p.spacing = 200.0;
    p.max_height = 3000.0;
    const gen_kind fractal[] = {GEN_FBM, GEN_FBM_ADVANCED, GEN_RIDGED, GEN_PLANET};
    for (size_t g = 0; g < sizeof fractal / sizeof fractal[0]; g++) {
        p.generator = fractal[g];
        float *a = tile(&p, 0, 0, 0, 0), *b = tile(&p, 0, 0, 1, 0);
        check_border(a, b, 1);
        free(a), free(b);
    }
    // Samples either side of the edge between face 0 (+X) and face 4 (+Z) are
    // neighbours on the sphere: their heights differ like neighbours inside a face.
    p.generator = GEN_FBM;
    int64_t n = world_grid_face_samples(&p);
    int last = (int)((n - 1) / TILE_SIZE);
    int li = (int)((n - 1) % TILE_SIZE);
    // Face 0's s = -1 column borders face 4's s = +1 column (a = tan: +Z side).
    float *f0 = tile(&p, 0, 0, 0, 0), *f4 = tile(&p, 4, 0, last, 0);
    double border = 0, inside = 0;
    for (int j = 0; j < TILE_SIZE; j++) {
        border = fmax(border, fabs(f0[j * TILE_SIZE] - f4[j * TILE_SIZE + li]));
        inside = fmax(inside, fabs(f0[j * TILE_SIZE] - f0[j * TILE_SIZE + 1]));
    }
    assert_true(border <= inside * 2.0 + 1e-3);
    free(f0), free(f4);
}

// The planet's face mapping and its inverse agree everywhere, including the edges and
// corners where faces meet (every direction belongs to one face).
static void test_face_direction_inverse(void **state) {
    (void)state;
    for (int face = 0; face < 6; face++)
        for (int i = 0; i <= 20; i++)
            for (int j = 0; j <= 20; j++) {
                double s = -1.0 + 0.1 * i, t = -1.0 + 0.1 * j, d[3], back[3], s2, t2;
                int f2;
                world_grid_face_direction(face, s, t, d);
                world_grid_direction_face(d, &f2, &s2, &t2);
                assert_true(s2 >= -1.0 - 1e-12 && s2 <= 1.0 + 1e-12);
                assert_true(t2 >= -1.0 - 1e-12 && t2 <= 1.0 + 1e-12);
                world_grid_face_direction(f2, s2, t2, back);
                for (int k = 0; k < 3; k++)
                    assert_true(fabs(back[k] - d[k]) < 1e-12);
                if (i > 0 && i < 20 && j > 0 && j < 20) { // inside: the same face back
                    assert_int_equal(f2, face);
                    assert_true(fabs(s2 - s) < 1e-12 && fabs(t2 - t) < 1e-12);
                }
            }
}

static void test_fractional_octaves(void **state) {
    (void)state;
    world_params p = flat_params(GEN_FBM);
    p.feature_size = 8.0 * 2048; // keep every octave below the band limit at level 0
    p.octaves = 3.0;
    float *o3 = tile(&p, 0, 0, 1, 1);
    p.octaves = 4.0;
    float *o4 = tile(&p, 0, 0, 1, 1);
    p.octaves = 3.5;
    float *o35 = tile(&p, 0, 0, 1, 1);
    double diff = 0, worst = 0;
    for (size_t k = 0; k < TILE_SAMPLES; k++) {
        double expect = o3[k] + 0.5 * ((double)o4[k] - o3[k]);
        worst = fmax(worst, fabs(o35[k] - expect));
        diff = fmax(diff, fabs((double)o4[k] - o3[k]));
    }
    assert_true(diff > 1.0);                  // the fourth octave is visible
    assert_true(worst < 1e-3 * p.max_height); // 3.5 lies halfway
    free(o3), free(o4), free(o35);
}

// Level L+1 against the level-L samples filtered with a [1 2 1]/4 tent around the
// co-located sample: the root-mean-square difference is small next to the terrain's
// own variation.
static void test_mip_levels(void **state) {
    (void)state;
    for (size_t g = 0; g < GENERATOR_COUNT; g++) {
        world_params p = flat_params(all_generators[g]);
        for (int level = 0; level < 4; level += 3) {
            float *fine[3][3];
            for (int dy = 0; dy < 3; dy++)
                for (int dx = 0; dx < 3; dx++)
                    fine[dy][dx] = tile(&p, 0, level, 2 + dx - 1, 2 + dy - 1);
            float *coarse = tile(&p, 0, level + 1, 1, 1);
            // Fine sample (x, z) relative to the 3x3 block of tiles centred on tile (2, 2).
#define FINE(x, z)                                                                                 \
    fine[((z) + TILE_SIZE) / TILE_SIZE][((x) + TILE_SIZE) / TILE_SIZE]                             \
        [(((z) + TILE_SIZE) % TILE_SIZE) * TILE_SIZE + ((x) + TILE_SIZE) % TILE_SIZE]
            double se = 0, mean = 0, var = 0;
            int n = 0;
            for (int j = 0; j < TILE_SIZE; j++) {
                for (int i = 0; i < TILE_SIZE; i++) {
                    // Coarse tile (1,1) sample i is level-0 sample 2*(256+i): index 2i of tile 2.
                    int x = 2 * i, z = 2 * j;
                    if (x < -TILE_SIZE + 1 || z < -TILE_SIZE + 1 || x > 2 * TILE_SIZE - 2 ||
                        z > 2 * TILE_SIZE - 2)
                        continue;
                    double f = 0;
                    const double w[3] = {0.25, 0.5, 0.25};
                    for (int b = -1; b <= 1; b++)
                        for (int a = -1; a <= 1; a++)
                            f += w[a + 1] * w[b + 1] * FINE(x + a, z + b);
                    double c = coarse[j * TILE_SIZE + i];
                    se += (c - f) * (c - f);
                    mean += f;
                    var += f * f;
                    n++;
                }
            }
#undef FINE
            mean /= n;
            var = var / n - mean * mean;
            double rmse = sqrt(se / n), sd = sqrt(var);
            assert_true(n > 10000);
            assert_true(sd > 0.0);
            // The planet generator's ridged ranges keep more weight in their finest
            // octaves (crests are sharp), so the octave a coarser level leaves out
            // weighs more there.
            const double tolerance = all_generators[g] == GEN_PLANET ? 0.15 : 0.1;
            if (!(rmse < tolerance * sd))
                print_message("gen %d level %d rmse %g sd %g\n", (int)all_generators[g], level,
                              rmse, sd);
            assert_true(rmse < tolerance * sd);
            for (int dy = 0; dy < 3; dy++)
                for (int dx = 0; dx < 3; dx++)
                    free(fine[dy][dx]);
            free(coarse);
        }
    }
}

// Diamond-square tiles are exactly windows of one infinite array: a region that
// straddles four tiles, computed in one piece, equals the tiles sample for sample.
static void test_diamond_square_one_array(void **state) {
    (void)state;
    world_params p = flat_params(GEN_DIAMOND_SQUARE);
    int64_t tx[2] = {-1, 41}, ty[2] = {-1, -900};
    for (int c = 0; c < 2; c++) {
        for (int level = 0; level <= 2; level += 2) {
            enum { N = 300 };
            int64_t x0 = tx[c] * TILE_SIZE + 100, z0 = ty[c] * TILE_SIZE + 77;
            float *region = malloc(sizeof(float) * N * N);
            gen_diamond_square_region(&p, level, x0, z0, N, N, region);
            float *t[2][2];
            for (int b = 0; b < 2; b++)
                for (int a = 0; a < 2; a++)
                    t[b][a] = tile(&p, 0, level, (int)tx[c] + a, (int)ty[c] + b);
            for (int j = 0; j < N; j++)
                for (int i = 0; i < N; i++) {
                    int gi = 100 + i, gj = 77 + j;
                    float v = t[gj / TILE_SIZE][gi / TILE_SIZE]
                               [(gj % TILE_SIZE) * TILE_SIZE + gi % TILE_SIZE];
                    assert_true(v == region[j * N + i]);
                }
            for (int b = 0; b < 2; b++)
                for (int a = 0; a < 2; a++)
                    free(t[b][a]);
            free(region);
        }
    }
}

// Diamond-square mip levels are exact subsamples: the same field stopped earlier.
static void test_diamond_square_subsample(void **state) {
    (void)state;
    world_params p = flat_params(GEN_DIAMOND_SQUARE);
    float *coarse = tile(&p, 0, 1, -1, 0);
    float *f0 = tile(&p, 0, 0, -2, 0), *f1 = tile(&p, 0, 0, -1, 0);
    for (int j = 0; j < TILE_SIZE / 2; j++)
        for (int i = 0; i < TILE_SIZE; i++) {
            const float *src = i < TILE_SIZE / 2 ? f0 : f1;
            int fi = (2 * i) % TILE_SIZE;
            assert_true(coarse[j * TILE_SIZE + i] == src[(2 * j) * TILE_SIZE + fi]);
        }
    free(coarse), free(f0), free(f1);
}

static void test_heights_finite_and_bounded(void **state) {
    (void)state;
    for (size_t g = 0; g < GENERATOR_COUNT; g++) {
        world_params p = flat_params(all_generators[g]);
        for (int level = 0; level <= 20; level += 5) {
            float *t = tile(&p, 0, level, -5, 9);
            for (size_t k = 0; k < TILE_SAMPLES; k++) {
                assert_true(isfinite(t[k]));
                assert_true(fabs(t[k]) <= p.max_height + fabs(p.base_height));
            }
            free(t);
        }
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_determinism_threads_and_order),
        cmocka_unit_test(test_repeatable),
        cmocka_unit_test(test_seamless),
        cmocka_unit_test(test_planet_seamless),
        cmocka_unit_test(test_fractional_octaves),
        cmocka_unit_test(test_mip_levels),
        cmocka_unit_test(test_diamond_square_subsample),
        cmocka_unit_test(test_diamond_square_one_array),
        cmocka_unit_test(test_heights_finite_and_bounded),
        cmocka_unit_test(test_face_direction_inverse),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
