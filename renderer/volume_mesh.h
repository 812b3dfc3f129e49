// Meshes of the solid where volume edits are (editor/world/volume_grid.h): surface nets
// (Gibson 1998) over the combined signed distance of one brick and a one-voxel ring
// around it. Vertices come from the field alone, so where neighbouring bricks' meshes
// overlap (that ring) their triangles are the same: no crack where they meet.
#ifndef OROGEN_RENDERER_VOLUME_MESH_H
#define OROGEN_RENDERER_VOLUME_MESH_H

#include "editor/world/volume_grid.h"
#include "editor/world/world.h"
#include "io/err.h"

#include <stddef.h>
#include <stdint.h>

typedef struct volume_mesh {
    float *pos;    // 3 per vertex, metres from the brick's voxel (i0, j0, k0)
    float *normal; // 3 per vertex, unit, pointing out of the solid
    uint32_t *index;
    size_t vertex_count, index_count; // triangles: index_count / 3
    double origin[3];                 // world metres of the brick's voxel (i0, j0, k0)
} volume_mesh;

// Meshes brick `key` of w. An empty mesh (no surface crosses the brick) is not an error.
int volume_mesh_brick(world *w, const volume_grid *g, tile_key key, volume_mesh *out,
                      og_error *err);
void volume_mesh_free(volume_mesh *m);

#endif
