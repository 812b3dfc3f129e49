// Seed 003's diamond-square (Kerr 2007 flyover), seamless over an unbounded world.
#ifndef OROGEN_EDITOR_GEN_DIAMOND_H
#define OROGEN_EDITOR_GEN_DIAMOND_H

#include "editor/params/world_params.h"
#include "io/tile.h"

#include <stdint.h>

// Fills TILE_SAMPLES floats (metres) of a coarse tile.
void gen_diamond_square_tile(const world_params *p, tile_key key, float *out);

// Diamond-square over any rectangle of level-L sample indices (x0, z0 in units of 2^L
// level-0 samples), not only tile-aligned ones: the one big array tiles must match.
void gen_diamond_square_region(const world_params *p, int level, int64_t x0, int64_t z0, int nx,
                               int nz, float *out);

#endif
