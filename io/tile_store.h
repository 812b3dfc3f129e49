// The tile store: one SQLite file (WAL) beside a world's parameter file holding
// only the tiles a person sculpted, painted or imported. Unedited terrain is never
// stored; it is regenerated from the parameters.
//
// Blobs are losslessly compressed (a float-aware transform, then zstd) and carry
// a checksum. Writes happen in transactions, so a process killed at any instant
// leaves the old or the new state. A tile that fails its checksum or does not
// decompress is reported as corrupt (never a crash); callers fall back to the
// generated terrain.
//
// Thread-safe: one store may be used from several threads at once.
#ifndef OROGEN_IO_TILE_STORE_H
#define OROGEN_IO_TILE_STORE_H

#include "io/err.h"
#include "io/tile.h"

#include <stddef.h>
#include <stdint.h>

typedef struct tile_store tile_store;

typedef enum tile_store_status {
    TILE_STORE_OK = 0,
    TILE_STORE_NOT_FOUND = 1, // no such tile stored: use the generated terrain
    TILE_STORE_CORRUPT = 2,   // stored but unreadable: err names the tile; use generated terrain
    TILE_STORE_ERROR = -1     // I/O or database failure: err says what
} tile_store_status;

// Opens (creating if needed) the store at path. Fails with a message naming the
// path if it is not an Orogen tile store, names a format, schema or blob version this
// Orogen does not know (nothing is written then), or cannot be opened.
tile_store *tile_store_open(const char *path, og_error *err);
// tile_store_open, or when the store exists but cannot be written (a read-only file
// system or folder, an unwritable file, a full disk) opened for reading only:
// tile_store_read_only then names that cause. Never for a damaged or foreign store.
tile_store *tile_store_open_readable(const char *path, og_error *err);
// Why the store was opened for reading only ("" when it is writable).
const char *tile_store_read_only(const tile_store *store);
void tile_store_close(tile_store *store);
// What opening found and did, for the user ("" when nothing): a write-ahead log beside
// the store that is not its own (another store's, a copy's) is moved aside as
// PATH-wal.foreign before SQLite could replay it, never replayed.
const char *tile_store_warning(const tile_store *store);
const char *tile_store_path(const tile_store *store);
// The SQLite and zstd versions the store runs with ("SQLite 3.40.1, zstd 1.5.4").
const char *tile_store_library_versions(void);

// Reads one tile into out (bytes must equal tile_layer_bytes(key.layer)).
tile_store_status tile_store_get(tile_store *store, tile_key key, void *out, size_t bytes,
                                 og_error *err);

// Whether a tile is stored (cheap; no decompression).
int tile_store_has(tile_store *store, tile_key key);

// One tile to write (or delete when data is NULL) in a batch.
typedef struct tile_store_write {
    tile_key key;
    const void *data; // tile_layer_bytes(key.layer) bytes, or NULL to delete the tile
} tile_store_write;

// Writes a batch of tiles in one transaction: all of them land or none does.
// Returns 0, or -1 with err set (the store is unchanged).
int tile_store_put_batch(tile_store *store, const tile_store_write *writes, size_t count,
                         og_error *err);
static inline int tile_store_put(tile_store *store, tile_key key, const void *data, og_error *err) {
    tile_store_write w = {key, data};
    return tile_store_put_batch(store, &w, 1, err);
}

// Number of tiles stored, optionally for one layer only (layer < 0: all layers).
int64_t tile_store_count(tile_store *store, int layer);

// The store's own key = value facts besides its tiles (the meta table): which world's
// edits it holds ("world_id"). get returns 1 and copies the value, 0 when the key is
// not set, -1 with err on failure; set writes it in one transaction.
int tile_store_get_meta(tile_store *store, const char *key, char *value, size_t len, og_error *err);
int tile_store_set_meta(tile_store *store, const char *key, const char *value, og_error *err);

// Calls fn for every stored key (any order) until it returns non-zero.
int tile_store_each(tile_store *store, int (*fn)(void *user, tile_key key), void *user,
                    og_error *err);

// Copies every tile of the store files at sources (at most 4, later ones winning)
// into this store in one transaction, after deleting every tile first when replace is
// set; tiles present in both take the source's. The sources must not be mid-write.
// Used by save to move unsaved edits into the world's own store. A state_id (unless
// NULL) goes into the meta table in the same transaction: the saved state a recovery
// journal builds on is named by it, atomically with the tiles.
int tile_store_merge_from(tile_store *store, const char *const *sources, size_t count, int replace,
                          const char *state_id, og_error *err);
// Deletes every tile (one transaction).
int tile_store_clear(tile_store *store, og_error *err);

// Compression alone, exposed for tests and benchmarks: encode a tile payload into
// a self-describing blob (transform + zstd + checksum) and decode it back.
// encode returns the blob size or 0 on failure; *blob is malloc'd.
size_t tile_blob_encode(tile_layer layer, const void *data, void **blob);
// Returns 0, or -1 when the blob is corrupt (err says why).
int tile_blob_decode(tile_layer layer, const void *blob, size_t blob_bytes, void *out,
                     og_error *err);
// The store's own: the blob's checksum covers its key, so a blob moved to another key
// is corrupt there (encode/decode above use face, level, tx, ty = 0).
size_t tile_blob_encode_key(tile_key key, const void *data, void **blob);
int tile_blob_decode_key(tile_key key, const void *blob, size_t blob_bytes, void *out,
                         og_error *err);

#endif
