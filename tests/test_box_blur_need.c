// The smooth dab's blur computing only the results wanted (box_blur_twice_rows with a
// column range per row: strips of rows and columns skipped where no wanted result
// needs them) gives the bits of the whole blur at every wanted sample, for radii
// 1..12, areas up to 4k + 120 wide and high, and wanted ranges shaped as discs, as
// random ranges per row (not convex, some rows empty) and as nothing at all; rows
// are read in runs of columns that end where tiles would (every 37 columns here), the
// whole blur's from a plain array in one run. The same with the results left packed
// (box_blur_twice_packed), each wanted row's inside the area's floats.
#include "editor/tools/box_blur.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

static uint64_t rng = 0x6a09e667f3bcc909ull;

static double uniform(void) {
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct source {
    const float *data;
    int64_t w, h;
} source;

enum { TILE = 37 };

static const float *row_at(void *user, int64_t y, int64_t x, int64_t *end) {
    source *s = user;
    assert_true(y >= 0 && y < s->h && x >= 0 && x < s->w);
    *end = (x / TILE + 1) * TILE < s->w ? (x / TILE + 1) * TILE : s->w;
    return s->data + y * s->w + x;
}

static void test_wanted_results_match_the_whole_blur(void **state) {
    (void)state;
    long compared = 0;
    for (int c = 0; c < 300; c++) {
        int k = 1 + (int)(uniform() * 12);
        int64_t w = 4 * k + 1 + (int64_t)(uniform() * 120),
                h = 4 * k + 1 + (int64_t)(uniform() * 120);
        size_t n = (size_t)(w * h);
        float *in = malloc(n * sizeof *in), *whole = malloc(n * sizeof *whole);
        float *part = malloc(n * sizeof *part), *packed = malloc(n * sizeof *packed);
        int64_t(*need)[2] = malloc((size_t)h * sizeof *need), *at = malloc((size_t)h * sizeof *at);
        assert_true(in && whole && part && packed && need && at);
        for (size_t i = 0; i < n; i++)
            in[i] = (float)((uniform() - 0.3) * pow(10.0, uniform() * 5.0 - 2.0));
        double cx = (double)w * uniform(), cz = (double)h * uniform(), r = (double)w * uniform();
        for (int64_t z = 0; z < h; z++) {
            if (c % 3 == 0) { // a disc
                double dz = (double)z - cz, half = dz * dz < r * r ? sqrt(r * r - dz * dz) : -1;
                need[z][0] = (int64_t)floor(cx - half), need[z][1] = (int64_t)ceil(cx + half);
            } else if (c % 3 == 1) { // anything, empty rows too
                need[z][0] = (int64_t)(uniform() * (double)(w + 20)) - 10;
                need[z][1] = need[z][0] + (int64_t)(uniform() * (double)w) - w / 4;
            } else { // nothing
                need[z][0] = need[z][1] = 0;
            }
        }
        source s = {in, w, h};
        assert_int_equal(box_blur_twice(in, whole, w, h, k), 0);
        assert_int_equal(box_blur_twice_rows(row_at, &s, (const int64_t(*)[2])need, part, w, h, k),
                         0);
        assert_int_equal(
            box_blur_twice_packed(row_at, &s, (const int64_t(*)[2])need, packed, at, w, h, k), 0);
        for (int64_t z = 2 * k; z < h - 2 * k; z++) {
            int64_t a = need[z][0] > 2 * k ? need[z][0] : 2 * k;
            int64_t b = need[z][1] < w - 2 * k ? need[z][1] : w - 2 * k;
            if (a >= b) continue;
            if (memcmp(whole + z * w + a, part + z * w + a, (size_t)(b - a) * sizeof *part) != 0)
                fail_msg("case %d (k %d, %lld x %lld): row %lld, columns %lld..%lld differ", c, k,
                         (long long)w, (long long)h, (long long)z, (long long)a, (long long)b);
            assert_true(at[z] + a >= 0 && at[z] + b <= (int64_t)n);
            if (memcmp(whole + z * w + a, packed + at[z] + a, (size_t)(b - a) * sizeof *part) != 0)
                fail_msg("case %d (k %d, %lld x %lld): row %lld, columns %lld..%lld differ packed",
                         c, k, (long long)w, (long long)h, (long long)z, (long long)a,
                         (long long)b);
            compared += 2 * (b - a);
        }
        free(in), free(whole), free(part), free(packed), free(need), free(at);
    }
    print_message("%ld wanted results compared bit for bit\n", compared);
    assert_true(compared > 50000);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wanted_results_match_the_whole_blur),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
