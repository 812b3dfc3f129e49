// Runs a per-row function over a rectangle of a layer's level-0 samples, tile by
// tile through an edit (so every touched tile is snapshotted for undo), spread over
// all cores. The row function sees one row span inside one tile; it must only
// depend on the sample coordinates, so the result is the same however tiles split
// the rectangle (the seam guarantee).
#ifndef OROGEN_EDITOR_EDIT_ROWS_H
#define OROGEN_EDITOR_EDIT_ROWS_H

#include "editor/edit/edit.h"
#include "editor/world/layer_grid.h"

// row: the samples [x0, x1) of row z (float* for height layers, TILE_MATERIALS
// bytes per sample for materials). Called concurrently for different tiles.
typedef void (*edit_row_fn)(void *user, void *row, int64_t z, int64_t x0, int64_t x1);
// Whether a tile's part of the rectangle needs visiting (NULL: always). Lets a
// caller skip tiles its footprint only grazes, so they are not snapshotted.
typedef int (*edit_rows_wanted_fn)(void *user, grid_rect part);

// Narrows a tile's part of the rectangle in place to the samples fn may change (a
// rotated footprint's bounding box there): only those are snapshotted, taken into the
// active layer and encoded for undo. Returns 0 to skip the tile.
typedef int (*edit_rows_narrow_fn)(void *user, grid_rect *part);

// Applies fn over r (already clipped to the grid) and records r as dirty.
int edit_rows_apply(edit *e, const layer_grid *g, grid_rect r, edit_row_fn fn,
                    edit_rows_wanted_fn wanted, void *user, og_error *err);
// The same, fn called only over each tile's narrowed part.
int edit_rows_apply_narrowed(edit *e, const layer_grid *g, grid_rect r, edit_row_fn fn,
                             edit_rows_narrow_fn narrow, void *user, og_error *err);

// The same over a plain row-major array holding the samples of `area` (the
// reference path); r must lie inside area.
void edit_rows_apply_array(tile_layer layer, void *data, grid_rect area, grid_rect r,
                           edit_row_fn fn, void *user);

#endif
