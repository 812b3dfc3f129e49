// The smooth dab's box mean along rows on AVX-512 registers (editor/tools/box_rows.c)
// gives the bits of the pass of power-of-two runs it replaces (written out below as
// box_blur.c runs it), for every length 3..31, arrays of 31..300 samples (vector
// tails), unaligned addresses, and heights of very different sizes (where float
// rounding shows any change of order); it writes nothing outside the windows. Skipped
// where the processor lacks AVX-512 (box_rows_wide says so and writes nothing).
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

// box_blur.c's pass: runs of 2p from runs of p, the length's bits taken low first.
static void reference(const float *src, float *dst, int64_t n, int length) {
    int64_t windows = n - (length - 1), k = (length - 1) / 2;
    float inv = (float)(1.0 / length);
    float *run = malloc((size_t)n * sizeof *run), *next = malloc((size_t)n * sizeof *next);
    float *sum = malloc((size_t)n * sizeof *sum);
    memcpy(run, src, (size_t)n * sizeof *run);
    memcpy(sum, src, (size_t)n * sizeof *sum);
    int64_t covered = 1;
    for (int64_t p = 1; 2 * p <= length; p *= 2) {
        for (int64_t i = 0; i < n - (2 * p - 1); i++)
            next[i] = run[i] + run[i + p];
        float *t = run;
        run = next, next = t;
        if (!(length & 2 * p)) continue;
        if (covered + 2 * p == length) {
            for (int64_t i = 0; i < windows; i++)
                dst[k + i] = (sum[i] + run[i + covered]) * inv;
            break;
        }
        for (int64_t i = 0; i < windows; i++)
            sum[i] = sum[i] + run[i + covered];
        covered += 2 * p;
    }
    free(run), free(next), free(sum);
}

static void test_same_bits(void **state) {
    (void)state;
    enum { MAX = 300, PAD = 40 };
    float *src = malloc((MAX + PAD) * sizeof *src);
    float *want = malloc((MAX + PAD) * sizeof *want), *got = malloc((MAX + PAD) * sizeof *got);
    long compared = 0;
    for (int length = 3; length <= 31; length += 2)
        for (int n = length; n <= MAX; n += n < 64 ? 1 : 7) {
            int off = (int)(uniform() * 16);    // unaligned starts
            for (int i = 0; i < MAX + PAD; i++) // heights from millimetres to kilometres
                src[i] = (float)((uniform() - 0.3) * pow(10.0, uniform() * 6.0 - 3.0));
            for (int i = 0; i < MAX + PAD; i++)
                want[i] = got[i] = -12345.0f; // never a result: shows stray writes
            reference(src + off, want + off, n, length);
            if (box_rows_wide(src + off, got + off, n, length) != 0) {
                for (int i = 0; i < MAX + PAD; i++)
                    assert_true(got[i] == -12345.0f);
                print_message("no AVX-512 here: the pass of runs runs instead\n");
                free(src), free(want), free(got);
                skip();
            }
            if (memcmp(want, got, (MAX + PAD) * sizeof *got) != 0)
                fail_msg("length %d, %d samples at offset %d: the bits differ", length, n, off);
            compared += n - (length - 1);
        }
    print_message("%ld windows compared bit for bit\n", compared);
    assert_int_equal(box_rows_wide(src, got, 40, 33), -1); // longer boxes: the caller's pass
    assert_int_equal(box_rows_wide(src, got, 2, 3), -1);
    free(src), free(want), free(got);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_bits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
