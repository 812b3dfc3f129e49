#include "io/png_gray.h"

#include <fcntl.h>
#include <libdeflate.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

// The most samples read here (as RASTER_MAX_SAMPLES): larger files go to OpenImageIO.
#define MOST_SAMPLES ((uint64_t)1 << 30)

static uint32_t be32(const unsigned char *p) {
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

typedef struct header {
    uint32_t width, height;
    int bits;
} header;

// Checks the chunks (names, CRCs, order) and gathers the IDAT payloads at the start of
// the buffer, in place. 0 with *idat_len set, or -1: not a file this reader takes.
static int gather(unsigned char *file, size_t len, int max_size, header *h, size_t *idat_len) {
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (len < 8 || memcmp(file, signature, 8) != 0) return -1;
    size_t pos = 8, out = 0;
    int chunks = 0, idat_state = 0; // 0: none yet, 1: in the IDAT run, 2: after it
    for (;;) {
        if (len - pos < 12) return -1; // no IEND
        const uint32_t n = be32(file + pos);
        if (n > 0x7fffffffu || len - pos - 12 < n) return -1;
        const unsigned char *type = file + pos + 4, *data = type + 4;
        for (int i = 0; i < 4; i++)
            if (!((type[i] >= 'A' && type[i] <= 'Z') || (type[i] >= 'a' && type[i] <= 'z')))
                return -1;
        if (libdeflate_crc32(0, type, n + 4) != be32(data + n)) return -1;
        const int is_idat = !memcmp(type, "IDAT", 4);
        if (chunks++ == 0) {
            // IHDR: greyscale of 8 or 16 bits, deflate, adaptive filters, not interlaced.
            if (memcmp(type, "IHDR", 4) != 0 || n != 13) return -1;
            h->width = be32(data);
            h->height = be32(data + 4);
            h->bits = data[8];
            if (h->width < 1 || h->height < 1 || h->width > (uint32_t)max_size ||
                h->height > (uint32_t)max_size || (uint64_t)h->width * h->height > MOST_SAMPLES ||
                (h->bits != 8 && h->bits != 16) || data[9] != 0 || data[10] != 0 || data[11] != 0 ||
                data[12] != 0)
                return -1;
        } else if (is_idat) {
            if (idat_state == 2) return -1; // a second run of IDAT chunks
            idat_state = 1;
            memmove(file + out, data, n); // out <= the payload's offset: gathered in place
            out += n;
        } else if (!memcmp(type, "IEND", 4)) {
            if (idat_state == 0) return -1;
            *idat_len = out;
            return 0;
        } else {
            if (idat_state == 1) idat_state = 2;
            // Critical chunks (PLTE, a second IHDR, unknown ones) and the two ancillary
            // ones that change what OpenImageIO reads (significant bits, transparency).
            if ((type[0] & 0x20) == 0 || !memcmp(type, "sBIT", 4) || !memcmp(type, "tRNS", 4))
                return -1;
        }
        pos += 12 + (size_t)n;
    }
}

// PNG's Paeth predictor (a left, b above, c above left; ties to a, then b), without
// branches: which one wins depends on the data, and a mispredicted branch per byte
// would cost more than the arithmetic.
static int paeth(int a, int b, int c) {
    const int pa = abs(b - c), pb = abs(a - c), pc = abs(a + b - 2 * c);
    const int take_b = -(pb < pa), least = (pa & ~take_b) | (pb & take_b);
    const int took = (a & ~take_b) | (b & take_b), take_c = -(pc < least);
    return (took & ~take_c) | (c & take_c);
}

// Paeth's filter, the left pixel and the one above it kept in registers (through memory,
// every byte would wait for the store of the one before: twice as slow).
static void paeth2(unsigned char *row, const unsigned char *src, const unsigned char *up,
                   size_t n) {
    int a0 = 0, a1 = 0, c0 = 0, c1 = 0;
    for (size_t i = 0; i < n; i += 2) {
        const int b0 = up[i], b1 = up[i + 1];
        a0 = (src[i] + paeth(a0, b0, c0)) & 0xff;
        a1 = (src[i + 1] + paeth(a1, b1, c1)) & 0xff;
        row[i] = (unsigned char)a0;
        row[i + 1] = (unsigned char)a1;
        c0 = b0, c1 = b1;
    }
}

// Two rows, both Paeth-filtered, in one pass with the second a pixel behind (it needs
// the first's pixel above and above-left): four independent chains of dependent bytes
// instead of two, which the processor runs side by side.
static void paeth2_pair(unsigned char *row0, const unsigned char *src0, unsigned char *row1,
                        const unsigned char *src1, const unsigned char *up, size_t n) {
    int a0 = (src0[0] + up[0]) & 0xff, a1 = (src0[1] + up[1]) & 0xff; // Paeth(0, b, 0) = b
    int c0 = up[0], c1 = up[1], d0 = 0, d1 = 0, e0 = 0, e1 = 0;       // d: row 1's left, e: its c
    row0[0] = (unsigned char)a0;
    row0[1] = (unsigned char)a1;
    for (size_t i = 2; i < n; i += 2) {
        const int above0 = a0, above1 = a1, b0 = up[i], b1 = up[i + 1];
        a0 = (src0[i] + paeth(a0, b0, c0)) & 0xff;
        a1 = (src0[i + 1] + paeth(a1, b1, c1)) & 0xff;
        row0[i] = (unsigned char)a0;
        row0[i + 1] = (unsigned char)a1;
        c0 = b0, c1 = b1;
        d0 = (src1[i - 2] + paeth(d0, above0, e0)) & 0xff;
        d1 = (src1[i - 1] + paeth(d1, above1, e1)) & 0xff;
        row1[i - 2] = (unsigned char)d0;
        row1[i - 1] = (unsigned char)d1;
        e0 = above0, e1 = above1;
    }
    row1[n - 2] = (unsigned char)(src1[n - 2] + paeth(d0, a0, e0));
    row1[n - 1] = (unsigned char)(src1[n - 1] + paeth(d1, a1, e1));
}

static void paeth1(unsigned char *row, const unsigned char *src, const unsigned char *up,
                   size_t n) {
    int a = 0, c = 0;
    for (size_t i = 0; i < n; i++) {
        const int b = up[i];
        a = (src[i] + paeth(a, b, c)) & 0xff;
        row[i] = (unsigned char)a;
        c = b;
    }
}

// Undoes the filter of src (PNG's five, bpp bytes per pixel) into row, given the
// unfiltered row above (zeros above the first). -1 on an unknown filter.
static int unfilter(int filter, unsigned char *row, const unsigned char *src,
                    const unsigned char *up, size_t n, int bpp) {
    size_t i;
    switch (filter) {
    case 0:
        memcpy(row, src, n);
        return 0;
    case 1:
        memcpy(row, src, (size_t)bpp);
        for (i = (size_t)bpp; i < n; i++)
            row[i] = (unsigned char)(src[i] + row[i - bpp]);
        return 0;
    case 2:
        for (i = 0; i < n; i++)
            row[i] = (unsigned char)(src[i] + up[i]);
        return 0;
    case 3:
        for (i = 0; i < (size_t)bpp; i++)
            row[i] = (unsigned char)(src[i] + (up[i] >> 1));
        for (; i < n; i++)
            row[i] = (unsigned char)(src[i] + ((row[i - bpp] + up[i]) >> 1));
        return 0;
    case 4:
        if (bpp == 2)
            paeth2(row, src, up, n);
        else
            paeth1(row, src, up, n);
        return 0;
    default:
        return -1;
    }
}

// Unfilters the inflated rows (each a filter byte and n bytes) and converts them to
// floats. rows may lie inside out's last bytes: row y's floats end before row y + 1's
// bytes begin, and each row is unfiltered into a buffer of its own before its floats
// are written.
static int convert(const unsigned char *rows, const header *h, float *out) {
    const int bpp = h->bits / 8;
    const size_t n = (size_t)h->width * (size_t)bpp;
    unsigned char *buffers = calloc(3, n), *up = buffers, *row = buffers + n, *next = row + n;
    if (!buffers) return -1;
    int rc = 0;
    for (size_t y = 0; y < h->height && rc == 0;) {
        const unsigned char *src = rows + y * (n + 1);
        // Two Paeth rows of 16 bits at once (the usual case), else one row.
        const size_t count =
            bpp == 2 && y + 1 < h->height && src[0] == 4 && src[n + 1] == 4 ? 2 : 1;
        if (count == 2)
            paeth2_pair(row, src + 1, next, src + n + 2, up, n);
        else
            rc = unfilter(src[0], row, src + 1, up, n, bpp);
        for (size_t k = 0; k < count; k++, y++) {
            const unsigned char *r = k ? next : row;
            float *o = out + y * h->width;
            if (bpp == 2)
                for (size_t x = 0; x < h->width; x++)
                    o[x] = (float)((unsigned)r[2 * x] << 8 | r[2 * x + 1]);
            else
                for (size_t x = 0; x < h->width; x++)
                    o[x] = (float)r[x];
        }
        unsigned char *t = up;
        if (count == 2)
            up = next, next = t;
        else
            up = row, row = t;
    }
    free(buffers);
    return rc;
}

// The first 24 bytes: the signature and IHDR's size and start.
static int peek_size(int fd, uint32_t *width, uint32_t *height) {
    unsigned char b[24];
    if (pread(fd, b, sizeof b, 0) != (ssize_t)sizeof b || memcmp(b, "\x89PNG\r\n\x1a\n", 8) ||
        memcmp(b + 12, "IHDR", 4))
        return -1;
    *width = be32(b + 16);
    *height = be32(b + 20);
    return 0;
}

static int read_all(int fd, unsigned char *to, size_t len) {
    for (size_t got = 0; got < len;) {
        ssize_t n = pread(fd, to + got, len - got, (off_t)got);
        if (n <= 0) return -1; // shrank, or cannot be read: OpenImageIO says what happened
        got += (size_t)n;
    }
    return 0;
}

// malloc, asking for 2 MiB pages (a hint: transparent huge pages set to "madvise"): a
// 4097^2 raster's 67 MB otherwise take 16 000 page faults, 30-50 ms of a process
// whose work is 0.2 s.
static unsigned char *big_buffer(size_t len) {
    unsigned char *p = malloc(len);
    const uintptr_t huge = (uintptr_t)2 << 20, from = ((uintptr_t)p + huge - 1) & ~(huge - 1),
                    to = ((uintptr_t)p + len) & ~(huge - 1);
    if (p && to > from) madvise((void *)from, to - from, MADV_HUGEPAGE);
    return p;
}

// One buffer, the floats', holds the file, then its image data gathered at its start
// and the inflated rows at its end: fresh memory costs a page fault per 4 KiB, as much
// as inflating it (a 4097^2 16-bit PNG: 67 MB instead of 119 MB).
int png_gray_read(const char *path, int max_size, float **samples, int *width, int *height,
                  int *bits) {
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return 0;
    struct stat st;
    uint32_t w = 0, h_ = 0;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || peek_size(fd, &w, &h_) != 0 || w < 1 ||
        h_ < 1 || w > (uint32_t)max_size || h_ > (uint32_t)max_size ||
        (uint64_t)w * h_ > MOST_SAMPLES) {
        close(fd);
        return 0;
    }
    const size_t out_len = sizeof(float) * (size_t)w * (size_t)h_, len = (size_t)st.st_size;
    unsigned char *out = big_buffer(out_len), *file = len <= out_len ? out : malloc(len);
    unsigned char *idat = NULL;
    int ok = out && file && read_all(fd, file, len) == 0;
    close(fd);
    header h = {0, 0, 0};
    size_t idat_len = 0;
    ok = ok && gather(file, len, max_size, &h, &idat_len) == 0 && h.width == w && h.height == h_;
    const size_t rows_len =
        ok ? (size_t)h.height * ((size_t)h.width * (size_t)(h.bits / 8) + 1) : 0;
    unsigned char *rows = ok ? out + out_len - rows_len : NULL; // rows_len <= out_len
    // Image data that would overlap the rows (hardly compressed) moves out of the way.
    idat = !ok ? NULL : file != out || idat_len <= out_len - rows_len ? file : malloc(idat_len);
    if (idat && idat != file) memcpy(idat, file, idat_len);
    struct libdeflate_decompressor *d = idat ? libdeflate_alloc_decompressor() : NULL;
    // Exactly the image's bytes, the zlib checksum right (libpng's own checks).
    ok = d &&
         libdeflate_zlib_decompress(d, idat, idat_len, rows, rows_len, NULL) == LIBDEFLATE_SUCCESS;
    if (d) libdeflate_free_decompressor(d);
    if (idat != file) free(idat);
    if (file != out) free(file);
    ok = ok && convert(rows, &h, (float *)(void *)out) == 0;
    if (!ok) {
        free(out);
        return 0;
    }
    *samples = (float *)(void *)out;
    *width = (int)h.width;
    *height = (int)h.height;
    *bits = h.bits;
    return 1;
}
