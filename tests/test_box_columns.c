// The smooth dab's step down the columns (editor/tools/box_columns.c): every path this
// processor runs (the compiler's loop, AVX-512 intrinsics) gives the bits of the step
// box_blur.c ran before it (written out below: the first box's row kept as floats),
// over many steps in a row (the sums carried from step to step), for column ranges of
// every width 0..70 at every start 0..15 (vector tails, unaligned), with heights from
// millimetres to kilometres; and it writes nothing outside [c0, c1).
#include "editor/tools/box_columns.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

static uint64_t rng = 0x5851f42d4c957f2dull;

static double uniform(void) {
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

// box_blur.c's step before the ring held doubles.
static void reference(double *sum1, double *sum2, float *m, const float *old, const float *a,
                      const float *r, double inv, float *row, int64_t c0, int64_t c1) {
    for (int64_t x = c0; x < c1; x++) {
        float mid = (float)(sum1[x] * inv);
        m[x] = mid;
        double s = sum2[x] + ((double)mid - (double)old[x]);
        sum2[x] = s;
        row[x] = (float)(s * inv);
        sum1[x] += (double)a[x] - (double)r[x];
    }
}

enum { W = 96, STEPS = 12 };

static float height(void) {
    return (float)((uniform() - 0.3) * pow(10.0, uniform() * 6.0 - 3.0));
}

static void test_paths_match_the_float_ring_step(void **state) {
    (void)state;
    int paths = box_column_paths();
    assert_true(paths >= 1 && paths <= 2);
    float a[STEPS][W], r[STEPS][W], old[STEPS][W];
    long compared = 0;
    for (int c0 = 0; c0 < 16; c0++)
        for (int width = 0; width <= 70; width++) {
            int c1 = c0 + width;
            double inv = 1.0 / (2 * (int)(uniform() * 15 + 1) + 1);
            double sum1_0[W], sum2_0[W];
            for (int x = 0; x < W; x++) { // sums of a few heights, as the boxes hold
                sum1_0[x] = (double)height() + (double)height() + (double)height();
                sum2_0[x] = (double)height() + (double)height();
            }
            for (int s = 0; s < STEPS; s++)
                for (int x = 0; x < W; x++)
                    a[s][x] = height(), r[s][x] = height(), old[s][x] = height();
            // The reference, step after step.
            double want1[W], want2[W];
            float want_m[STEPS][W], want_row[STEPS][W];
            memcpy(want1, sum1_0, sizeof want1);
            memcpy(want2, sum2_0, sizeof want2);
            for (int s = 0; s < STEPS; s++) {
                for (int x = 0; x < W; x++)
                    want_m[s][x] = want_row[s][x] = -12345.0f; // never a result
                reference(want1, want2, want_m[s], old[s], a[s], r[s], inv, want_row[s], c0, c1);
            }
            for (int p = 0; p < paths; p++) {
                double got1[W], got2[W], got_m[STEPS][W], old_d[STEPS][W];
                float got_row[STEPS][W];
                memcpy(got1, sum1_0, sizeof got1);
                memcpy(got2, sum2_0, sizeof got2);
                for (int s = 0; s < STEPS; s++)
                    for (int x = 0; x < W; x++) {
                        got_m[s][x] = -12345.0, got_row[s][x] = -12345.0f;
                        old_d[s][x] = (double)old[s][x];
                    }
                for (int s = 0; s < STEPS; s++)
                    box_column_step_path(p, got1, got2, got_m[s], old_d[s], a[s], r[s], inv,
                                         got_row[s], c0, c1);
                assert_memory_equal(got1, want1, sizeof got1);
                assert_memory_equal(got2, want2, sizeof got2);
                for (int s = 0; s < STEPS; s++) {
                    assert_memory_equal(got_row[s], want_row[s], sizeof got_row[s]);
                    for (int x = 0; x < W; x++) {
                        double m = x >= c0 && x < c1 ? (double)want_m[s][x] : -12345.0;
                        if (memcmp(&got_m[s][x], &m, sizeof m) != 0)
                            fail_msg("path %d, columns %d..%d, step %d: ring column %d is %a, "
                                     "not %a",
                                     p, c0, c1, s, x, got_m[s][x], m);
                    }
                }
                compared += (long)width * STEPS;
            }
        }
    print_message("%ld column steps compared bit for bit\n", compared);
    assert_true(compared > 16L * 35 * 70 * STEPS);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paths_match_the_float_ring_step),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
