#include "io/tile.h"

#include <stdio.h>

size_t tile_layer_bytes(tile_layer layer) {
    switch (layer) {
    case TILE_LAYER_COARSE:
    case TILE_LAYER_DETAIL:
        return (size_t)TILE_SAMPLES * sizeof(float);
    case TILE_LAYER_MATERIAL:
        return (size_t)TILE_SAMPLES * TILE_MATERIALS;
    case TILE_LAYER_DETAIL_PD:
    case TILE_LAYER_VOLUME:
        return (size_t)TILE_SAMPLES * 2 * sizeof(int16_t);
    default:
        return 0;
    }
}

tile_format tile_layer_format(tile_layer layer) {
    if (layer == TILE_LAYER_MATERIAL) return TILE_FORMAT_U8X8;
    if (layer == TILE_LAYER_DETAIL_PD || layer == TILE_LAYER_VOLUME) return TILE_FORMAT_S16X2;
    return TILE_FORMAT_F32;
}

const char *tile_layer_name(tile_layer layer) {
    static const char *names[] = {"coarse", "detail", "material", "volume", "detail_pd"};
    return (unsigned)layer < TILE_LAYER_COUNT ? names[layer] : "unknown";
}

const char *tile_key_describe(tile_key key, char *buf, size_t len) {
    snprintf(buf, len, "%s face %d level %d tile (%d,%d)", tile_layer_name((tile_layer)key.layer),
             key.face, key.level, key.tx, key.ty);
    return buf;
}

uint64_t tile_key_hash(tile_key k) {
    uint64_t h = 0x9e3779b97f4a7c15ULL;
    int32_t f[5] = {k.layer, k.face, k.level, k.tx, k.ty};
    for (int i = 0; i < 5; i++) {
        h ^= (uint32_t)f[i];
        h *= 0xff51afd7ed558ccdULL;
        h ^= h >> 33;
    }
    return h;
}
