// Distance from a point to a triangle mesh (the nearest point on any of its faces),
// through a uniform grid of cells over the faces' bounds. Measures how far a simplified
// surface strays from the one it replaces, both ways (a Hausdorff distance).
#ifndef OROGEN_EDITOR_INTERCHANGE_MESH_DISTANCE_H
#define OROGEN_EDITOR_INTERCHANGE_MESH_DISTANCE_H

#include <stddef.h>
#include <stdint.h>

typedef struct mesh_distance {
    const float *pos;       // 3 per vertex (not owned)
    const uint32_t *index;  // 3 per face (not owned)
    double lo[3], cell;     // grid origin and cell size, metres
    int64_t n[3];           // cells per axis
    uint32_t *start, *face; // faces of cell c: face[start[c] .. start[c + 1])
} mesh_distance;

// Indexes `triangles` faces of index over pos (both must outlive it). Returns -1 when
// out of memory.
int mesh_distance_build(mesh_distance *d, const float *pos, const uint32_t *index,
                        size_t triangles);
// Distance from p to the nearest face; *nearest (may be NULL) that face (UINT32_MAX if
// none). A mesh with no faces is infinitely far.
double mesh_distance_to(const mesh_distance *d, const double p[3], uint32_t *nearest);
// 1 when some face lies within limit of p (cheaper: stops at the first); else 0, and
// *nearest (may be NULL) the nearest face found
// (UINT32_MAX if none).
int mesh_distance_within(const mesh_distance *d, const double p[3], double limit,
                         uint32_t *nearest);
void mesh_distance_free(mesh_distance *d);

#endif
