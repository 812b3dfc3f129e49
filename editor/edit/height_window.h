// The composite heights of a stack's height layers over a window, from the base: what a
// layer's mask reads (the layers below it) and what the composites blend over. Shared by
// the heights' composite (layer_composite.c) and the paint layers' (paint_composite.c).
#ifndef OROGEN_EDITOR_HEIGHT_WINDOW_H
#define OROGEN_EDITOR_HEIGHT_WINDOW_H

#include "editor/world/layer_grid.h"

grid_rect height_window_grow(grid_rect r, int by);
// Samples of composite around a height layer its mask reads (0 without a mask, hidden,
// or a paint layer: paint does not change heights).
int height_window_mask_border(const layer_info *l, double spacing);
// The painted coverage of layer l's mask over r (row-major, malloc'd into *out; NULL when
// its mask has no painted term); grid: a coarse grid of r's face.
int height_window_coverage(world *w, const layer_info *l, const layer_grid *grid, grid_rect r,
                           float **out, og_error *err);
// Layer l's mask over r: its weights from the composite below it (below: r grown by b
// samples, b its border) and its painted coverage; out r's size.
int height_window_mask(world *w, const layer_info *l, const layer_grid *grid, grid_rect r,
                       const float *below, int b, float *out, og_error *err);
// The composite of the visible height layers [0, upto) of t over r grown by extra samples
// (row-major, malloc'd into *out), from the base; grid: a coarse grid of r's face. A
// masked layer reads the composite below it around its part: the window starts wider by
// every such border and narrows layer by layer. When record is a layer index, weights
// (r's size) gets its weight, opacity times mask (-1, NULL: none).
int height_window_compose(world *w, const layer_table *t, const layer_grid *grid, grid_rect r,
                          int upto, int extra, int record, float *weights, float **out,
                          og_error *err);

#endif
