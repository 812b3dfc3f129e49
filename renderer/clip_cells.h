// Height bounds of a clipmap level's window in square cells of CLIP_CELL samples, so
// that a block of the level can be culled by its own heights rather than the whole
// level's (the frustum's and the nearer ground's tests, renderer/terrain_renderer.c).
// Rebuilt from the window's CPU mirror when it moved or was edited.
#ifndef OROGEN_RENDERER_CLIP_CELLS_H
#define OROGEN_RENDERER_CLIP_CELLS_H

#include "renderer/clip_window.h"

#include <stdint.h>

#define CLIP_CELL 8       // samples per cell side
#define CLIP_CELLS_MAX 64 // cells per side (windows up to 512 samples)

typedef struct clip_cells {
    int64_t have[2]; // the window origin (level sample indices) the bounds were built for
    int cells;       // per side; 0: not built
    // Cell (i, j) bounds samples [i, i + 1] * CLIP_CELL (both ends: the quads between two
    // cells lie in both) of the window, row-major.
    float lo[CLIP_CELLS_MAX * CLIP_CELLS_MAX], hi[CLIP_CELLS_MAX * CLIP_CELLS_MAX];
} clip_cells;

// The cells [*c0, *c1] of a window of `cells` cells holding its samples [a, b] (relative
// to its origin), clamped; 0 when they miss the window. Shared with clip_refine.c.
int clip_cell_span(int64_t a, int64_t b, int cells, int *c0, int *c1);
// From a window holding all of its samples (has_data).
void clip_cells_build(clip_cells *c, const clip_window *w);

// The lowest and highest height among the samples [i0, i1] x [j0, j1] (level sample
// indices, inclusive), clamped to the window; 0 when the cells are not built or the
// range misses the window.
int clip_cells_range(const clip_cells *c, int64_t i0, int64_t j0, int64_t i1, int64_t j1, float *lo,
                     float *hi);

#endif
