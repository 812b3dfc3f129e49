// Histograms of the composite's heights and slopes over an area, for the mask editor's
// ranges (app/layers_panel.c): a read-only query of the tile cache, made on the thread
// that holds the world (the window's, while no job runs; app/work_queue.h). A wide area
// is read at the mip level that keeps it within TERRAIN_HISTOGRAM_SIDE samples a side,
// so its slopes are those of that level's spacing (gentler than level 0's on rough
// ground); `spacing` says which.
#ifndef OROGEN_EDITOR_WORLD_TERRAIN_HISTOGRAM_H
#define OROGEN_EDITOR_WORLD_TERRAIN_HISTOGRAM_H

#include "editor/world/world.h"

#define TERRAIN_HISTOGRAM_BINS 48
#define TERRAIN_HISTOGRAM_SIDE 256

typedef struct terrain_histogram {
    double x0, z0, x1, z1;                // the area read, face-local metres
    double spacing;                       // metres between the samples read
    double height_min, height_max;        // the heights' range: the height bins span it
    float height[TERRAIN_HISTOGRAM_BINS]; // fraction of the samples in each bin
    float slope[TERRAIN_HISTOGRAM_BINS];  // degrees, 0 to 90 in equal bins
    size_t samples;
} terrain_histogram;

// Reads the composite within half metres of (cx, cz) on face (clamped to a bounded
// world's extent). -1 with err when the area is outside the world or a tile cannot be
// read.
int terrain_histogram_compute(world *w, int face, double cx, double cz, double half,
                              terrain_histogram *out, og_error *err);

#endif
