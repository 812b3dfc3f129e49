// Simplifies a volume surface (terrain with caves and overhangs: a welded, manifold mesh
// from export_solid_surface) to within a measured error, keeping it closed and manifold.
//
// meshoptimizer collapses edges (its sides, the open edges, kept in place so tiles still
// meet); each result is then checked as a reader would: every edge in two faces wound
// against each other (open only where the input was open), no faces on the same three
// vertices, no sliver, no face turned against the surface it replaces, and the distance
// both ways between the result and the input (from every input vertex to the result, from
// points on every result face, as dense as the input's vertices, to the input) within
// the error asked for. Where a check fails, the input's faces around the vertices
// involved are kept as they were and the rest simplified again, until every check passes
// (at worst the input comes back whole).
#ifndef OROGEN_EDITOR_INTERCHANGE_VOLUME_SIMPLIFY_H
#define OROGEN_EDITOR_INTERCHANGE_VOLUME_SIMPLIFY_H

#include "editor/world/volume_mesh.h"
#include "io/err.h"

typedef struct volume_simplify_report {
    double max_error; // metres: the largest distance measured either way
    int rounds;       // meshoptimizer runs
} volume_simplify_report;

int volume_simplify(volume_mesh *m, double error_m, volume_simplify_report *rep, og_error *err);

#endif
