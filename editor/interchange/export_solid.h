// The solid's surface for mesh exports where a region holds volume edits (caves,
// overhangs, arches): surface nets over the combined signed distance of the whole
// region, in blocks of 32 x 32 voxel columns whose shared border vertices are welded,
// so the heightfield and the volume edits make one surface with no seam between them.
#ifndef OROGEN_EDITOR_INTERCHANGE_EXPORT_SOLID_H
#define OROGEN_EDITOR_INTERCHANGE_EXPORT_SOLID_H

#include "editor/params/world_grid.h"
#include "editor/world/volume_mesh.h"
#include "editor/world/world.h"
#include "io/err.h"

// Whether volume bricks lie over the region (coarse samples [rect)): *has 1 or 0.
int export_solid_has_volume(world *w, grid_rect rect, int *has, og_error *err);
// The surface over the region's voxel columns (world metres, origin 0), welded: shared
// positions are one vertex, then made manifold (mesh_manifold.h). Open only at the
// region's sides.
// closed: a solid for printing and booleans instead, its sides on the region's edges and
// a floor below the lowest ground (by 5% of the relief, at least a metre): no open edge.
int export_solid_surface(world *w, grid_rect rect, int closed, volume_mesh *out, og_error *err);

#endif
