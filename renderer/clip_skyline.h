// Where the ground meets the sky on the screen, estimated from the clipmap levels' cell
// bounds (renderer/clip_cells.h), so that only the coarse parts near it are refined
// (renderer/clip_refine.h; render skyline=P). Against the full-resolution mesh most of a
// coarse level's error shows there: its ridges, drawn from samples 4 to 8 pixels apart,
// stand lower than the real ones and the sky shows through their missing teeth
// (bench_render 7: pixels within 3 px of the sky held 28-74% of the squared error).
//
// Per screen column the skyline is the highest of the cells' tops projected there (a
// cell's highest sample, placed at its centre, over the columns its width covers). A
// part is near the skyline where one of its cells' tops projects within a band under
// it. An estimate, not a bound: its only use is choosing what to refine, and a part
// refined or not joins its neighbours without cracks either way.
#ifndef OROGEN_RENDERER_CLIP_SKYLINE_H
#define OROGEN_RENDERER_CLIP_SKYLINE_H

#include "renderer/clip_cells.h"
#include "renderer/clip_refine.h"

#include <stdint.h>

#define CLIP_SKYLINE_COLUMNS 240
// The band under the skyline whose parts refine, in pixels per pixel of error at which
// they start to (render skyline=P: a band of CLIP_SKYLINE_BAND x P pixels).
#define CLIP_SKYLINE_BAND 2.0

typedef struct clip_skyline {
    double eye[3], forward[3], right[3], up[3]; // the camera (world metres, unit basis)
    double tan_half_x, tan_half_y;
    float top[CLIP_SKYLINE_COLUMNS]; // highest ground per column (screen y, -1 .. 1)
} clip_skyline;

// Starts a frame with no ground: tan_half_x, tan_half_y are the tangents of half the
// fields of view.
void clip_skyline_begin(clip_skyline *k, const double eye[3], const double forward[3],
                        const double right[3], const double up[3], double tan_half_x,
                        double tan_half_y);

// Adds the cells of a level whose samples are `spacing` metres apart, over its samples
// [i0, i1] x [j0, j1] (level sample indices, inclusive: what the level draws) except the
// cells wholly inside [h_i0, h_i1] x [h_j0, h_j1] (the finer level's square; an empty
// range for the finest level).
void clip_skyline_add_level(clip_skyline *k, const clip_cells *c, double spacing, int64_t i0,
                            int64_t j0, int64_t i1, int64_t j1, int64_t h_i0, int64_t h_j0,
                            int64_t h_i1, int64_t h_j1);

// Whether one of the cells over samples [i0, i1] x [j0, j1] of that level has its top
// within twice `band` under the skyline (the test before clip_skyline_weight, which
// measures the cells' refinement error).
int clip_skyline_near(const clip_skyline *k, const clip_cells *c, double spacing, int64_t i0,
                      int64_t j0, int64_t i1, int64_t j1, double band);

// The refinement weight (renderer/clip_refine.h) of a part over samples [i0, i1] x
// [j0, j1] of that level from its cells near the skyline only: the most of its cells'
// own weights (their error e seen from their nearest point, clip_refine_weight) times
// their nearness, 1 when the cell's top projects within `band` (screen units: 2 / height
// a pixel) under the skyline, falling to 0 at twice that.
float clip_skyline_weight(const clip_skyline *k, const clip_cells *c, clip_refine_cells *e,
                          double spacing, int64_t i0, int64_t j0, int64_t i1, int64_t j1,
                          double band, double pixels_per_radian, double pixels);

#endif
