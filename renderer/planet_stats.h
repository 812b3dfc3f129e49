// The planet viewport's figures for a frame (the status bar, the benchmarks).
#ifndef OROGEN_RENDERER_PLANET_STATS_H
#define OROGEN_RENDERER_PLANET_STATS_H

#include <stdint.h>

typedef struct planet_stats {
    uint64_t triangles;
    int draw_calls;
    int chunks_drawn, chunks_resident, finest_level, coarsest_level;
    uint64_t vertices_uploaded;      // this frame (chunk meshes built from tiles)
    uint64_t detail_texels_uploaded; // this frame (the detail window near the ground)
    int chunks_built;                // this frame
    int chunks_culled;               // behind the horizon or outside the view, this frame
    int chunks_occluded;             // chosen but hidden by nearer ground, this frame
    double cpu_ms;
} planet_stats;

#endif
