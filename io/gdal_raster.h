// Elevation rasters through GDAL (GeoTIFF, SRTM .hgt, ESRI ASCII grid and whatever
// else GDAL reads), in a module loaded on first use (io/modules/gdal_module.c).
#ifndef OROGEN_IO_GDAL_RASTER_H
#define OROGEN_IO_GDAL_RASTER_H

#include "io/err.h"

#include <stddef.h>

// Whether the GDAL module can be loaded (why says why not).
int gdal_raster_available(char *why, size_t why_len);

// Band 1 as float: nodata samples as NaN, the band's scale and offset applied, feet
// converted to metres. geotransform is GDAL's (all zero without georeferencing);
// *geographic is 1 when its units are degrees. *kind: 0 unsigned, 1 signed, 2 float.
int gdal_raster_read(const char *path, int max_size, long long max_samples, float **samples,
                     int *width, int *height, int *kind, int *bits, double geotransform[6],
                     int *geographic, char *desc, size_t desc_len, og_error *err);

// A float32 GeoTIFF with that geotransform (metres, no coordinate system), written
// atomically.
int gdal_raster_write_geotiff(const char *path, const float *samples, int width, int height,
                              const double geotransform[6], og_error *err);

#endif
