// Height rasters: voids filled from their surroundings, RAW sizes, degree spacing, and
// the import dialog's preview of a raster.
#include "editor/interchange/import.h"
#include "io/raster.h"
#include "support/test_support.h"

#include <math.h>
#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

// A plane with holes comes back as the plane near the holes' edges, and the count is right.
static void test_voids_filled_from_surroundings(void **state) {
    (void)state;
    enum { W = 64, H = 48 };
    float *s = malloc(sizeof(float) * W * H);
    for (int z = 0; z < H; z++)
        for (int x = 0; x < W; x++)
            s[z * W + x] = (float)(2 * x + 3 * z);
    int holes = 0;
    for (int z = 20; z < 24; z++)
        for (int x = 30; x < 34; x++, holes++)
            s[z * W + x] = NAN;
    s[0] = INFINITY; // an infinity is a void too
    holes++;
    assert_int_equal(raster_fill_voids(s, W, H), holes);
    for (int i = 0; i < W * H; i++)
        assert_true(isfinite(s[i]));
    // Filled values lie between the surrounding values (no overshoot), near the plane.
    for (int z = 20; z < 24; z++)
        for (int x = 30; x < 34; x++) {
            float want = (float)(2 * x + 3 * z);
            assert_true(s[z * W + x] >= 2 * 29 + 3 * 19 && s[z * W + x] <= 2 * 34 + 3 * 24);
            assert_true(fabsf(s[z * W + x] - want) < 6.0f);
        }
    assert_true(fabsf(s[0] - 0.0f) < 6.0f);
    // Untouched samples stay exactly as they were.
    assert_true(s[5 * W + 7] == (float)(2 * 7 + 3 * 5));
    free(s);
}

static void test_all_void_is_an_error(void **state) {
    (void)state;
    float s[9];
    for (int i = 0; i < 9; i++)
        s[i] = NAN;
    assert_int_equal(raster_fill_voids(s, 3, 3), -1);
    float t[4] = {1, 2, 3, 4};
    assert_int_equal(raster_fill_voids(t, 2, 2), 0);
}

static void test_metres_per_degree(void **state) {
    (void)state;
    double lat, lon;
    raster_metres_per_degree(0.0, &lat, &lon);
    assert_true(fabs(lat - 110574.0) < 2.0); // WGS84 at the equator
    assert_true(fabs(lon - 111320.0) < 2.0);
    raster_metres_per_degree(60.0, &lat, &lon);
    assert_true(fabs(lat - 111412.0) < 2.0);
    assert_true(fabs(lon - 55800.0) < 10.0);
}

static void write_bytes(const char *path, const void *data, size_t n) {
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    fclose(f);
}

static void test_raw_sizes_and_byte_order(void **state) {
    (void)state;
    const char *dir = test_tmpdir("raster");
    char path[4200];
    snprintf(path, sizeof path, "%s/a.r16", dir);
    unsigned char le[2 * 9];
    for (int i = 0; i < 9; i++)
        le[2 * i] = (unsigned char)(i + 1), le[2 * i + 1] = 0x80; // 0x8001 + i
    write_bytes(path, le, sizeof le);
    raster r;
    og_error err;
    assert_int_equal(raster_read(path, NULL, &r, &err), 0);
    assert_int_equal(r.width, 3);
    assert_int_equal(r.height, 3);
    assert_true(r.samples[0] == 32769.0f && r.samples[8] == 32777.0f);
    assert_int_equal(r.kind, RASTER_UNSIGNED);
    raster_free(&r);
    raster_read_options big = {.endian = RASTER_BIG};
    assert_int_equal(raster_read(path, &big, &r, &err), 0);
    assert_true(r.samples[0] == (float)0x0180);
    raster_free(&r);
    // 6 samples: not a square; 3x2 fits.
    write_bytes(path, le, 12);
    assert_int_equal(raster_read(path, NULL, &r, &err), -1);
    assert_non_null(strstr(err.msg, "6 uint16 samples is not a square"));
    assert_non_null(strstr(err.msg, "3x2"));
    assert_non_null(strstr(err.msg, path));
    raster_read_options wide = {.width = 3};
    assert_int_equal(raster_read(path, &wide, &r, &err), 0);
    assert_int_equal(r.height, 2);
    raster_free(&r);
    // float32 little-endian
    float f[4] = {1.5f, -2.0f, 1e6f, 0.25f};
    write_bytes(path, f, sizeof f);
    raster_read_options fl = {.raw_float = 1};
    assert_int_equal(raster_read(path, &fl, &r, &err), 0);
    assert_true(r.samples[1] == -2.0f && r.samples[2] == 1e6f);
    assert_int_equal(r.kind, RASTER_FLOAT);
    raster_free(&r);
    // odd byte count
    write_bytes(path, le, 7);
    assert_int_equal(raster_read(path, NULL, &r, &err), -1);
    assert_non_null(strstr(err.msg, "not a whole number"));
    test_rmtree(dir);
}

// The import dialog's preview: every sample lands in one histogram bin, the stored
// range is the file's, and the mapping is the one the import would use.
static void test_import_preview(void **state) {
    (void)state;
    const char *dir = test_tmpdir("preview");
    char path[4200];
    snprintf(path, sizeof path, "%s/ramp.r16", dir);
    enum { N = 33 };
    unsigned char bytes[N * N * 2];
    for (int i = 0; i < N * N; i++) {
        unsigned v = (unsigned)(i % N) * 2000u + 1000u; // 1000 .. 65000, one value per column
        bytes[2 * i] = (unsigned char)(v & 0xff);
        bytes[2 * i + 1] = (unsigned char)(v >> 8);
    }
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(bytes, 1, sizeof bytes, f), sizeof bytes);
    fclose(f);

    import_options o;
    import_options_defaults(&o);
    import_preview pv;
    og_error err = {{0}};
    assert_int_equal(import_preview_read(path, &o, &pv, &err), 0);
    assert_int_equal(pv.header.width, N);
    assert_int_equal(pv.header.height, N);
    assert_null(pv.header.samples);
    assert_int_equal(pv.has_sidecar, 0);
    assert_true(pv.stored_min == 1000 && pv.stored_max == 65000);
    long total = 0;
    for (int b = 0; b < IMPORT_PREVIEW_BINS; b++)
        total += pv.histogram[b];
    assert_int_equal(total, N * N);
    assert_int_equal(pv.histogram[0], N);                       // the first column
    assert_int_equal(pv.histogram[IMPORT_PREVIEW_BINS - 1], N); // the last

    // The default maps 0 .. 65535 to 0 .. max_height; min=/max= override it.
    double scale = 0, offset = -1;
    char how[300];
    assert_int_equal(
        import_preview_mapping(path, &pv, &o, 1000, &scale, &offset, how, sizeof how, &err), 0);
    assert_true(fabs(scale - 1000.0 / 65535) < 1e-12 && offset == 0);
    assert_int_equal(import_options_set(&o, "min", "-100", &err), 0);
    assert_int_equal(import_options_set(&o, "max", "400", &err), 0);
    assert_int_equal(
        import_preview_mapping(path, &pv, &o, 1000, &scale, &offset, how, sizeof how, &err), 0);
    assert_true(fabs(scale - 500.0 / 65535) < 1e-12 && offset == -100);

    // A file that is not there names itself.
    snprintf(path, sizeof path, "%s/missing.r16", dir);
    assert_int_not_equal(import_preview_read(path, &o, &pv, &err), 0);
    assert_non_null(strstr(err.msg, "missing.r16"));
    test_rmtree(dir);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_voids_filled_from_surroundings),
        cmocka_unit_test(test_all_void_is_an_error),
        cmocka_unit_test(test_metres_per_degree),
        cmocka_unit_test(test_raw_sizes_and_byte_order),
        cmocka_unit_test(test_import_preview),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
