// One brush dab: the brush resolved at a position, in the sample units of the layer
// it edits, and its application either to a world's tiles (through an edit) or to
// one plain array (the reference the tiled path must match bit for bit).
#ifndef OROGEN_EDITOR_BRUSH_DAB_H
#define OROGEN_EDITOR_BRUSH_DAB_H

#include "editor/tools/brush.h"
#include "editor/edit/edit.h"
#include "editor/world/layer_grid.h"

typedef struct brush_dab {
    const brush *brush;
    double cx, cz;  // centre, in samples
    double radius;  // in samples
    float strength; // brush strength x pressure
    double spacing; // metres per sample of the edited layer
    float target;   // flatten / set: height to blend toward
    // ramp: from (ax, az) at height ha to (bx, bz) at hb, in samples
    double ax, az, bx, bz;
    float ha, hb;
    uint64_t seed; // hydraulic: this dab's droplets
} brush_dab;

// The samples a dab can change (before clipping to the world).
grid_rect brush_dab_rect(const brush_dab *d);

// Applies the dab to the world (edits the tiles of g's layer through e).
int brush_dab_apply(edit *e, const layer_grid *g, const brush_dab *d, og_error *err);

// Applies the dab to a plain row-major array holding the samples of `area` (floats
// for coarse/detail, TILE_MATERIALS bytes per sample for the material layer).
// Samples outside `area` read as its nearest edge sample, as outside a bounded world.
// With area = the whole bounded world this is the same operation as brush_dab_apply.
int brush_dab_apply_array(const brush_dab *d, tile_layer layer, void *data, grid_rect area,
                          og_error *err);

#endif
