#include "editor/world/layer_rows.h"

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

const float *layer_rows_at(const layer_rows *rows, int64_t z, int64_t x, int64_t *end) {
    int64_t tz = world_grid_floor_div(z, TILE_SIZE), tx = world_grid_floor_div(x, TILE_SIZE);
    *end = (tx + 1) * TILE_SIZE < rows->r.x1 ? (tx + 1) * TILE_SIZE : rows->r.x1;
    const float *t = rows->views[(tz - rows->tz0) * rows->tw + (tx - rows->tx0)].data;
    return t + (z - tz * TILE_SIZE) * TILE_SIZE + (x - tx * TILE_SIZE);
}

void layer_rows_close(layer_rows *rows) {
    for (int64_t i = 0; i < rows->tw * rows->th; i++)
        tile_cache_release(rows->cache, &rows->views[i]);
    rows->tw = rows->th = 0;
}
