// Generated terrain: what a tile holds before anyone edits it. Pure functions of
// the world parameters and the tile key, so unedited terrain never needs storing
// and any tile can be regenerated bit-identically, in any order, on any thread.
#ifndef OROGEN_EDITOR_GEN_H
#define OROGEN_EDITOR_GEN_H

#include "editor/gen/gen_diamond.h"
#include "editor/gen/gen_faults.h"
#include "editor/gen/gen_hash.h"
#include "editor/gen/gen_planet.h"
#include "editor/gen/gen_scale.h"
#include "editor/params/world_params.h"
#include "io/tile.h"

#include <stdint.h>

// Fills one tile (tile_layer_bytes(key.layer) bytes). Coarse tiles come from the
// world's generator; detail tiles are zero offsets; material tiles give all weight
// to material 0; volume bricks hold no edit (editor/world/volume_grid.h). Returns -1
// for keys outside the world (planet face > 5, level beyond TILE_MAX_LEVEL).
int gen_tile(const world_params *p, tile_key key, void *out);

// The individual generators, for tests. Each fills TILE_SAMPLES floats (metres).
void gen_fractal_tile(const world_params *p, tile_key key, float *out);

#endif
