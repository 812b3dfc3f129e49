// Changing a world: every change is an edit (one undo step). An edit snapshots each
// tile the first time it touches it; recording turns the snapshots into the step's
// compressed deltas and publishes the changed areas (world_events.h). Undo and redo
// replay steps exactly.
#ifndef OROGEN_EDITOR_EDIT_H
#define OROGEN_EDITOR_EDIT_H

#include "editor/world/history.h"
#include "editor/world/layer_grid.h"
#include "editor/world/world.h"
#include "io/err.h"

typedef struct edit edit;

edit *edit_begin(world *w, const char *label, og_error *err);
world *edit_world(edit *e);

// How the edit's changes to the composite heights (coarse level-0 tiles, slot 0) reach
// the edit layers (editor/edit/layer_composite.h).
typedef enum edit_layer_mode {
    // The tool's result is what should be seen: the active layer takes what makes the
    // composite show it (smooth, flatten, set, terrace, erosion, import).
    EDIT_LAYER_RESULT = 0,
    // The tool's change is a delta the active layer adds (raise, lower, noise, stamps):
    // its opacity scales it like everything in the layer.
    EDIT_LAYER_DELTA,
    // The caller keeps layers and composite in step itself (layer commands).
    EDIT_LAYER_COMPOSED
} edit_layer_mode;
edit_layer_mode edit_get_layer_mode(const edit *e);
void edit_set_layer_mode(edit *e, edit_layer_mode mode);
// Makes the edit the world's starting state rather than an undo step (a world made
// from a raster is that raster): committing keeps the change and records no step, so
// the world holds no copy of it and undo has nothing to go back to.
void edit_set_starting_state(edit *e);
// Changes the world's parameters (the layer table) as part of the edit: at once, and
// undone with it. Returns -1 with err when the world refuses them.
int edit_set_params(edit *e, const world_params *params, og_error *err);

// Pins a level-0 tile for writing (loading or generating it if needed), snapshotting
// it on the edit's first touch. Thread-safe: parallel dab tasks call it. Refuses the
// composite's coarse tiles while the active layer is hidden or locked (err says so).
int edit_tile_acquire(edit *e, tile_key key, tile_view *view, og_error *err);
// The same when the caller writes only the tile-local samples `part` (x, z in [0,
// TILE_SIZE)): only they are copied for undo (the first time), and only they are
// compared and encoded at the commit, so a small change costs little in a big tile.
int edit_tile_acquire_part(edit *e, tile_key key, grid_rect part, tile_view *view, og_error *err);
// The same, also giving what edit_snapshot would after it (the tile's bytes before the
// edit and the part of them kept), found under the same lock (a mip update's per level).
int edit_tile_acquire_snapshot(edit *e, tile_key key, grid_rect part, tile_view *view,
                               const void **before, grid_rect *kept, og_error *err);
void edit_tile_release(edit *e, tile_view *view);
// Records a changed area (level-0 samples of that layer) and publishes it, except a
// coarse or material area, published once its mip levels are current (edit_mips_update).
// Thread-safe.
void edit_dirty(edit *e, tile_layer layer, int face, grid_rect r);

// For mip and PD maintenance: a touched tile's bytes before the edit (NULL if
// untouched), and the changed areas so far. Only the samples in *part (tile-local:
// what the edit acquired so far, NULL to ignore) are kept: the tile's other samples
// are unchanged, and the snapshot's bytes there are undefined.
const void *edit_snapshot(edit *e, tile_key key, grid_rect *part);
// The same for n tiles at once (one lock): before[i] and part[i] for keys[i].
void edit_snapshots(edit *e, const tile_key *keys, size_t n, const void **before, grid_rect *part);
size_t edit_dirty_rects(edit *e, const dirty_rect **rects);
// How many of the dirty areas have reached the mip levels and been published
// (edit_mips.c keeps it); later changes start new areas after them.
size_t edit_mips_current(const edit *e);
void edit_set_mips_current(edit *e, size_t count);
// Publishes the coarse and material dirty areas from index first on (their mip levels current):
// each change reaches the world's subscribers once, live or at the commit.
void edit_publish_from(edit *e, size_t first);

// Ends the edit as one undo step holding the touched tiles' deltas as they are now
// (edit_commit in edit_commit.h first brings mips and PD maps up to date: use that).
// On failure the world is restored to its state before the edit. Frees e either way.
int edit_record(edit *e, og_error *err);
// Starts encoding the deltas of the level-0 height tiles (a few at most) in the
// editing pool, for edit_record to collect: edit_commit calls it after the layer take,
// when nothing later writes them, and updates the mip levels meanwhile.
void edit_record_start(edit *e);
// Restores every touched tile and frees e.
void edit_abort(edit *e);

// Undo / redo one step: 1 if a step was replayed, 0 if there was none, -1 on error.
int edit_undo(world *w, og_error *err);
int edit_redo(world *w, og_error *err);
// Replays one step onto the world (undo: backwards), as undo and redo do, without
// touching the history (crash recovery rebuilds it around this).
int edit_apply_step(world *w, const history_step *s, int undo, og_error *err);
// `generate` as an undoable step: the world switches to new parameters (its layer table
// stays). The composite keeps its tiles as they were: layer_generate (layer_composite.h)
// is `generate` with the layers recomposed on the new terrain.
int edit_generate(world *w, const world_params *params, og_error *err);
// Whether the world may switch to params: -1 with err saying why not (volume edits on
// another voxel size).
int edit_generate_check(world *w, const world_params *params, og_error *err);
// A change of the material rules as an undoable step labelled label (no tile changes).
int edit_material_rules(world *w, const material_rules *rules, const char *label, og_error *err);

// Mip levels kept in step with level-0 edits on flat worlds, bounded or not (the
// viewport's clipmap reads that deep); larger worlds and planet faces: down to the level
// where one sample covers everything (edit_mips_top_level).
#define EDIT_MIP_LEVELS_UNBOUNDED 12

#endif
