// Image stamps on flat worlds, read a row span at a time (stamp_image.c, vectorised):
// bit for bit the values and edges of the sample-by-sample reading written out here
// (stamp.c's formula before the rows were vectorised), on every path the processor has
// (plain C, AVX2, AVX-512), for random images, rotations,
// scales (powers of two among them), mirrors and row spans (tails of every length); the span of a
// row holds every sample inside the footprint (within the image's support: every sample reading
// non-zero); add and subtract on an array match the formula's sums, the same with the support
// known.
#include "editor/params/world_params.h"
#include "editor/tools/brush.h"
#include "editor/tools/stamp.h"
#include "editor/tools/stamp_image.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static double uniform(void) {
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

// The reference: one sample of a flat image stamp, as stamp.c read it sample by sample.
static float reference(const stamp_image_map *m, int64_t x, int64_t z, double *edge) {
    double dx = (double)x * m->spacing - m->x, dz = (double)z * m->spacing - m->z;
    double u = (m->cos_r * dx + m->sin_r * dz) / m->half_w;
    double v = (-m->sin_r * dx + m->cos_r * dz) / m->half_h;
    *edge = fmax(fabs(u), fabs(v));
    if (!(*edge < 1.0)) return 0.0f;
    if (m->mirror_x) u = -u;
    if (m->mirror_z) v = -v;
    double px = (u + 1.0) * 0.5 * m->width - 0.5, py = (v + 1.0) * 0.5 * m->height - 0.5;
    px = fmin(fmax(px, 0.0), m->width - 1.0);
    py = fmin(fmax(py, 0.0), m->height - 1.0);
    int ix = (int)px, iy = (int)py;
    int jx = ix + 1 < m->width ? ix + 1 : ix, jy = iy + 1 < m->height ? iy + 1 : iy;
    double ax = px - ix, ay = py - iy;
    const float *im = m->pixels;
    double top = im[(size_t)iy * m->width + ix] * (1 - ax) + im[(size_t)iy * m->width + jx] * ax;
    double bot = im[(size_t)jy * m->width + ix] * (1 - ax) + im[(size_t)jy * m->width + jx] * ax;
    return (float)(top * (1 - ay) + bot * ay);
}

static float *random_image(int w, int h) {
    float *px = malloc((size_t)w * h * sizeof *px);
    assert_non_null(px);
    for (int i = 0; i < w * h; i++)
        px[i] = (float)(uniform() * 2.0 - 0.25);
    return px;
}

static stamp_image_map random_map(float *px, int w, int h) {
    double r = (uniform() * 720.0 - 360.0) * (M_PI / 180.0), scale = 0.1 + uniform() * 3.0;
    double spacing = uniform() < 0.5 ? 1.0 : 0.25 + uniform() * 4.0;
    return (stamp_image_map){.pixels = px,
                             .width = w,
                             .height = h,
                             .spacing = spacing,
                             .x = (uniform() - 0.5) * 500.0,
                             .z = (uniform() - 0.5) * 500.0,
                             .cos_r = cos(r),
                             .sin_r = sin(r),
                             .half_w = 0.5 * w * scale * spacing,
                             .half_h = 0.5 * h * scale * spacing,
                             .mirror_x = uniform() < 0.5,
                             .mirror_z = uniform() < 0.5};
}

static void test_values_match_reference(void **state) {
    (void)state;
    long inside = 0, compared = 0;
    float value[300];
    double edge[300];
    for (int trial = 0; trial < 300; trial++) {
        int w = 1 + (int)(uniform() * 40), h = 1 + (int)(uniform() * 40);
        if (trial % 3 == 0) w = h = 64; // the library's square stamps
        float *px = random_image(w, h);
        stamp_image_map m = random_map(px, w, h);
        if (trial % 3 == 1) { // half sizes powers of two: the vector paths multiply
            m.half_w = ldexp(1.0, (int)(uniform() * 8) - 2);
            m.half_h = trial % 2 ? m.half_w : ldexp(1.0, (int)(uniform() * 8) - 2);
        }
        double reach = (m.half_w + m.half_h) / m.spacing + 2;
        int64_t cx = (int64_t)floor(m.x / m.spacing), cz = (int64_t)floor(m.z / m.spacing);
        for (int row = 0; row < 20; row++) {
            int64_t z = cz + (int64_t)((uniform() * 2 - 1) * reach);
            int64_t x0 = cx - (int64_t)(uniform() * reach);
            int n = 1 + (int)(uniform() * 299);
            for (int path = 0; path < stamp_image_paths(); path++) {
                memset(edge, 0, sizeof edge);
                stamp_image_values_path(path, &m, z, x0, n, value, edge);
                for (int i = 0; i < n; i++) {
                    double e;
                    float want = reference(&m, x0 + i, z, &e);
                    assert_memory_equal(&edge[i], &e, sizeof e);
                    if (e < 1.0) {
                        assert_memory_equal(&value[i], &want, sizeof want);
                        inside++;
                    }
                    compared++;
                }
            }
        }
        free(px);
    }
    assert_true(inside > compared / 10); // the rows did cross the footprints
}

static void test_span_holds_the_footprint(void **state) {
    (void)state;
    for (int trial = 0; trial < 200; trial++) {
        int w = 1 + (int)(uniform() * 30), h = 1 + (int)(uniform() * 30);
        float *px = random_image(w, h);
        stamp_image_map m = random_map(px, w, h);
        if (trial % 10 == 0) m.cos_r = 1.0, m.sin_r = 0.0; // axis-aligned: flat bands
        if (trial % 10 == 1) m.cos_r = 0.0, m.sin_r = -1.0;
        int64_t reach = (int64_t)((m.half_w + m.half_h) / m.spacing) + 3;
        int64_t cx = (int64_t)floor(m.x / m.spacing), cz = (int64_t)floor(m.z / m.spacing);
        for (int64_t z = cz - reach; z <= cz + reach; z++) {
            int64_t x0 = cx - reach - (int64_t)(uniform() * 3), x1 = cx + reach, a, b;
            stamp_image_span(&m, z, x0, x1, &a, &b);
            assert_true(x0 <= a && a <= b && b <= x1);
            for (int64_t x = x0; x < x1; x++) {
                double e;
                reference(&m, x, z, &e);
                if (e < 1.0) assert_true(x >= a && x < b);
            }
        }
        free(px);
    }
}

// A random image that is 0 outside a disc (of random centre and radius) but for a few
// scattered pixels, or all 0, or nowhere 0.
static float *sparse_image(int w, int h, int trial) {
    float *px = random_image(w, h);
    double cx = uniform() * w, cy = uniform() * h, r = uniform() * 0.6 * (w > h ? w : h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int keep = trial % 7 == 1 ||
                       (trial % 7 != 0 && (hypot(x - cx, y - cy) < r || uniform() < 0.002));
            if (!keep) px[(size_t)y * w + x] = 0.0f;
        }
    return px;
}

static void test_support_holds_every_nonzero_reading(void **state) {
    (void)state;
    long nonzero = 0, narrowed = 0;
    for (int trial = 0; trial < 300; trial++) {
        int w = 1 + (int)(uniform() * 40), h = 1 + (int)(uniform() * 40);
        float *px = sparse_image(w, h, trial);
        stamp_image_map m = random_map(px, w, h);
        // As stamp.c scales it into metres.
        m.support = stamp_image_support(px, w, h) * fmax(2.0 * m.half_w / w, 2.0 * m.half_h / h);
        stamp_image_map whole = m;
        whole.support = 0.0;
        int64_t reach = (int64_t)((m.half_w + m.half_h) / m.spacing) + 3;
        int64_t cx = (int64_t)floor(m.x / m.spacing), cz = (int64_t)floor(m.z / m.spacing);
        for (int64_t z = cz - reach; z <= cz + reach; z++) {
            int64_t x0 = cx - reach, x1 = cx + reach, a, b, wa, wb;
            stamp_image_span(&m, z, x0, x1, &a, &b);
            stamp_image_span(&whole, z, x0, x1, &wa, &wb);
            assert_true(x0 <= a && b <= x1 && (a >= b || (wa <= a && b <= wb)));
            narrowed += (wb > wa ? wb - wa : 0) - (b > a ? b - a : 0);
            for (int64_t x = x0; x < x1; x++) {
                double e;
                float v = reference(&m, x, z, &e);
                if (e < 1.0 && v != 0.0f) {
                    assert_true(x >= a && x < b);
                    nonzero++;
                }
            }
        }
        free(px);
    }
    assert_true(nonzero > 1000 && narrowed > 1000); // both sides were met
}

// stamp_apply_array in add and subtract mode against the formula's sums, clamped.
static void test_array_add_subtract(void **state) {
    (void)state;
    world_params params;
    world_params_default(&params, WORLD_FLAT);
    params.spacing = 1.0;
    enum { SIDE = 120 };
    float *data = malloc(SIDE * SIDE * sizeof *data), *want = malloc(SIDE * SIDE * sizeof *want);
    assert_true(data && want);
    for (int trial = 0; trial < 40; trial++) {
        int w = 8 + (int)(uniform() * 40), h = 8 + (int)(uniform() * 40);
        stamp_source src = {.shape = -1, .width = w, .height = h};
        strcpy(src.name, "random");
        // Half the trials know the image's support (as stamp_find does): mostly 0
        // around, those keep to it, and the heights there (inside the height limit, not
        // -0) stay as the formula leaves them.
        int support = trial % 4 >= 2;
        src.pixels = support ? sparse_image(w, h, trial / 4) : random_image(w, h);
        if (support) src.support = stamp_image_support(src.pixels, w, h);
        stamp_placement p;
        stamp_placement_defaults(&p);
        p.x = 40.0 + uniform() * 40.0, p.z = 40.0 + uniform() * 40.0;
        p.rotation = uniform() * 360.0, p.scale = 0.5 + uniform() * 1.5;
        p.mirror_x = uniform() < 0.5, p.mirror_z = uniform() < 0.5;
        p.mode = trial % 2 ? STAMP_SUBTRACT : STAMP_ADD;
        p.intensity = trial % 5 == 0 ? 3e5 : uniform() * 200.0 - 50.0; // some past the limit
        for (int i = 0; i < SIDE * SIDE; i++)
            data[i] = want[i] = (float)(uniform() * 8e5 - 4e5);
        double r = p.rotation * (M_PI / 180.0);
        stamp_image_map m = {.pixels = src.pixels,
                             .width = w,
                             .height = h,
                             .spacing = 1.0,
                             .x = p.x,
                             .z = p.z,
                             .cos_r = cos(r),
                             .sin_r = sin(r),
                             .half_w = 0.5 * w * p.scale,
                             .half_h = 0.5 * h * p.scale,
                             .mirror_x = p.mirror_x,
                             .mirror_z = p.mirror_z};
        long changed = 0;
        for (int z = 0; z < SIDE; z++)
            for (int x = 0; x < SIDE; x++) {
                double e;
                float a = reference(&m, x, z, &e) * (float)p.intensity, old = want[z * SIDE + x];
                if (!(e < 1.0)) continue;
                float v = p.mode == STAMP_ADD ? old + a : old - a;
                if (v != v) v = old;
                want[z * SIDE + x] =
                    fminf(fmaxf(v, (float)-BRUSH_HEIGHT_LIMIT), (float)BRUSH_HEIGHT_LIMIT);
                changed += want[z * SIDE + x] != old;
            }
        og_error err;
        assert_int_equal(stamp_apply_array(&params, &src, &p, data, 0, 0, SIDE, SIDE, &err), 0);
        assert_memory_equal(data, want, SIDE * SIDE * sizeof *data);
        assert_true(changed > 0 || (support && trial / 4 % 7 == 0)); // all 0: none
        free(src.pixels);
    }
    free(data);
    free(want);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_values_match_reference),
        cmocka_unit_test(test_span_holds_the_footprint),
        cmocka_unit_test(test_support_holds_every_nonzero_reading),
        cmocka_unit_test(test_array_add_subtract),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
