// The raise dab's row kernel (editor/tools/raise_row.c): every path this processor runs
// (plain C, AVX2, AVX-512) gives the bits of the two-pass loop the dab ran before it
// (the smooth falloff's weights of a row, then each height plus weight x amount kept
// finite), taking its columns' squared distances from smooth_row_squares' table, for rows of every
// length 0..300 (vector tails), at unaligned addresses, with random centres, radii, strengths and
// amounts, and heights that are NaN, infinite or at the height limit; and it writes nothing past
// the row.
#include "editor/tools/brush.h"
#include "editor/tools/raise_row.h"
#include "editor/tools/smooth_row.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

static uint64_t rng = 0x2545f4914f6cdd1dull;

static double uniform(void) {
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

static float keep_finite(float v, float old) {
    v = v == v ? v : old;
    v = v > (float)BRUSH_HEIGHT_LIMIT ? (float)BRUSH_HEIGHT_LIMIT : v;
    return v < (float)-BRUSH_HEIGHT_LIMIT ? (float)-BRUSH_HEIGHT_LIMIT : v;
}

// The loops brush_dab.c ran before the kernel: weights first, then the sums.
static void reference(float *row, float fdx0, int k0, float dz2, float inv_r, float strength,
                      float amount, int n) {
    float w[320];
    for (int i = 0; i < n; i++) {
        float dx = fdx0 + (float)(k0 + i);
        float t = sqrtf(dx * dx + dz2) * inv_r;
        t = t < 1.0f ? t : 1.0f;
        w[i] = (1.0f - t * t * (3.0f - 2.0f * t)) * strength;
    }
    for (int i = 0; i < n; i++)
        row[i] = keep_finite(row[i] + w[i] * amount, row[i]);
}

static float height(void) {
    double u = uniform();
    if (u < 0.02) return NAN;
    if (u < 0.03) return uniform() < 0.5 ? INFINITY : -INFINITY;
    if (u < 0.05) return (float)((uniform() < 0.5 ? -1 : 1) * (BRUSH_HEIGHT_LIMIT - uniform()));
    return (float)((uniform() - 0.5) * 4000.0);
}

static void test_paths_match_the_two_pass_loop(void **state) {
    (void)state;
    int paths = raise_row_paths();
    assert_true(paths >= 1 && paths <= 3);
    enum { CAP = 320, PAD = 8 };
    float in[CAP + 2 * PAD], want[CAP + 2 * PAD], got[CAP + 2 * PAD], dx2[2 * CAP + 512];
    long compared = 0;
    for (int c = 0; c < 4000; c++) {
        int n = c < 301 ? c : (int)(uniform() * 301), off = (int)(uniform() * 7);
        double radius = 0.5 + uniform() * 200.0, cx = (uniform() - 0.5) * 1e4;
        double first = ceil(cx - radius), dz = (uniform() * 2.2 - 1.1) * radius;
        float fdx0 = (float)(first - cx), dzf = (float)dz;
        int k0 = (int)(uniform() * 2.0 * radius);
        // The dab's table from its first column: sample i's square at k0 + i.
        assert_true(k0 + n <= (int)(sizeof dx2 / sizeof *dx2));
        smooth_row_squares(dx2, fdx0, k0 + n);
        float inv_r = (float)(1.0 / radius), strength = (float)(uniform() * 1.5);
        float amount = (float)((uniform() - 0.4) * (c % 50 == 0 ? 4e6 : 60.0));
        for (int i = 0; i < CAP + 2 * PAD; i++)
            in[i] = height();
        memcpy(want, in, sizeof in);
        reference(want + PAD + off, fdx0, k0, dzf * dzf, inv_r, strength, amount, n);
        for (int p = 0; p < paths; p++) {
            memcpy(got, in, sizeof in);
            raise_row_smooth_path(p, got + PAD + off, dx2 + k0, dzf * dzf, inv_r, strength, amount,
                                  (float)BRUSH_HEIGHT_LIMIT, n);
            if (memcmp(got, want, sizeof got) != 0) {
                int i = 0;
                while (!memcmp(&got[i], &want[i], sizeof *got))
                    i++;
                fail_msg("path %d, case %d (n %d): sample %d is %a, the two-pass loop's %a", p, c,
                         n, i - PAD - off, (double)got[i], (double)want[i]);
            }
            // A row that ends its allocation (ASan sees a read or write past it).
            float *exact = malloc(sizeof(float) * (size_t)(n ? n : 1));
            assert_non_null(exact);
            memcpy(exact, in + PAD + off, sizeof(float) * (size_t)n);
            raise_row_smooth_path(p, exact, dx2 + k0, dzf * dzf, inv_r, strength, amount,
                                  (float)BRUSH_HEIGHT_LIMIT, n);
            assert_memory_equal(exact, want + PAD + off, sizeof(float) * (size_t)n);
            free(exact);
            compared += n;
        }
    }
    assert_true(compared > 4000L * 100);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paths_match_the_two_pass_loop),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
