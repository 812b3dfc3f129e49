// The smooth dab's box mean along rows (editor/tools/box_rows.c), the plain pass and
// the AVX-512 sweep alike, gives the bits of the pass of power-of-two runs written
// out below, for every length 3..31 and longer ones to 129 (the plain pass), arrays
// of up to 300 samples (vector tails), unaligned addresses, and heights of very different sizes
// (where float rounding shows any change of order); it writes nothing outside the windows. Where
// the processor lacks AVX-512, box_rows_wide says so and writes nothing.
#include "editor/tools/box_rows.h"

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
    return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

// box_blur.c's pass: runs of 2p from runs of p, the length's bits taken high first,
// each run starting where those before it end.
static void reference(const float *src, float *dst, int64_t n, int length, float scale) {
    int64_t windows = n - (length - 1), k = (length - 1) / 2;
    float *run[9];
    int top = 0;
    run[0] = malloc((size_t)n * sizeof *run[0]);
    memcpy(run[0], src, (size_t)n * sizeof *run[0]);
    for (int64_t p = 1; 2 * p <= length; p *= 2, top++) {
        run[top + 1] = malloc((size_t)n * sizeof *run[0]);
        for (int64_t i = 0; i < n - (2 * p - 1); i++)
            run[top + 1][i] = run[top][i] + run[top][i + p];
    }
    float *sum = malloc((size_t)n * sizeof *sum);
    memcpy(sum, run[top], (size_t)n * sizeof *sum);
    int64_t covered = 1 << top;
    for (int l = top - 1; l >= 0; l--) {
        if (!(length & (1 << l))) continue;
        for (int64_t i = 0; i < windows; i++)
            sum[i] = sum[i] + run[l][i + covered];
        covered += 1 << l;
    }
    for (int64_t i = 0; i < windows; i++)
        dst[k + i] = sum[i] * scale;
    for (int l = 0; l <= top; l++)
        free(run[l]);
    free(sum);
}

static void test_same_bits(void **state) {
    (void)state;
    enum { MAX = 300, PAD = 40 };
    float *src = malloc((MAX + PAD) * sizeof *src);
    float *want = malloc((MAX + PAD) * sizeof *want), *got = malloc((MAX + PAD) * sizeof *got);
    float *scratch = malloc((BOX_ROWS_LEVELS + 1) * (MAX + PAD) * sizeof *scratch);
    long compared = 0, wide = 0;
    for (int length = 3; length <= 129; length += length < 31 ? 2 : 14)
        for (int n = length; n <= MAX; n += n < 64 ? 1 : 7) {
            int off = (int)(uniform() * 16); // unaligned starts
            // Sums left whole (the blur's first pass), a mean, any scale (its second).
            float scales[3] = {1.0f, (float)(1.0 / length), (float)(uniform() * 0x1p-10)};
            float scale = scales[n % 3];
            for (int i = 0; i < MAX + PAD; i++) // heights from millimetres to kilometres
                src[i] = (float)((uniform() - 0.3) * pow(10.0, uniform() * 6.0 - 3.0));
            for (int path = 0; path < 3; path++) { // plain, AVX-512, the two as box_rows picks
                for (int i = 0; i < MAX + PAD; i++)
                    want[i] = got[i] = -12345.0f; // never a result: shows stray writes
                reference(src + off, want + off, n, length, scale);
                if (path == 0) box_rows_plain(src + off, got + off, n, length, scale, scratch);
                if (path == 2) box_rows(src + off, got + off, n, length, scale, scratch);
                if (path == 1 && box_rows_wide(src + off, got + off, n, length, scale) != 0) {
                    for (int i = 0; i < MAX + PAD; i++)
                        assert_true(got[i] == -12345.0f);
                    continue; // no AVX-512 here, or a longer box: the plain pass runs
                }
                wide += path == 1;
                if (memcmp(want, got, (MAX + PAD) * sizeof *got) != 0)
                    fail_msg("length %d, %d samples at offset %d, path %d: the bits differ", length,
                             n, off, path);
                compared += n - (length - 1);
            }
        }
    print_message("%ld windows compared bit for bit (%ld runs on AVX-512)\n", compared, wide);
    assert_int_equal(box_rows_wide(src, got, 40, 33, 1.0f), -1); // longer boxes: the plain pass
    assert_int_equal(box_rows_wide(src, got, 2, 3, 1.0f), -1);
    free(src), free(want), free(got), free(scratch);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_bits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
