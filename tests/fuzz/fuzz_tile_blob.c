// libFuzzer target: the tile blob decoder (header, checksums, zstd, the byte-plane
// transforms). The first byte picks the layer.
#include "io/tile_store.h"

#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < 1) return 0;
    tile_layer layer = (tile_layer)(data[0] % TILE_LAYER_COUNT);
    size_t bytes = tile_layer_bytes(layer);
    if (!bytes) return 0;
    void *out = malloc(bytes);
    og_error err;
    tile_blob_decode(layer, data + 1, size - 1, out, &err);
    free(out);
    return 0;
}
