// Engine presets whose heightmaps come in fixed sizes (Unity: 2^n+1 per terrain; Unreal:
// its recommended landscape sizes) take the whole region resampled to the nearest such
// size (fit=resample, the default), so placing the tiles at the printed scale reproduces
// the region's extent; fit=crop keeps samples as they are and drops the rest.
#ifndef OROGEN_EDITOR_INTERCHANGE_EXPORT_FIT_H
#define OROGEN_EDITOR_INTERCHANGE_EXPORT_FIT_H

#include "editor/params/world_params.h"

#include <stdint.h>

// The region's W x H samples resampled to out_w x out_h (tiles sharing their edge
// samples: cols x (tile - 1) + 1), corners on corners.
typedef struct export_fit {
    int64_t region_x0, region_z0; // the region's first sample (the layer's grid)
    int64_t region_w, region_h;   // its samples
    int64_t out_w, out_h;         // resampled samples of the whole set
} export_fit;

// The largest of sizes[] not above n, or 0.
int export_fit_largest(const int *sizes, int count, int64_t n);
// The size of sizes[] whose tiles (n - 1 samples apart, `tiles` of them sharing edges)
// come nearest to spanning `samples` (the smaller one on a tie).
int export_fit_nearest(const int *sizes, int count, int64_t samples, int tiles);

// Output sample i's position along an axis in region samples (exactly 0 and n - 1 at
// the ends): one expression, so tiles sharing an edge sample compute the same value.
double export_fit_position(int64_t i, int64_t out_n, int64_t region_n);
// The region samples [*s0, *s1) that output samples [i0, i1) of an axis read.
void export_fit_source(int64_t i0, int64_t i1, int64_t out_n, int64_t region_n, int64_t *s0,
                       int64_t *s1);
// Output samples [i0, i0 + ow) x [j0, j0 + oh) of the set, bilinear from src: region
// samples [sx0, sx0 + sw) x [sz0, sz0 + sh), row-major. Samples on a region sample copy it.
void export_fit_resample(const export_fit *f, const float *src, int64_t sw, int64_t sx0,
                         int64_t sz0, int64_t i0, int64_t j0, int64_t ow, int64_t oh, float *out);
// Metres between output samples along X and Z for the layer's spacing.
double export_fit_spacing_x(const export_fit *f, double spacing);
double export_fit_spacing_z(const export_fit *f, double spacing);
// GDAL's geotransform of output samples from (i0, j0) on: the world's (by `ratio`
// samples per coarse one) scaled by the resampling.
void export_fit_georef(const world_params *p, int ratio, const export_fit *f, int64_t i0,
                       int64_t j0, double gt[6]);

#endif
