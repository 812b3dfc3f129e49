// The undo history: a list of steps, each holding per touched tile the XOR of the
// tile's bytes before and after the step, compressed. XOR makes undo and redo the
// same exact operation (bits ^= delta) and compresses to almost nothing where the
// step left the tile unchanged. A memory budget drops the oldest steps.
//
// Pure bookkeeping: applying a step to a world is editor/edit/edit.c's job, and
// telling others what changed is the world's change notifications' (world_events.h).
#ifndef OROGEN_EDITOR_HISTORY_H
#define OROGEN_EDITOR_HISTORY_H

#include "editor/params/world_grid.h"
#include "editor/params/world_params.h"
#include "io/tile.h"

#include <stddef.h>
#include <stdint.h>

typedef struct history_tile {
    tile_key key;
    int was_pristine; // never edited before the step: undo may forget it (regenerate)
    size_t bytes;     // compressed delta size
    void *delta;
} history_tile;

// Apart from the step (14 KB each): a fresh zeroed 28 KB per step, most of it never
// used, cost a brush dab's commit a few page faults.
typedef struct history_params {
    world_params before, after;
} history_params;

typedef struct history_step {
    uint64_t id;
    char label[128];
    history_tile *tiles;
    size_t tile_count;
    int has_params; // a `generate`: the world's parameters before and after, in params
    history_params *params;
    dirty_rect *dirty;
    size_t dirty_count;
    size_t raw_bytes; // bytes of the tiles it covers, uncompressed (for reports)
    size_t bytes;     // memory the step holds
} history_step;

typedef struct history history;

history *history_create(size_t budget_bytes); // 0 = 512 MiB
void history_destroy(history *h);
// Something reads the steps' deltas on another thread after the calls that gave it them
// (the crash journal's writer): wait(user) returns once it has finished, and the history
// calls it before it frees or replaces a step's delta (a new step, an undo or redo, a
// budget change, its end). NULL: nothing to wait for.
void history_set_reader(history *h, void (*wait)(void *user), void *user);

// A new empty step (owned by the caller until pushed).
history_step *history_step_new(const char *label);
void history_step_free(history_step *s);
// Gives the step parameters (has_params); -1 when out of memory.
int history_step_set_params(history_step *s, const world_params *before, const world_params *after);
// The compressed XOR of before and after (tile_layer_bytes(layer) each): *delta is
// malloc'd, or NULL when the tile did not change. Returns -1 when out of memory.
// Thread-safe (pure).
int history_delta_encode(tile_layer layer, const void *before, const void *after, void **delta,
                         size_t *bytes);
// The same over the tile-local samples `part` only (the rest of the tile is the same
// before and after): the cost follows the changed area, not the tile. Its delta says
// which part it covers; history_tile_apply takes either kind.
int history_delta_encode_part(tile_layer layer, const void *before, const void *after,
                              grid_rect part, void **delta, size_t *bytes);
// The same without zstd (zero runs only), at memory speed: for a commit, whose step
// history_push then has zstd tried on in the background (see history.c).
int history_delta_encode_part_quick(tile_layer layer, const void *before, const void *after,
                                    grid_rect part, void **delta, size_t *bytes);
// Adds an encoded delta to a step (takes ownership of delta).
int history_step_add_delta(history_step *s, tile_key key, int was_pristine, void *delta,
                           size_t bytes);
int history_step_add_dirty(history_step *s, dirty_rect r);
// Applies a stored delta to a tile's bytes in place (undo and redo alike).
int history_tile_apply(const history_tile *t, void *data);

// Takes ownership of s: drops every redo step, appends s, then drops the oldest
// steps while over budget (never s itself). Returns how many old steps were dropped.
// s's deltas may be replaced by smaller ones (zstd, tried in the background) at the
// next push, peek or budget change: call these from one thread, the one that edits.
size_t history_push(history *h, history_step *s);
// The step undo would revert / redo would reapply, or NULL; *_done moves past it.
history_step *history_undo_peek(history *h);
void history_undo_done(history *h);
history_step *history_redo_peek(history *h);
void history_redo_done(history *h);

size_t history_count(const history *h);    // steps held
size_t history_position(const history *h); // steps applied (the rest can be redone)
const history_step *history_at(const history *h, size_t i);
size_t history_bytes(const history *h);
size_t history_budget(const history *h);
size_t history_set_budget(history *h, size_t budget_bytes); // returns steps dropped
uint64_t history_dropped_total(const history *h);

// Unsaved-changes tracking: the state when mark_saved was last called vs now.
void history_mark_saved(history *h);
int history_modified(const history *h);
// The position (steps applied) at which the world was last saved, or -1 when that
// state is not in the history any more (dropped, or replaced by a new branch).
long history_saved_position(const history *h);

#endif
