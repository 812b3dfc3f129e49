// A bounded flat world's heights seen whole at a coarse mip level (at most 2 x 2 tiles),
// for placing the first view: the lowest ground, and the land nearest the centre. A world
// made from a heightmap of an island keeps the ocean floor of its tile as flat ground
// (0 m, far above the flat default's -400 m sea), often for tens of kilometres around the
// centre: the first view then faces the island, not an empty plain.
#ifndef OROGEN_RENDERER_LAND_SCAN_H
#define OROGEN_RENDERER_LAND_SCAN_H

#include "editor/world/world.h"
#include "io/err.h"

typedef struct land_scan {
    float *height;          // nx * nz samples, row by row (owned)
    int nx, nz;             // samples across and down
    double step;            // metres between samples
    double origin;          // metres from the world's edge to the first sample, both ways
    double lowest, highest; // metres, over the samples
} land_scan;

// Reads the world's composite heights at the coarsest level that still has at least 128
// samples across its narrower side (all of them for a smaller world). Fails for planets and
// unbounded worlds. Free with land_scan_free.
int land_scan_read(world *w, land_scan *s, og_error *err);
void land_scan_free(land_scan *s);

// The sample nearest to (cx, cz) metres that stands above `above` metres with a slope to
// its next samples under max_slope: its position in metres in *x, *z. Returns 1 when one
// was found, 0 when none.
int land_scan_nearest(const land_scan *s, double cx, double cz, double above, double max_slope,
                      double *x, double *z);

#endif
