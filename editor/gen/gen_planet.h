// The "planet" generator: continents, mountain ranges and valleys that read at every
// altitude (domain-warped continents, ridged ranges in belts, ridged hills).
#ifndef OROGEN_EDITOR_GEN_PLANET_H
#define OROGEN_EDITOR_GEN_PLANET_H

#include "editor/params/world_params.h"
#include "io/tile.h"

// Fills TILE_SAMPLES floats (metres) of a coarse tile.
void gen_planet_tile(const world_params *p, tile_key key, float *out);

#endif
