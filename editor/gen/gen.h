// Generated terrain: what a tile holds before anyone edits it. Pure functions of
// the world parameters and the tile key, so unedited terrain never needs storing
// and any tile can be regenerated bit-identically, in any order, on any thread.
#ifndef OROGEN_EDITOR_GEN_H
#define OROGEN_EDITOR_GEN_H

#include "editor/gen/gen_hash.h"
#include "editor/params/world_params.h"
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

#endif
