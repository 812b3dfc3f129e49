// Makes a welded triangle mesh a manifold one, as Blender, Houdini and game engines
// expect: no degenerate triangles (nor two on the same three vertices), no edge of more than two
// faces, each edge's two faces wound against each other, no vertex that no face uses. Surface nets
// give one vertex per cell, so where two sheets of the surface pass through one cell (a thin wall,
// a tunnel under a thin roof) they share a vertex and four faces share an edge; here each vertex is
// split into one copy per sheet of faces around it.
#ifndef OROGEN_EDITOR_INTERCHANGE_MESH_MANIFOLD_H
#define OROGEN_EDITOR_INTERCHANGE_MESH_MANIFOLD_H

#include "editor/world/volume_mesh.h"
#include "io/err.h"

typedef struct mesh_manifold_report {
    long long degenerate_dropped; // repeated vertex, zero area, or twins of one triangle
    long long vertices_split;     // copies added where sheets met at a vertex
    long long faces_dropped;      // faces left crowding an edge after the split
    long long unused_dropped;     // vertices no face used
} mesh_manifold_report;

int mesh_make_manifold(volume_mesh *m, mesh_manifold_report *rep, og_error *err);
// A face's three vertices in ascending order: faces on the same vertices compare equal.
void mesh_face_sorted(const uint32_t *t, uint32_t out[3]);

#endif
