// Stamps: the functional shapes (zero outside and at the edge of the footprint,
// continuous and C1 there and everywhere, finite for any input, named) and the
// built-in library (committed files equal a fresh run of the generator, every stamp
// loads, peaks at 1 and is 0 on its border).
#include "editor/tools/stamp_library.h"
#include "editor/tools/stamp_shapes.h"
#include "editor/tools/stamp.h"
#include "editor/tools/stamp_image_cache.h"
#include "editor/tools/stamp_user.h"
#include "io/image_read.h"

#include "support/test_support.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

static const char *shape_name(int s) {
    return stamp_shape_name((stamp_shape)s);
}
static float value(int s, float u, float v) {
    return stamp_shape_value((stamp_shape)s, u, v);
}

static void test_shape_names(void **state) {
    (void)state;
    const char *want[STAMP_SHAPE_COUNT] = {"gaussian", "crater", "cone",
                                           "volcano",  "mesa",   "ridge"};
    for (int s = 0; s < STAMP_SHAPE_COUNT; s++) {
        assert_string_equal(shape_name(s), want[s]);
        assert_int_equal(stamp_shape_from_name(want[s]), s);
    }
    assert_null(shape_name(STAMP_SHAPE_COUNT));
    assert_null(shape_name(-1));
    assert_int_equal(stamp_shape_from_name("Gaussian"), -1);
    assert_int_equal(stamp_shape_from_name("crate"), -1);
    assert_int_equal(stamp_shape_from_name(""), -1);
    assert_int_equal(stamp_shape_from_name(NULL), -1);
    assert_true(value(STAMP_SHAPE_COUNT, 0.0f, 0.0f) == 0.0f);
}

// Points on the footprint's edge at parameter t in [0, 1): the unit circle, or the
// boundary of the unit square for the ridge. scale > 1 is outside, < 1 inside.
static void edge_point(int s, double t, double scale, float *u, float *v) {
    if (s == STAMP_SHAPE_RIDGE) {
        double a = 4.0 * t, f = a - floor(a);
        int side = (int)a;
        double x = side == 0 ? 1.0 : side == 1 ? 1.0 - 2.0 * f : side == 2 ? -1.0 : -1.0 + 2.0 * f;
        double y = side == 0 ? -1.0 + 2.0 * f : side == 1 ? 1.0 : side == 2 ? 1.0 - 2.0 * f : -1.0;
        *u = (float)(x * scale), *v = (float)(y * scale);
    } else {
        *u = (float)(cos(2.0 * M_PI * t) * scale), *v = (float)(sin(2.0 * M_PI * t) * scale);
    }
}

static void test_zero_outside_and_on_edge(void **state) {
    (void)state;
    const double scales[] = {1.0, 1.0 + 1e-6, 1.01, 1.5, 3.0, 1e3, 1e20};
    for (int s = 0; s < STAMP_SHAPE_COUNT; s++)
        for (size_t k = 0; k < sizeof scales / sizeof scales[0]; k++)
            for (int i = 0; i < 1000; i++) {
                float u, v;
                edge_point(s, i / 1000.0, scales[k], &u, &v);
                if (fabsf(u) < 1.0f && fabsf(v) < 1.0f && u * u + v * v < 1.0f)
                    continue; // rounding put it inside
                if (value(s, u, v) != 0.0f)
                    fail_msg("%s(%g, %g) = %g, want 0", shape_name(s), u, v, value(s, u, v));
            }
    // The corners of the square are outside the disc.
    for (int s = 0; s < STAMP_SHAPE_COUNT; s++)
        if (s != STAMP_SHAPE_RIDGE) assert_true(value(s, 0.8f, -0.8f) == 0.0f);
}

// Value and slope reach 0 at the edge: just inside, the value is second order small.
static void test_continuous_at_edge(void **state) {
    (void)state;
    const double h = 1e-3;
    for (int s = 0; s < STAMP_SHAPE_COUNT; s++)
        for (int i = 0; i < 1000; i++) {
            float u, v;
            edge_point(s, (i + 0.5) / 1000.0, 1.0 - h, &u, &v);
            float got = value(s, u, v);
            if (!(fabsf(got) < 20.0 * h * h))
                fail_msg("%s(%g, %g) = %g just inside the edge", shape_name(s), u, v, got);
        }
}

// Over the whole footprint and beyond: first differences bounded (continuous) and
// second differences of order h^2 (no kinks: a slope jump of 0.05 would show as 5e-6).
static void test_smooth_everywhere(void **state) {
    (void)state;
    const float h = 1e-4f;
    uint32_t rng = 12345;
    for (int s = 0; s < STAMP_SHAPE_COUNT; s++)
        for (int i = 0; i < 200000; i++) {
            rng = rng * 1664525u + 1013904223u;
            float u = (float)((rng >> 8) / 16777216.0 * 2.4 - 1.2);
            rng = rng * 1664525u + 1013904223u;
            float v = (float)((rng >> 8) / 16777216.0 * 2.4 - 1.2);
            for (int axis = 0; axis < 2; axis++) {
                float du = axis ? 0.0f : h, dv = axis ? h : 0.0f;
                float a = value(s, u - du, v - dv), b = value(s, u, v),
                      c = value(s, u + du, v + dv);
                float d1 = fabsf(c - b), d2 = fabsf(a - 2.0f * b + c);
                if (d1 > 8.0f * h || d2 > 2e-6f)
                    fail_msg("%s at (%.7g, %.7g) axis %d: steps %g, %g", shape_name(s), u, v, axis,
                             c - b, b - a);
            }
        }
}

static void test_finite_for_any_input(void **state) {
    (void)state;
    const float special[] = {0.0f,    -0.0f,    1e-40f,   -1e-40f,   FLT_MIN, 0.5f,    -0.999999f,
                             1.0f,    -1.0f,    1.0001f,  1e10f,     -1e19f,  1.9e19f, 1e30f,
                             FLT_MAX, -FLT_MAX, INFINITY, -INFINITY, NAN};
    const int n = (int)(sizeof special / sizeof special[0]);
    for (int s = 0; s < STAMP_SHAPE_COUNT; s++) {
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                float got = value(s, special[i], special[j]);
                assert_true(isfinite(got));
                if (fabsf(special[i]) > 1.0f || fabsf(special[j]) > 1.0f || isnan(special[i]) ||
                    isnan(special[j]))
                    assert_true(got == 0.0f);
            }
        for (int j = 0; j <= 800; j++)
            for (int i = 0; i <= 800; i++) {
                float got = value(s, -2.0f + i * 0.005f, -2.0f + j * 0.005f);
                if (!(got >= -1.0f && got <= 1.0f))
                    fail_msg("%s: %g outside [-1, 1]", shape_name(s), got);
                if (s != STAMP_SHAPE_CRATER && got < 0.0f)
                    fail_msg("%s: negative %g", shape_name(s), got);
            }
    }
}

// Along the radius: the maximum and where it is, the minimum.
static void radial_extremes(int s, float *max, float *at, float *min) {
    *max = -2.0f, *min = 2.0f, *at = 0.0f;
    for (int i = 0; i <= 1000; i++) {
        float r = i / 1000.0f, h = value(s, r * 0.6f, r * 0.8f);
        if (h > *max) *max = h, *at = r;
        if (h < *min) *min = h;
    }
}

static void test_shape_profiles(void **state) {
    (void)state;
    float max, at, min;
    // Crater: bowl below 0 in the middle, a raised rim around r = 0.65.
    radial_extremes(STAMP_SHAPE_CRATER, &max, &at, &min);
    assert_true(value(STAMP_SHAPE_CRATER, 0.0f, 0.0f) < -0.5f);
    assert_true(min == value(STAMP_SHAPE_CRATER, 0.0f, 0.0f));
    assert_true(max > 0.2f);
    assert_true(at > 0.6f && at < 0.7f);
    assert_true(value(STAMP_SHAPE_CRATER, 0.85f, 0.0f) > 0.0f); // ejecta
    // Gaussian, cone: 1 at the centre, falling monotonically.
    for (int s = STAMP_SHAPE_GAUSSIAN; s <= STAMP_SHAPE_CONE; s += 2) {
        assert_true(value(s, 0.0f, 0.0f) == 1.0f);
        for (int i = 1; i <= 1000; i++)
            assert_true(value(s, i / 1000.0f, 0.0f) <= value(s, (i - 1) / 1000.0f, 0.0f));
    }
    assert_float_equal(value(STAMP_SHAPE_GAUSSIAN, 0.5f, 0.0f),
                       (exp(-1.0) - exp(-4.0) * 4.0) / (1.0 - 5.0 * exp(-4.0)), 1e-6);
    // Volcano: the caldera floor is below its rim, the rim is the summit.
    radial_extremes(STAMP_SHAPE_VOLCANO, &max, &at, &min);
    assert_true(value(STAMP_SHAPE_VOLCANO, 0.0f, 0.0f) < max - 0.2f);
    assert_true(at > 0.1f && at < 0.25f);
    // Mesa: exactly flat on top, low at the foot.
    for (int i = 0; i <= 500; i++)
        assert_true(value(STAMP_SHAPE_MESA, i / 1000.0f, 0.0f) == 1.0f);
    assert_true(value(STAMP_SHAPE_MESA, 0.8f, 0.0f) < 0.1f);
    // Ridge: long along u, narrow across, highest on the crest line.
    assert_true(value(STAMP_SHAPE_RIDGE, 0.0f, 0.0f) == 1.0f);
    assert_true(value(STAMP_SHAPE_RIDGE, 0.6f, 0.0f) > 0.5f);
    assert_true(value(STAMP_SHAPE_RIDGE, 0.0f, 0.6f) == 0.0f);
    assert_true(value(STAMP_SHAPE_RIDGE, 0.3f, 0.1f) < value(STAMP_SHAPE_RIDGE, 0.3f, 0.0f));
    assert_true(value(STAMP_SHAPE_RIDGE, -0.4f, 0.2f) == value(STAMP_SHAPE_RIDGE, 0.4f, -0.2f));
}

static void check_border_and_range(const char *what, const float *px, int n) {
    float max = 0.0f;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            float h = px[(size_t)j * n + i];
            if (!(h >= 0.0f && h <= 1.0f)) fail_msg("%s (%d, %d) = %g", what, i, j, h);
            if ((i == 0 || j == 0 || i == n - 1 || j == n - 1) && h != 0.0f)
                fail_msg("%s: border (%d, %d) = %g, want 0", what, i, j, h);
            max = h > max ? h : max;
        }
    if (max != 1.0f) fail_msg("%s: peak %g, want 1", what, max);
}

static void test_library_entries(void **state) {
    (void)state;
    int n = stamp_library_count();
    assert_true(n >= 8);
    assert_null(stamp_library_entry_at(-1));
    assert_null(stamp_library_entry_at(n));
    char *readme = test_read_file(OROGEN_RESOURCE_DIR "/stamps/README.md", NULL);
    assert_non_null(readme);
    for (int i = 0; i < n; i++) {
        const stamp_library_entry *e = stamp_library_entry_at(i);
        assert_non_null(e);
        assert_true(strlen(e->name) > 0 && strlen(e->about) > 0);
        for (int k = 0; k < i; k++)
            assert_string_not_equal(e->name, stamp_library_entry_at(k)->name);
        char file[256];
        snprintf(file, sizeof file, "`%s.png`", e->name);
        if (!strstr(readme, file)) fail_msg("resources/stamps/README.md does not list %s", file);
    }
    free(readme);
}

// Rendering is deterministic, at any size, with the border at 0 and the peak at 1.
static void test_library_render(void **state) {
    (void)state;
    enum { N = 65 };
    float a[N * N], b[N * N];
    for (int i = 0; i < stamp_library_count(); i++) {
        assert_int_equal(stamp_library_render(i, N, a), 0);
        assert_int_equal(stamp_library_render(i, N, b), 0);
        assert_memory_equal(a, b, sizeof a);
        check_border_and_range(stamp_library_entry_at(i)->name, a, N);
    }
    assert_int_equal(stamp_library_render(-1, N, a), -1);
    assert_int_equal(stamp_library_render(stamp_library_count(), N, a), -1);
    assert_int_equal(stamp_library_render(0, 2, a), -1);
}

static float *load(const char *dir, const char *name) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.png", dir, name);
    float *px;
    int w, h;
    og_error err;
    if (image_read_luminance(path, &px, &w, &h, &err) != 0) fail_msg("%s", err.msg);
    assert_int_equal(w, STAMP_LIBRARY_SIZE);
    assert_int_equal(h, STAMP_LIBRARY_SIZE);
    return px;
}

// The committed stamps are this generator's output: a fresh run matches every pixel.
static void test_committed_library_is_regenerated(void **state) {
    (void)state;
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", test_tmpdir("stamps"));
    og_error err;
    if (stamp_library_generate(dir, &err) != 0) fail_msg("%s", err.msg);
    const char *committed = OROGEN_RESOURCE_DIR "/stamps";
    for (int i = 0; i < stamp_library_count(); i++) {
        const char *name = stamp_library_entry_at(i)->name;
        float *want = load(dir, name), *got = load(committed, name);
        check_border_and_range(name, got, STAMP_LIBRARY_SIZE);
        double worst = 0.0;
        for (size_t k = 0; k < (size_t)STAMP_LIBRARY_SIZE * STAMP_LIBRARY_SIZE; k++)
            worst = fmax(worst, fabs((double)want[k] - got[k]));
        if (worst > 1.0 / 65535 + 1e-7)
            fail_msg("resources/stamps/%s.png differs from make_stamps output by %g; "
                     "regenerate with make_stamps resources/stamps",
                     name, worst);
        free(want), free(got);
    }
    test_rmtree(dir);
    assert_int_equal(stamp_library_generate("/nonexistent/folder", &err), -1);
    assert_non_null(strstr(err.msg, "/nonexistent/folder"));
}

// An image dropped on the editor (stamp_add) is copied byte for byte into the user
// folder, under its own name or the one given, never over another stamp; bad names,
// built-in names and files that are not images are refused with the file named.
static void test_user_stamp_add(void **state) {
    (void)state;
    char dir[4096], user[4200], src[4200], junk[4200];
    snprintf(dir, sizeof dir, "%s", test_tmpdir("user_stamps"));
    snprintf(user, sizeof user, "%s/deep/stamps", dir); // made on demand
    snprintf(src, sizeof src, "%s/stamps/hills.png", OROGEN_RESOURCE_DIR);
    char name[256];
    og_error err = {{0}};
    assert_int_equal(
        stamp_user_add(src, "my_hills", OROGEN_RESOURCE_DIR, user, name, sizeof name, &err), 0);
    assert_string_equal(name, "my_hills");
    assert_int_equal(
        stamp_user_add(src, "my_hills", OROGEN_RESOURCE_DIR, user, name, sizeof name, &err), 0);
    assert_string_equal(name, "my_hills_2"); // taken: a new name, the first kept
    size_t a_len = 0, b_len = 0;
    char *a = test_read_file(src, &a_len), path[4400];
    snprintf(path, sizeof path, "%s/my_hills_2.png", user);
    char *b = test_read_file(path, &b_len);
    assert_non_null(a);
    assert_non_null(b);
    assert_true(a_len == b_len && memcmp(a, b, a_len) == 0);
    free(a), free(b);
    stamp_source s;
    assert_int_equal(stamp_find("my_hills_2", OROGEN_RESOURCE_DIR, user, &s, &err), 0);
    stamp_source_free(&s);
    // Refusals, each naming what is wrong.
    assert_int_equal(stamp_user_add(src, NULL, OROGEN_RESOURCE_DIR, user, name, sizeof name, &err),
                     -1);
    assert_non_null(strstr(err.msg, "'hills' is a built-in stamp"));
    assert_int_equal(
        stamp_user_add(src, "crater", OROGEN_RESOURCE_DIR, user, name, sizeof name, &err), -1);
    assert_int_equal(
        stamp_user_add(src, "bad name", OROGEN_RESOURCE_DIR, user, name, sizeof name, &err), -1);
    assert_non_null(strstr(err.msg, "cannot name a stamp"));
    snprintf(junk, sizeof junk, "%s/junk.png", dir);
    test_write_file(junk, "not a png", 9);
    assert_int_equal(stamp_user_add(junk, NULL, OROGEN_RESOURCE_DIR, user, name, sizeof name, &err),
                     -1);
    assert_non_null(strstr(err.msg, junk));
    snprintf(junk, sizeof junk, "%s/notes.txt", dir);
    test_write_file(junk, "text", 4);
    assert_int_equal(stamp_user_add(junk, NULL, OROGEN_RESOURCE_DIR, user, name, sizeof name, &err),
                     -1);
    assert_non_null(strstr(err.msg, "not an image"));
    test_rmtree(dir);
}

// A stamp image read again is the kept decode, unless the file changed: rewritten in
// place, replaced (a new inode) or removed. Ramps A and B differ in every pixel.
static void ramp(float *px, int n, float offset) {
    for (int i = 0; i < n * n; i++)
        px[i] = offset + 0.5f * (float)i / (float)(n * n);
}

static int reads_as(const char *path, const float *want, int n) {
    stamp_source s;
    og_error err = {{0}};
    if (stamp_find(path, NULL, NULL, &s, &err) != 0) return 0;
    int same = s.width == n && s.height == n;
    for (int i = 0; same && i < n * n; i++)
        same = fabsf(s.pixels[i] - want[i]) < 1e-4f;
    stamp_source_free(&s);
    return same;
}

static void test_image_read_again(void **state) {
    (void)state;
    enum { N = 64 };
    static float a[N * N], b[N * N];
    ramp(a, N, 0.0f), ramp(b, N, 0.25f);
    char dir[4096], path[4200], other[4200];
    snprintf(dir, sizeof dir, "%s", test_tmpdir("stamp_again"));
    snprintf(path, sizeof path, "%s/a.png", dir);
    snprintf(other, sizeof other, "%s/b.png", dir);
    og_error err = {{0}};
    assert_int_equal(image_write_gray16(path, a, N, N, &err), 0);
    assert_int_equal(image_write_gray16(other, b, N, N, &err), 0);
    assert_true(reads_as(path, a, N));
    assert_true(reads_as(path, a, N)); // the kept copy; the caller's copy was freed
    // Rewritten in place (same inode): read again.
    size_t len = 0;
    char *bytes = test_read_file(other, &len);
    assert_non_null(bytes);
    test_write_file(path, bytes, len);
    assert_true(reads_as(path, b, N));
    // Replaced by a rename (a new inode), as image editors save: read again.
    assert_int_equal(image_write_gray16(path, a, N, N, &err), 0);
    assert_true(reads_as(path, a, N));
    // The decode is really kept: bytes changed behind the file's back (same inode, size
    // and time) still read as the kept image.
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    char *a_bytes = test_read_file(path, &len);
    assert_non_null(a_bytes);
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    assert_int_equal(fwrite("XXXX", 1, 4, f), 4); // the PNG signature, now unreadable
    fclose(f);
    struct timespec times[2] = {st.st_atim, st.st_mtim};
    assert_int_equal(utimensat(AT_FDCWD, path, times, 0), 0);
    assert_true(reads_as(path, a, N));
    stamp_image_cache_clear();
    assert_false(reads_as(path, a, N)); // forgotten: read, and it is no longer a PNG
    test_write_file(path, a_bytes, len);
    assert_true(reads_as(path, a, N));
    // Removed: an error, not the kept image.
    assert_int_equal(unlink(path), 0);
    stamp_source s;
    assert_int_equal(stamp_find(path, NULL, NULL, &s, &err), -1);
    assert_non_null(strstr(err.msg, "does not exist"));
    free(bytes), free(a_bytes);
    test_rmtree(dir);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shape_names),
        cmocka_unit_test(test_zero_outside_and_on_edge),
        cmocka_unit_test(test_continuous_at_edge),
        cmocka_unit_test(test_smooth_everywhere),
        cmocka_unit_test(test_finite_for_any_input),
        cmocka_unit_test(test_shape_profiles),
        cmocka_unit_test(test_library_entries),
        cmocka_unit_test(test_library_render),
        cmocka_unit_test(test_committed_library_is_regenerated),
        cmocka_unit_test(test_user_stamp_add),
        cmocka_unit_test(test_image_read_again),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
