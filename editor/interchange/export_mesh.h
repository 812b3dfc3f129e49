// Meshes out: a region of the coarse layer as triangles in metres with +Y up (glTF's
// axes; Blender's importer shows it Z-up at true size): OBJ with normals and UVs,
// binary PLY, or glTF 2.0 binary (.glb) with a base-colour texture from the terrain's
// height and slope. Optional simplification to a height error in metres
// (meshoptimizer, borders kept) and a closed base for 3D printing and booleans. A region
// with volume edits (caves, overhangs, arches) is exported as the solid's surface
// (export_solid.h): overhangs included, no seam where the edits meet the ground.
#ifndef OROGEN_EDITOR_INTERCHANGE_EXPORT_MESH_H
#define OROGEN_EDITOR_INTERCHANGE_EXPORT_MESH_H

#include "editor/params/world_grid.h"
#include "editor/world/world.h"
#include "io/err.h"

#include <stddef.h>

// The most samples one mesh export reads (4096^2 and then some).
#define EXPORT_MESH_MAX_SAMPLES ((int64_t)1 << 25)

typedef struct export_mesh_options {
    grid_rect rect;  // coarse samples
    double simplify; // metres of error allowed; 0: every sample a vertex
    int solid;       // walls and a floor: a closed mesh
    int centred;     // the region's centre at the origin (else world position)
} export_mesh_options;

typedef struct export_mesh_report {
    size_t vertices, triangles, input_triangles;
    double achieved_error; // metres (simplified meshes): vertical, or both ways for volume
    int volume;            // caves or overhangs: a volume surface, not a heightfield
    float lo[3], hi[3];    // bounding box, metres
} export_mesh_report;

// 1 when path names a mesh format (.obj .ply .glb).
int export_mesh_wanted(const char *path);
int export_mesh(world *w, const char *path, const export_mesh_options *o, export_mesh_report *rep,
                og_error *err);

#endif
