// Fault-line terrain: seamless cells of faults on flat worlds, great circles on planets.
#ifndef OROGEN_EDITOR_GEN_FAULTS_H
#define OROGEN_EDITOR_GEN_FAULTS_H

#include "editor/params/world_params.h"
#include "io/tile.h"

// Fills TILE_SAMPLES floats (metres) of a coarse tile.
void gen_faults_tile(const world_params *p, tile_key key, float *out);

#endif
