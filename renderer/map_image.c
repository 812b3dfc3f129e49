#include "renderer/map_image.h"

#include "editor/world_grid.h"

#include <math.h>
#include <stdlib.h>

static int64_t extent_samples(const world *w) {
    const world_params *p = world_get_params(w);
    return p->kind == WORLD_PLANET ? world_grid_face_samples(p) : p->size;
}

map_view map_view_default(const world *w) {
    const world_params *p = world_get_params(w);
    int64_t n = extent_samples(w);
    map_view v = {0, 0, p->spacing * 8.0, 0};
    if (n > 0) {
        v.cx = v.cz = 0.5 * (double)(n - 1) * p->spacing;
        v.mpp = (double)n * p->spacing / 1024.0;
    }
    return v;
}

int map_view_level(const world *w, const map_view *v) {
    double ratio = v->mpp / world_get_params(w)->spacing;
    int level = ratio > 1.0 ? (int)floor(log2(ratio)) : 0;
    return level > TILE_MAX_LEVEL ? TILE_MAX_LEVEL : level;
}

// First pixel whose centre lies at or after world coordinate edge.
static long first_pixel(double edge, double centre, double mpp, int size) {
    double p = ceil((edge - centre) / mpp + size * 0.5 - 0.5);
    return p < 0 ? 0 : (p > size ? size : (long)p);
}

static void shade(const world_params *p, const float *h, const uint8_t *known, double mpp, int w,
                  int hgt, uint8_t *rgba) {
    // Sun from the north-west, 45 degrees up.
    const double sx = -0.5, sy = 0.7071, sz = -0.5;
    double top = p->max_height + p->base_height;
    for (int j = 0; j < hgt; j++) {
        for (int i = 0; i < w; i++) {
            size_t k = (size_t)j * w + i;
            uint8_t *o = rgba + 4 * k;
            o[3] = 255;
            if (!known[k]) {
                o[0] = o[1] = o[2] = 24;
                continue;
            }
            int i0 = i > 0 && known[k - 1] ? i - 1 : i, i1 = i + 1 < w && known[k + 1] ? i + 1 : i;
            int j0 = j > 0 && known[k - w] ? j - 1 : j, j1 = j + 1 < hgt && known[k + w] ? j + 1 : j;
            double dx = i1 > i0 ? (h[(size_t)j * w + i1] - h[(size_t)j * w + i0]) / ((i1 - i0) * mpp) : 0;
            double dz = j1 > j0 ? (h[(size_t)j1 * w + i] - h[(size_t)j0 * w + i]) / ((j1 - j0) * mpp) : 0;
            double len = sqrt(dx * dx + 1.0 + dz * dz);
            double lambert = (-dx * sx + sy - dz * sz) / len;
            double light = 0.35 + 0.65 * (lambert < 0 ? 0 : lambert);
            double r, g, b, height = h[k];
            if (height < p->ocean_level) {
                double depth = fmin(1.0, (p->ocean_level - height) / (0.5 * p->max_height));
                r = 0.10 - 0.06 * depth, g = 0.32 - 0.18 * depth, b = 0.55 - 0.2 * depth;
                light = 0.8 + 0.2 * light;
            } else {
                double a = (height - p->ocean_level) / fmax(1e-6, top - p->ocean_level);
                a = a < 0 ? 0 : (a > 1 ? 1 : a);
                if (a < 0.5) // grass to rock
                    r = 0.30 + 0.30 * a, g = 0.50 - 0.10 * a, b = 0.22 + 0.10 * a;
                else if (a < 0.8) // rock
                    r = 0.45, g = 0.42, b = 0.38;
                else // snow
                    r = g = b = 0.92;
            }
            o[0] = (uint8_t)fmin(255.0, r * light * 255.0 + 0.5);
            o[1] = (uint8_t)fmin(255.0, g * light * 255.0 + 0.5);
            o[2] = (uint8_t)fmin(255.0, b * light * 255.0 + 0.5);
        }
    }
}

int map_image_compose(world *w, const map_view *v, int width, int height, uint8_t *rgba) {
    const world_params *p = world_get_params(w);
    size_t n = (size_t)width * height;
    float *h = calloc(n, sizeof *h);
    uint8_t *known = calloc(n, 1);
    if (!h || !known) {
        free(h), free(known);
        return -1;
    }
    int level = map_view_level(w, v);
    double step = p->spacing * ldexp(1.0, level);
    double tile_m = step * TILE_SIZE;
    int64_t extent = extent_samples(w);
    // The visible world rectangle, clamped to the world and to the int32 tile range.
    double x0 = v->cx - 0.5 * width * v->mpp, x1 = v->cx + 0.5 * width * v->mpp;
    double z0 = v->cz - 0.5 * height * v->mpp, z1 = v->cz + 0.5 * height * v->mpp;
    double lo = -(double)INT32_MAX * tile_m, hi = (double)INT32_MAX * tile_m;
    if (extent > 0) lo = 0, hi = (double)(extent - 1) * p->spacing;
    x0 = fmax(x0, lo), z0 = fmax(z0, lo), x1 = fmin(x1, hi), z1 = fmin(z1, hi);
    int pending = 0;
    tile_cache *cache = world_cache(w);
    if (x0 <= x1 && z0 <= z1) {
        int64_t tx0 = (int64_t)floor(x0 / tile_m), tx1 = (int64_t)floor(x1 / tile_m);
        int64_t tz0 = (int64_t)floor(z0 / tile_m), tz1 = (int64_t)floor(z1 / tile_m);
        for (int64_t ty = tz0; ty <= tz1; ty++) {
            for (int64_t tx = tx0; tx <= tx1; tx++) {
                tile_key key = {TILE_LAYER_COARSE, v->face, level, (int32_t)tx, (int32_t)ty};
                tile_view tv;
                if (tile_cache_request(cache, key, &tv) != TILE_READY) pending++;
                if (!tv.data) continue;
                // Pixels inside this tile's area (and inside the world).
                double ax = fmax((double)tx * tile_m, x0), bx = fmin((double)(tx + 1) * tile_m, x1 + 1e-9);
                double az = fmax((double)ty * tile_m, z0), bz = fmin((double)(ty + 1) * tile_m, z1 + 1e-9);
                long pi0 = first_pixel(ax, v->cx, v->mpp, width), pi1 = first_pixel(bx, v->cx, v->mpp, width);
                long pj0 = first_pixel(az, v->cz, v->mpp, height), pj1 = first_pixel(bz, v->cz, v->mpp, height);
                // The tile provided may be coarser than asked: index it at its own spacing.
                double tstep = p->spacing * ldexp(1.0, tv.key.level);
                double ox = (double)tv.key.tx * TILE_SIZE * tstep, oz = (double)tv.key.ty * TILE_SIZE * tstep;
                const float *data = tv.data;
                for (long j = pj0; j < pj1; j++) {
                    double z = v->cz + (j + 0.5 - height * 0.5) * v->mpp;
                    long sj = (long)floor((z - oz) / tstep);
                    sj = sj < 0 ? 0 : (sj >= TILE_SIZE ? TILE_SIZE - 1 : sj);
                    for (long i = pi0; i < pi1; i++) {
                        double x = v->cx + (i + 0.5 - width * 0.5) * v->mpp;
                        long si = (long)floor((x - ox) / tstep);
                        si = si < 0 ? 0 : (si >= TILE_SIZE ? TILE_SIZE - 1 : si);
                        size_t k = (size_t)j * width + i;
                        h[k] = data[sj * TILE_SIZE + si];
                        known[k] = 1;
                    }
                }
                tile_cache_release(cache, &tv);
            }
        }
    }
    shade(p, h, known, v->mpp, width, height, rgba);
    free(h);
    free(known);
    return pending;
}
