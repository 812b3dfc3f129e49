#include "editor/tools/erosion.h"

#include "editor/edit/parallel.h"
#include "editor/tools/hot_loop.h"
#include "io/progress.h"

#include <math.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

// Clamps a weight to [0, 1]; NaN and negatives become 0.
static inline float wclamp(float w) {
    const float a = w > 0.0f ? w : 0.0f;
    return a < 1.0f ? a : 1.0f;
}

// c ? a : b through the bits. With -ftrapping-math (our default) GCC will not turn a
// select whose arms do arithmetic into a vector blend; this form it does vectorise.
static inline float select_bits(int c, float a, float b) {
    uint32_t ua, ub, m = 0u - (uint32_t)(c != 0);
    memcpy(&ua, &a, sizeof ua);
    memcpy(&ub, &b, sizeof ub);
    ua = (ua & m) | (ub & ~m);
    memcpy(&a, &ua, sizeof a);
    return a;
}

int erosion_grid_validate(const erosion_grid *g, og_error *err) {
    if (!g) return og_error_set(err, "erosion grid: NULL");
    if (g->width < 1 || g->height < 1)
        return og_error_set(err, "width, height: expected >= 1 each, got %d x %d", g->width,
                            g->height);
    if ((int64_t)g->width * g->height > INT32_MAX)
        return og_error_set(err, "width x height: expected at most 2^31 - 1 cells, got %d x %d",
                            g->width, g->height);
    if (!g->heights) return og_error_set(err, "heights: NULL");
    if (!g->weight) return og_error_set(err, "weight: NULL");
    if (!(g->spacing >= 1e-4f && g->spacing <= 1e7f))
        return og_error_set(err, "spacing: expected 1e-4 to 1e7 metres, got %g",
                            (double)g->spacing);
    return 0;
}

// ---------------------------------------------------------------------------------
// Thermal

int erosion_thermal_validate(const thermal_params *p, og_error *err) {
    if (!p) return og_error_set(err, "thermal params: NULL");
    if (!(p->talus_deg > 0.0f && p->talus_deg <= 89.0f))
        return og_error_set(err, "talus_deg: expected an angle in (0, 89] degrees, got %g",
                            (double)p->talus_deg);
    if (p->iterations < 0 || p->iterations > 1000000)
        return og_error_set(err, "iterations: expected 0 to 1000000, got %d", p->iterations);
    if (!(p->rate > 0.0f && p->rate <= 1.0f))
        return og_error_set(err, "rate: expected a fraction in (0, 1], got %g", (double)p->rate);
    return 0;
}

// Rows [j0, j1) and columns [i0, i1) hold every cell with weight > 0. Returns 0 if none.
// Scans each row from both ends, so a row that is weighted near its ends costs little.
static int weighted_bounds(const erosion_grid *g, int *i0, int *i1, int *j0, int *j1) {
    const int W = g->width, H = g->height;
    *i0 = W, *i1 = 0, *j0 = H, *j1 = 0;
    for (int j = 0; j < H; j++) {
        const float *wr = g->weight + (size_t)j * W;
        int first = 0, last = W - 1;
        while (first < W && !(wr[first] > 0.0f))
            first++;
        if (first == W) continue;
        while (!(wr[last] > 0.0f))
            last--;
        if (first < *i0) *i0 = first;
        if (last + 1 > *i1) *i1 = last + 1;
        if (j < *j0) *j0 = j;
        *j1 = j + 1;
    }
    return *i0 < *i1;
}

// The thermal pass works on a copy of the weighted bounding box padded with one ring of
// zero-weight cells, so that every cell has eight neighbours and the row loops have no
// edge cases (GCC vectorises them). Per iteration and row: pass 1 finds each cell's
// share f of its excess to move; pass 2 gathers, for each cell, what it receives minus
// what it gives. The amount a pair exchanges is computed bit-identically from both
// sides, so mass is conserved up to the rounding of the sums.
typedef struct thermal_ws {
    int n, rows, stride; // box columns and rows; stride = n + 2
    float *h, *w;        // padded copies, (rows + 2) x stride; border weights are 0
    float *f[3];         // f of rows r - 1, r, r + 1 (ring; border entries stay 0)
    float *d[2];         // deltas of rows r - 1, r (ring)
    float ortho, diag;   // largest stable drop to an edge / corner neighbour, metres
    float half_rate;
} thermal_ws;

// The iteration is compiled twice, for baseline x86-64 and for AVX2 (about twice as fast),
// from the same always-inlined bodies; both give the same bits (lane-wise IEEE
// operations, no FMA).
#define ROW_KERNEL static inline __attribute__((always_inline))

// Excess drop from c towards a weighted neighbour, else 0.
static inline float excess_to(float hc, float hn, float wn, float thr) {
    float e = (hc - hn) - thr;
    return select_bits((wn > 0.0f) & (e > 0.0f), e, 0.0f);
}

// Pass 1: moving half the largest excess, split by excess, gives no neighbour more than
// half its own excess, so no pair overshoots its repose. Excesses are >= 0, so a zero
// sum means a zero max and f = 0.
ROW_KERNEL void share_row(float *restrict f, const float *restrict hm, const float *restrict hc,
                          const float *restrict hp, const float *restrict wm,
                          const float *restrict wc, const float *restrict wp, float ortho,
                          float diag, float half_rate, int n) {
    for (int x = 1; x <= n; x++) {
        const float h = hc[x];
        const float e0 = excess_to(h, hm[x - 1], wm[x - 1], diag);
        const float e1 = excess_to(h, hm[x], wm[x], ortho);
        const float e2 = excess_to(h, hm[x + 1], wm[x + 1], diag);
        const float e3 = excess_to(h, hc[x - 1], wc[x - 1], ortho);
        const float e4 = excess_to(h, hc[x + 1], wc[x + 1], ortho);
        const float e5 = excess_to(h, hp[x - 1], wp[x - 1], diag);
        const float e6 = excess_to(h, hp[x], wp[x], ortho);
        const float e7 = excess_to(h, hp[x + 1], wp[x + 1], diag);
        const float sum = ((e0 + e1) + (e2 + e3)) + ((e4 + e5) + (e6 + e7));
        float mx = e0;
        mx = select_bits(e1 > mx, e1, mx);
        mx = select_bits(e2 > mx, e2, mx);
        mx = select_bits(e3 > mx, e3, mx);
        mx = select_bits(e4 > mx, e4, mx);
        mx = select_bits(e5 > mx, e5, mx);
        mx = select_bits(e6 > mx, e6, mx);
        mx = select_bits(e7 > mx, e7, mx);
        f[x] = half_rate * (mx / select_bits(sum > 0.0f, sum, 1.0f));
    }
}

// What c receives from n minus what it gives to n, scaled by the smaller weight (0 for
// the halo). At most one of the two is non-zero. From n's side the same expressions
// give the same bits, negated.
static inline float exchange(float hc, float fc, float wc, float hn, float fn, float wn,
                             float thr) {
    const float down = hc - hn, up = -down; // exact negation: up == hn - hc
    const float eo = down - thr, ei = up - thr;
    const float give = fc * select_bits(eo > 0.0f, eo, 0.0f);
    const float take = fn * select_bits(ei > 0.0f, ei, 0.0f);
    return (take - give) * select_bits(wc < wn, wc, wn);
}

// Pass 2.
ROW_KERNEL void delta_row(float *restrict d, const float *restrict hm, const float *restrict hc,
                          const float *restrict hp, const float *restrict wm,
                          const float *restrict wc, const float *restrict wp,
                          const float *restrict fm, const float *restrict fc,
                          const float *restrict fp, float ortho, float diag, int n) {
    for (int x = 1; x <= n; x++) {
        const float h = hc[x], f = fc[x], w = wc[x];
        float s = exchange(h, f, w, hm[x - 1], fm[x - 1], wm[x - 1], diag);
        s += exchange(h, f, w, hm[x], fm[x], wm[x], ortho);
        s += exchange(h, f, w, hm[x + 1], fm[x + 1], wm[x + 1], diag);
        s += exchange(h, f, w, hc[x - 1], fc[x - 1], wc[x - 1], ortho);
        s += exchange(h, f, w, hc[x + 1], fc[x + 1], wc[x + 1], ortho);
        s += exchange(h, f, w, hp[x - 1], fp[x - 1], wp[x - 1], diag);
        s += exchange(h, f, w, hp[x], fp[x], wp[x], ortho);
        s += exchange(h, f, w, hp[x + 1], fp[x + 1], wp[x + 1], diag);
        d[x] = s;
    }
}

// Adds deltas to weighted cells; others keep their bits.
ROW_KERNEL void apply_row(float *restrict h, const float *restrict w, const float *restrict d,
                          int n) {
    for (int x = 1; x <= n; x++)
        h[x] = select_bits(w[x] > 0.0f, h[x] + d[x], h[x]);
}

static inline float *ws_row(const thermal_ws *ws, float *base, int r) {
    return base + (size_t)r * ws->stride;
}

ROW_KERNEL void thermal_share(thermal_ws *ws, int r) {
    float *f = ws->f[r % 3];
    if (r > ws->rows) {
        memset(f, 0, sizeof(float) * (size_t)ws->stride);
        return;
    }
    share_row(f, ws_row(ws, ws->h, r - 1), ws_row(ws, ws->h, r), ws_row(ws, ws->h, r + 1),
              ws_row(ws, ws->w, r - 1), ws_row(ws, ws->w, r), ws_row(ws, ws->w, r + 1), ws->ortho,
              ws->diag, ws->half_rate, ws->n);
}

// One iteration. Row r's delta needs the old heights of rows r - 1 .. r + 1 and f of
// the same rows, so row r - 1 is updated once row r's delta is known.
ROW_KERNEL void thermal_iterations(thermal_ws *ws, int iterations) {
    for (int it = 0; it < iterations; it++) {
        memset(ws->f[0], 0, sizeof(float) * (size_t)ws->stride); // row 0 is border
        thermal_share(ws, 1);
        for (int r = 1; r <= ws->rows; r++) {
            thermal_share(ws, r + 1);
            delta_row(ws->d[r % 2], ws_row(ws, ws->h, r - 1), ws_row(ws, ws->h, r),
                      ws_row(ws, ws->h, r + 1), ws_row(ws, ws->w, r - 1), ws_row(ws, ws->w, r),
                      ws_row(ws, ws->w, r + 1), ws->f[(r - 1) % 3], ws->f[r % 3],
                      ws->f[(r + 1) % 3], ws->ortho, ws->diag, ws->n);
            if (r > 1)
                apply_row(ws_row(ws, ws->h, r - 1), ws_row(ws, ws->w, r - 1), ws->d[(r - 1) % 2],
                          ws->n);
        }
        apply_row(ws_row(ws, ws->h, ws->rows), ws_row(ws, ws->w, ws->rows), ws->d[ws->rows % 2],
                  ws->n);
    }
}

static void thermal_run_base(thermal_ws *ws, int iterations) {
    thermal_iterations(ws, iterations);
}

#if defined(__x86_64__) || defined(__i386__)
#define HAVE_AVX2_PATH 1
__attribute__((target("avx2"))) static void thermal_run_avx2(thermal_ws *ws, int iterations) {
    thermal_iterations(ws, iterations);
}
#endif

// Test hook (not in the header): 0 forces the baseline build so tests can check that
// both give the same bits.
void erosion_allow_avx2(int allow);
static atomic_int allow_avx2 = 1;
void erosion_allow_avx2(int allow) {
    atomic_store(&allow_avx2, allow);
}

static void thermal_run(thermal_ws *ws, int iterations) {
#ifdef HAVE_AVX2_PATH
    if (atomic_load_explicit(&allow_avx2, memory_order_relaxed) && __builtin_cpu_supports("avx2")) {
        thermal_run_avx2(ws, iterations);
        return;
    }
#endif
    thermal_run_base(ws, iterations);
}

void erosion_thermal(erosion_grid *g, const thermal_params *p) {
    if (erosion_grid_validate(g, NULL) || erosion_thermal_validate(p, NULL)) return;
    if (p->iterations == 0) return;
    int i0, i1, j0, j1;
    if (!weighted_bounds(g, &i0, &i1, &j0, &j1)) return;
    thermal_ws ws = {.n = i1 - i0, .rows = j1 - j0, .stride = i1 - i0 + 2};
    const size_t plane = (size_t)ws.stride * (size_t)(ws.rows + 2),
                 row_bytes = sizeof(float) * (size_t)ws.stride;
    float *block = malloc((2 * plane + 5 * (size_t)ws.stride) * sizeof(float));
    if (!block) return;
    ws.h = block;
    ws.w = block + plane;
    memset(block + 2 * plane, 0, 5 * row_bytes); // f and delta rings, borders included
    for (int k = 0; k < 3; k++)
        ws.f[k] = block + 2 * plane + (size_t)k * ws.stride;
    for (int k = 0; k < 2; k++)
        ws.d[k] = block + 2 * plane + (size_t)(3 + k) * ws.stride;
    // The border has weight 0 and height 0 (only ever read next to a zero weight).
    memset(ws_row(&ws, ws.h, 0), 0, row_bytes);
    memset(ws_row(&ws, ws.w, 0), 0, row_bytes);
    memset(ws_row(&ws, ws.h, ws.rows + 1), 0, row_bytes);
    memset(ws_row(&ws, ws.w, ws.rows + 1), 0, row_bytes);
    for (int r = 1; r <= ws.rows; r++) {
        const size_t src = (size_t)(j0 + r - 1) * g->width + i0;
        float *h = ws_row(&ws, ws.h, r), *w = ws_row(&ws, ws.w, r);
        memcpy(h + 1, g->heights + src, sizeof(float) * (size_t)ws.n);
        for (int x = 1; x <= ws.n; x++)
            w[x] = wclamp(g->weight[src + x - 1]);
        h[0] = h[ws.n + 1] = w[0] = w[ws.n + 1] = 0.0f;
    }

    const double tan_talus = tan((double)p->talus_deg * (3.14159265358979323846 / 180.0));
    ws.ortho = (float)(tan_talus * g->spacing);
    ws.diag = (float)(tan_talus * g->spacing * 1.4142135623730951);
    ws.half_rate = 0.5f * p->rate;
    // In batches, so a cancelled run stops soon (the caller then throws the grid away).
    for (int done = 0; done < p->iterations;) {
        int batch = p->iterations - done < 8 ? p->iterations - done : 8;
        thermal_run(&ws, batch);
        done += batch;
        if (og_progress_report(g->progress, done, p->iterations) != 0) break;
    }

    // Write back runs of weighted cells only.
    for (int r = 1; r <= ws.rows; r++) {
        float *dst = g->heights + (size_t)(j0 + r - 1) * g->width + i0; // cell x is dst[x - 1]
        const float *h = ws_row(&ws, ws.h, r), *w = ws_row(&ws, ws.w, r);
        for (int x = 1; x <= ws.n;) {
            if (!(w[x] > 0.0f)) {
                x++;
                continue;
            }
            int end = x + 1;
            while (end <= ws.n && w[end] > 0.0f)
                end++;
            memcpy(dst + x - 1, h + x, sizeof(float) * (size_t)(end - x));
            x = end;
        }
    }
    free(block);
}

// ---------------------------------------------------------------------------------
// Hydraulic

void hydraulic_params_default(hydraulic_params *p) {
    *p = (hydraulic_params){
        .seed = 1,
        .droplets = 10000,
        .max_lifetime = 30,
        .inertia = 0.05f,
        .capacity = 4.0f,
        .min_capacity = 0.01f,
        .erosion = 0.3f,
        .deposition = 0.3f,
        .evaporation = 0.01f,
        .gravity = 4.0f,
        .radius_cells = 3.0f,
        .initial_water = 1.0f,
        .initial_speed = 1.0f,
    };
}

// NaN fails every comparison, so `in_range` rejects it.
static int in_range(float v, float lo, float hi) {
    return v >= lo && v <= hi;
}

int erosion_hydraulic_validate(const hydraulic_params *p, og_error *err) {
    if (!p) return og_error_set(err, "hydraulic params: NULL");
    if (p->droplets < 0 || p->droplets > 100000000)
        return og_error_set(err, "droplets: expected 0 to 100000000, got %d", p->droplets);
    if (p->max_lifetime < 1 || p->max_lifetime > 10000)
        return og_error_set(err, "max_lifetime: expected 1 to 10000 steps, got %d",
                            p->max_lifetime);
    static const struct {
        const char *name;
        size_t offset;
        float lo, hi;
        int open_lo; // lower bound excluded
    } F[] = {
        {"inertia", offsetof(hydraulic_params, inertia), 0, 1, 0},
        {"capacity", offsetof(hydraulic_params, capacity), 0, 1000, 0},
        {"min_capacity", offsetof(hydraulic_params, min_capacity), 0, 1000, 0},
        {"erosion", offsetof(hydraulic_params, erosion), 0, 1, 0},
        {"deposition", offsetof(hydraulic_params, deposition), 0, 1, 0},
        {"evaporation", offsetof(hydraulic_params, evaporation), 0, 1, 0},
        {"gravity", offsetof(hydraulic_params, gravity), 0, 1000, 0},
        {"radius_cells", offsetof(hydraulic_params, radius_cells), 0, 32, 1},
        {"initial_water", offsetof(hydraulic_params, initial_water), 0, 1000, 1},
        {"initial_speed", offsetof(hydraulic_params, initial_speed), 0, 1000, 0},
    };
    for (size_t k = 0; k < sizeof F / sizeof F[0]; k++) {
        float v = *(const float *)((const char *)p + F[k].offset);
        if (!in_range(v, F[k].lo, F[k].hi) || (F[k].open_lo && v == F[k].lo))
            return og_error_set(err, "%s: expected a number in %c%g, %g], got %g", F[k].name,
                                F[k].open_lo ? '(' : '[', (double)F[k].lo, (double)F[k].hi,
                                (double)v);
    }
    return 0;
}

// splitmix64: tiny, well mixed, and the same everywhere.
static inline uint64_t rng_next(uint64_t *s) {
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
// Uniform in [0, 1) with 24 bits, exact in float.
static inline float rng_unit(uint64_t *s) {
    return (float)(rng_next(s) >> 40) * 0x1p-24f;
}

// The erosion disc: cells within radius r of the centre, weights (r - distance)
// normalised to sum 1.
typedef struct disc {
    int count, reach; // reach = largest |di| or |dj|
    int *di, *dj;
    ptrdiff_t *off; // dj * width + di
    float *w;
    // The same disc as rows of `lanes` cells (a multiple of 8, from di = -reach), the
    // weights 0 past its edge, so eroding it runs 8 cells at a time: row r starts at
    // row_off[r] from the centre, its weights at row_w + r * lanes.
    int rows, lanes;
    ptrdiff_t *row_off;
    float *row_w;
} disc;

static int disc_build(disc *d, float r, int width) {
    int R = (int)ceilf(r);
    size_t max = (size_t)(2 * R + 1) * (2 * R + 1);
    d->di = malloc(max * sizeof *d->di);
    d->dj = malloc(max * sizeof *d->dj);
    d->off = malloc(max * sizeof *d->off);
    d->w = malloc(max * sizeof *d->w);
    if (!d->di || !d->dj || !d->off || !d->w) return -1;
    d->count = 0, d->reach = 0;
    double sum = 0.0;
    for (int dj = -R; dj <= R; dj++) {
        for (int di = -R; di <= R; di++) {
            double dist = sqrt((double)(di * di + dj * dj));
            if (dist >= r) continue;
            d->di[d->count] = di, d->dj[d->count] = dj;
            d->off[d->count] = (ptrdiff_t)dj * width + di;
            d->w[d->count] = (float)(r - dist);
            sum += r - dist;
            if (abs(di) > d->reach) d->reach = abs(di);
            if (abs(dj) > d->reach) d->reach = abs(dj);
            d->count++;
        }
    }
    for (int k = 0; k < d->count; k++)
        d->w[k] = (float)(d->w[k] / sum);
    d->rows = 2 * d->reach + 1;
    d->lanes = (2 * d->reach + 1 + 7) / 8 * 8;
    d->row_off = malloc((size_t)d->rows * sizeof *d->row_off);
    d->row_w = calloc((size_t)d->rows * (size_t)d->lanes, sizeof *d->row_w);
    if (!d->row_off || !d->row_w) return -1;
    for (int r = 0; r < d->rows; r++)
        d->row_off[r] = (ptrdiff_t)(r - d->reach) * width - d->reach;
    for (int k = 0; k < d->count; k++)
        d->row_w[(d->dj[k] + d->reach) * d->lanes + d->di[k] + d->reach] = d->w[k];
    return 0;
}

// Columns right of the centre the row layout reaches (its padding included).
static int disc_reach_right(const disc *d) {
    return d->lanes - d->reach - 1;
}

static void disc_free(disc *d) {
    free(d->di), free(d->dj), free(d->off), free(d->w), free(d->row_off), free(d->row_w);
}

typedef struct droplet_ctx {
    float *h;
    const float *wt;
    int W, H;
    disc disc;
    // What earlier drops could not place because of float rounding; the next drop adds
    // it, so a whole call loses at most one rounding.
    double carry;
    float end_x, end_y; // where the last droplet died
} droplet_ctx;

// A droplet may stand at (x, y) when its bilinear cell lies in the grid and all four
// corners are weighted.
static inline int alive_at(const droplet_ctx *c, float x, float y) {
    if (!(x >= 0.0f && y >= 0.0f && x < (float)(c->W - 1) && y < (float)(c->H - 1))) return 0;
    int i = (int)x, j = (int)y;
    if (i > c->W - 2 || j > c->H - 2) return 0; // float rounding at the upper edge
    size_t k = (size_t)j * c->W + i;
    return c->wt[k] > 0.0f && c->wt[k + 1] > 0.0f && c->wt[k + c->W] > 0.0f &&
           c->wt[k + c->W + 1] > 0.0f;
}

static inline float bilinear(const float *h, int W, float x, float y) {
    int i = (int)x, j = (int)y;
    float u = x - (float)i, v = y - (float)j;
    const float *p = h + (size_t)j * W + i;
    return (p[0] * (1.0f - u) + p[1] * u) * (1.0f - v) + (p[W] * (1.0f - u) + p[W + 1] * u) * v;
}

// Adds d to a weighted cell; returns the change actually stored (rounding included),
// which is what the mass books record.
static inline double add_height(float *h, float d) {
    float old = *h, nw = old + d;
    *h = nw;
    return (double)nw - (double)old;
}

// Lowers cell n by amount x disc weight dw x its weight, never below floor_h; returns
// the change stored. Branch-free: a zero-weight cell gets old - (+0), its own bits
// (even -0).
static inline double erode_cell(droplet_ctx *c, ptrdiff_t n, float amount, float dw,
                                float floor_h) {
    const float old = c->h[n];
    float room = old - floor_h, take = amount * dw * c->wt[n];
    room = room > 0.0f ? room : 0.0f;
    take = take < room ? take : room;
    const float nw = old - take;
    c->h[n] = nw;
    return (double)old - (double)nw;
}

// The disc's rows, 8 cells at a time (erode_cell's arithmetic; cells past the disc
// get a weight of 0 and so their own bits back). One double sum per lane, added up in
// a fixed order at the end: still deterministic, and the loop vectorises.
HOT_LOOP static double erode_rows(float *h, const float *wt, const disc *d, ptrdiff_t centre,
                                  float amount, float floor_h) {
    double lane[8] = {0};
    for (int r = 0; r < d->rows; r++) {
        float *row = h + centre + d->row_off[r];
        const float *rw = wt + centre + d->row_off[r], *dw = d->row_w + (size_t)r * d->lanes;
        for (int t0 = 0; t0 < d->lanes; t0 += 8)
            for (int t = 0; t < 8; t++) {
                const float old = row[t0 + t];
                float room = old - floor_h, take = amount * dw[t0 + t] * rw[t0 + t];
                room = room > 0.0f ? room : 0.0f;
                take = take < room ? take : room;
                const float nw = old - take;
                row[t0 + t] = nw;
                lane[t] += (double)old - (double)nw;
            }
    }
    return ((lane[0] + lane[1]) + (lane[2] + lane[3])) +
           ((lane[4] + lane[5]) + (lane[6] + lane[7]));
}

// Erodes the disc around the node nearest (x, y); returns the height removed.
static double erode_disc(droplet_ctx *c, float x, float y, float amount, float floor_h) {
    const int ci = (int)(x + 0.5f), cj = (int)(y + 0.5f);
    const ptrdiff_t centre = (ptrdiff_t)cj * c->W + ci;
    const disc *d = &c->disc;
    if (ci - d->reach >= 0 && ci + disc_reach_right(d) < c->W && cj - d->reach >= 0 &&
        cj + d->reach < c->H)
        return erode_rows(c->h, c->wt, d, centre, amount, floor_h);
    double s0 = 0.0;
    for (int k = 0; k < d->count; k++) {
        int i = ci + d->di[k], j = cj + d->dj[k];
        if (i >= 0 && i < c->W && j >= 0 && j < c->H)
            s0 += erode_cell(c, centre + d->off[k], amount, d->w[k], floor_h);
    }
    return s0;
}

// Lays `amount` over the weighted cells of the disc around the node nearest (x, y),
// in proportion to disc weight x cell weight, so that all of it lands. Returns the
// height added.
static double drop_disc(droplet_ctx *c, float x, float y, double amount) {
    const int ci = (int)(x + 0.5f), cj = (int)(y + 0.5f);
    const size_t centre = (size_t)cj * c->W + ci;
    const disc *d = &c->disc;
    double total = 0.0;
    for (int k = 0; k < d->count; k++) {
        int i = ci + d->di[k], j = cj + d->dj[k];
        if (i < 0 || i >= c->W || j < 0 || j >= c->H) continue;
        total += (double)d->w[k] * c->wt[(size_t)((ptrdiff_t)centre + d->off[k])];
    }
    // total > 0 while the droplet's cell is weighted (its nearest node is a weighted
    // corner); the fallback only guards against weights that underflow.
    if (!(total > 0.0)) return add_height(&c->h[centre], (float)amount);
    double added = 0.0;
    for (int k = 0; k < d->count; k++) {
        int i = ci + d->di[k], j = cj + d->dj[k];
        if (i < 0 || i >= c->W || j < 0 || j >= c->H) continue;
        size_t n = (size_t)((ptrdiff_t)centre + d->off[k]);
        double w = (double)d->w[k] * c->wt[n];
        if (w > 0.0) added += add_height(&c->h[n], (float)(amount * (w / total)));
    }
    // Big loads round visibly in float; the centre (a weighted corner) takes the rest.
    if (added != amount) added += add_height(&c->h[centre], (float)(amount - added));
    return added;
}

#define SPAWN_AHEAD 16

// Asks for the cache lines of the disc around (x, y) (both ends of each row).
static void prefetch_disc(const droplet_ctx *c, float x, float y) {
    const int ci = (int)(x + 0.5f), cj = (int)(y + 0.5f), R = c->disc.reach;
    const int i0 = ci - R < 0 ? 0 : ci - R, i1 = ci + R >= c->W ? c->W - 1 : ci + R;
    for (int j = cj - R; j <= cj + R; j++) {
        if (j < 0 || j >= c->H) continue;
        const size_t row = (size_t)j * c->W;
        __builtin_prefetch(c->h + row + i0, 1);
        __builtin_prefetch(c->h + row + i1, 1);
        __builtin_prefetch(c->wt + row + i0, 0);
        __builtin_prefetch(c->wt + row + i1, 0);
    }
}

// Runs one droplet from (x, y); adds its books to r.
static void droplet_run(droplet_ctx *c, const hydraulic_params *p, float spacing, float x, float y,
                        uint64_t *rng, hydraulic_report *r) {
    const int W = c->W;
    const float inv_sp = 1.0f / spacing;
    const double min_cap = (double)p->min_capacity * spacing;
    float dx = 0.0f, dy = 0.0f, speed = p->initial_speed, water = p->initial_water;
    double sediment = 0.0;
    for (int life = 0; life < p->max_lifetime; life++) {
        const int i = (int)x, j = (int)y;
        const float u = x - (float)i, v = y - (float)j;
        float *q = c->h + (size_t)j * W + i;
        const float h00 = q[0], h10 = q[1], h01 = q[W], h11 = q[W + 1];
        const float gx = ((h10 - h00) * (1.0f - v) + (h11 - h01) * v) * inv_sp;
        const float gy = ((h01 - h00) * (1.0f - u) + (h11 - h10) * u) * inv_sp;
        const float h_here =
            (h00 * (1.0f - u) + h10 * u) * (1.0f - v) + (h01 * (1.0f - u) + h11 * u) * v;

        dx = dx * p->inertia - gx * (1.0f - p->inertia);
        dy = dy * p->inertia - gy * (1.0f - p->inertia);
        float len2 = dx * dx + dy * dy;
        if (!(len2 > 1e-20f)) {
            // Flat and still: a random direction (rejection in the unit disc keeps it
            // free of libm, hence the same on every machine).
            do {
                dx = 2.0f * rng_unit(rng) - 1.0f;
                dy = 2.0f * rng_unit(rng) - 1.0f;
                len2 = dx * dx + dy * dy;
            } while (!(len2 > 0.0625f && len2 <= 1.0f));
        }
        const float inv_len = 1.0f / sqrtf(len2);
        dx *= inv_len, dy *= inv_len;

        const float nx = x + dx, ny = y + dy;
        if (!alive_at(c, nx, ny)) break;
        r->steps++;
        const float dh = bilinear(c->h, W, nx, ny) - h_here;

        double cap = -(double)dh * speed * water * p->capacity;
        if (cap < min_cap) cap = min_cap;
        if (dh > 0.0f || sediment > cap) {
            // Uphill: fill the hollow the droplet is in, up to the next height if it
            // carries that much; else drop a share of the surplus. Into the four corners.
            double amount =
                dh > 0.0f ? (dh < sediment ? dh : sediment) : (sediment - cap) * p->deposition;
            const size_t k = (size_t)j * W + i;
            const float bw[4] = {(1.0f - u) * (1.0f - v), u * (1.0f - v), (1.0f - u) * v, u * v};
            const size_t at[4] = {k, k + 1, k + (size_t)W, k + (size_t)W + 1};
            double added = 0.0;
            for (int n = 0; n < 4; n++) {
                float put = (float)(amount * bw[n] * c->wt[at[n]]);
                if (put > 0.0f) added += add_height(&c->h[at[n]], put);
            }
            sediment -= added;
            r->deposited += added;
        } else {
            // Never more than the drop, and no cell below where the water goes next.
            double amount = (cap - sediment) * p->erosion;
            if (amount > -(double)dh) amount = -(double)dh;
            double removed = erode_disc(c, x, y, (float)amount, h_here + dh);
            sediment += removed;
            r->eroded += removed;
        }

        float s2 = speed * speed - dh * inv_sp * p->gravity;
        speed = s2 > 0.0f ? sqrtf(s2) : 0.0f;
        water *= 1.0f - p->evaporation;
        x = nx, y = ny;
    }
    c->end_x = x, c->end_y = y;
    const double load = sediment + c->carry;
    if (load > 0.0) {
        const double added = drop_disc(c, x, y, load);
        r->dropped += added;
        c->carry = load - added;
    } else {
        c->carry = load;
    }
}

// Droplets run in bands of columns, a band's droplets one after another in the order
// they were drawn. A droplet reaches at most max_lifetime cells from its start, plus
// the disc and its bilinear cell, so bands two apart never touch the same cell: the
// even bands run at the same time, then the odd ones. Which droplet runs where, and
// the random stream each walks with, depend on the seed and the grid alone, so the
// heights are the same on any number of threads.
typedef struct band_job {
    const droplet_ctx *base;
    const hydraulic_params *p;
    float spacing;
    uint64_t walk_seed;
    const float (*start)[2];  // the chunk's starts, in drawing order
    const uint32_t *order;    // indices into start, band by band
    const size_t *band_first; // band b's droplets: order[band_first[b] .. band_first[b + 1])
    int64_t first_droplet;    // the chunk's first droplet's number in the call
    int parity;               // the bands this run takes: parity, parity + 2, ...
    droplet_ctx *ends;        // per band: its carry and where its last droplet died
    hydraulic_report *reports;
    og_progress *progress;
    atomic_long *done;
    long total;
} band_job;

static int band_task(void *user, int task, og_error *err) {
    band_job *j = user;
    const int b = 2 * task + j->parity;
    if (og_progress_cancelled(j->progress)) return og_error_set(err, "cancelled");
    droplet_ctx c = *j->base;
    c.carry = j->ends[b].carry;
    hydraulic_report r = {0};
    const size_t a = j->band_first[b], e = j->band_first[b + 1];
    for (size_t m = a; m < e; m++) {
        if (m + SPAWN_AHEAD < e) { // a start is a random spot, far from the last droplet's
            const float *ahead = j->start[j->order[m + SPAWN_AHEAD]];
            prefetch_disc(&c, ahead[0], ahead[1]);
        }
        const uint32_t k = j->order[m];
        uint64_t rng = j->walk_seed ^ ((uint64_t)(j->first_droplet + k) * 0xD1B54A32D192ED03ull);
        droplet_run(&c, j->p, j->spacing, j->start[k][0], j->start[k][1], &rng, &r);
        r.droplets++;
        if ((r.droplets & 1023) == 0) {
            long done = atomic_fetch_add(j->done, 1024) + 1024;
            if (og_progress_report(j->progress, done, j->total) != 0)
                return og_error_set(err, "cancelled");
        }
    }
    if (e > a) j->ends[b] = c;
    hydraulic_report *t = &j->reports[b];
    t->eroded += r.eroded, t->deposited += r.deposited, t->dropped += r.dropped;
    t->droplets += r.droplets, t->steps += r.steps;
    return 0;
}

// Droplets are drawn and run this many at a time (bounded memory for any count).
enum { CHUNK = 1 << 16 };

// Test hook (not in the header): 0 runs the bands one after another on the caller, so
// tests can check that the threads change nothing.
void erosion_allow_threads(int allow);
static atomic_int allow_threads = 1;
void erosion_allow_threads(int allow) {
    atomic_store(&allow_threads, allow);
}

static int run_bands(int tasks, band_job *job, og_error *err) {
    if (atomic_load_explicit(&allow_threads, memory_order_relaxed))
        return parallel_run(tasks, band_task, job, err);
    int rc = 0;
    for (int t = 0; t < tasks && rc == 0; t++)
        rc = band_task(job, t, err);
    return rc;
}

void erosion_hydraulic(erosion_grid *g, const hydraulic_params *p, hydraulic_report *report) {
    hydraulic_report rep = {0};
    if (report) *report = rep;
    if (erosion_grid_validate(g, NULL) || erosion_hydraulic_validate(p, NULL)) return;
    const int W = g->width, H = g->height;
    if (W < 2 || H < 2 || p->droplets == 0) return;

    // Spawn table: every bilinear cell whose four corners are weighted, with the
    // running sum of its mean corner weight; a guide table (Chen & Asau's cutpoints)
    // makes finding the cell for a random running sum O(1) on average.
    size_t cells = (size_t)(W - 1) * (H - 1), count = 0;
    uint32_t *spawn_cell = malloc(cells * sizeof *spawn_cell);
    uint32_t *guide = malloc(cells * sizeof *guide);
    double *spawn_cdf = malloc(cells * sizeof *spawn_cdf);
    // The droplets read clamped weights (clamping was an eighth of their work).
    float *wt = malloc((size_t)W * H * sizeof *wt);
    droplet_ctx c = {.h = g->heights, .wt = wt, .W = W, .H = H};
    // The disc's row layout reaches furthest right: its padding to 8 cells.
    const int reach = ((2 * (int)ceilf(p->radius_cells) + 1 + 7) / 8) * 8;
    const int band_width = 2 * (p->max_lifetime + reach + 2);
    const int bands = (W + band_width - 1) / band_width;
    float(*start)[2] = malloc(CHUNK * sizeof *start);
    uint32_t *order = malloc(CHUNK * sizeof *order);
    size_t *band_first = calloc((size_t)bands + 2, sizeof *band_first);
    droplet_ctx *ends = calloc((size_t)bands, sizeof *ends);
    hydraulic_report *reports = calloc((size_t)bands, sizeof *reports);
    if (!spawn_cell || !guide || !spawn_cdf || !wt || !start || !order || !band_first || !ends ||
        !reports || disc_build(&c.disc, p->radius_cells, W))
        goto done;
    for (size_t k = 0; k < (size_t)W * H; k++)
        wt[k] = wclamp(g->weight[k]);
    double total = 0.0;
    for (int j = 0; j < H - 1; j++) {
        const float *w0 = wt + (size_t)j * W, *w1 = w0 + W;
        for (int i = 0; i < W - 1; i++) {
            const float a = w0[i], b = w0[i + 1], d = w1[i], e = w1[i + 1];
            if (a > 0.0f && b > 0.0f && d > 0.0f && e > 0.0f) {
                total += 0.25 * ((double)a + b + d + e);
                spawn_cell[count] = (uint32_t)((size_t)j * W + i);
                spawn_cdf[count] = total;
                count++;
            }
        }
    }
    if (count == 0) goto done;
    for (size_t m = 0, k = 0; m < count; m++) {
        const double cut = total * ((double)m / (double)count);
        while (k < count - 1 && spawn_cdf[k] <= cut)
            k++;
        guide[m] = (uint32_t)k;
    }

    uint64_t spawn_rng = p->seed;
    atomic_long done_count;
    atomic_init(&done_count, 0);
    band_job job = {.base = &c,
                    .p = p,
                    .spacing = g->spacing,
                    .walk_seed = p->seed ^ 0x6A09E667F3BCC909ull,
                    .start = (const float(*)[2])start,
                    .order = order,
                    .band_first = band_first,
                    .ends = ends,
                    .reports = reports,
                    .progress = g->progress,
                    .done = &done_count,
                    .total = p->droplets};
    int cancelled = 0;
    for (int first = 0; first < p->droplets && !cancelled; first += CHUNK) {
        const int n = p->droplets - first < CHUNK ? p->droplets - first : CHUNK;
        for (int m = 0; m < n; m++) {
            // The first entry whose running sum exceeds `pick` (the last one if none
            // does): start at the guide, then walk either way, so rounding in the cuts
            // is harmless.
            const double u = (double)(rng_next(&spawn_rng) >> 11) * 0x1p-53, pick = u * total;
            size_t k = guide[(size_t)(u * (double)count)];
            while (k < count - 1 && spawn_cdf[k] <= pick)
                k++;
            while (k > 0 && spawn_cdf[k - 1] > pick)
                k--;
            const int i = (int)(spawn_cell[k] % (uint32_t)W),
                      j = (int)(spawn_cell[k] / (uint32_t)W);
            float x = (float)i + rng_unit(&spawn_rng), y = (float)j + rng_unit(&spawn_rng);
            if ((int)x != i) x = (float)i; // rounded up into the next cell
            if ((int)y != j) y = (float)j;
            start[m][0] = x, start[m][1] = y;
        }
        // Each band's droplets together, in drawing order (a counting sort).
        memset(band_first, 0, ((size_t)bands + 2) * sizeof *band_first);
        for (int m = 0; m < n; m++)
            band_first[(int)start[m][0] / band_width + 2]++;
        for (int b = 0; b < bands; b++)
            band_first[b + 2] += band_first[b + 1];
        for (int m = 0; m < n; m++)
            order[band_first[(int)start[m][0] / band_width + 1]++] = (uint32_t)m;
        job.first_droplet = first;
        og_error err;
        for (int parity = 0; parity < 2 && !cancelled; parity++) {
            job.parity = parity;
            int tasks = (bands - parity + 1) / 2;
            cancelled = run_bands(tasks, &job, &err) != 0;
        }
    }
    // What the bands' last drops could not place for rounding lands where the last
    // band's last droplet died.
    double carry = 0.0;
    int last = -1;
    for (int b = 0; b < bands; b++) {
        rep.eroded += reports[b].eroded, rep.deposited += reports[b].deposited;
        rep.dropped += reports[b].dropped, rep.droplets += reports[b].droplets;
        rep.steps += reports[b].steps;
        carry += ends[b].carry;
        if (reports[b].droplets) last = b;
    }
    if (!cancelled && last >= 0 && carry > 0.0) {
        c.carry = 0.0;
        rep.dropped += drop_disc(&c, ends[last].end_x, ends[last].end_y, carry);
    }

done:
    disc_free(&c.disc);
    free(spawn_cell);
    free(guide);
    free(wt);
    free(spawn_cdf);
    free(start);
    free(order);
    free(band_first);
    free(ends);
    free(reports);
    if (report) *report = rep;
}
