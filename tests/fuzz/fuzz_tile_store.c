// libFuzzer target: opening a tile store file and loading every tile it lists (the
// identity and schema checks, SQLite reading a damaged file, the blob decoder).
#include "fuzz_support.h"
#include "io/tile_store.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

typedef struct reader {
    tile_store *store;
    int loaded;
} reader;

static int load_one(void *user, tile_key key) {
    reader *r = user;
    size_t bytes = tile_layer_bytes((tile_layer)key.layer);
    if (!bytes || ++r->loaded > 64) return 0;
    void *out = malloc(bytes);
    og_error err;
    tile_store_get(r->store, key, out, bytes, &err);
    free(out);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const char *path = fuzz_file("f.tiles", data, size);
    og_error err;
    tile_store *s = tile_store_open(path, &err);
    if (s) {
        reader r = {s, 0};
        tile_store_each(s, load_one, &r, &err);
        tile_store_count(s, -1);
        char value[128];
        tile_store_get_meta(s, "world_id", value, sizeof value, &err);
        tile_store_close(s);
    }
    // The next input starts from its own bytes alone.
    char side[600];
    snprintf(side, sizeof side, "%s-wal", path);
    unlink(side);
    snprintf(side, sizeof side, "%s-shm", path);
    unlink(side);
    return 0;
}
