#include "editor/tools/box_blur.h"

#include "editor/tools/hot_loop.h"

#include <pthread.h>
#include <stdlib.h>

// Along rows, a block of rows is one flat array: a window's sum is a few adds of
// shifted copies, every loop vectorised, no transposes. Windows that wrap from one
// row into the next give values no kept sample uses.

// dst[i] = a[i] + a[i + shift]: the sums of 2p samples from those of p.
HOT_LOOP static void add_shifted(float *dst, const float *a, int64_t shift, int64_t n) {
    for (int64_t i = 0; i < n; i++)
        dst[i] = a[i] + a[i + shift];
}

HOT_LOOP static void add_arrays(float *dst, const float *a, const float *b, int64_t n) {
    for (int64_t i = 0; i < n; i++)
        dst[i] = a[i] + b[i];
}

HOT_LOOP static void add_scaled(float *dst, const float *a, const float *b, float k, int64_t n) {
    for (int64_t i = 0; i < n; i++)
        dst[i] = (a[i] + b[i]) * k;
}

// dst[i + k] = mean of src[i .. i + length - 1] (length = 2k + 1 odd, >= 3), for
// every window inside [0, n). The window's sum is built from the sums
// of power-of-two runs (one pass per doubling), the runs taken low bit first: the
// additions, and so the rounding, are the same for every window. scratch: 3n floats.
static void box_pass(const float *src, float *dst, int64_t n, int length, float *scratch) {
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

// Down columns: a running sum per column, updated row by row, so the inner loops run
// across independent columns and vectorise. In double: sums of floats are exact there,
// so the result does not depend on where the sum started. Rows [r0, r1), columns
// [c0, c1) of dst.
HOT_LOOP static void box_columns(const float *src, float *dst, int64_t w, int k, double *sum,
                                 int64_t r0, int64_t r1, int64_t c0, int64_t c1) {
    double inv = 1.0 / (2 * k + 1);
    for (int64_t x = c0; x < c1; x++)
        sum[x] = 0.0;
    for (int64_t i = r0 - k; i <= r0 + k; i++)
        for (int64_t x = c0; x < c1; x++)
            sum[x] += src[i * w + x];
    for (int64_t i = r0; i < r1; i++) {
        float *o = dst + i * w;
        for (int64_t x = c0; x < c1; x++)
            o[x] = (float)(sum[x] * inv);
        if (i + 1 == r1) break;
        const float *a = src + (i + k + 1) * w, *r = src + (i - k) * w;
        for (int64_t x = c0; x < c1; x++)
            sum[x] += (double)a[x] - (double)r[x];
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

const float *box_blur_twice(const float *in, int64_t w, int64_t h, int k) {
    int64_t n = w * h, length = 2 * k + 1;
    float *scratch = k >= 1 ? thread_scratch((size_t)n * 5) : NULL;
    if (!scratch) return NULL;
    float *mid = scratch + 3 * n, *out = scratch + 4 * n;
    if (w <= 4 * k || h <= 4 * k) return out; // no sample 2k inside every edge
    // Each pass's results start k samples (k rows) further in and end as many earlier.
    // Along rows in blocks of rows whose sums of runs fit the first-level cache.
    int64_t block = 2048 / w > 1 ? 2048 / w : 1;
    for (int64_t z0 = 0; z0 < h; z0 += block) {
        int64_t rows = h - z0 < block ? h - z0 : block, bn = rows * w;
        box_pass(in + z0 * w, mid, bn, (int)length, scratch);
        box_pass(mid + k, out + z0 * w + k, bn - 2 * k, (int)length, scratch);
    }
    double *sum = (double *)scratch; // the runs are done with
    box_columns(out, mid, w, k, sum, k, h - k, 2 * k, w - 2 * k);
    box_columns(mid, out, w, k, sum, 2 * k, h - 2 * k, 2 * k, w - 2 * k);
    return out;
}
