// Simplifies a heightfield grid into right triangles of a regular hierarchy (RTIN, as in
// Mapbox's Martini): a triangle splits at its long edge's midpoint while the ground
// strays from it there or anywhere below it, so the mesh never folds, never cracks and
// covers the grid exactly, border included. Any W x D grid: the hierarchy spans the
// next 2^k + 1 square and triangles reaching past the grid split until they lie inside.
#ifndef OROGEN_EDITOR_INTERCHANGE_HEIGHTFIELD_SIMPLIFY_H
#define OROGEN_EDITOR_INTERCHANGE_HEIGHTFIELD_SIMPLIFY_H

#include <stddef.h>
#include <stdint.h>

typedef struct heightfield_rtin {
    int64_t w, d, tile; // grid samples; the hierarchy's square side (2^k)
    float *error;       // per sample: the largest deviation a split there would remove
} heightfield_rtin;

// Builds the error hierarchy of the w x d heights h (row-major). Returns -1 when out of
// memory.
int heightfield_rtin_build(heightfield_rtin *r, const float *h, int64_t w, int64_t d);
// Triangles for a threshold (metres): every triangle whose split would remove more is
// split. *idx (malloc'd, 3 per triangle) names samples j * w + i, counter-clockwise seen
// from +Y with Z toward the viewer (the grid mesh's winding). Returns -1 when out of memory.
int heightfield_rtin_mesh(const heightfield_rtin *r, double threshold, uint32_t **idx,
                          size_t *indices);
void heightfield_rtin_free(heightfield_rtin *r);

#endif
