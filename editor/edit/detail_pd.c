#include "editor/edit/detail_pd.h"

#include "editor/world/layer_grid.h"
#include "editor/params/world_grid.h"

#include <math.h>
#include <stdlib.h>

static int16_t to_fixed(double slope) {
    double v = nearbyint(slope * DETAIL_PD_SCALE);
    if (!(v > -32767.0)) v = v != v ? 0.0 : -32767.0; // NaN cannot occur; be safe
    if (v > 32767.0) v = 32767.0;
    return (int16_t)v;
}

void detail_pd_encode(const float row[5], const float column[5], double spacing, int16_t out[2]) {
    double k = 1.0 / (12.0 * spacing);
    out[0] = to_fixed(((double)row[0] - 8.0 * row[1] + 8.0 * row[3] - row[4]) * k);
    out[1] = to_fixed(((double)column[0] - 8.0 * column[1] + 8.0 * column[3] - column[4]) * k);
}

static int update_rect(world *w, const layer_grid *g, grid_rect pd, og_error *err) {
    grid_rect src = {pd.x0 - 2, pd.z0 - 2, pd.x1 + 2, pd.z1 + 2};
    int64_t sw = src.x1 - src.x0, sh = src.z1 - src.z0;
    float *h = malloc((size_t)(sw * sh) * sizeof *h);
    if (!h) return og_error_set(err, "out of memory updating the detail normals");
    if (layer_grid_read(w, g, src, h, err) != 0) {
        free(h);
        return -1;
    }
    tile_cache *cache = world_cache(w);
    int rc = 0;
    for (int64_t tz = world_grid_floor_div(pd.z0, TILE_SIZE); tz * TILE_SIZE < pd.z1 && rc == 0;
         tz++)
        for (int64_t tx = world_grid_floor_div(pd.x0, TILE_SIZE); tx * TILE_SIZE < pd.x1 && rc == 0;
             tx++) {
            grid_rect r =
                grid_rect_intersect(pd, (grid_rect){tx * TILE_SIZE, tz * TILE_SIZE,
                                                    (tx + 1) * TILE_SIZE, (tz + 1) * TILE_SIZE});
            if (grid_rect_empty(r)) continue;
            tile_view v;
            tile_key key = {TILE_LAYER_DETAIL_PD, g->face, 0, (int32_t)tx, (int32_t)tz};
            if (tile_cache_acquire_write(cache, key, &v, err) != 0) {
                rc = -1;
                break;
            }
            int16_t *t = v.data;
            for (int64_t z = r.z0; z < r.z1; z++)
                for (int64_t x = r.x0; x < r.x1; x++) {
                    const float *c = h + (z - src.z0) * sw + (x - src.x0);
                    float row[5] = {c[-2], c[-1], c[0], c[1], c[2]};
                    float col[5] = {c[-2 * sw], c[-sw], c[0], c[sw], c[2 * sw]};
                    detail_pd_encode(
                        row, col, g->spacing,
                        t + 2 * ((z - tz * TILE_SIZE) * TILE_SIZE + (x - tx * TILE_SIZE)));
                }
            tile_cache_release(cache, &v);
        }
    free(h);
    return rc;
}

int detail_pd_update(world *w, const dirty_rect *rects, size_t count, og_error *err) {
    for (size_t i = 0; i < count; i++) {
        if (rects[i].layer != TILE_LAYER_DETAIL) continue;
        layer_grid g;
        if (layer_grid_init(&g, world_get_params(w), TILE_LAYER_DETAIL, rects[i].face, err) != 0)
            return -1;
        grid_rect r = rects[i].rect;
        grid_rect pd = layer_grid_clip(&g, (grid_rect){r.x0 - 2, r.z0 - 2, r.x1 + 2, r.z1 + 2});
        if (!grid_rect_empty(pd) && update_rect(w, &g, pd, err) != 0) return -1;
    }
    return 0;
}
