// The document: a world's parameters, its tile store and the tile cache over
// them. Everything that reads or changes terrain goes through a world.
#ifndef OROGEN_EDITOR_WORLD_H
#define OROGEN_EDITOR_WORLD_H

#include "editor/params/world_params.h"
#include "editor/world/recovery_journal.h"
#include "editor/world/world_events.h"
#include "io/err.h"
#include "io/tile_cache.h"
#include "io/tile_store.h"

#include <stdint.h>

typedef struct world_settings {
    size_t cache_budget_bytes;   // 0 = 1 GiB
    size_t history_budget_bytes; // undo memory; 0 = 512 MiB
    int workers;                 // 0 = 2
    // Warnings (corrupt tiles, unknown keys while loading); NULL = stderr.
    void (*warn)(void *user, const char *message);
    void *warn_user;
    // Where the world publishes its changes. Shared by every world the program opens
    // (so a subscriber hears WORLD_EVENT_REPLACED and keeps its subscription); NULL =
    // the world makes a private hub, freed with it.
    world_events *events;
    // A script drives this run (-c, --batch FILE): the script is the record of its edits,
    // so a journal the run began (of a never-saved or a saved world) is removed when the
    // world closes, unless the script failed (world_keep_journal). A kill leaves it for
    // `recover`; a journal taken over by `recover` or set aside stays.
    int scripted;
} world_settings;

typedef struct world world;
typedef struct history history;

// A new, unsaved world. Its edits live in a scratch tile store in $TMPDIR until
// the first save moves them beside the parameter file.
world *world_create(const world_params *params, const world_settings *settings, og_error *err);
// Loads NAME.world / NAME.planet and opens its tile store. Diagnostics (bad values,
// unknown keys) go to settings->warn; *errors counts the errors among them.
// Returns NULL (err set) only when the file cannot be read or the store cannot be opened.
world *world_load(const char *path, const world_settings *settings, int *errors, og_error *err);
// Frees the world. Unsaved edits are discarded: the world's files stay as last saved.
void world_close(world *w);

// Saves the parameter file to path (NULL: the current path) and the tile store
// beside it, copying stored tiles when saving somewhere new. Atomic per file. On
// failure the world keeps working as before (its cache is replaced only once the
// new one runs). Publishes WORLD_EVENT_SAVED.
// Unless force is set, it refuses to write over what it would destroy: its own file
// when that loaded with errors (the bad lines would become defaults), or an existing
// file that is not a parameter file.
int world_save(world *w, const char *path, int force, og_error *err);
// Errors the parameter file had when loaded (0 for a clean file, and after a save).
int world_file_errors(const world *w);
// The first of those errors, one "LINE: error: MESSAGE" per line ("" when none).
const char *world_file_problems(const world *w);
// Why save will not write over the world's own files without force ("" when it
// will): its tile store was missing, empty or another world's when it was loaded.
const char *world_read_only(const world *w);

// Crash recovery (recovery_journal.h). Records a committed step, or its undo or redo,
// in the journal beside the world's file, or for a never-saved world in the recovery
// folder (edit.c calls it for every history change; a read-only world keeps none).
void world_journal_record(world *w, recovery_kind kind, const history_step *s);
// Waits until the journal's file holds every record made (its writer thread writes each
// one after world_journal_record returns): for readers of this session's journal file.
void world_journal_wait(const world *w);
// Steps a session that did not save left in the journal, on the state the world was
// loaded in (0: none), and when the last was made.
size_t world_recoverable(const world *w, int64_t *when);
const char *world_recovery_path(const world *w); // "" for a never-saved world
const char *world_state_id(const world *w);      // the saved state edits build on
// While `recover` replays the journal, its steps are not recorded again.
void world_journal_pause(world *w, int paused);
// A never-saved world made from a file: the text its crash journal keeps beside its base
// parameters (the command layer's: the raster, its options and a checksum of its
// samples), so a journal need not copy what a replay can read again from the file.
// NULL or "" = none. Set before the world's first journaled step.
int world_set_base_source(world *w, const char *source, og_error *err);
// After `recover`: this session's records follow the first keep_bytes of journal (NULL:
// the world's own), which is now this session's.
int world_journal_continue(world *w, const char *journal, size_t keep_bytes, og_error *err);
// Whether this session has written a journal (edited, or recovered) since its last save.
int world_session_journaled(const world *w);
// The script driving this run failed (a save on a full disk, a bad command): the journal
// it began stays when the world closes, for `recover`.
void world_keep_journal(world *w);
// The folder of never-saved worlds' journals ($OROGEN_RECOVER_DIR, else
// $XDG_STATE_HOME/orogen/recover, else ~/.local/state/orogen/recover), created if need be.
int world_recovery_dir(char *out, size_t len, og_error *err);
// After recovering a never-saved world's journal into w: the journal becomes w's own
// (its first keep_bytes), under this process's name.
int world_adopt_journal(world *w, const char *journal, size_t keep_bytes, og_error *err);
// `recover discard`: removes the journal.
int world_recover_discard(world *w, og_error *err);

// Replaces the generation parameters (the `generate` command): cached generated
// tiles are dropped, edited (stored) tiles stay, and so do the material rules. On failure nothing
// changes (the old cache runs until the new one does). Publishes WORLD_EVENT_PARAMS.
int world_regenerate(world *w, const world_params *params, og_error *err);

// Replaces the automatic material rules: how the ground looks, not what it is (no tile
// changes; the renderer reads them from the parameters each frame).
void world_set_material_rules(world *w, const material_rules *rules);

const world_params *world_get_params(const world *w);
// The hub the world publishes its changes to (world_settings.events, or its own).
world_events *world_event_hub(world *w);
// Publishes e on the world's hub (editor/world/world_events.h says who may call it when).
void world_publish(world *w, const world_event *e);
// Publishes that level-0 samples r of a layer on a face changed.
void world_publish_area(world *w, tile_layer layer, int face, grid_rect r);
const char *world_path(const world *w); // "" for a never-saved world
tile_cache *world_cache(world *w);
// The world's own tile store (NULL until saved), and the journal of unsaved edits
// (where the cache writes dirty tiles; merged into the store by world_save).
tile_store *world_store(world *w);
tile_store *world_journal(world *w);
// The undo history (editor/history.h; applied by editor/edit.h).
history *world_history(world *w);
// Whether the world differs from its last save (or from how it was created or loaded).
int world_is_modified(const world *w);
// Reports something the user should know that is not an error (settings->warn).
void world_warn(const world *w, const char *message);

// Coarse height in metres at face-local metres (x, z): bilinear between level-0 samples.
// Fails for positions outside a bounded world or a non-existent face.
int world_sample(world *w, int face, double x, double z, double *height, og_error *err);

// A 64-bit digest of the level-0 coarse heights of every sample whose position lies in
// [x0, x1] x [z0, z1] metres (face-local), visited tile by tile in row-major tile
// order, each tile's covered samples row-major. *count gets the number of samples.
int world_hash(world *w, int face, double x0, double z0, double x1, double z1, uint64_t *digest,
               uint64_t *count, og_error *err);

#endif
