// The unit of everything Orogen stores, caches and renders: a fixed square of
// samples addressed by (layer, face, level, tx, ty). README.md, "How it fits together", says how
// tiles make a world.
#ifndef OROGEN_IO_TILE_H
#define OROGEN_IO_TILE_H

#include <stddef.h>
#include <stdint.h>

// Samples per tile side, for every layer.
#define TILE_SIZE 256
#define TILE_SAMPLES (TILE_SIZE * TILE_SIZE)
// Material weight channels per sample (uint8 weights that sum to 255).
#define TILE_MATERIALS 8
// Deepest mip level a key may name (level L samples are 2^L apart).
#define TILE_MAX_LEVEL 24
// Fixed-point scale of the detail PD layer: slope 1 (45 degrees) = 4096; range +-8.
#define DETAIL_PD_SCALE 4096.0f

typedef enum tile_layer {
    TILE_LAYER_COARSE = 0,   // float32 metres, one per coarse sample
    TILE_LAYER_DETAIL = 1,   // float32 metres offset, detail_ratio samples per coarse sample
    TILE_LAYER_MATERIAL = 2, // TILE_MATERIALS x uint8 weights per sample
    // Volume edits (overhangs, caves, arches): bricks of VOLUME_BRICK_X x _Y x _Z voxels,
    // two int16 per voxel (editor/world/volume_grid.h says what they mean). For this layer
    // the key's `level` is the brick's vertical index (any int32): bricks have no mips.
    TILE_LAYER_VOLUME = 3,
    // Partial derivatives of the detail layer (Crause 2010's PD map): int16 d/dx, d/dz per
    // detail sample, slope x DETAIL_PD_SCALE. Derived data the editor keeps current.
    TILE_LAYER_DETAIL_PD = 4,
    TILE_LAYER_COUNT
} tile_layer;

// A volume brick: 32 x 32 voxels across (x, z), 64 up (y): TILE_SAMPLES voxels, so a
// brick is stored, cached, snapshotted and compressed like a detail-slope tile.
#define VOLUME_BRICK_X 32
#define VOLUME_BRICK_Z 32
#define VOLUME_BRICK_Y 64

typedef struct tile_key {
    int32_t layer; // tile_layer, and above its low 8 bits the edit-layer slot (tile_key_slot)
    int32_t face;  // 0 for flat worlds, 0-5 for planet cube faces
    int32_t level; // mip level, 0 = full resolution
    int32_t tx, ty;
} tile_key;

// How a tile's bytes are laid out; the store picks its compression transform from it.
typedef enum tile_format {
    TILE_FORMAT_F32 = 1,  // TILE_SAMPLES float32
    TILE_FORMAT_U8X8 = 2, // TILE_SAMPLES x TILE_MATERIALS uint8, interleaved per sample
    TILE_FORMAT_S16X2 = 3 // TILE_SAMPLES x 2 int16, interleaved per sample (or voxel)
} tile_format;

static inline int tile_key_equal(tile_key a, tile_key b) {
    return a.layer == b.layer && a.face == b.face && a.level == b.level && a.tx == b.tx &&
           a.ty == b.ty;
}

// Edit layers (editor/layers/layer_table.h) keep their tiles apart from the world's own by
// a slot in key.layer above the kind: slot 0 is the composite (what everyone reads), slot
// 1 the base under the layers (generated terrain), slot 2 and up a user layer's stable
// id. So the store, cache, history and journal keep them apart with no new key field;
// tile_layer_bytes/format/name take such a packed value as its kind.
#define TILE_SLOT_SHIFT 8
#define TILE_SLOT_BASE 1
#define TILE_SLOT_MAX (INT32_MAX >> TILE_SLOT_SHIFT)
static inline tile_layer tile_key_kind(tile_key key) {
    return (tile_layer)(key.layer & ((1 << TILE_SLOT_SHIFT) - 1));
}
static inline int32_t tile_key_slot(tile_key key) {
    return key.layer >> TILE_SLOT_SHIFT;
}
static inline int32_t tile_layer_in_slot(tile_layer kind, int32_t slot) {
    return (int32_t)kind | slot << TILE_SLOT_SHIFT;
}

// A well-mixed 64-bit hash of a key, for hash tables.
uint64_t tile_key_hash(tile_key key);

// Bytes and format of one tile of a layer (0 bytes: not a layer).
size_t tile_layer_bytes(tile_layer layer);
tile_format tile_layer_format(tile_layer layer);
const char *tile_layer_name(tile_layer layer);

// "coarse face 0 level 2 tile (3,-7)" into buf; returns buf. For messages.
const char *tile_key_describe(tile_key key, char *buf, size_t len);

// Whether the key's level is a mip level (every layer but the volume layer's bricks).
static inline int tile_key_has_mips(tile_key key) {
    return key.layer != TILE_LAYER_VOLUME;
}

#endif
