// The smooth dab's two box means down the columns in strips of 16 on AVX-512 registers
// (editor/tools/box_columns.c) give the bits of box_blur.c's sweep row by row across
// all columns (written out below as it ran before: the first box's rows kept as
// floats in a ring), for radii 1..20, areas from just over 4k to 4k + 70 wide and high,
// column ranges that start and end anywhere (partial strips), and heights from
// millimetres to kilometres, over all rows or a band of them; nothing outside the
// result's rows and columns is written.
// Skipped where the processor lacks AVX-512 (box_columns_wide says so and writes
// nothing).
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

// box_blur.c's sweep: running sums per column in double, row by row.
static void reference(const float *src, float *out, int64_t w, int64_t h, int k, int64_t c0,
                      int64_t c1) {
    double inv = 1.0 / (2 * k + 1);
    int64_t slots = 2 * k + 2;
    double *sum1 = calloc((size_t)w, sizeof *sum1), *sum2 = calloc((size_t)w, sizeof *sum2);
    float *ring = calloc((size_t)(slots * w), sizeof *ring),
          *zero = calloc((size_t)w, sizeof *zero);
    float *spare = calloc((size_t)w, sizeof *spare);
    for (int64_t i = 0; i <= 2 * k; i++)
        for (int64_t x = c0; x < c1; x++)
            sum1[x] += src[i * w + x];
    for (int64_t i = k; i < h - k; i++) {
        float *m = ring + (i % slots) * w;
        const float *old = i - k > 2 * k ? ring + ((i - 2 * k - 1) % slots) * w : zero;
        const float *r = src + (i - k) * w, *a = i + 1 < h - k ? src + (i + k + 1) * w : r;
        float *row = i >= 3 * k ? out + (i - k) * w : spare;
        for (int64_t x = c0; x < c1; x++) {
            float mid = (float)(sum1[x] * inv);
            m[x] = mid;
            double s = sum2[x] + ((double)mid - (double)old[x]);
            sum2[x] = s;
            row[x] = (float)(s * inv);
            sum1[x] += (double)a[x] - (double)r[x];
        }
    }
    free(sum1), free(sum2), free(ring), free(zero), free(spare);
}

static void test_strips_match_the_row_sweep(void **state) {
    (void)state;
    long compared = 0;
    for (int c = 0; c < 400; c++) {
        int k = 1 + (int)(uniform() * 20);
        int64_t w = 4 * k + 1 + (int64_t)(uniform() * 70),
                h = 4 * k + 1 + (int64_t)(uniform() * 70);
        int64_t c0 = 2 * k + (int64_t)(uniform() * (double)(w - 4 * k));
        int64_t c1 = c0 + (int64_t)(uniform() * (double)(w - 2 * k - c0 + 1));
        if (c % 4 == 0) c0 = 2 * k, c1 = w - 2 * k; // the blur's own range
        size_t n = (size_t)(w * h);
        float *src = malloc(n * sizeof *src), *want = malloc(n * sizeof *want);
        float *got = malloc(n * sizeof *got);
        double *ring = malloc((size_t)(2 * k + 2) * 16 * sizeof *ring);
        const float **rows = malloc((size_t)h * sizeof *rows);
        assert_true(src && want && got && ring && rows);
        for (int64_t y = 0; y < h; y++)
            rows[y] = src + y * w;
        for (size_t i = 0; i < n; i++) {
            src[i] = (float)((uniform() - 0.3) * pow(10.0, uniform() * 6.0 - 3.0));
            want[i] = got[i] = -12345.0f; // never a result: shows stray writes
        }
        reference(src, want, w, h, k, c0, c1);
        if (box_columns_wide(rows, got, w, k, ring, c0, c1, 0, h) != 0) {
            for (size_t i = 0; i < n; i++)
                assert_true(got[i] == -12345.0f);
            print_message("no AVX-512 here: box_blur.c's sweep runs instead\n");
            free(src), free(want), free(got), free(ring), free(rows);
            skip();
        }
        if (memcmp(want, got, n * sizeof *got) != 0) {
            size_t i = 0;
            while (!memcmp(&want[i], &got[i], sizeof *got))
                i++;
            fail_msg("k %d, %lld x %lld, columns %lld..%lld: row %lld column %lld is %a, the "
                     "sweep's %a",
                     k, (long long)w, (long long)h, (long long)c0, (long long)c1,
                     (long long)(i / (size_t)w), (long long)(i % (size_t)w), (double)got[i],
                     (double)want[i]);
        }
        compared += (long)((c1 - c0) * (h - 4 * k));
        // Rows [y0, y1) alone: the sweep of that part of the area, at its rows.
        int64_t y0 = (int64_t)(uniform() * (double)(h - 4 * k)), y1 = y0 + 4 * k + 1;
        y1 += (int64_t)(uniform() * (double)(h - y1 + 1));
        for (size_t i = 0; i < n; i++)
            want[i] = got[i] = -12345.0f;
        reference(src + y0 * w, want + y0 * w, w, y1 - y0, k, c0, c1);
        assert_int_equal(box_columns_wide(rows, got, w, k, ring, c0, c1, y0, y1), 0);
        assert_memory_equal(want, got, n * sizeof *got);
        compared += (long)((c1 - c0) * (y1 - y0 - 4 * k));
        free(src), free(want), free(got), free(ring), free(rows);
    }
    print_message("%ld results compared bit for bit\n", compared);
    assert_true(compared > 100000);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_strips_match_the_row_sweep),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
