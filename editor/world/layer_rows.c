#include "editor/world/layer_rows.h"

#include <string.h>

int layer_rows_open(world *w, const layer_grid *g, grid_rect r, layer_rows *rows, og_error *err) {
    grid_rect in = layer_grid_clip(g, r);
    if (g->layer == TILE_LAYER_MATERIAL || grid_rect_empty(r) || in.x0 != r.x0 || in.x1 != r.x1 ||
        in.z0 != r.z0 || in.z1 != r.z1)
        return 1;
    *rows = (layer_rows){.cache = world_cache(w), .r = r};
    rows->tx0 = world_grid_floor_div(r.x0, TILE_SIZE);
    rows->tz0 = world_grid_floor_div(r.z0, TILE_SIZE);
    rows->tw = world_grid_floor_div(r.x1 - 1, TILE_SIZE) - rows->tx0 + 1;
    rows->th = world_grid_floor_div(r.z1 - 1, TILE_SIZE) - rows->tz0 + 1;
    if (rows->tw * rows->th > LAYER_ROWS_TILES) return 1;
    for (int64_t i = 0; i < rows->tw * rows->th; i++) {
        tile_key key = {g->layer, g->face, 0, (int32_t)(rows->tx0 + i % rows->tw),
                        (int32_t)(rows->tz0 + i / rows->tw)};
        if (tile_cache_acquire(rows->cache, key, &rows->views[i], err) != 0) {
            rows->tw = i, rows->th = 1; // release those pinned so far
            layer_rows_close(rows);
            return -1;
        }
    }
    return 0;
}

void layer_rows_read(const layer_rows *rows, int64_t z, int64_t x0, int64_t x1, float *dst) {
    int64_t tz = world_grid_floor_div(z, TILE_SIZE), local_z = z - tz * TILE_SIZE;
    const tile_view *v = rows->views + (tz - rows->tz0) * rows->tw;
    for (int64_t x = x0; x < x1;) {
        int64_t tx = world_grid_floor_div(x, TILE_SIZE), end = (tx + 1) * TILE_SIZE;
        if (end > x1) end = x1;
        const float *t = v[tx - rows->tx0].data;
        memcpy(dst + (x - x0), t + local_z * TILE_SIZE + (x - tx * TILE_SIZE),
               (size_t)(end - x) * sizeof *dst);
        x = end;
    }
}

void layer_rows_close(layer_rows *rows) {
    for (int64_t i = 0; i < rows->tw * rows->th; i++)
        tile_cache_release(rows->cache, &rows->views[i]);
    rows->tw = rows->th = 0;
}
