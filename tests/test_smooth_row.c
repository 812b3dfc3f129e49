// The smooth dab's row kernel (editor/tools/smooth_row.c): every path this processor
// runs (plain C, AVX2, AVX-512), given the squares smooth_row_squares makes once per
// dab, gives the bits of the two loops the dab ran before it
// (the smooth falloff's weights of a row, then each height moved toward its smoothed
// value by its weight where the weight is > 0, kept finite), inverted or not, for rows
// of every length 0..300 (vector tails), at unaligned addresses, with random centres,
// radii and strengths, and heights and smoothed values that are NaN, infinite or at
// the height limit; and it writes nothing past the row.
#include "editor/tools/brush.h"
#include "editor/tools/smooth_row.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

static uint64_t rng = 0x7f4a7c159e3779b9ull;

static double uniform(void) {
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

static float keep_finite(float v, float old) {
    v = v == v ? v : old;
    v = v > (float)BRUSH_HEIGHT_LIMIT ? (float)BRUSH_HEIGHT_LIMIT : v;
    return v < (float)-BRUSH_HEIGHT_LIMIT ? (float)-BRUSH_HEIGHT_LIMIT : v;
}

// The loops brush_dab.c ran before the kernel: weights first, then the blend.
static void reference(float *row, const float *smoothed, float fdx0, int k0, float dz2, float inv_r,
                      float strength, int invert, int n) {
    float w[320];
    for (int i = 0; i < n; i++) {
        float dx = fdx0 + (float)(k0 + i);
        float t = sqrtf(dx * dx + dz2) * inv_r;
        t = t < 1.0f ? t : 1.0f;
        w[i] = (1.0f - t * t * (3.0f - 2.0f * t)) * strength;
    }
    for (int i = 0; i < n; i++) {
        float old = row[i];
        float v = keep_finite(old + (invert ? -w[i] : w[i]) * (smoothed[i] - old), old);
        row[i] = w[i] > 0.0f ? v : old;
    }
}

static float height(void) {
    double u = uniform();
    if (u < 0.02) return NAN;
    if (u < 0.03) return uniform() < 0.5 ? INFINITY : -INFINITY;
    if (u < 0.05) return (float)((uniform() < 0.5 ? -1 : 1) * (BRUSH_HEIGHT_LIMIT - uniform()));
    return (float)((uniform() - 0.5) * 4000.0);
}

static void test_paths_match_the_two_loops(void **state) {
    (void)state;
    int paths = smooth_row_paths();
    assert_true(paths >= 1 && paths <= 3);
    enum { CAP = 320, PAD = 8 };
    float in[CAP + 2 * PAD], smoothed[CAP + 2 * PAD], want[CAP + 2 * PAD], got[CAP + 2 * PAD];
    long compared = 0, moved = 0;
    for (int c = 0; c < 4000; c++) {
        int n = c < 301 ? c : (int)(uniform() * 301), off = (int)(uniform() * 7);
        double radius = 0.5 + uniform() * 200.0, cx = (uniform() - 0.5) * 1e4;
        double first = ceil(cx - radius), dz = (uniform() * 2.2 - 1.1) * radius;
        float fdx0 = (float)(first - cx), dzf = (float)dz;
        int k0 = (int)(uniform() * 2.0 * radius), invert = c % 3 == 0;
        float inv_r = (float)(1.0 / radius), strength = (float)(uniform() * 1.5);
        if (c % 40 == 1) strength = 0.0f;
        for (int i = 0; i < CAP + 2 * PAD; i++) {
            in[i] = height();
            // Mostly near the height (as a blur gives), sometimes far or not finite.
            smoothed[i] = uniform() < 0.9 ? in[i] + (float)((uniform() - 0.5) * 50.0) : height();
        }
        // The dab's squares from its first column, as many as this row reaches.
        float *dx2 = malloc(sizeof(float) * (size_t)(k0 + n + 1));
        assert_non_null(dx2);
        smooth_row_squares(dx2, fdx0, k0 + n);
        memcpy(want, in, sizeof in);
        reference(want + PAD + off, smoothed + PAD + off, fdx0, k0, dzf * dzf, inv_r, strength,
                  invert, n);
        for (int i = 0; i < CAP + 2 * PAD; i++)
            moved += memcmp(&want[i], &in[i], sizeof *in) != 0;
        for (int p = 0; p < paths; p++) {
            memcpy(got, in, sizeof in);
            smooth_row_blend_path(p, got + PAD + off, smoothed + PAD + off, dx2 + k0, dzf * dzf,
                                  inv_r, strength, invert, (float)BRUSH_HEIGHT_LIMIT, n);
            if (memcmp(got, want, sizeof got) != 0) {
                int i = 0;
                while (!memcmp(&got[i], &want[i], sizeof *got))
                    i++;
                fail_msg("path %d, case %d (n %d): sample %d is %a, the two loops' %a", p, c, n,
                         i - PAD - off, (double)got[i], (double)want[i]);
            }
            // A row and smoothed values that end their allocations (ASan sees a read or
            // write past them).
            size_t bytes = sizeof(float) * (size_t)(n ? n : 1);
            float *exact = malloc(bytes), *exact_s = malloc(bytes), *exact_d = malloc(bytes);
            assert_non_null(exact);
            assert_non_null(exact_s);
            assert_non_null(exact_d);
            memcpy(exact, in + PAD + off, sizeof(float) * (size_t)n);
            memcpy(exact_s, smoothed + PAD + off, sizeof(float) * (size_t)n);
            memcpy(exact_d, dx2 + k0, sizeof(float) * (size_t)n);
            smooth_row_blend_path(p, exact, exact_s, exact_d, dzf * dzf, inv_r, strength, invert,
                                  (float)BRUSH_HEIGHT_LIMIT, n);
            assert_memory_equal(exact, want + PAD + off, sizeof(float) * (size_t)n);
            free(exact);
            free(exact_s);
            free(exact_d);
            compared += n;
        }
        free(dx2);
    }
    print_message("%ld samples compared bit for bit, %ld moved\n", compared, moved);
    assert_true(compared > 4000L * 100);
    assert_true(moved > 4000L * 20); // the weights reach most rows: the blend is exercised
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paths_match_the_two_loops),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
