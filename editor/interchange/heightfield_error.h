// How far a simplified heightfield mesh strays from its grid, measured as a reader
// would: the largest vertical deviation at every grid sample (the border included), and
// the triangles that fold (face down, or stand on edge with no area seen from above) or
// leave samples uncovered. meshoptimizer's own error is a 3D quadric estimate that
// understates the vertical error on slopes, so simplification is judged by this.
#ifndef OROGEN_EDITOR_INTERCHANGE_HEIGHTFIELD_ERROR_H
#define OROGEN_EDITOR_INTERCHANGE_HEIGHTFIELD_ERROR_H

#include <stddef.h>
#include <stdint.h>

typedef struct heightfield_grid {
    const float *h;            // w x d heights, row-major
    int64_t w, d;              // samples
    double spacing;            // metres between samples
    double origin_x, origin_z; // position of sample (0, 0)
} heightfield_grid;

typedef struct heightfield_error {
    double max_deviation; // metres
    long long folded;     // triangles facing down or on edge
    long long uncovered;  // grid samples under no triangle
} heightfield_error;

// Triangles idx (indices / 3 of them) over positions pos (x, y, z at the start of every
// stride floats), counter-clockwise from above as the grid's own. Returns -1 when out of
// memory.
int heightfield_error_measure(const heightfield_grid *g, const float *pos, size_t stride,
                              const uint32_t *idx, size_t indices, heightfield_error *out);

#endif
