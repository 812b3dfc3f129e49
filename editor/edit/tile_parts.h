// Areas of level-0 samples cut along tile edges, each tile once: the unit of work the
// composites (layer_composite.h, paint_composite.h) hand to the parallel pool.
#ifndef OROGEN_EDITOR_TILE_PARTS_H
#define OROGEN_EDITOR_TILE_PARTS_H

#include "editor/edit/edit.h"
#include "editor/params/world_grid.h"

#include <stddef.h>
#include <stdint.h>

// The part of one tile: local sample columns [x0, x1), rows [z0, z1).
typedef struct tile_part {
    int face;
    int32_t tx, ty;
    int x0, z0, x1, z1;
} tile_part;

typedef struct tile_parts {
    tile_part *parts;
    size_t count, cap;
} tile_parts;

// Adds r's part of every tile it touches; -1 when out of memory.
int tile_parts_add_rect(tile_parts *l, int face, grid_rect r);
// Sorts by face and tile and merges each tile's parts into their bounding box.
void tile_parts_merge(tile_parts *l);
void tile_parts_free(tile_parts *l);

// Grows changed (local to a part; empty: x0 > x1) by the sample (x, z).
static inline void tile_part_touch(grid_rect *changed, int x, int z) {
    if (changed->x0 > changed->x1) *changed = (grid_rect){x, z, x + 1, z + 1};
    if (x < changed->x0) changed->x0 = x;
    if (z < changed->z0) changed->z0 = z;
    if (x + 1 > changed->x1) changed->x1 = x + 1;
    if (z + 1 > changed->z1) changed->z1 = z + 1;
}
// Marks changed (local to the samples r of a part) dirty in the edit, when not empty.
void tile_part_publish(edit *e, tile_layer kind, int face, grid_rect r, grid_rect changed);

#endif
