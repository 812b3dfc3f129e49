// Keeps the composite's material weights (slot 0 material tiles, what the renderer and
// exports read) equal to the ground's own paint (the base, slot 1) with every visible
// paint layer laid over it by its coverage (editor/layers/paint_blend.h), weighted by its
// opacity and mask (a paint layer's mask reads the composite heights of the height layers
// below it). Part of the edit that changes them, so undo restores both exactly.
#ifndef OROGEN_EDITOR_PAINT_COMPOSITE_H
#define OROGEN_EDITOR_PAINT_COMPOSITE_H

#include "editor/edit/edit.h"
#include "editor/edit/tile_parts.h"

// Recomputes the material composite over the parts (merged here).
int paint_recompose(edit *e, tile_parts *parts, og_error *err);
// After heights changed over parts: recomputes the materials where a visible paint
// layer's mask reads them (the parts grown by its mask's border); nothing otherwise.
int paint_recompose_masked(edit *e, const tile_part *parts, size_t count, og_error *err);
// At the end of a paint tool's edit: what the tool did to the composite's materials over
// parts goes into the active paint layer (or, with a height layer active, the base) as
// the least coverage that shows it, and the composite follows. The top paint layer at
// full weight keeps the tool's result bit for bit.
int paint_take_edit(edit *e, tile_parts *parts, og_error *err);
// Over keys (material tiles): paint layer `below` (an index) takes what it and the paint
// layer above it show together, opacity and masks included (paint_blend_merge); the
// caller sets its opacity to 1, clears its mask and removes the upper layer.
int paint_merge_tiles(edit *e, int below, const tile_key *keys, size_t count, og_error *err);

#endif
