// The greyscale PNG reader (io/png_gray.c) against OpenImageIO's, which it stands in
// for: PNGs written here chunk by chunk (every filter, 8 and 16 bits, image data split
// over many IDAT chunks, ancillary chunks) read to the same samples; files it must
// leave to OpenImageIO (interlaced, colour, palette, 1-4 bits, sBIT, tRNS, bad CRCs,
// bad filters, short or long image data, cut anywhere) are left, and
// image_read_channel then gives exactly what OpenImageIO gives, the same values or an
// error naming the file. Random damage to a good file, with counts.
#include "io/image_read.h"
#include "io/module_load.h"
#include "io/png_gray.h"

#include "support/test_support.h"

#include <dlfcn.h>
#include <libdeflate.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

// OIIO 2.4's PNG reader leaks a std::string when libpng longjmps out of a read of a
// damaged file (see test_image_read.c).
const char *__lsan_default_suppressions(void) {
    return "leak:PNGInput::PngReadCallback\n";
}
const char *__asan_default_options(void) {
    return "fast_unwind_on_malloc=0";
}

typedef int (*read_channel_fn)(const char *, const char *, int, float **, int *, int *, int *,
                               int *, char *, size_t, og_error *);

// OpenImageIO's reader itself, from the image module.
static read_channel_fn oiio_read_channel(void) {
    static read_channel_fn fn;
    if (!fn) {
        char why[1024];
        void *h = module_open("OROGEN_IMAGE_MODULE", "liborogen_image.so", OROGEN_IMAGE_MODULE_PATH,
                              why, sizeof why);
        if (!h) fail_msg("%s", why);
        fn = (read_channel_fn)dlsym(h, "orogen_image_module_read_channel");
        assert_non_null(fn);
    }
    return fn;
}

// ---- a PNG writer, chunk by chunk ------------------------------------------------------

typedef struct png_buf {
    unsigned char *data;
    size_t len, cap;
} png_buf;

static void put(png_buf *b, const void *p, size_t n) {
    if (b->len + n > b->cap) {
        b->cap = (b->len + n) * 2;
        b->data = realloc(b->data, b->cap);
        assert_non_null(b->data);
    }
    memcpy(b->data + b->len, p, n);
    b->len += n;
}

static void put32(png_buf *b, uint32_t v) {
    const unsigned char be[4] = {(unsigned char)(v >> 24), (unsigned char)(v >> 16),
                                 (unsigned char)(v >> 8), (unsigned char)v};
    put(b, be, 4);
}

static void chunk(png_buf *b, const char *type, const void *data, uint32_t n) {
    put32(b, n);
    const size_t at = b->len;
    put(b, type, 4);
    put(b, data, n);
    put32(b, libdeflate_crc32(0, b->data + at, n + 4));
}

typedef struct png_spec {
    int width, height, bits, colour, interlace;
    int filter;            // 0-4 for every row, 5: row y gets y % 5, 6: an invalid 5 on row 1
    int idat_size;         // bytes per IDAT chunk (0: one chunk)
    int extra_rows;        // image data for this many rows more (negative: fewer)
    const char *ancillary; // a chunk written before the image data ("gAMA", "sBIT", ...)
    int noise;             // samples that hardly compress
} png_spec;

static int paeth(int a, int b, int c) {
    int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

// Random samples (seeded), filtered as spec says; returns the file, and the samples
// as stored in *expect (width x height) when expect is not NULL.
static png_buf make_png(const png_spec *s, uint32_t seed, float **expect) {
    const int channels = s->colour == 2 ? 3 : s->colour == 4 ? 2 : s->colour == 6 ? 4 : 1;
    const int bpp = (s->bits * channels + 7) / 8;
    const size_t row = ((size_t)s->width * (size_t)(s->bits * channels) + 7) / 8;
    const int rows = s->height + s->extra_rows;
    unsigned char *raw = calloc((size_t)rows * row, 1), *out = calloc((size_t)rows * (row + 1), 1);
    if (expect) *expect = malloc(sizeof(float) * (size_t)s->width * (size_t)s->height);
    // Smooth terrain-like values with noise, so every filter has work.
    for (int y = 0; y < rows; y++)
        for (size_t i = 0; i < row; i++) {
            seed = seed * 1664525u + 1013904223u;
            raw[(size_t)y * row + i] =
                (unsigned char)((i % 2 && s->bits == 16) || s->noise
                                    ? seed >> 24
                                    : (i * 3 + (size_t)y * 5) / 7 + (seed >> 29));
        }
    for (int y = 0; y < rows; y++) {
        const unsigned char *r = raw + (size_t)y * row, *up = y ? r - row : NULL;
        unsigned char *o = out + (size_t)y * (row + 1);
        int f = s->filter < 5 ? s->filter : s->filter == 5 ? y % 5 : (y == 1 ? 5 : 1);
        o[0] = (unsigned char)f;
        for (size_t i = 0; i < row; i++) {
            int a = i >= (size_t)bpp ? r[i - bpp] : 0, b = up ? up[i] : 0,
                c = up && i >= (size_t)bpp ? up[i - bpp] : 0;
            int pred = f == 1 ? a : f == 2 ? b : f == 3 ? (a + b) / 2 : f == 4 ? paeth(a, b, c) : 0;
            o[1 + i] = (unsigned char)(r[i] - pred);
        }
    }
    if (expect)
        for (int y = 0; y < s->height; y++)
            for (int x = 0; x < s->width; x++) {
                const unsigned char *p = raw + (size_t)y * row;
                (*expect)[(size_t)y * s->width + x] =
                    s->bits == 16 ? (float)(p[2 * x] << 8 | p[2 * x + 1]) : (float)p[x];
            }
    struct libdeflate_compressor *c = libdeflate_alloc_compressor(6);
    const size_t n = (size_t)rows * (row + 1), bound = libdeflate_zlib_compress_bound(c, n);
    unsigned char *z = malloc(bound);
    const size_t zlen = libdeflate_zlib_compress(c, out, n, z, bound);
    libdeflate_free_compressor(c);
    assert_true(zlen > 0);
    png_buf b = {0};
    put(&b, "\x89PNG\r\n\x1a\n", 8);
    unsigned char ihdr[13];
    for (int i = 0; i < 4; i++) {
        ihdr[i] = (unsigned char)((uint32_t)s->width >> (24 - 8 * i));
        ihdr[4 + i] = (unsigned char)((uint32_t)s->height >> (24 - 8 * i));
    }
    ihdr[8] = (unsigned char)s->bits;
    ihdr[9] = (unsigned char)s->colour;
    ihdr[10] = ihdr[11] = 0;
    ihdr[12] = (unsigned char)s->interlace;
    chunk(&b, "IHDR", ihdr, 13);
    if (s->colour == 3) {
        unsigned char plte[768];
        for (int i = 0; i < 768; i++)
            plte[i] = (unsigned char)i;
        chunk(&b, "PLTE", plte, 768);
    }
    if (s->ancillary) {
        const unsigned char data[4] = {0, 0, 0xb1, 0x8f}; // gAMA 1/2.2; sBIT 0; tRNS 0, 0
        chunk(&b, s->ancillary, data,
              !strcmp(s->ancillary, "sBIT")   ? 1
              : !strcmp(s->ancillary, "tRNS") ? 2
                                              : 4);
    }
    chunk(&b, "tEXt", "Comment\0made by test_png_gray", 29);
    const size_t step = s->idat_size > 0 ? (size_t)s->idat_size : zlen;
    for (size_t at = 0; at < zlen; at += step)
        chunk(&b, "IDAT", z + at, (uint32_t)(zlen - at < step ? zlen - at : step));
    if (s->idat_size == 7) chunk(&b, "IDAT", "", 0); // an empty one at the end
    chunk(&b, "IEND", "", 0);
    free(raw);
    free(out);
    free(z);
    return b;
}

// What image_read_channel gives for path (our reader, else OIIO) equals what OIIO
// gives: the same result and size, the same samples bit for bit or an error naming
// the file. Returns whether our reader took the file.
static int same_as_oiio(const char *path) {
    float *a = NULL, *b = NULL;
    int aw = 0, ah = 0, ak = -1, abits = 0, bw = 0, bh = 0, bk = -1, bbits = 0;
    char adesc[256] = "", bdesc[256] = "";
    og_error aerr = {{0}}, berr = {{0}};
    const int arc = image_read_channel(path, NULL, IMAGE_MAX_SIZE, &a, &aw, &ah, &ak, &abits, adesc,
                                       sizeof adesc, &aerr);
    const int brc = oiio_read_channel()(path, NULL, IMAGE_MAX_SIZE, &b, &bw, &bh, &bk, &bbits,
                                        bdesc, sizeof bdesc, &berr);
    if (arc != brc)
        fail_msg("%s: ours %d (%s), OIIO's %d (%s)", path, arc, aerr.msg, brc, berr.msg);
    if (arc == 0) {
        assert_int_equal(aw, bw);
        assert_int_equal(ah, bh);
        assert_int_equal(ak, bk);
        assert_int_equal(abits, bbits);
        assert_string_equal(adesc, bdesc);
        assert_memory_equal(a, b, sizeof(float) * (size_t)aw * (size_t)ah);
    } else {
        assert_non_null(strstr(aerr.msg, path));
    }
    free(a);
    free(b);
    float *c = NULL;
    int cw, ch, cbits;
    const int took = png_gray_read(path, IMAGE_MAX_SIZE, &c, &cw, &ch, &cbits);
    free(c);
    return took;
}

static void write_png(const char *path, const png_spec *s, uint32_t seed, float **expect) {
    png_buf b = make_png(s, seed, expect);
    test_write_file(path, b.data, b.len);
    free(b.data);
}

// Every filter, both depths, odd sizes, image data in many chunks, ancillary chunks
// that change nothing: read by our reader, to OIIO's samples and the expected ones.
static void test_reads_as_oiio(void **state) {
    (void)state;
    static const int sizes[][2] = {{1, 1}, {1, 7}, {5, 1}, {33, 17}, {200, 3}, {64, 64}};
    static const char *const harmless[] = {NULL, "gAMA", "pHYs"};
    int n = 0;
    for (int bits = 8; bits <= 16; bits += 8)
        for (int f = 0; f <= 5; f++)
            for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) {
                png_spec s = {sizes[k][0], sizes[k][1], bits, 0, 0, f, 0, 0, NULL, 0};
                s.noise = k == 4 && f == 0;     // its image data is larger than the rows
                s.idat_size = (int)(k % 3) * 7; // one chunk, 7 bytes, 14 bytes
                s.ancillary = harmless[(k + (size_t)f) % 3];
                const char *path = test_in_folder("g.png");
                float *expect;
                write_png(path, &s, (uint32_t)(k * 31 + (size_t)f), &expect);
                if (!same_as_oiio(path))
                    fail_msg("%d-bit %d x %d filter %d not read here", bits, s.width, s.height, f);
                float *v;
                int w, h, got_bits;
                assert_int_equal(png_gray_read(path, IMAGE_MAX_SIZE, &v, &w, &h, &got_bits), 1);
                assert_int_equal(got_bits, bits);
                assert_memory_equal(v, expect, sizeof(float) * (size_t)w * (size_t)h);
                free(v);
                free(expect);
                n++;
            }
    assert_int_equal(n, 72);
}

// Files this reader leaves to OIIO; image_read_channel still gives OIIO's result.
static void test_leaves_the_rest_to_oiio(void **state) {
    (void)state;
    static const png_spec others[] = {
        {20, 9, 16, 0, 1, 4, 0, 0, NULL, 0},   // interlaced
        {20, 9, 8, 2, 0, 4, 0, 0, NULL, 0},    // RGB
        {20, 9, 16, 4, 0, 4, 0, 0, NULL, 0},   // grey + alpha
        {20, 9, 8, 3, 0, 1, 0, 0, NULL, 0},    // palette
        {20, 9, 4, 0, 0, 1, 0, 0, NULL, 0},    // 4-bit grey
        {20, 9, 1, 0, 0, 0, 0, 0, NULL, 0},    // 1-bit grey
        {20, 9, 16, 0, 0, 4, 0, 0, "sBIT", 0}, // significant bits
        {20, 9, 16, 0, 0, 4, 0, 0, "tRNS", 0}, // a transparent grey
        {20, 9, 16, 0, 0, 6, 0, 0, NULL, 0},   // filter 5 on row 1
        {20, 9, 16, 0, 0, 4, 0, 1, NULL, 0},   // a row too many
        {20, 9, 16, 0, 0, 4, 0, -1, NULL, 0},  // a row short
    };
    for (size_t i = 0; i < sizeof others / sizeof *others; i++) {
        const char *path = test_in_folder("o.png");
        write_png(path, &others[i], (uint32_t)i, NULL);
        if (same_as_oiio(path)) fail_msg("case %zu read here, not by OIIO", i);
    }
}

// A wrong CRC (in the image data, in an ancillary chunk), no IEND, the file cut at
// every length, and a 1-byte change anywhere: our reader takes none of the broken
// files, and image_read_channel agrees with OIIO on all of them.
static void test_damage(void **state) {
    (void)state;
    png_spec s = {37, 23, 16, 0, 0, 5, 300, 0, "gAMA", 0};
    png_buf good = make_png(&s, 7, NULL);
    const char *path = test_in_folder("d.png");
    unsigned char *bad = malloc(good.len);
    // The last IDAT's CRC, then a byte of gAMA's data (gAMA's chunk starts at 33).
    memcpy(bad, good.data, good.len);
    bad[good.len - 12 - 1] ^= 1;
    test_write_file(path, bad, good.len);
    assert_int_equal(same_as_oiio(path), 0);
    memcpy(bad, good.data, good.len);
    bad[33 + 8 + 2] ^= 0x40;
    test_write_file(path, bad, good.len);
    assert_int_equal(same_as_oiio(path), 0);
    int taken = 0, cuts = 0;
    for (size_t len = 0; len < good.len; len += len < 64 ? 1 : 97, cuts++) {
        test_write_file(path, good.data, len);
        taken += same_as_oiio(path);
    }
    assert_int_equal(taken, 0);
    assert_true(cuts > 64);
    int changed = 0;
    uint32_t seed = 99;
    for (int i = 0; i < 300; i++) {
        memcpy(bad, good.data, good.len);
        seed = seed * 1664525u + 1013904223u;
        const size_t at = (seed >> 8) % good.len;
        bad[at] ^= (unsigned char)(1 + (seed >> 28));
        test_write_file(path, bad, good.len);
        // Every change breaks the signature, a CRC or the structure: none is taken.
        changed += !same_as_oiio(path);
    }
    assert_int_equal(changed, 300);
    free(bad);
    free(good.data);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reads_as_oiio),
        cmocka_unit_test(test_leaves_the_rest_to_oiio),
        cmocka_unit_test(test_damage),
    };
    return cmocka_run_group_tests(tests, test_folder_setup, test_folder_teardown);
}
