#include "editor/tools/box_blur.h"

#include "editor/tools/box_columns.h"
#include "editor/tools/box_rows.h"

#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

// The blur's buffers, one per thread, kept for its life: a dab's (500 KB at r = 64)
// allocated afresh came from the kernel each time, and its page faults cost more than
// the blur.
typedef struct scratch {
    float *data;
    size_t size;
} scratch;

enum { KEEP_FLOATS = 1 << 20 };

static pthread_key_t scratch_key;
static pthread_once_t scratch_once = PTHREAD_ONCE_INIT;

static void free_scratch(void *p) {
    scratch *s = p;
    free(s->data);
    free(s);
}

static void make_scratch_key(void) {
    pthread_key_create(&scratch_key, free_scratch);
}

static float *thread_scratch(size_t floats) {
    pthread_once(&scratch_once, make_scratch_key);
    scratch *s = pthread_getspecific(scratch_key);
    if (!s) {
        if (!(s = calloc(1, sizeof *s))) return NULL;
        if (pthread_setspecific(scratch_key, s) != 0) {
            free(s);
            return NULL;
        }
    }
    // A large dab's buffers (a radius of 512 takes 33 MB) go back at the next smaller one.
    if (s->size < floats || (s->size > KEEP_FLOATS && floats <= KEEP_FLOATS)) {
        free(s->data);
        s->size = 0;
        if (!(s->data = malloc(floats * sizeof *s->data))) return NULL;
        s->size = floats;
    }
    return s->data;
}

// Floats rounded up to whole cache lines, so every buffer starts on one.
static size_t lines(int64_t floats) {
    return ((size_t)floats + 15) & ~(size_t)15;
}

// A plain array's row y from column x (w floats a row), contiguous to its end.
static const float *array_row(void *user, int64_t y, int64_t x, int64_t *end) {
    const float *in = ((const float *const *)user)[0];
    int64_t w = (int64_t)(intptr_t)((const float *const *)user)[1];
    *end = w;
    return in + y * w + x;
}

static int blur(box_row_at at, void *user, const int64_t (*need)[2], float *out, int64_t *row_at,
                int64_t w, int64_t h, int k);

int box_blur_twice(const float *in, float *out, int64_t w, int64_t h, int k) {
    const float *array[2] = {in, (const float *)(intptr_t)w};
    return blur(array_row, (void *)array, NULL, out, NULL, w, h, k);
}

// Whether row z wants a result in columns [c0, c1) or within 2k of them (the row boxes
// of a wanted result read the column boxes' results 2k either side).
static int feeds(const int64_t (*need)[2], int64_t z, int k, int64_t c0, int64_t c1) {
    return need[z][0] < need[z][1] && need[z][0] - 2 * k < c1 && need[z][1] + 2 * k > c0;
}

enum { CHUNK = BOX_COLUMNS_WIDTH }; // columns box_columns takes at a time on AVX-512

// The columns [c0, c1) of chunk j of a run from column r0.
static void chunk_columns(int64_t r0, int64_t r1, int64_t j, int64_t *c0, int64_t *c1) {
    *c0 = r0 + CHUNK * j, *c1 = *c0 + CHUNK < r1 ? *c0 + CHUNK : r1;
}

// The result rows [*first, *last] whose row boxes read columns [c0, c1) (first > last:
// none).
static void chunk_rows(const int64_t (*need)[2], int64_t h, int k, int64_t c0, int64_t c1,
                       int64_t *first, int64_t *last) {
    *first = 2 * k, *last = h - 2 * k - 1;
    if (!need) return;
    while (*first <= *last && !feeds(need, *first, k, c0, c1))
        ++*first;
    while (*last > *first && !feeds(need, *last, k, c0, c1))
        --*last;
}

// Column runs: [0, w) split where the source's rows stop being contiguous (tile edges).
static int64_t run_end(box_row_at at, void *user, int64_t x) {
    int64_t end;
    at(user, 0, x, &end);
    return end;
}

// Down the columns first (in chunks of CHUNK columns, each over the rows whose row
// boxes read it), the results packed row after row (row z's columns keep[z]: those
// its wanted results' row boxes read); then along the packed rows in blocks of a
// few thousand samples (windows that run from one row into the next give values no
// wanted result takes), each wanted result copied to out.
// row_at NULL: results copied to out as a w x h area; else left packed in out (row z's
// column x at out[row_at[z] + x]).
static int blur(box_row_at at, void *user, const int64_t (*need)[2], float *out, int64_t *row_at,
                int64_t w, int64_t h, int k) {
    int64_t length = 2 * k + 1;
    if (k < 1 || w <= 4 * k || h <= 4 * k) return 0; // no sample 2k inside every edge
    if (length >= (1 << BOX_ROWS_LEVELS)) return -1; // past any brush's radius
    enum { BLOCK = 2048 };
    // The four boxes' sums are scaled once, at the end, to their mean.
    const float scale = (float)(1.0 / ((double)length * length * length * length));
    int64_t bmax = BLOCK + w;
    // packed rows; the pointers to the area's rows (a run's) and to the packed rows; the
    // packed rows' columns (keep, int64); box_columns' ring; a block's first box and
    // result; box_rows' runs
    size_t at_src = lines(w * h), at_dst = at_src + lines(2 * h), at_keep = at_dst + lines(2 * h);
    size_t at_ring = at_keep + lines(4 * h),
           at_first = at_ring + lines((2 * k + 2) * BOX_COLUMNS_WIDTH);
    size_t at_res = at_first + lines(bmax), at_runs = at_res + lines(bmax);
    // and each chunk's rows (f, l: int64; fewer chunks than w + 2)
    size_t at_chunks = at_runs + lines((BOX_ROWS_LEVELS + 1) * bmax);
    float *scratch = thread_scratch(at_chunks + lines(4 * (w + 2)));
    if (!scratch) return -1;
    float *packed = scratch, *ring = scratch + at_ring;
    float *first = scratch + at_first, *res = scratch + at_res;
    const float **src = (const float **)(void *)(scratch + at_src);
    float **dst = (float **)(void *)(scratch + at_dst);
    // Row z's packed columns: [keep[z][0], keep[z][1]), those its wanted results' row
    // boxes read (none for a row without any); the column boxes write only those.
    int64_t(*keep)[2] = (int64_t(*)[2])(void *)(scratch + at_keep);
    int64_t(*rows)[2] = (int64_t(*)[2])(void *)(scratch + at_chunks); // chunk c's f, l
    for (int64_t z = 0; z < h; z++) {
        int64_t x0 = need ? need[z][0] : 2 * k, x1 = need ? need[z][1] : w - 2 * k;
        x0 = x0 > 2 * k ? x0 : 2 * k, x1 = x1 < w - 2 * k ? x1 : w - 2 * k;
        int wanted = z >= 2 * k && z < h - 2 * k && x0 < x1;
        keep[z][0] = wanted ? x0 - 2 * k : 0, keep[z][1] = wanted ? x1 + 2 * k : 0;
    }
    for (int64_t r0 = 0, r1, c = 0; r0 < w; r0 = r1) {
        r1 = run_end(at, user, r0);
        for (int64_t j = 0; r0 + CHUNK * j < r1; j++, c++) {
            int64_t c0, c1;
            chunk_columns(r0, r1, j, &c0, &c1);
            chunk_rows(need, h, k, c0, c1, &rows[c][0], &rows[c][1]);
        }
    }
    for (int64_t z = 0, p = 0; z < h; z++) {
        dst[z] = packed + p - keep[z][0];
        p += keep[z][1] - keep[z][0];
    }
    for (int64_t r0 = 0, r1, c = 0; r0 < w; r0 = r1) {
        r1 = run_end(at, user, r0);
        for (int64_t y = 0; y < h; y++)
            src[y] = at(user, y, r0, &r1) - r0;
        for (int64_t j = 0; r0 + CHUNK * j < r1; j++, c++) {
            int64_t c0, c1;
            chunk_columns(r0, r1, j, &c0, &c1);
            if (rows[c][0] <= rows[c][1])
                box_columns(src, dst, (const int64_t(*)[2])keep, k, ring, c0, c1, rows[c][0],
                            rows[c][1] + 1);
        }
    }
    // Rows with wanted results, consecutive ones in a block.
    for (int64_t z = 2 * k; z < h - 2 * k;) {
        int64_t z1 = z, n = 0;
        while (z1 < h - 2 * k && n < BLOCK) {
            int64_t x0 = need ? need[z1][0] : 2 * k, x1 = need ? need[z1][1] : w - 2 * k;
            if (x0 >= x1 || x1 <= 2 * k || x0 >= w - 2 * k) break;
            n += keep[z1][1] - keep[z1][0], z1++;
        }
        if (z1 == z) {
            z++;
            continue;
        }
        float *block = dst[z] + keep[z][0];
        float *into = row_at ? out + (block - packed) : res; // where block[i]'s result goes
        box_rows(block, first, n, (int)length, 1.0f, scratch + at_runs);
        box_rows(first + k, into + k, n - 2 * k, (int)length, scale, scratch + at_runs);
        if (row_at) {
            for (; z < z1; z++)
                row_at[z] = dst[z] - packed;
            continue;
        }
        for (; z < z1; z++) {
            int64_t x0 = need ? need[z][0] : 2 * k, x1 = need ? need[z][1] : w - 2 * k;
            x0 = x0 > 2 * k ? x0 : 2 * k, x1 = x1 < w - 2 * k ? x1 : w - 2 * k;
            memcpy(out + z * w + x0, res + (dst[z] + x0 - block), (size_t)(x1 - x0) * sizeof *out);
        }
    }
    return 0;
}

int box_blur_twice_rows(box_row_at at, void *user, const int64_t (*need)[2], float *out, int64_t w,
                        int64_t h, int k) {
    return blur(at, user, need, out, NULL, w, h, k);
}

int box_blur_twice_packed(box_row_at at, void *user, const int64_t (*need)[2], float *out,
                          int64_t *row_at, int64_t w, int64_t h, int k) {
    return blur(at, user, need, out, row_at, w, h, k);
}
