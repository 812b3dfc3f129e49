// What a heightmap export reads (export.h, layers=): the composite, one height layer's
// signed change over the layers below it, or the composite up to a layer.
#ifndef OROGEN_EDITOR_EXPORT_LAYER_READ_H
#define OROGEN_EDITOR_EXPORT_LAYER_READ_H

#include "editor/world/layer_grid.h"

// What to read: export.h's export_layers values.
enum { EXPORT_READ_COMPOSITE = 0, EXPORT_READ_CHANGE = 1, EXPORT_READ_UPTO = 2 };

// Checks layers= against the world's stack: -1 with err naming the layer when there is
// no such height layer, or when the export is not of the coarse grid (grid).
int export_layers_check(world *w, const char *path, int what, const char *name, tile_layer grid,
                        og_error *err);
// Reads the samples r of what (g: the coarse grid) into out (row-major): the composite,
// layer name's change (0 where it changes nothing; the layer counts as visible) or the
// composite up to it.
int export_layers_read(world *w, const layer_grid *g, int what, const char *name, grid_rect r,
                       float *out, og_error *err);

#endif
