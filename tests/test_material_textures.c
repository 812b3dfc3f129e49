// Procedural material textures: the same bytes every time (and pinned hashes, so a
// change on another machine or compiler shows), row noise bit-identical to the point
// noise, seamless wrapping, each material's colour family, real variation, and a
// height channel with range. To look at them: build/material_sheet OUT.png writes a
// contact sheet.
#include "renderer/material_textures.h"
#include "renderer/periodic_noise.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#define S MATERIAL_TEXTURE_SIZE
#define COUNT MATERIAL_TEXTURE_COUNT

static unsigned char tex[COUNT][S * S * 4];

static int setup(void **state) {
    (void)state;
    for (int i = 0; i < COUNT; i++)
        material_texture_generate(i, tex[i]);
    return 0;
}

static uint64_t fnv1a(const unsigned char *p, size_t n) {
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static void test_names(void **state) {
    (void)state;
    const char *want[COUNT] = {"sand", "grass", "rock", "snow", "dirt", "gravel", "moss", "cliff"};
    for (int i = 0; i < COUNT; i++)
        assert_string_equal(material_texture_name(i), want[i]);
    assert_null(material_texture_name(-1));
    assert_null(material_texture_name(COUNT));
    // Out of range fills mid grey rather than leaving the buffer as it was.
    static unsigned char grey[S * S * 4];
    material_texture_generate(COUNT, grey);
    assert_int_equal(grey[0], 128);
    assert_int_equal(grey[sizeof grey - 1], 128);
}

// Two calls give the same bytes, and the bytes are the ones pinned here: the recipes
// use integer hashing and float math without FMA (-ffp-contract=off) and no libm but
// sqrtf, so every machine must agree. Changing a recipe on purpose means new hashes
// (the failure message prints them).
static void test_deterministic(void **state) {
    (void)state;
    // FNV-1a 64 of the RGBA bytes; the same from GCC -O0 (sanitizers), GCC -O3 and
    // clang -O3 -march=native.
    static const uint64_t pinned[COUNT] = {
        0xa85f76983e864611ull, // sand
        0x556767d5b02382bbull, // grass
        0x147b95b1bbbd66baull, // rock
        0x26d906ff1b07e2eeull, // snow
        0x8e4f361fc3b6ba83ull, // dirt
        0x0e9fe5a94ad0bea4ull, // gravel
        0xa31538a5e172bc36ull, // moss
        0x698f23f69069bbe1ull, // cliff
    };
    static unsigned char again[S * S * 4];
    int mismatch = 0;
    for (int i = 0; i < COUNT; i++) {
        material_texture_generate(i, again);
        assert_memory_equal(again, tex[i], sizeof again);
        const uint64_t h = fnv1a(tex[i], sizeof again);
        if (h != pinned[i]) {
            fprintf(stderr, "%s: hash 0x%016llxull, pinned 0x%016llxull\n",
                    material_texture_name(i), (unsigned long long)h, (unsigned long long)pinned[i]);
            mismatch = 1;
        }
    }
    assert_false(mismatch);
}

// The row functions equal the point functions exactly (== on floats: the row sum can
// turn a -0 into +0, which changes no byte), for power-of-two and other periods, at
// several rows.
static void test_rows_match_points(void **state) {
    (void)state;
    float row[S];
    pnoise_cell cells[S];
    const int periods[] = {1, 2, 3, 5, 7, 13, 32, 96};
    const int ys[] = {0, 1, 77, 128, 255};
    for (size_t pi = 0; pi < sizeof periods / sizeof periods[0]; pi++)
        for (size_t yi = 0; yi < sizeof ys / sizeof ys[0]; yi++) {
            const int p = periods[pi];
            const float v = (float)ys[yi] / (float)S;
            pnoise_row(9, p, 2 * p + 1, v, S, row);
            for (int x = 0; x < S; x++) {
                const float u = (float)x / (float)S;
                const float want = pnoise(9, u * (float)p, v * (float)(2 * p + 1), p, 2 * p + 1);
                if (row[x] != want)
                    fail_msg("pnoise_row p=%d y=%d x=%d: %.9g != %.9g", p, ys[yi], x, row[x], want);
            }
            pnoise_fbm_row(11, p, 3, 0.55f, v, S, row);
            for (int x = 0; x < S; x++) {
                const float u = (float)x / (float)S;
                const float want = pnoise_fbm(11, u * (float)p, v * (float)p, p, 3, 0.55f);
                if (row[x] != want)
                    fail_msg("pnoise_fbm_row p=%d y=%d x=%d: %.9g != %.9g", p, ys[yi], x, row[x],
                             want);
            }
            pnoise_cells_row(13, p, 0.8f, v, S, cells);
            for (int x = 0; x < S; x++) {
                const float u = (float)x / (float)S;
                const pnoise_cell want = pnoise_cells(13, u * (float)p, v * (float)p, p, 0.8f);
                const pnoise_cell *c = &cells[x];
                if (c->f1 != want.f1 || c->f2 != want.f2 || c->dx != want.dx || c->dy != want.dy ||
                    c->id != want.id)
                    fail_msg("pnoise_cells_row p=%d y=%d x=%d: f1 %.9g != %.9g", p, ys[yi], x,
                             cells[x].f1, want.f1);
            }
        }
}

// Noise repeats over its period in both directions (to rounding: x + 3 is not exactly
// one period on from x in float).
static void test_noise_periodic(void **state) {
    (void)state;
    for (int k = 0; k < 200; k++) {
        const float x = (float)k * 0.137f, y = (float)k * 0.291f;
        assert_float_equal(pnoise(5, x, y, 3, 7), pnoise(5, x + 3.0f, y - 7.0f, 3, 7), 1e-4);
        assert_float_equal(pnoise_fbm(5, x, y, 4, 3, 0.5f),
                           pnoise_fbm(5, x + 4.0f, y + 8.0f, 4, 3, 0.5f), 1e-4);
        const pnoise_cell a = pnoise_cells(5, x, y, 6, 1.0f);
        const pnoise_cell b = pnoise_cells(5, x - 6.0f, y + 12.0f, 6, 1.0f);
        assert_int_equal(a.id, b.id);
        assert_float_equal(a.f1, b.f1, 1e-4);
    }
}

// Mean absolute difference, over all four channels, between column (or row) a and b.
static double line_diff(const unsigned char *t, int a, int b, int columns) {
    double sum = 0.0;
    for (int k = 0; k < S; k++) {
        const unsigned char *p = columns ? t + 4 * (k * S + a) : t + 4 * (a * S + k);
        const unsigned char *q = columns ? t + 4 * (k * S + b) : t + 4 * (b * S + k);
        for (int c = 0; c < 4; c++)
            sum += fabs((double)p[c] - (double)q[c]);
    }
    return sum / (4.0 * S);
}

// Across the wrap (column 255 to column 0, row 255 to row 0) the texture changes no
// more than between neighbours inside it: at most as much as the most different
// neighbouring pair (strata and ripples make some pairs legitimately differ more than
// the mean), and within twice the mean.
static void test_tileable(void **state) {
    (void)state;
    for (int i = 0; i < COUNT; i++)
        for (int columns = 0; columns < 2; columns++) {
            double mean = 0.0, worst = 0.0;
            for (int a = 0; a + 1 < S; a++) {
                const double d = line_diff(tex[i], a, a + 1, columns);
                mean += d;
                worst = d > worst ? d : worst;
            }
            mean /= S - 1;
            const double seam = line_diff(tex[i], S - 1, 0, columns);
            if (seam > worst + 0.25 || seam > 2.0 * mean)
                fail_msg("%s: %s wrap differs by %.2f; neighbours by %.2f on average, %.2f at most",
                         material_texture_name(i), columns ? "column" : "row", seam, mean, worst);
        }
}

typedef struct stats {
    double mean[4], sd_luma, a_lo, a_hi; // a_lo, a_hi: 5th and 95th percentile of A
} stats;

static stats measure(const unsigned char *t) {
    stats s = {{0}, 0, 0, 0};
    double l_sum = 0.0, l_sq = 0.0;
    size_t hist[256] = {0};
    for (int i = 0; i < S * S; i++) {
        const unsigned char *p = t + 4 * i;
        for (int c = 0; c < 4; c++)
            s.mean[c] += p[c];
        const double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        l_sum += l;
        l_sq += l * l;
        hist[p[3]]++;
    }
    for (int c = 0; c < 4; c++)
        s.mean[c] /= S * S;
    const double lm = l_sum / (S * S);
    s.sd_luma = sqrt(l_sq / (S * S) - lm * lm);
    size_t acc = 0;
    int lo = -1, hi = -1;
    for (int v = 0; v < 256; v++) {
        acc += hist[v];
        if (lo < 0 && acc >= (size_t)(0.05 * S * S)) lo = v;
        if (hi < 0 && acc >= (size_t)(0.95 * S * S)) hi = v;
    }
    s.a_lo = lo;
    s.a_hi = hi;
    return s;
}

static void test_colour_families(void **state) {
    (void)state;
    stats st[COUNT];
    for (int i = 0; i < COUNT; i++) {
        st[i] = measure(tex[i]);
        fprintf(stderr,
                "%-6s mean RGB %5.1f %5.1f %5.1f  A %5.1f  sd(luma) %4.1f  A 5-95%% %3.0f-%3.0f\n",
                material_texture_name(i), st[i].mean[0], st[i].mean[1], st[i].mean[2],
                st[i].mean[3], st[i].sd_luma, st[i].a_lo, st[i].a_hi);
    }
    const double *m;
    m = st[0].mean; // sand: warm beige
    assert_true(m[0] > m[1] && m[1] > m[2] && m[0] > 160 && m[2] > 90);
    m = st[1].mean; // grass: green
    assert_true(m[1] > m[0] && m[1] > m[2] && m[1] > 50);
    m = st[2].mean; // rock: grey-brown, mid
    assert_true(m[0] >= m[2] && fabs(m[0] - m[2]) < 30 && m[1] > 70 && m[1] < 170);
    m = st[3].mean; // snow: bright, blue-white
    assert_true(m[0] > 200 && m[1] > 200 && m[2] > 200 && m[2] >= m[0]);
    m = st[4].mean; // dirt: brown, darker than sand
    assert_true(m[0] > m[1] && m[1] > m[2] && m[0] < 150 && m[0] - m[2] > 20);
    m = st[5].mean; // gravel: grey
    assert_true(fabs(m[0] - m[2]) < 20 && m[1] > 60 && m[1] < 160);
    m = st[6].mean; // moss: dark green
    assert_true(m[1] > m[0] && m[1] > m[2] && m[1] < 110);
    m = st[7].mean; // cliff: dark grey-brown, darker than rock
    assert_true(m[0] >= m[2] && m[1] < st[2].mean[1] && m[1] < 110);
}

static void test_not_flat_and_height_range(void **state) {
    (void)state;
    for (int i = 0; i < COUNT; i++) {
        const stats s = measure(tex[i]);
        const double min_sd = i == 3 ? 3.0 : 8.0; // snow is meant to be soft
        if (s.sd_luma < min_sd)
            fail_msg("%s: luminance sd %.2f < %.1f", material_texture_name(i), s.sd_luma, min_sd);
        if (s.a_hi - s.a_lo < 60)
            fail_msg("%s: height 5th-95th percentile only %.0f-%.0f", material_texture_name(i),
                     s.a_lo, s.a_hi);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_names),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_rows_match_points),
        cmocka_unit_test(test_noise_periodic),
        cmocka_unit_test(test_tileable),
        cmocka_unit_test(test_colour_families),
        cmocka_unit_test(test_not_flat_and_height_range),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
