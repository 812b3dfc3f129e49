// Keeps the composite (the coarse tiles everyone reads: slot 0 of io/tile.h) equal to
// the base under the edit layers blended with every visible layer (editor/layers/
// layer_blend.h), over the areas edits and layer changes touch, as part of the edit
// that changes them (so undo restores both exactly).
#ifndef OROGEN_EDITOR_LAYER_COMPOSITE_H
#define OROGEN_EDITOR_LAYER_COMPOSITE_H

#include "editor/edit/edit.h"

// Recomputes the composite over the level-0 samples r of a face from the base and the
// world's visible layers (its current table).
int layer_recompose(edit *e, int face, grid_rect r, og_error *err);
// The same over whole tiles (level-0 keys of any slot: their face, tx, ty count).
int layer_recompose_tiles(edit *e, const tile_key *keys, size_t count, og_error *err);

// At the end of a tool's edit (edit_commit): what the tool did to the composite goes
// into the active layer, as its layer mode says (edit.h), and the composite is
// recomputed over the changed area. Nothing for an EDIT_LAYER_COMPOSED edit.
int layer_take_edit(edit *e, og_error *err);

// The level-0 tiles a layer holds (id: layer_info.id), in the cache, the unsaved edits or
// the saved store, sorted and each once: *keys malloc'd (NULL when none).
int layer_tiles(world *w, int32_t id, tile_key **keys, size_t *count, og_error *err);
// How many of those hold something (a sample that is not NaN).
int layer_count_filled(world *w, int32_t id, size_t *filled, og_error *err);

// Sets layer `to`'s tiles at keys to layer `from`'s (slots; from < 0: to nothing, NaN).
int layer_copy_tiles(edit *e, int32_t from, int32_t to, const tile_key *keys, size_t count,
                     og_error *err);
// Over keys: layer `below` (an index) takes what it and the layer above it show together
// (layer_blend_solve: exact where a float allows), for `layer merge` (the caller then
// removes the upper layer).
int layer_merge_tiles(edit *e, int below, const tile_key *keys, size_t count, og_error *err);

#endif
