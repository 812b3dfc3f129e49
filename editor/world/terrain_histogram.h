// Histograms of the composite's heights, slopes, curvatures and flow over an area, for the
// mask editor's ranges (app/mask_editor.c): a read-only query of the tile cache, made on the thread
// that holds the world (the window's, while no job runs; app/work_queue.h). A wide area
// is read at the mip level that keeps it within TERRAIN_HISTOGRAM_SIDE samples a side,
// so its slopes are those of that level's spacing (gentler than level 0's on rough
// ground; curvatures too); `spacing` says which. Flow is the upstream area
// (editor/layers/layer_mask.h) over the area read, at its spacing: a catchment reaching
// past the area is cut there, as the mask's is past its evaluation window.
#ifndef OROGEN_EDITOR_WORLD_TERRAIN_HISTOGRAM_H
#define OROGEN_EDITOR_WORLD_TERRAIN_HISTOGRAM_H

#include "editor/world/world.h"

#define TERRAIN_HISTOGRAM_BINS 48
#define TERRAIN_HISTOGRAM_SIDE 256

typedef struct terrain_histogram {
    double x0, z0, x1, z1;                   // the area read, face-local metres
    double spacing;                          // metres between the samples read
    double height_min, height_max;           // the heights' range: the height bins span it
    float height[TERRAIN_HISTOGRAM_BINS];    // fraction of the samples in each bin
    float slope[TERRAIN_HISTOGRAM_BINS];     // degrees, 0 to 90 in equal bins
    double curvature_min, curvature_max;     // the middle 98% of the curvatures: the bins span it
    float curvature[TERRAIN_HISTOGRAM_BINS]; // -100 x Laplacian; the tails in the end bins
    double flow_min, flow_max;               // m2: a sample's own cell to the largest area
    float flow[TERRAIN_HISTOGRAM_BINS];      // equal bins of log10 of the area
    size_t samples;
} terrain_histogram;

// The area's flow as terrain_histogram_compute_flow gives it: w x h samples `spacing`
// apart from (x0, z0), row-major, m2 of upstream area each.
typedef struct terrain_flow_field {
    float *area;
    int w, h;
    double x0, z0, spacing;
} terrain_flow_field;

// Reads the composite within half metres of (cx, cz) on face (clamped to a bounded
// world's extent, or to the face of a planet: face-local metres, sample i at i x
// world_grid_sample_metres). -1 with err when the area is outside the world or a tile cannot be
// read.
int terrain_histogram_compute(world *w, int face, double cx, double cz, double half,
                              terrain_histogram *out, og_error *err);
// The same, and the flow over the area into *flow (its area freed first when set; on
// error it is left empty). terrain_flow_field_free empties it.
int terrain_histogram_compute_flow(world *w, int face, double cx, double cz, double half,
                                   terrain_histogram *out, terrain_flow_field *flow, og_error *err);
void terrain_flow_field_free(terrain_flow_field *flow);

#endif
