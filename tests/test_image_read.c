// Image I/O through OpenImageIO: grey and colour, 8/16-bit and half/float, PNG, TIFF
// and EXR files made by oiiotool from PNM/PFM files written here, so every expected
// pixel is known; errors that name the file; the 16-bit PNG writer round trip; the
// 8-bit RGB reader (grey replicated, alpha dropped, 16-bit and float converted) and the
// RGB PNG writer.
#include "io/image_read.h"

#include "support/test_support.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

// OIIO 2.4's PNG reader leaks a std::string when libpng longjmps out of a read of a
// damaged file (fixed upstream in OIIO PR #5289): tell LeakSanitizer about that one.
// The suppression needs the full stack, and libstdc++ has no frame pointers.
const char *__lsan_default_suppressions(void) {
    return "leak:PNGInput::PngReadCallback\n";
}
const char *__asan_default_options(void) {
    return "fast_unwind_on_malloc=0";
}

// oiiotool SRC ARGS -o DST, inside the scratch folder.
static void oiiotool(const char *src, const char *args, const char *dst) {
    char cmd[12000];
    snprintf(cmd, sizeof cmd, "oiiotool '%s' %s -o '%s'", test_in_folder(src), args,
             test_in_folder(dst));
    if (system(cmd) != 0) fail_msg("failed (is openimageio-tools installed?): %s", cmd);
}

// Binary PGM: maxval 255 (one byte) or 65535 (two bytes, big-endian).
static void write_pgm(const char *name, int w, int h, int maxval, const unsigned *v) {
    char buf[4096];
    int n = snprintf(buf, sizeof buf, "P5\n%d %d\n%d\n", w, h, maxval);
    for (int i = 0; i < w * h; i++) {
        if (maxval > 255) buf[n++] = (char)(v[i] >> 8);
        buf[n++] = (char)(v[i] & 0xFF);
    }
    test_write_file(test_in_folder(name), buf, (size_t)n);
}

// PFM with channels 1 ("Pf") or 3 ("PF"): little-endian floats, rows bottom to top.
static void write_pfm(const char *name, int w, int h, int channels, const float *v) {
    char buf[4096];
    int n = snprintf(buf, sizeof buf, "%s\n%d %d\n-1.0\n", channels == 3 ? "PF" : "Pf", w, h);
    for (int y = h - 1; y >= 0; y--)
        for (int i = 0; i < w * channels; i++) {
            uint32_t u;
            memcpy(&u, &v[y * w * channels + i], 4);
            for (int b = 0; b < 4; b++)
                buf[n++] = (char)(u >> (8 * b));
        }
    test_write_file(test_in_folder(name), buf, (size_t)n);
}

static float *read_ok(const char *name, int w, int h) {
    float *px = (float *)1;
    int gw = -1, gh = -1;
    og_error err = {{0}};
    if (image_read_luminance(test_in_folder(name), &px, &gw, &gh, &err) != 0)
        fail_msg("%s: %s", name, err.msg);
    assert_non_null(px);
    assert_int_equal(gw, w);
    assert_int_equal(gh, h);
    return px;
}

// Reading must fail with a message naming the file and containing what.
static void read_fails(const char *path, const char *what) {
    float *px = (float *)1;
    int w = -1, h = -1;
    og_error err = {{0}};
    assert_int_equal(image_read_luminance(path, &px, &w, &h, &err), -1);
    assert_null(px);
    assert_int_equal(w, 0);
    assert_int_equal(h, 0);
    if (!strstr(err.msg, path) || !strstr(err.msg, what))
        fail_msg("message \"%s\" lacks \"%s\" or \"%s\"", err.msg, path, what);
}

static void test_grey_png_8bit(void **state) {
    (void)state;
    const unsigned v[6] = {0, 1, 128, 255, 16, 32};
    write_pgm("g8.pgm", 3, 2, 255, v);
    oiiotool("g8.pgm", "-d uint8", "g8.png");
    float *px = read_ok("g8.png", 3, 2);
    for (int i = 0; i < 6; i++) // row-major from the top row
        assert_float_equal(px[i], v[i] / 255.0, 1e-7);
    free(px);
}

// From float k / 65535, which oiiotool rounds back to k (its PNM reader maps
// 16-bit 65535 to 65534, so a PGM cannot be the source here).
static void test_grey_png_16bit(void **state) {
    (void)state;
    const unsigned k[6] = {0, 1, 32768, 65535, 12345, 54321};
    float v[6];
    for (int i = 0; i < 6; i++)
        v[i] = (float)(k[i] / 65535.0);
    write_pfm("g16.pfm", 2, 3, 1, v);
    oiiotool("g16.pfm", "-d uint16", "g16.png");
    float *px = read_ok("g16.png", 2, 3);
    for (int i = 0; i < 6; i++)
        assert_float_equal(px[i], k[i] / 65535.0, 1e-7);
    free(px);
}

// Float formats keep values outside [0, 1]; half holds these exactly.
static void test_float_exr_tiff_half(void **state) {
    (void)state;
    const float v[6] = {-2.5f, 0.0f, 0.25f, 1000.0f, 3.0f, -0.125f};
    write_pfm("f.pfm", 3, 2, 1, v);
    oiiotool("f.pfm", "-d float", "f.exr");
    oiiotool("f.pfm", "-d float", "f.tif");
    oiiotool("f.pfm", "-d half", "h.exr");
    oiiotool("f.pfm", "-d float --tile 16 16", "tiled.exr");
    const char *names[] = {"f.exr", "f.tif", "h.exr", "tiled.exr"};
    for (int k = 0; k < 4; k++) {
        float *px = read_ok(names[k], 3, 2);
        for (int i = 0; i < 6; i++)
            if (px[i] != v[i]) fail_msg("%s pixel %d: %g != %g", names[k], i, px[i], v[i]);
        free(px);
    }
}

// Rec. 709 weights: pure primaries give the weights themselves.
static void test_rgb_luminance_weights(void **state) {
    (void)state;
    const float v[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    write_pfm("rgb.pfm", 3, 1, 3, v);
    oiiotool("rgb.pfm", "-d float", "rgb.exr");
    float *px = read_ok("rgb.exr", 3, 1);
    assert_float_equal(px[0], 0.2126, 1e-7);
    assert_float_equal(px[1], 0.7152, 1e-7);
    assert_float_equal(px[2], 0.0722, 1e-7);
    free(px);
}

// 8-bit colour, with and without alpha: the alpha channel changes nothing (colour is
// read as stored, not premultiplied by alpha). The file stores the bytes 200, 100, 50
// with alpha 64: oiiotool is told the colour is already unassociated.
static void test_rgb_and_rgba_png(void **state) {
    (void)state;
    const float c[6] = {200 / 255.0f, 100 / 255.0f, 50 / 255.0f, 1.0f, 0.0f, 0.0f};
    write_pfm("c.pfm", 2, 1, 3, c);
    oiiotool("c.pfm", "-d uint8", "rgb.png");
    oiiotool("c.pfm", "--ch R,G,B,A=0.25 --attrib:type=int oiio:UnassociatedAlpha 1 -d uint8",
             "rgba.png");
    const double want0 = (0.2126 * 200 + 0.7152 * 100 + 0.0722 * 50) / 255.0, want1 = 0.2126;
    const char *names[] = {"rgb.png", "rgba.png"};
    for (int k = 0; k < 2; k++) {
        float *px = read_ok(names[k], 2, 1);
        assert_float_equal(px[0], want0, 2e-6);
        assert_float_equal(px[1], want1, 2e-6);
        free(px);
    }
    char cmd[9000];
    snprintf(cmd, sizeof cmd, "iinfo '%s' | grep -q '4 channel, uint8 png'",
             test_in_folder("rgba.png"));
    assert_int_equal(system(cmd), 0);
}

static void test_errors_name_the_file(void **state) {
    (void)state;
    read_fails(test_in_folder("missing.png"), "cannot open");
    test_write_file(test_in_folder("text.png"), "just some text\n", 15);
    read_fails(test_in_folder("text.png"), "not an image");
    read_fails(test_folder(), "folder");
    float *px = NULL;
    int w, h;
    assert_int_equal(image_read_luminance(NULL, &px, &w, &h, NULL), -1); // err may be NULL
}

// The size limit is per side: 16384 wide is fine, 16385 is refused before any allocation.
static void test_size_limit(void **state) {
    (void)state;
    char cmd[9000];
    snprintf(cmd, sizeof cmd, "oiiotool --create 16384x1 1 -d uint8 -o '%s'",
             test_in_folder("ok.png"));
    assert_int_equal(system(cmd), 0);
    snprintf(cmd, sizeof cmd, "oiiotool --create 1x16385 1 -d uint8 -o '%s'",
             test_in_folder("tall.png"));
    assert_int_equal(system(cmd), 0);
    free(read_ok("ok.png", 16384, 1));
    read_fails(test_in_folder("tall.png"), "1 x 16385, larger than the 16384 x 16384 limit");
}

static void test_truncated_png(void **state) {
    (void)state;
    enum { N = 200 };
    float *v = malloc(sizeof(float) * N * N);
    uint32_t s = 1;
    for (int i = 0; i < N * N; i++) { // noise, so the file is long and every row matters
        s = s * 1664525u + 1013904223u;
        v[i] = (float)(s >> 8) / 16777216.0f;
    }
    og_error err;
    assert_int_equal(image_write_gray16(test_in_folder("full.png"), v, N, N, &err), 0);
    free(v);
    size_t len;
    char *bytes = test_read_file(test_in_folder("full.png"), &len);
    assert_non_null(bytes);
    test_write_file(test_in_folder("cut.png"), bytes, len / 2);
    test_write_file(test_in_folder("head.png"), bytes, 40); // the signature and part of IHDR
    free(bytes);
    read_fails(test_in_folder("cut.png"), "cut.png");
    read_fails(test_in_folder("head.png"), "head.png");
}

static void test_not_finite_pixels(void **state) {
    (void)state;
    const float v[6] = {0.5f, 0.25f, 1.0f, 2.0f, NAN, INFINITY};
    write_pfm("nan.pfm", 3, 2, 1, v);
    oiiotool("nan.pfm", "-d float", "nan.exr");
    read_fails(test_in_folder("nan.exr"), "pixel (1, 1) is not finite");
    const float w[6] = {0.5f, 0.25f, 1.0f, 2.0f, 3.0f, -INFINITY};
    write_pfm("inf.pfm", 3, 2, 1, w);
    oiiotool("inf.pfm", "-d half", "inf.exr");
    read_fails(test_in_folder("inf.exr"), "pixel (2, 1) is not finite");
    // Infinite green and blue cancel to NaN in the luminance: still caught.
    const float c[6] = {0.1f, 0.2f, 0.3f, 0.0f, INFINITY, -INFINITY};
    write_pfm("cinf.pfm", 2, 1, 3, c);
    oiiotool("cinf.pfm", "-d float", "cinf.tif");
    read_fails(test_in_folder("cinf.tif"), "pixel (1, 0) is not finite");
}

static int count_entries(const char *path) {
    DIR *d = opendir(path);
    assert_non_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));)
        n += e->d_name[0] != '.';
    closedir(d);
    return n;
}

static void test_write_gray16_round_trip(void **state) {
    (void)state;
    char sub[4200];
    snprintf(sub, sizeof sub, "%s/w", test_folder());
    char cmd[8800];
    snprintf(cmd, sizeof cmd, "mkdir '%s'", sub);
    assert_int_equal(system(cmd), 0);
    char path[4300];
    snprintf(path, sizeof path, "%s/out.png", sub);
    const float v[8] = {0.0f, 1.0f, 0.5f, 1.0f / 65535, -3.0f, 7.0f, 0.25f, 0.999f};
    og_error err;
    assert_int_equal(image_write_gray16(path, v, 4, 2, &err), 0);
    assert_int_equal(image_write_gray16(path, v, 4, 2, &err), 0); // replaces it
    assert_int_equal(count_entries(sub), 1);                      // no temp file left
    float *px;
    int w, h;
    assert_int_equal(image_read_luminance(path, &px, &w, &h, &err), 0);
    assert_int_equal(w, 4);
    assert_int_equal(h, 2);
    for (int i = 0; i < 8; i++) {
        float want = v[i] < 0.0f ? 0.0f : v[i] > 1.0f ? 1.0f : v[i];
        assert_float_equal(px[i], want, 0.5 / 65535 + 1e-7);
    }
    free(px);
    snprintf(cmd, sizeof cmd, "iinfo '%s' | grep -q '1 channel, uint16 png'", path);
    assert_int_equal(system(cmd), 0); // 16-bit grey, as OIIO itself sees it

    const float bad[2] = {0.5f, NAN};
    assert_int_equal(image_write_gray16(path, bad, 2, 1, &err), -1);
    assert_non_null(strstr(err.msg, "pixel (1, 0)"));
    assert_int_equal(image_write_gray16(path, v, 0, 2, &err), -1);
    assert_non_null(strstr(err.msg, path));
    snprintf(path, sizeof path, "%s/no/such/folder/out.png", test_folder());
    assert_int_equal(image_write_gray16(path, v, 4, 2, &err), -1);
    assert_non_null(strstr(err.msg, path));
    assert_int_equal(count_entries(sub), 1);
}

static unsigned char *read_rgb_ok(const char *name, int w, int h) {
    unsigned char *px = (unsigned char *)1;
    int gw = -1, gh = -1;
    og_error err = {{0}};
    if (image_read_rgb8(test_in_folder(name), &px, &gw, &gh, &err) != 0)
        fail_msg("%s: %s", name, err.msg);
    assert_non_null(px);
    assert_int_equal(gw, w);
    assert_int_equal(gh, h);
    return px;
}

static void test_write_rgb8_round_trip(void **state) {
    (void)state;
    char sub[4200];
    snprintf(sub, sizeof sub, "%s/rgbw", test_folder());
    char cmd[8800];
    snprintf(cmd, sizeof cmd, "mkdir '%s'", sub);
    assert_int_equal(system(cmd), 0);
    char path[4300];
    snprintf(path, sizeof path, "%s/out.png", sub);
    enum { W = 7, H = 5 };
    unsigned char v[W * H * 3];
    uint32_t s = 7;
    for (int i = 0; i < W * H * 3; i++) {
        s = s * 1664525u + 1013904223u;
        v[i] = (unsigned char)(s >> 24);
    }
    v[0] = 0; // both ends of the range
    v[1] = 255;
    og_error err;
    assert_int_equal(image_write_rgb8(path, v, W, H, &err), 0);
    assert_int_equal(image_write_rgb8(path, v, W, H, &err), 0); // replaces it
    assert_int_equal(count_entries(sub), 1);                    // no temp file left
    unsigned char *px;
    int w, h;
    assert_int_equal(image_read_rgb8(path, &px, &w, &h, &err), 0);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    assert_memory_equal(px, v, sizeof v); // exact, rows top-first
    free(px);
    snprintf(cmd, sizeof cmd, "iinfo '%s' | grep -q '3 channel, uint8 png'", path);
    assert_int_equal(system(cmd), 0);

    // Bad sizes and a missing folder fail, name the file and leave nothing behind.
    assert_int_equal(image_write_rgb8(path, v, 0, H, &err), -1);
    assert_non_null(strstr(err.msg, path));
    assert_int_equal(image_write_rgb8(path, v, W, IMAGE_MAX_SIZE + 1, &err), -1);
    assert_non_null(strstr(err.msg, "1 to 16384 per side"));
    snprintf(path, sizeof path, "%s/no/such/folder/out.png", test_folder());
    assert_int_equal(image_write_rgb8(path, v, W, H, &err), -1);
    assert_non_null(strstr(err.msg, path));
    assert_int_equal(image_write_rgb8(NULL, v, W, H, NULL), -1); // err may be NULL
    assert_int_equal(count_entries(sub), 1);
}

// Grey, 8- and 16-bit, reads with the value in all three channels.
static void test_read_rgb8_grey_replicated(void **state) {
    (void)state;
    const unsigned v[6] = {0, 1, 128, 255, 16, 32};
    write_pgm("rg8.pgm", 3, 2, 255, v);
    oiiotool("rg8.pgm", "-d uint8", "rg8.png");
    unsigned char *px = read_rgb_ok("rg8.png", 3, 2);
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 3; c++)
            assert_int_equal(px[3 * i + c], v[i]);
    free(px);
    // 16-bit k * 257 is exactly 8-bit k.
    float f[6];
    for (int i = 0; i < 6; i++)
        f[i] = (float)(v[i] * 257 / 65535.0);
    write_pfm("rg16.pfm", 2, 3, 1, f);
    oiiotool("rg16.pfm", "-d uint16", "rg16.png");
    px = read_rgb_ok("rg16.png", 2, 3);
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 3; c++)
            assert_int_equal(px[3 * i + c], v[i]);
    free(px);
}

// RGBA drops the alpha and keeps the colour as stored; float is clamped and rounded.
static void test_read_rgb8_alpha_and_float(void **state) {
    (void)state;
    const float c[6] = {200 / 255.0f, 100 / 255.0f, 50 / 255.0f, 1.0f, 0.0f, 0.0f};
    write_pfm("rc.pfm", 2, 1, 3, c);
    oiiotool("rc.pfm", "--ch R,G,B,A=0.25 --attrib:type=int oiio:UnassociatedAlpha 1 -d uint8",
             "rc.png");
    unsigned char *px = read_rgb_ok("rc.png", 2, 1);
    const unsigned char want[6] = {200, 100, 50, 255, 0, 0};
    assert_memory_equal(px, want, 6);
    free(px);

    const float f[6] = {-1.0f, 0.0f, 0.2f, 0.5f, 1.0f, 7.0f};
    write_pfm("rf.pfm", 2, 1, 3, f);
    oiiotool("rf.pfm", "-d float", "rf.exr");
    px = read_rgb_ok("rf.exr", 2, 1);
    const unsigned char wantf[6] = {0, 0, 51, 128, 255, 255}; // 0.5 * 255 = 127.5 rounds up
    assert_memory_equal(px, wantf, 6);
    free(px);
}

static void test_read_rgb8_errors(void **state) {
    (void)state;
    unsigned char *px = (unsigned char *)1;
    int w = -1, h = -1;
    og_error err;
    const char *path = test_in_folder("absent.png");
    assert_int_equal(image_read_rgb8(path, &px, &w, &h, &err), -1);
    assert_null(px);
    assert_int_equal(w, 0);
    assert_int_equal(h, 0);
    assert_non_null(strstr(err.msg, path));
    assert_non_null(strstr(err.msg, "cannot open"));
    test_write_file(test_in_folder("rtext.png"), "not a png\n", 10);
    path = test_in_folder("rtext.png");
    assert_int_equal(image_read_rgb8(path, &px, &w, &h, &err), -1);
    assert_non_null(strstr(err.msg, path));
    assert_int_equal(image_read_rgb8(test_folder(), &px, &w, &h, &err), -1);
    assert_non_null(strstr(err.msg, "folder"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grey_png_8bit),
        cmocka_unit_test(test_grey_png_16bit),
        cmocka_unit_test(test_float_exr_tiff_half),
        cmocka_unit_test(test_rgb_luminance_weights),
        cmocka_unit_test(test_rgb_and_rgba_png),
        cmocka_unit_test(test_errors_name_the_file),
        cmocka_unit_test(test_size_limit),
        cmocka_unit_test(test_truncated_png),
        cmocka_unit_test(test_not_finite_pixels),
        cmocka_unit_test(test_write_gray16_round_trip),
        cmocka_unit_test(test_write_rgb8_round_trip),
        cmocka_unit_test(test_read_rgb8_grey_replicated),
        cmocka_unit_test(test_read_rgb8_alpha_and_float),
        cmocka_unit_test(test_read_rgb8_errors),
    };
    return cmocka_run_group_tests(tests, test_folder_setup, test_folder_teardown);
}
