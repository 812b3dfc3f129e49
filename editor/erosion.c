#include "editor/erosion.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

// Clamps a weight to [0, 1]; NaN and negatives become 0. Two plain selects, so that
// vector loops can use max and min.
static inline float wclamp(float w) {
    float a = w > 0.0f ? w : 0.0f;
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
    if (!(g->spacing > 0.0f) || !isfinite(g->spacing))
        return og_error_set(err, "spacing: expected a finite number > 0 metres, got %g",
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
static int weighted_bounds(const erosion_grid *g, int *i0, int *i1, int *j0, int *j1) {
    int W = g->width, H = g->height;
    *i0 = W, *i1 = 0, *j0 = H, *j1 = 0;
    for (int j = 0; j < H; j++) {
        const float *wr = g->weight + (size_t)j * W;
        int first = -1, last = -1;
        for (int i = 0; i < W; i++) {
            if (wclamp(wr[i]) > 0.0f) {
                if (first < 0) first = i;
                last = i;
            }
        }
        if (first < 0) continue;
        if (first < *i0) *i0 = first;
        if (last + 1 > *i1) *i1 = last + 1;
        if (j < *j0) *j0 = j;
        *j1 = j + 1;
    }
    return *i0 < *i1;
}

static const int DI[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
static const int DJ[8] = {-1, -1, -1, 0, 0, 1, 1, 1};

// The thermal pass works a row at a time over the weighted bounding box, in loops the
// compiler vectorises. Deltas live in a ring of three rows: row j - 1 is final, and no
// longer read, once row j has been processed, so it is applied then.
typedef struct thermal_ws {
    const erosion_grid *g;
    int i0, i1, j0, j1, n; // box; n = i1 - i0
    float thr[8];          // largest stable drop per direction, metres
    float half_rate;
    float *e[8];    // excess drop towards each neighbour of the current row
    float *f, *out; // per cell: share of the excess moved; total outflow
    float *ring[3]; // deltas of rows j - 1, j, j + 1
} thermal_ws;

static inline float *ring_row(const thermal_ws *ws, int j) {
    return ws->ring[(j - ws->j0) % 3];
}

// The row kernels stay out of line: inlined, they lose `restrict` and GCC stops
// vectorising them.
#define ROW_KERNEL static __attribute__((noinline))

// e = the drop beyond the threshold where both ends are weighted, else 0.
ROW_KERNEL void excess_row(float *restrict e, const float *restrict hc, const float *restrict hn,
                           const float *restrict wc, const float *restrict wn, float thr, int n) {
    for (int x = 0; x < n; x++) {
        float d = hc[x] - hn[x] - thr;
        int keep = (wc[x] > 0.0f) & (wn[x] > 0.0f) & (d > 0.0f); // no branches: vectorises
        e[x] = keep ? d : 0.0f;
    }
}

// Moves f x e x (smaller weight) to the neighbour; out collects the cell's loss.
ROW_KERNEL void scatter_row(float *restrict dn, float *restrict out, const float *restrict f,
                            const float *restrict e, const float *restrict wc,
                            const float *restrict wn, int n) {
    for (int x = 0; x < n; x++) {
        float a = wclamp(wc[x]), b = wclamp(wn[x]);
        float t = f[x] * e[x] * (a < b ? a : b);
        dn[x] += t;
        out[x] += t;
    }
}

// Half the largest excess, split by excess: no neighbour gets more than half its own
// excess, so no pair overshoots its repose. Also clears out.
ROW_KERNEL void share_row(float *restrict f, float *restrict out, const float *const e[8],
                          float half_rate, int n) {
    const float *restrict e0 = e[0], *restrict e1 = e[1], *restrict e2 = e[2], *restrict e3 = e[3],
                          *restrict e4 = e[4], *restrict e5 = e[5], *restrict e6 = e[6],
                          *restrict e7 = e[7];
    for (int x = 0; x < n; x++) {
        float sum = ((e0[x] + e1[x]) + (e2[x] + e3[x])) + ((e4[x] + e5[x]) + (e6[x] + e7[x]));
        float mx = e0[x];
        mx = select_bits(e1[x] > mx, e1[x], mx);
        mx = select_bits(e2[x] > mx, e2[x], mx);
        mx = select_bits(e3[x] > mx, e3[x], mx);
        mx = select_bits(e4[x] > mx, e4[x], mx);
        mx = select_bits(e5[x] > mx, e5[x], mx);
        mx = select_bits(e6[x] > mx, e6[x], mx);
        mx = select_bits(e7[x] > mx, e7[x], mx);
        // Excesses are >= 0, so a zero sum means a zero max and f = 0.
        f[x] = half_rate * (mx / select_bits(sum > 0.0f, sum, 1.0f));
        out[x] = 0.0f;
    }
}

ROW_KERNEL void subtract_row(float *restrict d, const float *restrict out, int n) {
    for (int x = 0; x < n; x++)
        d[x] -= out[x];
}

static void thermal_row(thermal_ws *ws, int j) {
    const erosion_grid *g = ws->g;
    const int W = g->width, n = ws->n;
    const float *hc = g->heights + (size_t)j * W + ws->i0;
    const float *wc = g->weight + (size_t)j * W + ws->i0;
    int valid[8];
    for (int k = 0; k < 8; k++) {
        const int nj = j + DJ[k], lo = (DI[k] < 0), hi = (DI[k] > 0) ? n - 1 : n;
        float *e = ws->e[k];
        valid[k] = nj >= ws->j0 && nj < ws->j1 && lo < hi;
        if (!valid[k]) {
            memset(e, 0, sizeof(float) * (size_t)n); // outside the box: all weights are 0
            continue;
        }
        const ptrdiff_t shift = (ptrdiff_t)DJ[k] * W + DI[k];
        e[0] = e[n - 1] = 0.0f;
        excess_row(e + lo, hc + lo, hc + shift + lo, wc + lo, wc + shift + lo, ws->thr[k], hi - lo);
    }
    share_row(ws->f, ws->out, (const float *const *)ws->e, ws->half_rate, n);
    for (int k = 0; k < 8; k++) {
        if (!valid[k]) continue;
        const int lo = (DI[k] < 0), hi = (DI[k] > 0) ? n - 1 : n;
        const ptrdiff_t shift = (ptrdiff_t)DJ[k] * W + DI[k];
        float *dn = ring_row(ws, j + DJ[k]) + DI[k];
        scatter_row(dn + lo, ws->out + lo, ws->f + lo, ws->e[k] + lo, wc + lo, wc + shift + lo,
                    hi - lo);
    }
    subtract_row(ring_row(ws, j), ws->out, n);
}

// Adds row j's deltas to its weighted cells (others are rewritten with their own bits)
// and clears the ring row for reuse.
ROW_KERNEL void apply_row(float *restrict h, const float *restrict w, float *restrict d, int n) {
    for (int x = 0; x < n; x++) {
        h[x] = select_bits(w[x] > 0.0f, h[x] + d[x], h[x]);
        d[x] = 0.0f;
    }
}

static void thermal_apply(thermal_ws *ws, int j) {
    const erosion_grid *g = ws->g;
    const size_t row = (size_t)j * g->width + ws->i0;
    apply_row(g->heights + row, g->weight + row, ring_row(ws, j), ws->n);
}

void erosion_thermal(erosion_grid *g, const thermal_params *p) {
    if (erosion_grid_validate(g, NULL) || erosion_thermal_validate(p, NULL)) return;
    if (p->iterations == 0) return;
    thermal_ws ws = {.g = g};
    if (!weighted_bounds(g, &ws.i0, &ws.i1, &ws.j0, &ws.j1)) return;
    ws.n = ws.i1 - ws.i0;
    float *block = calloc((size_t)13 * ws.n, sizeof(float));
    if (!block) return;
    for (int k = 0; k < 8; k++)
        ws.e[k] = block + (size_t)k * ws.n;
    ws.f = block + (size_t)8 * ws.n;
    ws.out = block + (size_t)9 * ws.n;
    for (int r = 0; r < 3; r++)
        ws.ring[r] = block + (size_t)(10 + r) * ws.n;

    const double tan_talus = tan((double)p->talus_deg * (3.14159265358979323846 / 180.0));
    const float ortho = (float)(tan_talus * g->spacing);
    const float diag = (float)(tan_talus * g->spacing * 1.4142135623730951);
    for (int k = 0; k < 8; k++)
        ws.thr[k] = DI[k] != 0 && DJ[k] != 0 ? diag : ortho;
    ws.half_rate = 0.5f * p->rate;

    for (int it = 0; it < p->iterations; it++) {
        for (int j = ws.j0; j < ws.j1; j++) {
            thermal_row(&ws, j);
            if (j > ws.j0) thermal_apply(&ws, j - 1);
        }
        thermal_apply(&ws, ws.j1 - 1);
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
    return 0;
}

static void disc_free(disc *d) {
    free(d->di), free(d->dj), free(d->off), free(d->w);
}

typedef struct droplet_ctx {
    float *h;
    const float *wt;
    int W, H;
    disc disc;
} droplet_ctx;

// A droplet may stand at (x, y) when its bilinear cell lies in the grid and all four
// corners are weighted.
static inline int alive_at(const droplet_ctx *c, float x, float y) {
    if (!(x >= 0.0f && y >= 0.0f && x < (float)(c->W - 1) && y < (float)(c->H - 1))) return 0;
    int i = (int)x, j = (int)y;
    if (i > c->W - 2 || j > c->H - 2) return 0; // float rounding at the upper edge
    size_t k = (size_t)j * c->W + i;
    return wclamp(c->wt[k]) > 0.0f && wclamp(c->wt[k + 1]) > 0.0f &&
           wclamp(c->wt[k + c->W]) > 0.0f && wclamp(c->wt[k + c->W + 1]) > 0.0f;
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

// Lowers the weighted cells of the disc around the node nearest (x, y) by amount x
// disc weight x cell weight, never below `floor_h`. Returns the height removed.
static double erode_disc(droplet_ctx *c, float x, float y, double amount, float floor_h) {
    const int ci = (int)(x + 0.5f), cj = (int)(y + 0.5f);
    const size_t centre = (size_t)cj * c->W + ci;
    const disc *d = &c->disc;
    const int inside =
        ci - d->reach >= 0 && ci + d->reach < c->W && cj - d->reach >= 0 && cj + d->reach < c->H;
    double removed = 0.0;
    for (int k = 0; k < d->count; k++) {
        if (!inside) {
            int i = ci + d->di[k], j = cj + d->dj[k];
            if (i < 0 || i >= c->W || j < 0 || j >= c->H) continue;
        }
        size_t n = (size_t)((ptrdiff_t)centre + d->off[k]);
        float w = wclamp(c->wt[n]);
        if (w == 0.0f) continue;
        float room = c->h[n] - floor_h;
        if (!(room > 0.0f)) continue;
        float take = (float)(amount * d->w[k] * w);
        if (take > room) take = room;
        if (take > 0.0f) removed -= add_height(&c->h[n], -take);
    }
    return removed;
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
        total += (double)d->w[k] * wclamp(c->wt[(size_t)((ptrdiff_t)centre + d->off[k])]);
    }
    // total > 0 while the droplet's cell is weighted (its nearest node is a weighted
    // corner); the fallback only guards against weights that underflow.
    if (!(total > 0.0)) return add_height(&c->h[centre], (float)amount);
    double added = 0.0;
    for (int k = 0; k < d->count; k++) {
        int i = ci + d->di[k], j = cj + d->dj[k];
        if (i < 0 || i >= c->W || j < 0 || j >= c->H) continue;
        size_t n = (size_t)((ptrdiff_t)centre + d->off[k]);
        double w = (double)d->w[k] * wclamp(c->wt[n]);
        if (w > 0.0) added += add_height(&c->h[n], (float)(amount * (w / total)));
    }
    return added;
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
        const float dh = bilinear(c->h, W, nx, ny) - h_here;

        double cap = -(double)dh * speed * water * p->capacity;
        if (cap < min_cap) cap = min_cap;
        if (dh > 0.0f || sediment > cap) {
            // Uphill: fill the hollow behind up to the new height if possible;
            // otherwise drop a share of the surplus. Into the cell's four corners.
            double amount =
                dh > 0.0f ? (dh < sediment ? dh : sediment) : (sediment - cap) * p->deposition;
            const size_t k = (size_t)j * W + i;
            const float bw[4] = {(1.0f - u) * (1.0f - v), u * (1.0f - v), (1.0f - u) * v, u * v};
            const size_t at[4] = {k, k + 1, k + (size_t)W, k + (size_t)W + 1};
            double added = 0.0;
            for (int n = 0; n < 4; n++) {
                float put = (float)(amount * bw[n] * wclamp(c->wt[at[n]]));
                if (put > 0.0f) added += add_height(&c->h[at[n]], put);
            }
            sediment -= added;
            r->deposited += added;
        } else {
            // Never more than the drop, and no cell below where the water goes next.
            double amount = (cap - sediment) * p->erosion;
            if (amount > -(double)dh) amount = -(double)dh;
            double removed = erode_disc(c, x, y, amount, h_here + dh);
            sediment += removed;
            r->eroded += removed;
        }

        float s2 = speed * speed - dh * inv_sp * p->gravity;
        speed = s2 > 0.0f ? sqrtf(s2) : 0.0f;
        water *= 1.0f - p->evaporation;
        x = nx, y = ny;
    }
    if (sediment > 0.0) r->dropped += drop_disc(c, x, y, sediment);
}

void erosion_hydraulic(erosion_grid *g, const hydraulic_params *p, hydraulic_report *report) {
    hydraulic_report rep = {0};
    if (report) *report = rep;
    if (erosion_grid_validate(g, NULL) || erosion_hydraulic_validate(p, NULL)) return;
    const int W = g->width, H = g->height;
    if (W < 2 || H < 2 || p->droplets == 0) return;

    // Spawn table: every bilinear cell whose four corners are weighted, with the
    // running sum of its mean corner weight (sampled by bisection).
    size_t cells = (size_t)(W - 1) * (H - 1), count = 0;
    uint32_t *spawn_cell = malloc(cells * sizeof *spawn_cell);
    double *spawn_cdf = malloc(cells * sizeof *spawn_cdf);
    droplet_ctx c = {.h = g->heights, .wt = g->weight, .W = W, .H = H};
    if (!spawn_cell || !spawn_cdf || disc_build(&c.disc, p->radius_cells, W)) goto done;
    double total = 0.0;
    for (int j = 0; j < H - 1; j++) {
        const float *w0 = g->weight + (size_t)j * W, *w1 = w0 + W;
        for (int i = 0; i < W - 1; i++) {
            float a = wclamp(w0[i]), b = wclamp(w0[i + 1]), d = wclamp(w1[i]),
                  e = wclamp(w1[i + 1]);
            if (a > 0.0f && b > 0.0f && d > 0.0f && e > 0.0f) {
                total += 0.25 * ((double)a + b + d + e);
                spawn_cell[count] = (uint32_t)((size_t)j * W + i);
                spawn_cdf[count] = total;
                count++;
            }
        }
    }
    if (count == 0) goto done;

    uint64_t rng = p->seed;
    for (int n = 0; n < p->droplets; n++) {
        double pick = (double)(rng_next(&rng) >> 11) * 0x1p-53 * total;
        size_t lo = 0, hi = count - 1; // first entry whose running sum exceeds pick
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (spawn_cdf[mid] > pick)
                hi = mid;
            else
                lo = mid + 1;
        }
        const int i = (int)(spawn_cell[lo] % (uint32_t)W), j = (int)(spawn_cell[lo] / (uint32_t)W);
        float x = (float)i + rng_unit(&rng), y = (float)j + rng_unit(&rng);
        if ((int)x != i) x = (float)i; // rounded up into the next cell
        if ((int)y != j) y = (float)j;
        droplet_run(&c, p, g->spacing, x, y, &rng, &rep);
        rep.droplets++;
    }

done:
    disc_free(&c.disc);
    free(spawn_cell);
    free(spawn_cdf);
    if (report) *report = rep;
}
