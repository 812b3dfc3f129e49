#include "editor/tools/box_blur.h"

#include "editor/tools/box_columns.h"
#include "editor/tools/box_rows.h"
#include "editor/tools/hot_loop.h"

#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

// Along rows, a block of rows is one flat array: a window's sum is a few adds of
// shifted copies, every loop vectorised, no transposes. Windows that wrap from one
// row into the next give values no kept sample uses.

// dst[i] = a[i] + a[i + shift]: the sums of 2p samples from those of p.
HOT_LOOP_WIDE static void add_shifted(float *dst, const float *a, int64_t shift, int64_t n) {
    for (int64_t i = 0; i < n; i++)
        dst[i] = a[i] + a[i + shift];
}

HOT_LOOP_WIDE static void add_arrays(float *dst, const float *a, const float *b, int64_t n) {
    for (int64_t i = 0; i < n; i++)
        dst[i] = a[i] + b[i];
}

HOT_LOOP_WIDE static void add_scaled(float *dst, const float *a, const float *b, float k,
                                     int64_t n) {
    for (int64_t i = 0; i < n; i++)
        dst[i] = (a[i] + b[i]) * k;
}

// dst[i + k] = mean of src[i .. i + length - 1] (length = 2k + 1 odd, >= 3), for
// every window inside [0, n). The window's sum is built from the sums
// of power-of-two runs (one pass per doubling), the runs taken low bit first: the
// additions, and so the rounding, are the same for every window. scratch: 3n floats.
static void box_pass(const float *src, float *dst, int64_t n, int length, float *scratch) {
    if (box_rows_wide(src, dst, n, length) == 0) return; // the same sums on registers
    int64_t windows = n - (length - 1), k = (length - 1) / 2;
    float inv = (float)(1.0 / length);
    float *runs[2] = {scratch, scratch + n}, *acc = scratch + 2 * n;
    const float *run = src; // sums of p samples from each start
    const float *sum = src; // sums of the runs of length's bits below p (bit 1 is set)
    int64_t covered = 1;
    for (int64_t p = 1; 2 * p <= length; p *= 2) {
        float *next = run == runs[0] ? runs[1] : runs[0];
        add_shifted(next, run, p, n - (2 * p - 1));
        run = next;
        if (!(length & 2 * p)) continue;
        if (covered + 2 * p == length) {
            add_scaled(dst + k, sum, run + covered, inv, windows);
            return;
        }
        add_arrays(acc, sum, run + covered, windows);
        sum = acc;
        covered += 2 * p;
    }
}

// Down columns, both boxes in one sweep: a running sum per column for the first box
// and one for the second over the first's rows (kept, rounded to float, in a ring of
// 2k + 2 rows), updated row by row, so the inner loop runs across independent columns
// and vectorises. In double: sums of floats are exact there, so the result does not
// depend on where the sum started. The additions are those of two separate passes in
// the same order (the second box's sum starts as its first 2k + 1 rows come).
// Columns [c0, c1) of the rows of src (w wide, h rows), rows [2k, h - 2k) of the result.
HOT_LOOP_WIDE static void first_rows(const float *src, int64_t w, int k, double *sum1, int64_t c0,
                                     int64_t c1) {
    for (int64_t x = c0; x < c1; x++)
        sum1[x] = 0.0;
    for (int64_t i = 0; i <= 2 * k; i++)
        for (int64_t x = c0; x < c1; x++)
            sum1[x] += src[i * w + x];
}

// One step down: the first box's row from sum1 (into ring row m, as a double), the
// second box's sum takes it and drops row old, its row goes to row, and sum1 moves on
// (adds row a, drops row r). Each column's operations run in the order of the two
// passes.
HOT_LOOP_WIDE static void column_step(double *restrict sum1, double *restrict sum2,
                                      double *restrict m, const double *restrict old,
                                      const float *restrict a, const float *restrict r, double inv,
                                      float *restrict row, int64_t c0, int64_t c1) {
    for (int64_t x = c0; x < c1; x++) {
        double mid = (double)(float)(sum1[x] * inv);
        m[x] = mid;
        double s = sum2[x] + (mid - old[x]);
        sum2[x] = s;
        row[x] = (float)(s * inv);
        sum1[x] += (double)a[x] - (double)r[x];
    }
}

// zero: a row of zeros (w doubles): while the second box's first 2k + 1 rows come,
// it drops nothing (x - 0 is x exactly, signed zeros too). Row z of the result goes to
// out's row z; the second box's rows before its first whole sum go to spare (w floats).
// The ring holds the first box's rows as doubles (each a float widened).
static void box_columns_twice(const float *src, float *out, int64_t w, int64_t h, int k,
                              double *sum1, double *sum2, double *ring, const double *zero,
                              float *spare, int64_t c0, int64_t c1) {
    double inv = 1.0 / (2 * k + 1);
    int64_t slots = 2 * k + 2;
    first_rows(src, w, k, sum1, c0, c1);
    for (int64_t x = c0; x < c1; x++)
        sum2[x] = 0.0;
    // Row i of the first box (i in [k, h - k)); the second's row i - k is done once
    // i >= 3k (before, its row goes to a ring row not yet used).
    for (int64_t i = k; i < h - k; i++) {
        double *m = ring + (i % slots) * w;
        const double *old = i - k > 2 * k ? ring + ((i - 2 * k - 1) % slots) * w : zero;
        // The first box's sum of rows [i - k, i + k] moves to [i - k + 1, i + k + 1]
        // (after the last row it is not read again: a - a leaves it).
        const float *r = src + (i - k) * w, *a = i + 1 < h - k ? src + (i + k + 1) * w : r;
        float *row = i >= 3 * k ? out + (i - k) * w : spare;
        column_step(sum1, sum2, m, old, a, r, inv, row, c0, c1);
    }
}

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

// Copies n samples of row y of a plain array (w floats a row) from column x0.
static void array_row(void *user, int64_t y, int64_t x0, int64_t n, float *dst) {
    const float *in = ((const float *const *)user)[0];
    int64_t w = (int64_t)(intptr_t)((const float *const *)user)[1];
    memcpy(dst, in + y * w + x0, (size_t)n * sizeof *dst);
}

int box_blur_twice(const float *in, float *out, int64_t w, int64_t h, int k) {
    const float *array[2] = {in, (const float *)(intptr_t)w};
    return box_blur_twice_rows(array_row, (void *)array, NULL, out, w, h, k);
}

// Strips of 16 columns from 2k (the last one narrower) that box_columns_wide sweeps.
static int64_t strip_count(int64_t w, int k) {
    return (w - 4 * k + 15) / 16;
}

// Whether a wanted result of row z lies in columns [c0, c1).
static int wants(const int64_t (*need)[2], int64_t z, int64_t c0, int64_t c1) {
    return need[z][0] < c1 && need[z][1] > c0 && need[z][0] < need[z][1];
}

// Where only some results are wanted (need): the rows [from[j], to[j]) strip j's column
// boxes take (those within 2k of a wanted result in it; from >= to: none), the first
// and last wanted rows found from each end.
static void strip_rows(const int64_t (*need)[2], int64_t w, int64_t h, int k, int64_t *from,
                       int64_t *to) {
    for (int64_t j = 0; j < strip_count(w, k); j++) {
        int64_t c0 = 2 * k + 16 * j, c1 = c0 + 16 < w - 2 * k ? c0 + 16 : w - 2 * k;
        int64_t first = 2 * k, last = h - 2 * k - 1;
        while (first <= last && !wants(need, first, c0, c1))
            first++;
        while (last > first && !wants(need, last, c0, c1))
            last--;
        from[j] = first - 2 * k, to[j] = first <= last ? last + 2 * k + 1 : 0;
    }
}

int box_blur_twice_rows(box_row_reader read, void *user, const int64_t (*need)[2], float *out,
                        int64_t w, int64_t h, int k) {
    int64_t n = w * h, length = 2 * k + 1;
    if (k < 1 || w <= 4 * k || h <= 4 * k) return 0; // no sample 2k inside every edge
    // Along rows in blocks of rows whose sums of runs fit the first-level cache, each
    // block's rows read into `input` as it comes.
    int64_t block = 2048 / w > 1 ? 2048 / w : 1, bmax = block * w;
    int64_t strips = strip_count(w, k);
    // runs: 3 blocks; a block's rows; a block's first box; the rows' result; the ring
    // of the first box down columns (doubles); a row of zeros (doubles); a spare row;
    // the two columns' sums (doubles); each row's start in the rows' result
    // (pointers); the strips' rows (int64)
    size_t at_input = lines(3 * bmax), at_first = at_input + lines(bmax);
    size_t at_mid = at_first + lines(bmax);
    size_t at_ring = at_mid + lines(n);
    // (2k + 2) rows of doubles, w wide (or 16 for box_columns_wide's strips)
    size_t at_zero = at_ring + lines(2 * (2 * k + 2) * (w > 16 ? w : 16));
    size_t at_spare = at_zero + lines(2 * w), at_sums = at_spare + lines(w);
    size_t at_rows = at_sums + lines(4 * w), at_strips = at_rows + lines(2 * h);
    size_t floats = at_strips + lines(4 * strips);
    float *scratch = thread_scratch(floats);
    if (!scratch) return -1;
    float *input = scratch + at_input, *first = scratch + at_first, *mid = scratch + at_mid;
    double *ring = (double *)(scratch + at_ring);
    const float **rows = (const float **)(void *)(scratch + at_rows);
    int64_t *from = (int64_t *)(void *)(scratch + at_strips), *to = from + strips;
    // Only some results wanted (a disc's): each block of rows is blurred over the
    // columns of the strips its rows feed, one after the other in mid (rows[y] + x: row
    // y at column x), and each strip's column boxes run over its own rows only.
    int banded = need && box_columns_have_wide();
    if (banded) strip_rows(need, w, h, k, from, to);
    // Each pass's results start k samples (k rows) further in and end as many earlier.
    float *band = mid;
    for (int64_t z0 = 0; z0 < h; z0 += block) {
        int64_t count = h - z0 < block ? h - z0 : block, x0 = 0, bw = w;
        if (banded) { // the strips that take some of the block's rows
            int64_t jl = strips, jh = -1;
            for (int64_t j = 0; j < strips; j++)
                if (from[j] < z0 + count && to[j] > z0) {
                    jl = j < jl ? j : jl;
                    jh = j;
                }
            if (jl > jh) continue; // none
            int64_t end = 2 * k + 16 * (jh + 1) < w - 2 * k ? 2 * k + 16 * (jh + 1) : w - 2 * k;
            x0 = 16 * jl, bw = end + 2 * k - x0; // columns [2k + 16 jl - 2k, end + 2k)
        }
        for (int64_t z = 0; z < count; z++) {
            read(user, z0 + z, x0, bw, input + z * bw);
            rows[z0 + z] = band + z * bw - x0;
        }
        box_pass(input, first, count * bw, (int)length, scratch);
        box_pass(first + k, band + k, count * bw - 2 * k, (int)length, scratch);
        band += count * bw;
    }
    if (banded) {
        for (int64_t j = 0; j < strips; j++) {
            int64_t c0 = 2 * k + 16 * j, c1 = c0 + 16 < w - 2 * k ? c0 + 16 : w - 2 * k;
            box_columns_wide(rows, out, w, k, ring, c0, c1, from[j], to[j]);
        }
        return 0;
    }
    if (box_columns_wide(rows, out, w, k, ring, 2 * k, w - 2 * k, 0, h) == 0) return 0;
    double *sums = (double *)(scratch + at_sums);
    double *zero = (double *)(scratch + at_zero);
    memset(zero, 0, (size_t)w * sizeof *zero);
    box_columns_twice(mid, out, w, h, k, sums, sums + w, ring, zero, scratch + at_spare, 2 * k,
                      w - 2 * k);
    return 0;
}
