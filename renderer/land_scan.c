#include "renderer/land_scan.h"

#include "io/tile.h"
#include "io/tile_cache.h"

#include <math.h>
#include <stdlib.h>

// Level L's sample i lies at level-0 sample i 2^L + 2^L - 1 (each mip sample is centred on
// its middle child: editor/edit/mip_rows.h).
static double level_position(int64_t i, int level) {
    return (double)i * (double)(1LL << level) + (double)((1LL << level) - 1);
}

int land_scan_read(world *w, land_scan *s, og_error *err) {
    const world_params *p = world_get_params(w);
    *s = (land_scan){0};
    if (p->kind == WORLD_PLANET || p->size <= 0)
        return og_error_set(err, "only a bounded flat world can be scanned whole");
    int64_t n = p->size, nz = world_params_size_z(p), narrow = n < nz ? n : nz;
    int level = 0;
    while (level < TILE_MAX_LEVEL && (narrow >> (level + 1)) >= 128)
        level++;
    // The samples whose position lies inside the world.
    int nx = 0, ny = 0;
    while (level_position(nx, level) <= (double)(n - 1))
        nx++;
    while (level_position(ny, level) <= (double)(nz - 1))
        ny++;
    s->height = malloc((size_t)nx * (size_t)ny * sizeof *s->height);
    if (!s->height) return og_error_set(err, "out of memory scanning the world's heights");
    s->nx = nx, s->nz = ny, s->step = p->spacing * (double)(1LL << level);
    s->lowest = INFINITY, s->highest = -INFINITY;
    tile_cache *cache = world_cache(w);
    for (int ty = 0; ty * TILE_SIZE < ny; ty++)
        for (int tx = 0; tx * TILE_SIZE < nx; tx++) {
            tile_key key = {TILE_LAYER_COARSE, 0, level, tx, ty};
            tile_view v;
            if (tile_cache_acquire(cache, key, &v, err) != 0) {
                land_scan_free(s);
                return -1;
            }
            const float *h = v.data;
            for (int j = 0; j < TILE_SIZE && ty * TILE_SIZE + j < ny; j++)
                for (int i = 0; i < TILE_SIZE && tx * TILE_SIZE + i < nx; i++) {
                    float g = h[j * TILE_SIZE + i];
                    s->height[(size_t)(ty * TILE_SIZE + j) * nx + tx * TILE_SIZE + i] = g;
                    if (g < s->lowest) s->lowest = g;
                    if (g > s->highest) s->highest = g;
                }
            tile_cache_release(cache, &v);
        }
    // Positions in metres: sample i at level_position(i) level-0 samples from the origin.
    s->origin = level_position(0, level) * p->spacing;
    return 0;
}

void land_scan_free(land_scan *s) {
    free(s->height);
    s->height = NULL;
}

int land_scan_nearest(const land_scan *s, double cx, double cz, double above, double max_slope,
                      double *x, double *z) {
    double best = INFINITY;
    for (int j = 0; j + 1 < s->nz; j++)
        for (int i = 0; i + 1 < s->nx; i++) {
            const float *h = s->height + (size_t)j * s->nx + i;
            if (!(h[0] > above)) continue;
            double slope = hypot(h[1] - h[0], h[s->nx] - h[0]) / s->step;
            if (!(slope < max_slope)) continue;
            double px = s->origin + i * s->step, pz = s->origin + j * s->step;
            double d = hypot(px - cx, pz - cz);
            if (d < best) best = d, *x = px, *z = pz;
        }
    return best < INFINITY;
}
