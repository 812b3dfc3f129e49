// Where samples are: the mapping from (face, level, tile, sample) to positions.
//
// Flat worlds: coarse sample (gx, gz) sits at world (gx * spacing, gz * spacing) metres;
// a level-L tile's sample (i, j) is coarse sample ((tx*TILE_SIZE + i) << L, (ty*TILE_SIZE + j) <<
// L), so every mip sample coincides with a level-0 sample.
//
// Planets: six cube faces of face_samples x face_samples cells each; a level-L sample
// is the centre of the 2^L x 2^L block of level-0 cells it covers (box-filter aligned),
// projected onto the sphere with a tangent warp that evens out cell areas.
#ifndef OROGEN_EDITOR_WORLD_GRID_H
#define OROGEN_EDITOR_WORLD_GRID_H

#include "editor/params/world_params.h"
#include "io/tile.h"

#include <stdint.h>

// Level-0 cells per planet face side: the face's arc (pi/2 * radius) over spacing,
// rounded up to a whole number of tiles.
int64_t world_grid_face_samples(const world_params *p);
// Metres between level-0 samples as face-local coordinates count them: a flat world's
// spacing; on a planet the datum's arc per cell (a face's quarter circle over its
// samples: the spacing or a little less, far less on a planet smaller than a tile of
// samples at its spacing, as seed 004's radius-10 planet), so face-local metres, brush
// radii, `info` and sidecars are true metres on the sphere at every size.
double world_grid_sample_metres(const world_params *p);

// Unit direction from the planet centre through face-local coordinates s, t in [-1, 1].
void world_grid_face_direction(int face, double s, double t, double dir[3]);
// The same from the warped coordinates a = tan(s pi/4), b = tan(t pi/4), for loops
// that compute each row's and column's tangent once.
void world_grid_face_direction_warped(int face, double a, double b, double dir[3]);

// The inverse: the face a direction (any length > 0) passes through and its face-local
// coordinates s, t in [-1, 1].
void world_grid_direction_face(const double dir[3], int *face, double *s, double *t);
// Face `face`'s coordinates of any direction on its side of the centre (past [-1, 1]
// beyond its edges: the face's coordinates extend onto its neighbours). 0 when dir
// points away from the face's axis.
int world_grid_face_coords_on(int face, const double dir[3], double *s, double *t);

// Face-local coordinate in [-1, 1] of the centre of level-L sample index i (any tile).
double world_grid_face_coord(const world_params *p, int level, int64_t i);

// Level-0 sample index of sample i in a level-L tile row starting at tile t.
static inline int64_t world_grid_index(int32_t t, int i, int level) {
    return ((int64_t)t * TILE_SIZE + i) * ((int64_t)1 << level);
}

// Floor division for tile coordinates of negative sample indices.
static inline int64_t world_grid_floor_div(int64_t a, int64_t b) {
    int64_t q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

// Half-open rectangle of sample indices [x0, x1) x [z0, z1).
typedef struct grid_rect {
    int64_t x0, z0, x1, z1;
} grid_rect;

static inline int grid_rect_empty(grid_rect r) {
    return r.x0 >= r.x1 || r.z0 >= r.z1;
}
grid_rect grid_rect_intersect(grid_rect a, grid_rect b);
grid_rect grid_rect_union(grid_rect a, grid_rect b); // of non-empty rects

// A changed area of one layer's level-0 samples on one face (edits, undo, redo).
typedef struct dirty_rect {
    tile_layer layer;
    int face;
    grid_rect rect;
} dirty_rect;

#endif
