// Our EXR writer read back by OpenEXR (through OpenImageIO): every sample bit for bit
// at sizes with and without a partial last block of rows, compressible and
// incompressible samples (stored blocks), odd floats; the same bytes on one core as on
// all of them and on every run; the umask's mode; bad sizes and unwritable places
// refused, naming the file and leaving no temp file.
#include "io/exr_write.h"
#include "io/image_read.h"

#include "support/test_support.h"

#include <dirent.h>
#include <math.h>
#include <sched.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <stdarg.h>
#include <setjmp.h>
#include <cmocka.h>

// Samples of kind: 0 terrain-like (compresses), 1 random bits (does not: stored
// blocks), 2 one value, 3 odd floats (-0, subnormals, extremes, NaN, infinities).
static float *samples(int w, int h, int kind, unsigned seed) {
    float *s = malloc(sizeof(float) * (size_t)w * h);
    for (int i = 0; i < w * h; i++) {
        seed = seed * 1664525u + 1013904223u;
        uint32_t bits = seed ^ (seed >> 13) * 2654435761u;
        switch (kind) {
        case 0:
            s[i] = 500.0f + 300.0f * sinf((float)(i % w) * 0.01f) * cosf((float)(i / w) * 0.02f);
            break;
        case 1:
            bits &= 0xbf7fffffu; // finite: keep the exponent's top bit clear
            memcpy(&s[i], &bits, 4);
            break;
        case 2:
            s[i] = 123.25f;
            break;
        default: {
            const float odd[] = {-0.0f, 1e-45f,   -1e-40f,   3.4e38f, -3.4e38f,
                                 NAN,   INFINITY, -INFINITY, 1.0f};
            s[i] = odd[bits % 9];
        }
        }
    }
    return s;
}

// Reads name back through OpenImageIO/OpenEXR and compares every sample's bits.
static void read_back_equal(const char *name, const float *want, int w, int h) {
    float *got = NULL;
    int gw, gh, kind, bits;
    char desc[256];
    og_error err = {{0}};
    int rc = image_read_channel(test_in_folder(name), "Y", 65536, &got, &gw, &gh, &kind, &bits,
                                desc, sizeof desc, &err);
    if (rc != 0) fail_msg("%s", err.msg);
    assert_int_equal(gw, w);
    assert_int_equal(gh, h);
    assert_int_equal(bits, 32);
    for (int i = 0; i < w * h; i++)
        if (memcmp(&got[i], &want[i], 4) != 0)
            fail_msg("%s: sample (%d, %d) reads %g, wrote %g", name, i % w, i / w, (double)got[i],
                     (double)want[i]);
    free(got);
}

static void test_round_trip(void **state) {
    (void)state;
    const int sizes[][2] = {{1, 1}, {3, 1}, {1, 17}, {33, 47}, {64, 16}, {257, 300}, {5, 33}};
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++)
        for (int kind = 0; kind < 4; kind++) {
            const int w = sizes[i][0], h = sizes[i][1];
            float *s = samples(w, h, kind, (unsigned)(i * 7 + kind));
            og_error err = {{0}};
            if (exr_write_float(test_in_folder("r.exr"), s, w, h, "Y", &err) != 0)
                fail_msg("%s", err.msg);
            read_back_equal("r.exr", s, w, h);
            free(s);
        }
}

// The same samples through OpenImageIO's own EXR writer read back the same.
static void test_same_values_as_openimageio(void **state) {
    (void)state;
    const int w = 300, h = 70;
    float *s = samples(w, h, 0, 5);
    og_error err = {{0}};
    assert_int_equal(exr_write_float(test_in_folder("ours.exr"), s, w, h, "Y", &err), 0);
    assert_int_equal(
        image_write_samples(test_in_folder("oiio.exr"), s, w, h, IMAGE_WRITE_FLOAT, "Y", &err), 0);
    read_back_equal("ours.exr", s, w, h);
    read_back_equal("oiio.exr", s, w, h);
    free(s);
}

static char *file_bytes(const char *name, size_t *len) {
    char *b = test_read_file(test_in_folder(name), len);
    assert_non_null(b);
    return b;
}

// One core or all, first run or second: the same bytes.
static void test_same_bytes_any_threads(void **state) {
    (void)state;
    const int w = 1000, h = 700; // 44 blocks: more than the ring of slots
    float *s = samples(w, h, 0, 9);
    for (int i = 0; i < w * h; i += 7)
        s[i] += (float)(i % 13); // some blocks less compressible than others
    og_error err = {{0}};
    assert_int_equal(exr_write_float(test_in_folder("all1.exr"), s, w, h, "Y", &err), 0);
    assert_int_equal(exr_write_float(test_in_folder("all2.exr"), s, w, h, "Y", &err), 0);
    cpu_set_t all, one;
    assert_int_equal(sched_getaffinity(0, sizeof all, &all), 0);
    CPU_ZERO(&one);
    for (int c = 0; c < CPU_SETSIZE; c++)
        if (CPU_ISSET(c, &all)) {
            CPU_SET(c, &one);
            break;
        }
    assert_int_equal(sched_setaffinity(0, sizeof one, &one), 0);
    int rc = exr_write_float(test_in_folder("one.exr"), s, w, h, "Y", &err);
    sched_setaffinity(0, sizeof all, &all);
    assert_int_equal(rc, 0);
    size_t l1, l2, l3;
    char *a = file_bytes("all1.exr", &l1), *b = file_bytes("all2.exr", &l2),
         *c = file_bytes("one.exr", &l3);
    assert_true(l1 == l2 && l1 == l3);
    assert_memory_equal(a, b, l1);
    assert_memory_equal(a, c, l1);
    assert_true(l1 < (size_t)w * h * 4); // it did compress
    read_back_equal("one.exr", s, w, h);
    free(a), free(b), free(c), free(s);
}

static int temp_files_left(void) {
    DIR *d = opendir(test_folder());
    struct dirent *e;
    int n = 0;
    while ((e = readdir(d)))
        n += strstr(e->d_name, ".tmp-") != NULL;
    closedir(d);
    return n;
}

static void test_mode_and_refusals(void **state) {
    (void)state;
    float s[4] = {1, 2, 3, 4};
    og_error err = {{0}};
    mode_t old = umask(027);
    int rc = exr_write_float(test_in_folder("mode.exr"), s, 2, 2, "Y", &err);
    umask(old);
    assert_int_equal(rc, 0);
    struct stat st;
    assert_int_equal(stat(test_in_folder("mode.exr"), &st), 0);
    assert_int_equal(st.st_mode & 0777, 0640);

    assert_int_equal(exr_write_float(test_in_folder("z.exr"), s, 0, 2, "Y", &err), -1);
    assert_non_null(strstr(err.msg, "z.exr: cannot write a 0 x 2 image"));
    assert_int_equal(exr_write_float(test_in_folder("n.exr"), s, 2, 2, "", &err), -1);
    assert_non_null(strstr(err.msg, "n.exr: EXR channel names"));
    assert_int_equal(exr_write_float(test_in_folder("no/such/folder.exr"), s, 2, 2, "Y", &err), -1);
    assert_non_null(strstr(err.msg, "folder.exr: cannot create a temp file"));
    assert_int_equal(exr_write_float(test_folder(), s, 2, 2, "Y", &err), -1); // a folder
    assert_non_null(strstr(err.msg, test_folder()));
    assert_int_equal(temp_files_left(), 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_same_values_as_openimageio),
        cmocka_unit_test(test_same_bytes_any_threads),
        cmocka_unit_test(test_mode_and_refusals),
    };
    return cmocka_run_group_tests(tests, test_folder_setup, test_folder_teardown);
}
