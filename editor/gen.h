// Generated terrain: what a tile holds before anyone edits it. Pure functions of
// the world parameters and the tile key, so unedited terrain never needs storing
// and any tile can be regenerated bit-identically, in any order, on any thread.
#ifndef OROGEN_EDITOR_GEN_H
#define OROGEN_EDITOR_GEN_H

#include "editor/world_params.h"
#include "io/tile.h"

#include <stdint.h>

// Fills one tile (tile_layer_bytes(key.layer) bytes). Coarse tiles come from the
// world's generator; detail tiles are zero offsets; material tiles give all weight
// to material 0. Returns -1 for keys outside the world (planet face > 5, level
// beyond TILE_MAX_LEVEL, volume layer).
int gen_tile(const world_params *p, tile_key key, void *out);

// The wavelength in metres of the generator's lowest octave (resolves feature_size = 0).
double gen_feature_size(const world_params *p);

// Octaves actually summed at a mip level: the parameter's count, minus the octaves
// whose wavelength is shorter than two samples at that level (band limiting).
double gen_octaves_at_level(const world_params *p, int level);

// The individual generators, for tests. Each fills TILE_SAMPLES floats (metres).
void gen_fractal_tile(const world_params *p, tile_key key, float *out);
void gen_diamond_square_tile(const world_params *p, tile_key key, float *out);
void gen_faults_tile(const world_params *p, tile_key key, float *out);
// Diamond-square over any rectangle of level-L sample indices (x0, z0 in units of 2^L
// level-0 samples), not only tile-aligned ones: the one big array tiles must match.
void gen_diamond_square_region(const world_params *p, int level, int64_t x0, int64_t z0, int nx,
                               int nz, float *out);

// Integer hashing shared by the generators: well-mixed 32 bits from coordinates.
static inline uint32_t gen_hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}
static inline uint32_t gen_hash_3(uint32_t a, uint32_t b, uint32_t c) {
    return gen_hash32(a ^ gen_hash32(b ^ gen_hash32(c + 0x9e3779b9U)));
}
// Uniform in [-1, 1) from a hash.
static inline float gen_hash_unit(uint32_t h) {
    return (float)(int32_t)h * (1.0f / 2147483648.0f);
}

#endif
