// A top-down shaded map of a world, composed on the CPU from the tile cache: the
// editor's map view. It never waits for tiles: what is not ready is drawn from the
// nearest coarser level the cache holds (or left dark), and the caller is told how
// many tiles are still coming so it can compose again.
#ifndef OROGEN_RENDERER_MAP_IMAGE_H
#define OROGEN_RENDERER_MAP_IMAGE_H

#include "editor/world.h"

#include <stdint.h>

typedef struct map_view {
    double cx, cz;  // face-local metres at the image centre
    double mpp;     // metres per pixel
    int face;       // planet face shown (0 for flat worlds)
} map_view;

// A view that shows the world's middle (or the origin of an unbounded world).
map_view map_view_default(const world *w);

// The mip level whose sample spacing best matches the view's metres per pixel.
int map_view_level(const world *w, const map_view *v);

// Fills rgba (width x height x 4 bytes, rows top to bottom = increasing z). Returns the
// number of tiles that were not ready (drawn coarser or dark) — 0 means final.
int map_image_compose(world *w, const map_view *v, int width, int height, uint8_t *rgba);

#endif
