// The volume layer: what a person carved out of or added to the terrain in 3D
// (caves, overhangs, arches). The heightfield stays the base; the solid is
//
//     solid = (below the heightfield  UNION  ADD)  MINUS  SUB
//
// where ADD and SUB are shapes the volume tools build. Each voxel keeps its signed
// distance to both shapes (negative inside), so the combined signed distance is
//
//     d(p) = max(min(d_height(p), d_add(p)), -d_sub(p))
//
// Voxels sit on a world-space lattice: voxel (i, j, k) is at (i, j, k) x voxel metres
// (x, y up, z), voxel size = spacing / volume_ratio, so voxel (i r, j, k r) stands on
// coarse sample (i, k). Volume edits are in world space: editing the heightfield
// under or over them later leaves them where they were (a carved cave stays at its
// height when the hill above is lowered; an added arch stays when the ground under it
// is raised, and the ground then fills it from below).
//
// Storage: bricks of VOLUME_BRICK_X x _Y x _Z voxels (io/tile.h), keyed (volume, face 0,
// level = j / VOLUME_BRICK_Y, tx = i / VOLUME_BRICK_X, ty = k / VOLUME_BRICK_Z), each
// voxel two int16 (ADD then SUB distance, VOLUME_UNITS per voxel, VOLUME_FAR = no shape
// within VOLUME_FAR_VOXELS, read as infinitely far). Only edited bricks exist in the store: memory
// follows what was edited, not the world's size. Distances are exact within VOLUME_EXACT_VOXELS of
// a shape's surface and clamped beyond.
#ifndef OROGEN_EDITOR_VOLUME_GRID_H
#define OROGEN_EDITOR_VOLUME_GRID_H

#include "editor/params/world_params.h"
#include "editor/world/world.h"
#include "io/err.h"
#include "io/tile.h"

#include <math.h>
#include <stdint.h>

#define VOLUME_UNITS 256.0f
#define VOLUME_FAR INT16_MAX
#define VOLUME_FAR_VOXELS (VOLUME_FAR / VOLUME_UNITS)
// How far beyond a shape's surface its tools write exact distances (the narrow band
// the viewport's mesher and the .vdb export read).
#define VOLUME_EXACT_VOXELS 4.0

typedef struct volume_grid {
    double voxel;     // metres
    double spacing;   // coarse spacing, metres
    int ratio;        // voxels per coarse spacing
    int64_t extent;   // bounded world: coarse samples along X; 0 = unbounded
    int64_t extent_z; // and along Z
} volume_grid;

// Voxels of a box: [i0, i1) x [j0, j1) x [k0, k1).
typedef struct volume_box {
    int64_t i0, j0, k0, i1, j1, k1;
} volume_box;

// Flat worlds only (planets refuse, naming why).
int volume_grid_init(volume_grid *g, const world_params *p, og_error *err);

// Checks a 3D position given by a user: finite, inside a bounded world's extent,
// and within the range the volume's int32 bricks address.
int volume_grid_check_position(const volume_grid *g, const double p[3], og_error *err);

// The voxels within `margin` metres of the box [lo, hi] (metres).
volume_box volume_grid_box_around(const volume_grid *g, const double lo[3], const double hi[3],
                                  double margin);
int64_t volume_box_voxels(volume_box b);
// Bricks a box touches, and their keys (out holds volume_box_bricks(b) keys; by level,
// then row, then column). Returns how many it wrote.
int64_t volume_box_bricks(volume_box b);
size_t volume_box_brick_keys(volume_box b, tile_key *out);

static inline int64_t volume_floor_div(int64_t a, int64_t b) {
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

// The brick holding voxel (i, j, k).
static inline tile_key volume_brick_key(int64_t i, int64_t j, int64_t k) {
    tile_key key = {TILE_LAYER_VOLUME, 0, (int32_t)volume_floor_div(j, VOLUME_BRICK_Y),
                    (int32_t)volume_floor_div(i, VOLUME_BRICK_X),
                    (int32_t)volume_floor_div(k, VOLUME_BRICK_Z)};
    return key;
}

// Offset of voxel (i, j, k) of the brick key in int16 pairs: x fastest, then z, then y.
static inline size_t volume_brick_offset(tile_key key, int64_t i, int64_t j, int64_t k) {
    int64_t li = i - (int64_t)key.tx * VOLUME_BRICK_X, lj = j - (int64_t)key.level * VOLUME_BRICK_Y,
            lk = k - (int64_t)key.ty * VOLUME_BRICK_Z;
    return (size_t)((lj * VOLUME_BRICK_Z + lk) * VOLUME_BRICK_X + li);
}

// The box of voxels a brick holds.
volume_box volume_brick_box(tile_key key);
// The intersection of two boxes (empty: i0 >= i1 or ...).
volume_box volume_box_intersect(volume_box a, volume_box b);
static inline int volume_box_empty(volume_box b) {
    return b.i0 >= b.i1 || b.j0 >= b.j1 || b.k0 >= b.k1;
}

// Stored units <-> metres. VOLUME_FAR reads as infinitely far (so it never caps the
// heightfield's distance).
static inline float volume_to_metres(int16_t v, double voxel) {
    if (v == VOLUME_FAR) return INFINITY;
    return (float)(v / VOLUME_UNITS * voxel);
}
static inline int16_t volume_from_metres(double d, double voxel) {
    double u = nearbyint(d / voxel * VOLUME_UNITS);
    return (int16_t)(u > VOLUME_FAR ? VOLUME_FAR : u < -VOLUME_FAR ? -VOLUME_FAR : u);
}

// The combined signed distance from the three distances (metres).
static inline float volume_combine(float d_height, float d_add, float d_sub) {
    return fmaxf(fminf(d_height, d_add), -d_sub);
}

// The heightfield under a set of columns, as the volume sees it: the coarse layer,
// bilinear between samples. Column (i, k) stands at (i, k) x step metres (step: the
// voxel size, or an export's).
typedef struct volume_heights {
    int64_t i0, k0, w, h; // columns [i0, i0 + w) x [k0, k0 + h)
    float *height;        // per column, metres
    float *slope_scale;   // per column: 1 / sqrt(1 + |grad h|^2)
} volume_heights;

int volume_heights_read(world *w, const volume_grid *g, double step, int64_t i0, int64_t k0,
                        int64_t i1, int64_t k1, volume_heights *out, og_error *err);
void volume_heights_free(volume_heights *vh);

// Signed distance to the heightfield's solid at height y over column (i, k) (metres,
// negative below the ground): the vertical distance scaled by the slope, exact on
// planes and first-order elsewhere.
static inline float volume_heights_distance(const volume_heights *vh, int64_t i, int64_t k,
                                            double y) {
    size_t c = (size_t)((k - vh->k0) * vh->w + (i - vh->i0));
    return (float)((y - vh->height[c]) * vh->slope_scale[c]);
}

// The combined signed distance at every voxel of box into out (x fastest, then z, then
// y; metres), with vh covering the box's columns. Reads brick by brick.
int volume_field_read(world *w, const volume_grid *g, const volume_heights *vh, volume_box box,
                      float *out, og_error *err);

// Reads voxels anywhere, keeping the last few bricks pinned (for passes that walk a
// brick and its borders).
#define VOLUME_READER_SLOTS 32
typedef struct volume_reader {
    tile_cache *cache;
    tile_view views[VOLUME_READER_SLOTS];
    int used[VOLUME_READER_SLOTS];
} volume_reader;

void volume_reader_init(volume_reader *r, world *w);
// The (ADD, SUB) pair of voxel (i, j, k), or NULL with err set.
const int16_t *volume_reader_pair(volume_reader *r, int64_t i, int64_t j, int64_t k, og_error *err);
void volume_reader_close(volume_reader *r);

// The keys of every volume brick the world has written (saved or not; after undo a
// brick may hold no edit any more), sorted, without duplicates. malloc'd.
int volume_list_bricks(world *w, tile_key **keys, size_t *count, og_error *err);

// Whether any volume brick holds an edit (*has 1 or 0): bricks undone back to no edit
// do not count.
int volume_has_edits(world *w, int *has, og_error *err);

// Samples the combined solid's signed distance at a point (metres; trilinear in the
// volume voxels around it, bilinear in the heights). For `vsample` and tests.
int volume_sample(world *w, const double p[3], double *distance, og_error *err);

#endif
