// Where a world's samples lie on the Earth: a world made from georeferenced data keeps
// the source's coordinate reference system and geotransform (world_params geo_crs,
// geo_transform), so its exports land where the source did.
#ifndef OROGEN_EDITOR_WORLD_GEOREF_H
#define OROGEN_EDITOR_WORLD_GEOREF_H

#include "editor/params/world_params.h"

#include <stdint.h>

// Whether the world carries a geotransform from its source.
int world_georef_present(const world_params *p);

// GDAL's geotransform of an image whose sample (0, 0) is layer sample (x0, z0), for a
// layer with ratio samples per coarse sample (1 coarse, detail_ratio detail): the
// world's georeference, or without one local metres north-up (X east, rows toward +Z
// = south), the corner half a sample outside the first sample's centre either way.
void world_georef_region(const world_params *p, int ratio, int64_t x0, int64_t z0, double gt[6]);

#endif
