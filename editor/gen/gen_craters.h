// Impact craters at every scale, laid over the "craters" generator's fBm (gen_craters.c).
#ifndef OROGEN_EDITOR_GEN_CRATERS_H
#define OROGEN_EDITOR_GEN_CRATERS_H

#include "editor/params/world_params.h"
#include "io/tile.h"

// Adds the craters to a coarse tile's heights (metres), clamped to base_height +-
// max_height.
void gen_craters_add(const world_params *p, tile_key key, float *out);

#endif
