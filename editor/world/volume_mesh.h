// Meshes of the solid (terrain with its volume edits, editor/world/volume_grid.h):
// surface nets (Gibson 1998) over the combined signed distance. A mesh holds the quads
// of the voxel edges it owns; vertices come from the field alone, so meshes of
// neighbouring boxes meet exactly (the viewport's brick meshes overlap by a voxel; an
// export's blocks share their border vertices and weld into one closed surface).
#ifndef OROGEN_EDITOR_VOLUME_MESH_H
#define OROGEN_EDITOR_VOLUME_MESH_H

#include "editor/world/volume_grid.h"
#include "editor/world/world.h"
#include "io/err.h"

#include <stddef.h>
#include <stdint.h>

typedef struct volume_mesh {
    float *pos;    // 3 per vertex, metres from origin
    float *normal; // 3 per vertex, unit, pointing out of the solid
    uint32_t *index;
    size_t vertex_count, index_count; // triangles: index_count / 3
    double origin[3];                 // world metres
} volume_mesh;

// The surface crossing the voxel edges that start at voxels in `starts` and end inside
// `within` (volume_box_everything(): no limit), positions relative to origin (metres).
// An empty mesh (no surface there) is not an error.
// With solid (may be NULL), voxels outside that box count as air (mirroring the
// nearest voxel inside it), so the surface closes along its sides and floor.
int volume_mesh_edges(world *w, const volume_grid *g, volume_box starts, volume_box within,
                      const volume_box *solid, const double origin[3], volume_mesh *out,
                      og_error *err);
volume_box volume_box_everything(void);
// The viewport's mesh of brick `key`: its edges and a ring of one voxel around them,
// relative to the brick's first voxel.
int volume_mesh_brick(world *w, const volume_grid *g, tile_key key, volume_mesh *out,
                      og_error *err);
void volume_mesh_free(volume_mesh *m);

#endif
