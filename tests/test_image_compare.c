// Image comparison: the RMSE by hand (identical, uniform difference, a small worked
// example), the file comparison and its errors, and the image_rmse tool the shell
// golden-image tests use (output, exit codes, the amplified diff image).
#include "io/image_compare.h"
#include "io/image_read.h"

#include "support/test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

static void write_rgb(const char *name, const unsigned char *rgb, int w, int h) {
    og_error err;
    if (image_write_rgb8(test_in_folder(name), rgb, w, h, &err) != 0) fail_msg("%s", err.msg);
}

static void test_rmse_identical_is_zero(void **state) {
    (void)state;
    unsigned char a[30];
    for (int i = 0; i < 30; i++)
        a[i] = (unsigned char)(i * 37);
    assert_true(image_rmse_rgb8(a, a, 10) == 0.0);
    assert_true(image_rmse_rgb8(a, a, 0) == 0.0); // no pixels: no error
}

// Every channel of every pixel off by d gives exactly d, whichever image is brighter.
static void test_rmse_uniform_difference(void **state) {
    (void)state;
    unsigned char a[48], b[48];
    for (int d = 1; d <= 255; d += 127) {
        for (int i = 0; i < 48; i++) {
            a[i] = (unsigned char)(i % 2 ? 0 : 255 - d);
            b[i] = (unsigned char)(a[i] + d);
        }
        assert_float_equal(image_rmse_rgb8(a, b, 16), d, 1e-12);
        assert_float_equal(image_rmse_rgb8(b, a, 16), d, 1e-12);
    }
}

// Four pixels; three have one channel off by 6: sqrt(3 * 36 / (4 * 3)) = sqrt(9) = 3.
// Two pixels, one off by (3, 4, 0): sqrt(25 / 6).
static void test_rmse_worked_example(void **state) {
    (void)state;
    const unsigned char a[12] = {10, 20, 30, 10, 20, 30, 10, 20, 30, 10, 20, 30};
    const unsigned char b[12] = {16, 20, 30, 10, 14, 30, 10, 20, 36, 10, 20, 30};
    assert_float_equal(image_rmse_rgb8(a, b, 4), 3.0, 1e-12);
    const unsigned char c[6] = {0, 0, 0, 9, 9, 9}, e[6] = {3, 4, 0, 9, 9, 9};
    assert_float_equal(image_rmse_rgb8(c, e, 2), sqrt(25.0 / 6.0), 1e-12);
}

// A 4 x 2 image reduced by 2 to 2 x 1: each pixel the rounded mean of its 2 x 2 block
// (rows top first), channels apart; k = 1 copies.
static void test_box_down(void **state) {
    (void)state;
    const unsigned char big[24] = {0, 10, 255, 1, 10, 255, 100, 0, 0, 100, 0, 0,
                                   0, 10, 255, 2, 10, 254, 100, 0, 0, 101, 0, 3};
    unsigned char out[6] = {0};
    image_box_down_rgb8(big, 2, 1, 2, out);
    const unsigned char want[6] = {1, 10, 255, 100, 0, 1}; // 3/4 -> 1, 1019/4 -> 255, 3/4 -> 1
    assert_memory_equal(out, want, 6);
    unsigned char copy[24];
    image_box_down_rgb8(big, 4, 2, 1, copy);
    assert_memory_equal(copy, big, 24);
}

static void test_rmse_files(void **state) {
    (void)state;
    const unsigned char a[12] = {10, 20, 30, 10, 20, 30, 10, 20, 30, 10, 20, 30};
    const unsigned char b[12] = {16, 20, 30, 10, 14, 30, 10, 20, 36, 10, 20, 30};
    write_rgb("a.png", a, 2, 2);
    write_rgb("b.png", b, 2, 2);
    write_rgb("wide.png", a, 4, 1);
    double rmse = -1;
    og_error err;
    assert_int_equal(
        image_rmse_files(test_in_folder("a.png"), test_in_folder("b.png"), &rmse, &err), 0);
    assert_float_equal(rmse, 3.0, 1e-12);

    // Sizes differ: both files and both sizes named.
    char want[9000];
    snprintf(want, sizeof want, "%s is 2x2 but %s is 4x1", test_in_folder("a.png"),
             test_in_folder("wide.png"));
    assert_int_equal(
        image_rmse_files(test_in_folder("a.png"), test_in_folder("wide.png"), &rmse, &err), -1);
    if (strcmp(err.msg, want) != 0) fail_msg("\"%s\" != \"%s\"", err.msg, want);

    // Unreadable: the message names the file that is.
    const char *missing = test_in_folder("missing.png");
    assert_int_equal(image_rmse_files(test_in_folder("a.png"), missing, &rmse, &err), -1);
    assert_non_null(strstr(err.msg, missing));
    assert_int_equal(image_rmse_files(missing, test_in_folder("a.png"), &rmse, &err), -1);
    assert_non_null(strstr(err.msg, missing));
}

static void test_diff_amplified_and_clamped(void **state) {
    (void)state;
    const unsigned char a[6] = {0, 10, 200, 255, 0, 7}, b[6] = {1, 0, 100, 0, 0, 7};
    unsigned char d[6];
    image_diff_rgb8(a, b, 2, 4, d);
    const unsigned char want[6] = {4, 40, 255, 255, 0, 0};
    assert_memory_equal(d, want, 6);
}

// Runs the tool; returns its exit status and puts its stdout in out.
static int run_tool(const char *args, char *out, size_t cap) {
    char cmd[10000];
    snprintf(cmd, sizeof cmd, "'%s' %s 2>/dev/null", OROGEN_IMAGE_RMSE, args);
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    size_t n = fread(out, 1, cap - 1, p);
    out[n] = 0;
    int st = pclose(p);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static void test_tool(void **state) {
    (void)state;
    const unsigned char a[12] = {10, 20, 30, 10, 20, 30, 10, 20, 30, 10, 20, 30};
    const unsigned char b[12] = {16, 20, 30, 10, 14, 30, 10, 20, 36, 10, 20, 30};
    write_rgb("ta.png", a, 2, 2);
    write_rgb("tb.png", b, 2, 2);
    write_rgb("twide.png", a, 4, 1);
    char out[256], args[9000];

    snprintf(args, sizeof args, "'%s' '%s'", test_in_folder("ta.png"), test_in_folder("ta.png"));
    assert_int_equal(run_tool(args, out, sizeof out), 0);
    assert_string_equal(out, "rmse=0.000000\n");

    snprintf(args, sizeof args, "'%s' '%s' --max 3", test_in_folder("ta.png"),
             test_in_folder("tb.png"));
    assert_int_equal(run_tool(args, out, sizeof out), 0); // equal to the limit passes
    assert_string_equal(out, "rmse=3.000000\n");

    snprintf(args, sizeof args, "'%s' '%s' --max 2.5 --diff '%s'", test_in_folder("ta.png"),
             test_in_folder("tb.png"), test_in_folder("diff.png"));
    assert_int_equal(run_tool(args, out, sizeof out), 1);
    assert_string_equal(out, "rmse=3.000000\n");
    unsigned char *d;
    int w, h;
    og_error err;
    assert_int_equal(image_read_rgb8(test_in_folder("diff.png"), &d, &w, &h, &err), 0);
    assert_int_equal(w, 2);
    assert_int_equal(h, 2);
    const unsigned char want[12] = {24, 0, 0, 0, 24, 0, 0, 0, 24, 0, 0, 0};
    assert_memory_equal(d, want, 12);
    free(d);

    snprintf(args, sizeof args, "'%s' '%s'", test_in_folder("ta.png"), test_in_folder("twide.png"));
    assert_int_equal(run_tool(args, out, sizeof out), 2); // size mismatch
    snprintf(args, sizeof args, "'%s' '%s'", test_in_folder("ta.png"), test_in_folder("none.png"));
    assert_int_equal(run_tool(args, out, sizeof out), 2); // unreadable
    snprintf(args, sizeof args, "'%s'", test_in_folder("ta.png"));
    assert_int_equal(run_tool(args, out, sizeof out), 2); // usage
    snprintf(args, sizeof args, "'%s' '%s' --max x", test_in_folder("ta.png"),
             test_in_folder("tb.png"));
    assert_int_equal(run_tool(args, out, sizeof out), 2); // bad number
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rmse_identical_is_zero),
        cmocka_unit_test(test_rmse_uniform_difference),
        cmocka_unit_test(test_rmse_worked_example),
        cmocka_unit_test(test_box_down),
        cmocka_unit_test(test_rmse_files),
        cmocka_unit_test(test_diff_amplified_and_clamped),
        cmocka_unit_test(test_tool),
    };
    return cmocka_run_group_tests(tests, test_folder_setup, test_folder_teardown);
}
