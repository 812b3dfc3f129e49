// The tile cache: between the tile store and generators on one side and the
// editor and renderer on the other. A RAM budget with LRU eviction (dirty tiles
// are written back to the store first), worker threads that load or generate,
// and a request call that never blocks: it answers "not ready yet" and offers the
// nearest coarser level that is ready.
#ifndef OROGEN_IO_TILE_CACHE_H
#define OROGEN_IO_TILE_CACHE_H

#include "io/err.h"
#include "io/tile.h"
#include "io/tile_store.h"

#include <stddef.h>
#include <stdint.h>

typedef struct tile_cache tile_cache;

// Where tiles that are not stored come from: fills tile_layer_bytes(key.layer)
// bytes; returns -1 when the key lies outside the world. Must be thread-safe and
// deterministic (called from the workers).
typedef int (*tile_source_fn)(void *user, tile_key key, void *out);

typedef struct tile_cache_desc {
    size_t budget_bytes;   // resident tile payload limit; 0 = 1 GiB
    int workers;           // loader/generator threads; 0 = 2
    tile_source_fn source; // required
    void *source_user;
    tile_store *store;      // optional; read first, and where dirty tiles go
    tile_store *base_store; // optional; read (never written) when store lacks a tile:
                            // the saved world under a journal of unsaved edits
    // Warnings that are not errors of the caller (a corrupt stored tile that fell
    // back to generated terrain, a failed write-back). Called from any thread.
    void (*warn)(void *user, const char *message);
    void *warn_user;
} tile_cache_desc;

typedef enum tile_status {
    TILE_READY = 0,   // view holds the requested tile
    TILE_PENDING = 1, // queued or in progress; view may hold a coarser level (or nothing)
    TILE_INVALID = -1 // the key lies outside the world
} tile_status;

// A pinned tile: stays resident until released. Read-only unless from acquire_write.
typedef struct tile_view {
    tile_key key;  // the tile actually provided (coarser than asked for a fallback)
    void *data;    // NULL when nothing is provided
    int edited;    // the tile came from a store or was written since generated
                   // (as it was when pinned)
    void *handle_; // internal
} tile_view;

typedef struct tile_cache_stats {
    uint64_t hits, misses; // requests answered from RAM / not
    uint64_t generated, loaded, written, evicted, corrupt;
    size_t resident_bytes; // tile payloads in RAM (the budgeted quantity)
    size_t resident_tiles;
    size_t budget_bytes;
    size_t queue_depth;    // tiles waiting for a worker
    size_t overhead_bytes; // bookkeeping outside the budget: entries and hash buckets
    int workers;
} tile_cache_stats;

tile_cache *tile_cache_create(const tile_cache_desc *desc, og_error *err);
// Stops the workers and frees everything. Dirty tiles are written back first;
// returns -1 with err set if that write fails (the tiles are lost only then).
int tile_cache_destroy(tile_cache *cache, og_error *err);
// The same without writing dirty tiles back: for a store about to be deleted (a world's
// scratch store of unsaved tiles at its close), where the write-back is wasted work.
void tile_cache_destroy_discarding(tile_cache *c);

// Never blocks on I/O or generation. TILE_READY: view pins the tile. TILE_PENDING:
// the tile is queued; view pins the nearest coarser ready level covering the same
// area if there is one (view->data NULL otherwise). Release any non-NULL view.
tile_status tile_cache_request(tile_cache *cache, tile_key key, tile_view *view);
// Blocks until the tile is resident and pins it. Returns -1 for keys outside the world.
int tile_cache_acquire(tile_cache *cache, tile_key key, tile_view *view, og_error *err);
// As acquire, for writing: the tile is marked dirty (written back before eviction).
// Waits while the tile is being written to the store, which reads it unlocked.
int tile_cache_acquire_write(tile_cache *cache, tile_key key, tile_view *view, og_error *err);
void tile_cache_release(tile_cache *cache, tile_view *view);
// The resident tile holds generated terrain again (undo back to never-edited terrain,
// or an edit that touched a never-edited tile without changing it):
// it stays in memory, shown without a gap, but as if just generated (not dirty nor
// edited), so it is never written back and a later generate replaces it. Returns -1 if
// the tile is pinned or still being produced, 0 otherwise (also when not resident).
int tile_cache_mark_generated(tile_cache *cache, tile_key key);

// Keys of the resident tiles of a layer that hold edits (loaded from a store, or
// written since generated): up to max into out; returns how many there are.
size_t tile_cache_edited_keys(tile_cache *cache, int layer, tile_key *out, size_t max);

// Writes every dirty tile to the store in one transaction. Tiles stay resident.
int tile_cache_flush(tile_cache *cache, og_error *err);
// Whether any resident tile has changes not yet written to the store.
int tile_cache_has_dirty(tile_cache *cache);

void tile_cache_stats_get(tile_cache *cache, tile_cache_stats *out);

#endif
