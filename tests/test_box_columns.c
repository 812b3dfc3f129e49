// The smooth dab's two box sums down the columns (editor/tools/box_columns.c, float
// running sums re-anchored every 2k + 1 rows) give the same bits on every path and
// for every choice of rows asked for: the AVX-512 strips (where the processor has
// them) against the plain C loop, and rows [y0, y1) asked for alone against the whole
// area's sweep at those rows, for radii 1..20, areas from just over 4k to 4k + 70,
// column ranges that start and end anywhere (partial strips), heights from
// millimetres to kilometres and cliffs between them. Nothing outside the columns
// asked for, or above the anchor at or above y0, or from y1 on, or outside the
// columns each row keeps, is written.
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

enum { NEVER = -12345 }; // never a result: shows stray writes

typedef void (*columns_fn)(const float *const *rows, float *const *out, const int64_t (*keep)[2],
                           int k, float *ring, int64_t c0, int64_t c1, int64_t y0, int64_t y1);

// The columns each row keeps (NULL: all of them).
static const int64_t (*keep)[2];

// Runs fn into a fresh out (every sample NEVER first).
static void run(columns_fn fn, const float *const *rows, float *out, int64_t w, int64_t h, int k,
                int64_t c0, int64_t c1, int64_t y0, int64_t y1) {
    float *ring = malloc((size_t)(2 * k + 2) * BOX_COLUMNS_WIDTH * sizeof *ring);
    float **to = malloc((size_t)h * sizeof *to);
    assert_true(ring && to);
    for (int64_t i = 0; i < w * h; i++)
        out[i] = (float)NEVER;
    for (int64_t y = 0; y < h; y++)
        to[y] = out + y * w;
    fn(rows, to, keep, k, ring, c0, c1, y0, y1);
    free(ring), free(to);
}

static void same_bits(const float *want, const float *got, int64_t w, int64_t x0, int64_t x1,
                      int64_t y0, int64_t y1, const char *what, int c) {
    for (int64_t y = y0; y < y1; y++)
        for (int64_t x = x0; x < x1; x++)
            if (memcmp(&want[y * w + x], &got[y * w + x], sizeof *got) != 0)
                fail_msg("case %d, %s: row %lld column %lld is %a, not %a", c, what, (long long)y,
                         (long long)x, (double)got[y * w + x], (double)want[y * w + x]);
}

static void test_paths_and_row_ranges_agree(void **state) {
    (void)state;
    long compared = 0;
    int wide = box_columns_have_wide();
    if (!wide) print_message("no AVX-512 here: the plain loop against itself only\n");
    for (int c = 0; c < 400; c++) {
        int k = 1 + (int)(uniform() * 20);
        int64_t w = 4 * k + 1 + (int64_t)(uniform() * 70),
                h = 4 * k + 1 + (int64_t)(uniform() * 70);
        int64_t c0 = (int64_t)(uniform() * (double)w);
        int64_t c1 = c0 + 1 + (int64_t)(uniform() * (double)(w - c0));
        if (c % 4 == 0) c0 = 0, c1 = w;
        size_t n = (size_t)(w * h);
        float *src = malloc(n * sizeof *src), *plain = malloc(n * sizeof *plain);
        float *got = malloc(n * sizeof *got);
        const float **rows = malloc((size_t)h * sizeof *rows);
        assert_true(src && plain && got && rows);
        for (int64_t y = 0; y < h; y++)
            rows[y] = src + y * w;
        double base = c % 3 == 0 ? 0.0 : 2000.0 * uniform();
        for (size_t i = 0; i < n; i++) {
            src[i] = (float)(base + (uniform() - 0.3) * pow(10.0, uniform() * 6.0 - 3.0));
            if (c % 5 == 0 && (i % (size_t)w) > (size_t)w / 2) src[i] += 3000.0f; // a cliff
        }
        run(box_columns_plain, rows, plain, w, h, k, c0, c1, 2 * k, h - 2 * k);
        // Nothing outside the columns and rows asked for.
        for (int64_t y = 0; y < h; y++)
            for (int64_t x = 0; x < w; x++)
                if (x < c0 || x >= c1 || y < 2 * k || y >= h - 2 * k)
                    assert_true(plain[y * w + x] == (float)NEVER);
        if (wide) {
            run(box_columns, rows, got, w, h, k, c0, c1, 2 * k, h - 2 * k);
            same_bits(plain, got, w, 0, w, 0, h, "AVX-512 against plain", c);
        }
        compared += (long)((c1 - c0) * (h - 4 * k));
        // Rows [y0, y1) alone: the whole sweep's bits there, nothing from y1 on or
        // above y0's anchor.
        int64_t y0 = 2 * k + (int64_t)(uniform() * (double)(h - 4 * k));
        int64_t y1 = y0 + 1 + (int64_t)(uniform() * (double)(h - 2 * k - y0));
        int64_t anchor = box_columns_anchor(y0, k);
        assert_true(anchor <= y0 && anchor > y0 - (2 * k + 1) &&
                    (anchor - 2 * k) % (2 * k + 1) == 0);
        for (int path = 0; path < 1 + wide; path++) {
            run(path ? box_columns : box_columns_plain, rows, got, w, h, k, c0, c1, y0, y1);
            same_bits(plain, got, w, c0, c1, y0, y1, path ? "AVX-512, part" : "plain, part", c);
            for (int64_t y = 0; y < h; y++)
                for (int64_t x = 0; x < w; x++)
                    if (x < c0 || x >= c1 || y < anchor || y >= y1)
                        assert_true(got[y * w + x] == (float)NEVER);
            compared += (long)((c1 - c0) * (y1 - y0));
        }
        // Rows keeping only some columns (some none, some all): the whole sweep's bits
        // there, nothing else written.
        int64_t(*kept)[2] = malloc((size_t)h * sizeof *kept);
        assert_non_null(kept);
        for (int64_t y = 0; y < h; y++) {
            kept[y][0] = (int64_t)(uniform() * (double)(w + 10)) - 5;
            kept[y][1] = kept[y][0] + (int64_t)(uniform() * (double)(w + 10)) - w / 4;
            if (y % 7 == 3) kept[y][0] = -3, kept[y][1] = w + 3;
        }
        keep = (const int64_t(*)[2])kept;
        for (int path = 0; path < 1 + wide; path++) {
            run(path ? box_columns : box_columns_plain, rows, got, w, h, k, c0, c1, 2 * k,
                h - 2 * k);
            for (int64_t y = 0; y < h; y++)
                for (int64_t x = 0; x < w; x++) {
                    int in = x >= c0 && x < c1 && y >= 2 * k && y < h - 2 * k && x >= kept[y][0] &&
                             x < kept[y][1];
                    if (in) same_bits(plain, got, w, x, x + 1, y, y + 1, "kept columns", c);
                    if (!in) assert_true(got[y * w + x] == (float)NEVER);
                    compared += in;
                }
        }
        keep = NULL;
        free(kept);
        free(src), free(plain), free(got), free(rows);
    }
    print_message("%ld results compared bit for bit\n", compared);
    assert_true(compared > 100000);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paths_and_row_ranges_agree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
