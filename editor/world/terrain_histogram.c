#include "editor/world/terrain_histogram.h"

#include "editor/layers/layer_mask.h"
#include "editor/params/world_grid.h"
#include "io/tile_cache.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

// Level-L samples [gx0, gx1] x [gz0, gz1] into out (row-major), tile by tile.
static int read_grid(world *w, int face, int level, int64_t gx0, int64_t gz0, int64_t gx1,
                     int64_t gz1, float *out, og_error *err) {
    int64_t across = gx1 - gx0 + 1;
    int64_t tx0 = world_grid_floor_div(gx0, TILE_SIZE), tx1 = world_grid_floor_div(gx1, TILE_SIZE);
    int64_t tz0 = world_grid_floor_div(gz0, TILE_SIZE), tz1 = world_grid_floor_div(gz1, TILE_SIZE);
    for (int64_t tz = tz0; tz <= tz1; tz++)
        for (int64_t tx = tx0; tx <= tx1; tx++) {
            tile_key key = {TILE_LAYER_COARSE, face, level, (int32_t)tx, (int32_t)tz};
            tile_view v;
            if (tile_cache_acquire(world_cache(w), key, &v, err) != 0) return -1;
            const float *h = v.data;
            int64_t bx = tx * TILE_SIZE, bz = tz * TILE_SIZE;
            for (int64_t z = bz > gz0 ? bz : gz0; z <= gz1 && z < bz + TILE_SIZE; z++)
                for (int64_t x = bx > gx0 ? bx : gx0; x <= gx1 && x < bx + TILE_SIZE; x++)
                    out[(z - gz0) * across + (x - gx0)] = h[(z - bz) * TILE_SIZE + (x - bx)];
            tile_cache_release(world_cache(w), &v);
        }
    return 0;
}

static int by_value(const void *a, const void *b) {
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

// Fractions of the finite values of v[0..n) in equal bins over [lo, hi] (the tails in
// the end bins).
static void count_bins(const float *v, size_t n, double lo, double hi, float *bins_out) {
    const int bins = TERRAIN_HISTOGRAM_BINS;
    size_t counted = 0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(v[i])) continue;
        double at = fmin(fmax((v[i] - lo) / (hi - lo) * bins, 0), bins - 1);
        bins_out[(int)at] += 1;
        counted++;
    }
    for (int b = 0; b < bins && counted; b++)
        bins_out[b] /= (float)counted;
}

// Curvatures of the grid's inner samples and flow over all of it, binned into out; the
// flow areas left in *flow (NULL: freed).
static int curvature_and_flow(const float *h, int64_t nx, int64_t nz, double step,
                              terrain_histogram *out, float **flow, og_error *err) {
    size_t inner = (size_t)((nx - 2) * (nz - 2)), n = (size_t)(nx * nz);
    float *k = malloc(inner * sizeof *k), *sorted = malloc(n * sizeof *sorted);
    float *area = malloc(n * sizeof *area);
    if (!k || !sorted || !area || layer_mask_flow_area(h, (int)nx, (int)nz, 0, step, area) != 0) {
        free(k), free(sorted), free(area);
        return og_error_set(err, "histogram: out of memory");
    }
    layer_mask_curvature(h, (int)nx - 2, (int)nz - 2, 1, step, k);
    size_t finite = 0;
    for (size_t i = 0; i < inner; i++)
        if (isfinite(k[i])) sorted[finite++] = k[i];
    qsort(sorted, finite, sizeof *sorted, by_value);
    out->curvature_min = finite ? sorted[finite / 100] : 0;
    out->curvature_max = finite ? sorted[finite - 1 - finite / 100] : 0;
    if (!(out->curvature_max > out->curvature_min)) // flat ground: a range around it
        out->curvature_min -= 1, out->curvature_max += 1;
    count_bins(k, inner, out->curvature_min, out->curvature_max, out->curvature);
    double most = step * step;
    for (size_t i = 0; i < n; i++) {
        if (isfinite(area[i])) most = fmax(most, area[i]);
        sorted[i] = isfinite(area[i]) ? (float)log10(fmax(area[i], step * step)) : NAN;
    }
    out->flow_min = step * step, out->flow_max = most > step * step ? most : step * step * 10;
    count_bins(sorted, n, log10(out->flow_min), log10(out->flow_max), out->flow);
    free(k), free(sorted);
    if (flow)
        *flow = area;
    else
        free(area);
    return 0;
}

void terrain_flow_field_free(terrain_flow_field *flow) {
    free(flow->area);
    memset(flow, 0, sizeof *flow);
}

int terrain_histogram_compute(world *w, int face, double cx, double cz, double half,
                              terrain_histogram *out, og_error *err) {
    return terrain_histogram_compute_flow(w, face, cx, cz, half, out, NULL, err);
}

int terrain_histogram_compute_flow(world *w, int face, double cx, double cz, double half,
                                   terrain_histogram *out, terrain_flow_field *flow,
                                   og_error *err) {
    if (flow) terrain_flow_field_free(flow);
    const world_params *p = world_get_params(w);
    double sp = world_grid_sample_metres(p);
    memset(out, 0, sizeof *out);
    if (!isfinite(cx) || !isfinite(cz) || !(half > 0))
        return og_error_set(err, "histogram: the area needs a finite centre and a size");
    int level = 0;
    while (level < TILE_MAX_LEVEL && 2 * half / (sp * ldexp(1, level)) > TERRAIN_HISTOGRAM_SIDE)
        level++;
    double step = sp * ldexp(1, level);
    double x0 = cx - half, z0 = cz - half, x1 = cx + half, z1 = cz + half;
    if (p->kind == WORLD_PLANET) { // within the face
        double m = (double)(world_grid_face_samples(p) - 1) * sp;
        x0 = fmax(x0, 0), z0 = fmax(z0, 0), x1 = fmin(x1, m), z1 = fmin(z1, m);
    } else if (p->size > 0) { // a bounded world: within its samples
        double xm = (double)(p->size - 1) * sp, zm = (double)(world_params_size_z(p) - 1) * sp;
        x0 = fmax(x0, 0), z0 = fmax(z0, 0), x1 = fmin(x1, xm), z1 = fmin(z1, zm);
    }
    int64_t gx0 = (int64_t)ceil(x0 / step), gz0 = (int64_t)ceil(z0 / step);
    int64_t gx1 = (int64_t)floor(x1 / step), gz1 = (int64_t)floor(z1 / step);
    if (gx1 - gx0 < 2 || gz1 - gz0 < 2)
        return og_error_set(err, "histogram: the area around (%.1f, %.1f) is outside the world", cx,
                            cz);
    if (fabs((double)gx0) > 2e9 || fabs((double)gx1) > 2e9 || fabs((double)gz0) > 2e9 ||
        fabs((double)gz1) > 2e9)
        return og_error_set(err, "histogram: the area lies beyond the int32 tile range");
    int64_t nx = gx1 - gx0 + 1, nz = gz1 - gz0 + 1;
    float *h = malloc((size_t)(nx * nz) * sizeof *h);
    if (!h) return og_error_set(err, "histogram: out of memory");
    if (read_grid(w, face, level, gx0, gz0, gx1, gz1, h, err) != 0) {
        free(h);
        return -1;
    }
    double lo = INFINITY, hi = -INFINITY;
    for (int64_t i = 0; i < nx * nz; i++)
        if (isfinite(h[i])) lo = fmin(lo, h[i]), hi = fmax(hi, h[i]);
    if (!(lo <= hi)) lo = hi = 0;
    out->x0 = (double)gx0 * step, out->z0 = (double)gz0 * step;
    out->x1 = (double)gx1 * step, out->z1 = (double)gz1 * step;
    out->spacing = step;
    out->height_min = lo, out->height_max = hi > lo ? hi : lo + 1;
    const int bins = TERRAIN_HISTOGRAM_BINS;
    double hspan = out->height_max - out->height_min;
    size_t n = 0, ns = 0;
    for (int64_t z = 0; z < nz; z++)
        for (int64_t x = 0; x < nx; x++) {
            float v = h[z * nx + x];
            if (!isfinite(v)) continue;
            int b = (int)((v - out->height_min) / hspan * bins);
            out->height[b < 0 ? 0 : b >= bins ? bins - 1 : b] += 1;
            n++;
            if (x == 0 || z == 0 || x == nx - 1 || z == nz - 1) continue;
            // Central differences, as masks read slopes (editor/layers/layer_mask.h).
            double dx = (h[z * nx + x + 1] - h[z * nx + x - 1]) / (2 * step);
            double dz = (h[(z + 1) * nx + x] - h[(z - 1) * nx + x]) / (2 * step);
            double deg = atan(sqrt(dx * dx + dz * dz)) * 180.0 / M_PI;
            if (!isfinite(deg)) continue;
            int s = (int)(deg / 90.0 * bins);
            out->slope[s < 0 ? 0 : s >= bins ? bins - 1 : s] += 1;
            ns++;
        }
    for (int b = 0; b < bins; b++) {
        out->height[b] = n ? out->height[b] / (float)n : 0;
        out->slope[b] = ns ? out->slope[b] / (float)ns : 0;
    }
    out->samples = n;
    float *area = NULL;
    int rc = curvature_and_flow(h, nx, nz, step, out, flow ? &area : NULL, err);
    free(h);
    if (rc != 0) return -1;
    if (flow) *flow = (terrain_flow_field){area, (int)nx, (int)nz, out->x0, out->z0, step};
    return 0;
}
