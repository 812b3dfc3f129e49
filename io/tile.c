#include "io/tile.h"

#include <stdio.h>

size_t tile_layer_bytes(tile_layer layer) {
    if ((int)layer < 0) return 0;
    switch ((tile_layer)(layer & ((1 << TILE_SLOT_SHIFT) - 1))) {
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
    layer = (tile_layer)(layer & ((1 << TILE_SLOT_SHIFT) - 1));
    if (layer == TILE_LAYER_MATERIAL) return TILE_FORMAT_U8X8;
    if (layer == TILE_LAYER_DETAIL_PD || layer == TILE_LAYER_VOLUME) return TILE_FORMAT_S16X2;
    return TILE_FORMAT_F32;
}

const char *tile_layer_name(tile_layer layer) {
    static const char *names[] = {"coarse", "detail", "material", "volume", "detail_pd"};
    if ((int)layer >= 0) layer = (tile_layer)(layer & ((1 << TILE_SLOT_SHIFT) - 1));
    return (unsigned)layer < TILE_LAYER_COUNT ? names[layer] : "unknown";
}

const char *tile_key_describe(tile_key key, char *buf, size_t len) {
    char slot[48] = "";
    if (tile_key_slot(key) == TILE_SLOT_BASE)
        snprintf(slot, sizeof slot, " (base)");
    else if (tile_key_slot(key) > TILE_SLOT_BASE)
        snprintf(slot, sizeof slot, " (edit layer %d)", (int)tile_key_slot(key));
    snprintf(buf, len, "%s%s face %d level %d tile (%d,%d)", tile_layer_name((tile_layer)key.layer),
             slot, key.face, key.level, key.tx, key.ty);
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
