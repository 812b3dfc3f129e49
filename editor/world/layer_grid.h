// A layer's full-resolution sample grid on one face, as the editing tools see it: one
// big (possibly unbounded) array addressed by int64 sample indices, whatever tiles
// hold it. Coarse and material samples sit `spacing` metres apart; detail samples
// spacing / detail_ratio apart, with detail sample k*ratio on coarse sample k.
#ifndef OROGEN_EDITOR_LAYER_GRID_H
#define OROGEN_EDITOR_LAYER_GRID_H

#include "editor/params/world_grid.h"
#include "editor/world/world.h"
#include "io/err.h"
#include "io/tile.h"

#include <stdint.h>

typedef struct layer_grid {
    tile_layer layer; // TILE_LAYER_COARSE, _DETAIL or _MATERIAL
    int face;
    double spacing; // metres between samples
    int64_t extent; // samples along X of a bounded world, per side of a planet face; 0 = unbounded
    int64_t extent_z; // samples along Z (a bounded flat world may be rectangular)
} layer_grid;

int layer_grid_init(layer_grid *g, const world_params *p, tile_layer layer, int face,
                    og_error *err);

// The part of r inside the grid (all of r when unbounded).
grid_rect layer_grid_clip(const layer_grid *g, grid_rect r);
// Samples within radius metres of (x, z) metres, clipped to the grid.
grid_rect layer_grid_disc_rect(const layer_grid *g, double x, double z, double radius);

// Copies the float samples of r (coarse or detail) into out (row-major, r's width).
// Samples outside a bounded grid read as the nearest edge sample.
int layer_grid_read(world *w, const layer_grid *g, grid_rect r, float *out, og_error *err);
// The same for any layer, as stored: floats, or TILE_MATERIALS weight bytes per sample.
int layer_grid_read_samples(world *w, const layer_grid *g, grid_rect r, void *out, og_error *err);

// Position checks for user input: finite, and within int32 tile range.
int layer_grid_check_position(const layer_grid *g, double x, double z, og_error *err);

#endif
