// Where a coarse clipmap level is drawn at twice its density (renderer/clip_refine_mesh.h):
// per part of the level, from the screen-space error of its geometry. A level's vertices
// are its own mip samples; its refined vertices (half its spacing) take the finer heights
// of its shading window (renderer/clip_slopes.h). Per cell of CLIP_CELL x CLIP_CELL level
// samples this measures how far the refined vertices move from the level's surface (its
// geometric error at its own spacing) and the refined surface's height bounds (for
// culling); a part whose error, projected on the screen from the camera, exceeds about a
// pixel is refined. Its weight (0 to 1, rising with the projected error so that parts
// refine gradually as the camera nears, without popping) goes to a texture per level the
// vertex shader reads per quad.
#ifndef OROGEN_RENDERER_CLIP_REFINE_H
#define OROGEN_RENDERER_CLIP_REFINE_H

#include "renderer/clip_cells.h"
#include "renderer/clip_window.h"
#include "renderer/render_settings.h"

#include <epoxy/gl.h>
#include <stdint.h>

#define CLIP_REFINE_SIDE 256 // vertices per side of a level's weight map (its window's size)

typedef struct clip_refine_cells {
    int64_t have[2]; // the level window's origin they were built for
    int cells;       // per side; 0: not built
    // Over cell (i, j)'s samples [i, i + 1] * CLIP_CELL (as clip_cells.h): the refined
    // surface's lowest and highest vertex and its vertices' largest move from the level's
    // surface, metres.
    float lo[CLIP_CELLS_MAX * CLIP_CELLS_MAX], hi[CLIP_CELLS_MAX * CLIP_CELLS_MAX];
    float error[CLIP_CELLS_MAX * CLIP_CELLS_MAX];
    // Each cell is measured when first asked for (a frame in flight moves several
    // windows, and measuring all their cells cost 5-8 ms of it): the windows it reads
    // (they must not change until the next build), and which cells are measured.
    const clip_window *level, *fine;
    int k;
    unsigned char measured[CLIP_CELLS_MAX * CLIP_CELLS_MAX];
} clip_refine_cells;

// From a level's window and its current shading window `fine`, which holds `k` samples
// per level sample (k = 2 or 4); the cells are measured later, when asked for. Not built
// (cells 0) when either window is not whole.
void clip_refine_cells_build(clip_refine_cells *c, const clip_window *level,
                             const clip_window *fine, int k);

// The bounds and largest error over level samples [i0, i1] x [j0, j1] (inclusive,
// level sample indices); 0 when not built or the range misses the window.
int clip_refine_cells_range(clip_refine_cells *c, int64_t i0, int64_t j0, int64_t i1, int64_t j1,
                            float *lo, float *hi, float *error);
// Cell (i, j)'s index in lo, hi and error, measured first if it was not.
size_t clip_refine_cell(clip_refine_cells *c, int i, int j);

// Levels from this one on may be refined: on levels 1 and 2 (within 2 mips of the full
// resolution, seen steeply enough that their moves do not change what is in front)
// refining changed bench_render's RMSE against the full-resolution mesh by under 0.01 for
// a third more triangles.
#define CLIP_REFINE_MIN_LEVEL 3

// The refinement weight of a part whose geometric error is error_m metres, seen from the
// camera at `horizontal` metres across the ground and `distance` metres in all (its
// nearest point): the error's projection on the screen in pixels (a vertical move seen
// at that elevation) mapped to 0 at `pixels`, 1 at 1.5 x `pixels` (so parts refine
// gradually as the camera nears them); 0 when pixels is 0.
float clip_refine_weight(double error_m, double horizontal, double distance,
                         double pixels_per_radian, double pixels);

// The refinement weight of every vertex of every level, as a texture layer per level (R8,
// linear: a refined vertex between two takes their mean). A vertex's weight is the least
// of the parts that hold it, so the border of a refined part with an unrefined one, the
// trim or the finer level has weight 0 and lies on the level's surface.
typedef struct clip_refine_map {
    GLuint tex;
    unsigned char *now;  // this frame's, CLIP_REFINE_SIDE^2 per level
    unsigned char *sent; // what the texture holds
} clip_refine_map;

int clip_refine_map_init(clip_refine_map *m);
void clip_refine_map_free(clip_refine_map *m);
// Starts a level's weights for this frame: 1 everywhere but 0 over the vertices
// [h0, h1]^2 (the finer level's square, or the finest level's interior).
void clip_refine_map_begin(clip_refine_map *m, int level, int h0, int h1);
// Lowers the weights of the vertices [x0, x1] x [z0, z1] (inclusive, local units) of a
// level to at most w: a part's.
void clip_refine_map_limit(clip_refine_map *m, int level, int x0, int z0, int x1, int z1, float w);
// Sends a level's weights to its layer if they changed.
void clip_refine_map_upload(clip_refine_map *m, int level);

#endif
