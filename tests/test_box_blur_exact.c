// The smooth dab's blur (box_blur_twice: float running sums down columns re-anchored
// every 2k + 1 rows, float trees along rows) against the straightforward blur in
// double (each box mean summed afresh, no running sums), over random areas and radii
// 1..24 and k = 64 (a dab of radius 512), heights as terrain (a kilometre up with
// slopes and ripples), as noise from millimetres to kilometres, and with cliffs of
// kilometres between them. Every result is finite and within TOLERANCE x the largest
// height it reads (the 4k + 1 square around it) of the exact blur; the largest
// deviations seen are printed (as that fraction and in float steps of that height).
#include "editor/tools/box_blur.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

// A few float steps of the largest height read: the running sums add at most 2k
// changes since their anchor (each rounded at the scale of the heights it moves
// between), the anchors and the row boxes round like trees (log2 of the count).
#define TOLERANCE 0x1p-20

static uint64_t rng = 0x3c6ef372fe94f82bull;

static double uniform(void) {
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

// Two box means of radius k down columns then two along rows, each summed afresh
// in double; results 2k inside every edge.
static void reference(const float *in, double *out, int64_t w, int64_t h, int k) {
    double *a = calloc((size_t)(w * h), sizeof *a), *b = calloc((size_t)(w * h), sizeof *b);
    assert_true(a && b);
    for (int64_t i = 0; i < w * h; i++)
        a[i] = in[i];
    for (int pass = 0; pass < 4; pass++) {
        int64_t step = pass < 2 ? w : 1;
        int64_t lo = pass < 2 ? (pass + 1) * k : 2 * k,
                hi_y = pass < 2 ? h - (pass + 1) * k : h - 2 * k;
        int64_t lx = pass < 2 ? 0 : (pass - 1) * k, hx = pass < 2 ? w : w - (pass - 1) * k;
        for (int64_t y = lo; y < hi_y; y++)
            for (int64_t x = lx; x < hx; x++) {
                double s = 0;
                for (int t = -k; t <= k; t++)
                    s += a[y * w + x + t * step];
                b[y * w + x] = s / (2 * k + 1);
            }
        double *t = a;
        a = b, b = t;
    }
    memcpy(out, a, (size_t)(w * h) * sizeof *out);
    free(a), free(b);
}

static void test_blur_is_within_tolerance_of_the_exact_one(void **state) {
    (void)state;
    double worst[3] = {0, 0, 0}, worst_steps[3] = {0, 0, 0};
    long compared = 0;
    for (int c = 0; c < 150; c++) {
        int kind = c % 3; // terrain, noise, cliffs
        int k = c == 0 ? 64 : 1 + (int)(uniform() * 24);
        int64_t w = 4 * k + 1 + (int64_t)(uniform() * 100),
                h = 4 * k + 1 + (int64_t)(uniform() * 100);
        size_t n = (size_t)(w * h);
        float *in = malloc(n * sizeof *in), *got = malloc(n * sizeof *got);
        double *want = malloc(n * sizeof *want);
        assert_true(in && got && want);
        double base = 1000.0 * uniform(), sx = uniform() - 0.5, sz = uniform() - 0.5;
        for (int64_t z = 0; z < h; z++)
            for (int64_t x = 0; x < w; x++) {
                double v;
                if (kind == 0)
                    v = base + sx * (double)x + sz * (double)z + 3.0 * sin(0.1 * (double)x) +
                        2.0 * cos(0.13 * (double)z) + 0.01 * uniform();
                else
                    v = (uniform() - 0.3) * pow(10.0, uniform() * 6.0 - 3.0);
                if (kind == 2 && (x / 7 + z / 11) % 3 == 0) v += 3000.0;
                in[z * w + x] = (float)v;
            }
        reference(in, want, w, h, k);
        assert_int_equal(box_blur_twice(in, got, w, h, k), 0);
        // The largest height within 2k along rows (rowmax), then down columns.
        double *rowmax = calloc(n, sizeof *rowmax);
        assert_non_null(rowmax);
        for (int64_t z = 0; z < h; z++)
            for (int64_t x = 2 * k; x < w - 2 * k; x++)
                for (int64_t u = x - 2 * k; u <= x + 2 * k; u++)
                    rowmax[z * w + x] = fmax(rowmax[z * w + x], fabs((double)in[z * w + u]));
        for (int64_t z = 2 * k; z < h - 2 * k; z++)
            for (int64_t x = 2 * k; x < w - 2 * k; x++) {
                double scale = 0;
                for (int64_t y = z - 2 * k; y <= z + 2 * k; y++)
                    scale = fmax(scale, rowmax[y * w + x]);
                float g = got[z * w + x];
                double d = fabs((double)g - want[z * w + x]);
                if (!isfinite(g) || d > TOLERANCE * scale)
                    fail_msg("case %d (k %d, %lld x %lld): row %lld column %lld is %.9g, the "
                             "exact blur %.9g (largest height read %.9g)",
                             c, k, (long long)w, (long long)h, (long long)z, (long long)x,
                             (double)g, want[z * w + x], scale);
                if (scale > 0) worst[kind] = fmax(worst[kind], d / scale);
                float top = (float)scale;
                double ulp = fmax(nextafterf(top, INFINITY) - top, FLT_MIN);
                worst_steps[kind] = fmax(worst_steps[kind], d / ulp);
                compared++;
            }
        free(in), free(got), free(want), free(rowmax);
    }
    const char *kinds[3] = {"terrain", "noise mm..km", "cliffs of 3 km"};
    for (int i = 0; i < 3; i++)
        print_message("%s: largest deviation %.3g of the largest height read (2^%.1f), %.1f "
                      "float steps of that height\n",
                      kinds[i], worst[i], log2(worst[i] > 0 ? worst[i] : 1e-300), worst_steps[i]);
    print_message("%ld results compared\n", compared);
    assert_true(compared > 100000);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_blur_is_within_tolerance_of_the_exact_one),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
