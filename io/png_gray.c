#include "io/png_gray.h"

#include <fcntl.h>
#include <libdeflate.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

// The most samples read here (as RASTER_MAX_SAMPLES): larger files go to OpenImageIO.
#define MOST_SAMPLES ((uint64_t)1 << 30)

static uint32_t be32(const unsigned char *p) {
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

// The whole of a regular file, or NULL.
static unsigned char *read_whole(const char *path, size_t *len) {
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return NULL;
    struct stat st;
    unsigned char *data = NULL;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0 &&
        (uint64_t)st.st_size < ((uint64_t)1 << 40))
        data = malloc((size_t)st.st_size);
    size_t got = 0;
    while (data && got < (size_t)st.st_size) {
        ssize_t n = read(fd, data + got, (size_t)st.st_size - got);
        if (n <= 0) { // shrank, or cannot be read: OpenImageIO says what happened
            free(data);
            data = NULL;
        } else {
            got += (size_t)n;
        }
    }
    close(fd);
    *len = got;
    return data;
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
static void paeth2(unsigned char *row, const unsigned char *up, size_t n) {
    int a0 = 0, a1 = 0, c0 = 0, c1 = 0;
    for (size_t i = 0; i < n; i += 2) {
        const int b0 = up[i], b1 = up[i + 1];
        a0 = (row[i] + paeth(a0, b0, c0)) & 0xff;
        a1 = (row[i + 1] + paeth(a1, b1, c1)) & 0xff;
        row[i] = (unsigned char)a0;
        row[i + 1] = (unsigned char)a1;
        c0 = b0, c1 = b1;
    }
}

static void paeth1(unsigned char *row, const unsigned char *up, size_t n) {
    int a = 0, c = 0;
    for (size_t i = 0; i < n; i++) {
        const int b = up[i];
        a = (row[i] + paeth(a, b, c)) & 0xff;
        row[i] = (unsigned char)a;
        c = b;
    }
}

// Undoes row's filter (PNG's five, bpp bytes per pixel) given the unfiltered row above
// (zeros above the first). -1 on an unknown filter.
static int unfilter(int filter, unsigned char *row, const unsigned char *up, size_t n, int bpp) {
    size_t i;
    switch (filter) {
    case 0:
        return 0;
    case 1:
        for (i = (size_t)bpp; i < n; i++)
            row[i] = (unsigned char)(row[i] + row[i - bpp]);
        return 0;
    case 2:
        for (i = 0; i < n; i++)
            row[i] = (unsigned char)(row[i] + up[i]);
        return 0;
    case 3:
        for (i = 0; i < (size_t)bpp; i++)
            row[i] = (unsigned char)(row[i] + (up[i] >> 1));
        for (; i < n; i++)
            row[i] = (unsigned char)(row[i] + ((row[i - bpp] + up[i]) >> 1));
        return 0;
    case 4:
        if (bpp == 2)
            paeth2(row, up, n);
        else
            paeth1(row, up, n);
        return 0;
    default:
        return -1;
    }
}

// Unfilters the inflated rows in place and converts them to floats.
static int convert(unsigned char *rows, const header *h, float *out) {
    const int bpp = h->bits / 8;
    const size_t n = (size_t)h->width * (size_t)bpp;
    unsigned char *zeros = calloc(n, 1);
    if (!zeros) return -1;
    const unsigned char *up = zeros;
    int rc = 0;
    for (size_t y = 0; y < h->height && rc == 0; y++) {
        unsigned char *row = rows + y * (n + 1);
        rc = unfilter(row[0], row + 1, up, n, bpp);
        up = row + 1;
        float *o = out + y * h->width;
        if (bpp == 2)
            for (size_t x = 0; x < h->width; x++)
                o[x] = (float)((unsigned)up[2 * x] << 8 | up[2 * x + 1]);
        else
            for (size_t x = 0; x < h->width; x++)
                o[x] = (float)up[x];
    }
    free(zeros);
    return rc;
}

int png_gray_read(const char *path, int max_size, float **samples, int *width, int *height,
                  int *bits) {
    size_t len = 0, idat_len = 0;
    unsigned char *file = read_whole(path, &len), *rows = NULL;
    float *out = NULL;
    header h = {0, 0, 0};
    int ok = file && gather(file, len, max_size, &h, &idat_len) == 0;
    const size_t rows_len =
        ok ? (size_t)h.height * ((size_t)h.width * (size_t)(h.bits / 8) + 1) : 0;
    if (ok) {
        rows = malloc(rows_len);
        out = malloc(sizeof(float) * (size_t)h.width * (size_t)h.height);
    }
    struct libdeflate_decompressor *d = rows && out ? libdeflate_alloc_decompressor() : NULL;
    // Exactly the image's bytes, the zlib checksum right (libpng's own checks).
    ok = d &&
         libdeflate_zlib_decompress(d, file, idat_len, rows, rows_len, NULL) == LIBDEFLATE_SUCCESS;
    if (d) libdeflate_free_decompressor(d);
    free(file);
    ok = ok && convert(rows, &h, out) == 0;
    free(rows);
    if (!ok) {
        free(out);
        return 0;
    }
    *samples = out;
    *width = (int)h.width;
    *height = (int)h.height;
    *bits = h.bits;
    return 1;
}
