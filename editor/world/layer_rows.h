// A rectangle of a layer's float samples read row by row straight from its tiles (the
// tiles pinned while it is open), for kernels that read their input where it lies:
// no copy of the rectangle first.
#ifndef OROGEN_EDITOR_LAYER_ROWS_H
#define OROGEN_EDITOR_LAYER_ROWS_H

#include "editor/world/layer_grid.h"

enum { LAYER_ROWS_TILES = 16 }; // at most 4 x 4 tiles (a rectangle of 769^2 samples fits)

typedef struct layer_rows {
    tile_cache *cache;
    grid_rect r;
    int64_t tx0, tz0, tw, th;
    tile_view views[LAYER_ROWS_TILES]; // row-major, tw x th
} layer_rows;

// Pins the tiles of r (coarse or detail heights). 0; 1 when r is not wholly inside the
// grid or spans more than LAYER_ROWS_TILES tiles (nothing pinned: read it with
// layer_grid_read instead); -1 on error (err set).
int layer_rows_open(world *w, const layer_grid *g, grid_rect r, layer_rows *rows, og_error *err);
// Points at sample x of row z (r.z0 <= z < r.z1, r.x0 <= x < r.x1), contiguous in its
// tile up to column *end (the tile's right edge or r.x1, whichever comes first).
const float *layer_rows_at(const layer_rows *rows, int64_t z, int64_t x, int64_t *end);
void layer_rows_close(layer_rows *rows);

#endif
