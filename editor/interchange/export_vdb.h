// Export of the solid (terrain with its caves, overhangs and arches) as an OpenVDB
// level set: `export FILE.vdb [region=X0,Z0,X1,Z1] [voxel=M] [band=N] [fog=1] [depth=M]`.
// A FloatGrid "surface" of class level set, background band x voxel, a linear
// transform of voxel metres with index (i, j, k) at world (i, j, k) x voxel (y up),
// holding the heightfield's narrow-band signed distance over the region combined with
// the volume edits (editor/world/volume_grid.h); with fog=1 also a "density" fog
// volume (what Blender's volume objects render). The solid is the region's columns from
// depth metres below its lowest ground up to the surface: every inactive voxel and tile
// carries that solid's sign (interior -background), and the fog's density lies only
// there, so the file grows with the region. Metadata: creator, world, spacing,
// voxel, region. Written atomically.
#ifndef OROGEN_EDITOR_INTERCHANGE_EXPORT_VDB_H
#define OROGEN_EDITOR_INTERCHANGE_EXPORT_VDB_H

#include "editor/interchange/export.h"
#include "editor/world/world.h"
#include "io/err.h"

#include <stdint.h>

typedef struct export_vdb_report {
    double voxel;             // metres
    int band;                 // half width, voxels
    double floor;             // metres: the solid's bottom (the depth below the lowest ground)
    long long columns;        // voxel columns over the region
    long long bricks;         // volume bricks combined in
    long long active_voxels;  // in the level set
    long long voxels_written; // values computed
    int64_t lo[3], hi[3];     // index bounds of what was computed (inclusive)
    long long bytes;
} export_vdb_report;

int export_vdb_wanted(const char *path);
int export_vdb_file(world *w, const char *path, const export_options *o, export_vdb_report *rep,
                    og_error *err);

#endif
