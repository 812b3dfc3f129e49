// Elevation rasters through GDAL (GeoTIFF, SRTM .hgt, ESRI ASCII grid and whatever
// else GDAL reads), in a module loaded on first use (io/modules/gdal_module.c).
#ifndef OROGEN_IO_GDAL_RASTER_H
#define OROGEN_IO_GDAL_RASTER_H

#include "io/err.h"

#include <stddef.h>

// Longest coordinate reference system text kept (WKT, or an authority code).
#define GDAL_CRS_MAX 3584

// Where a raster lies: GDAL's geotransform (all zero without georeferencing), whether
// its units are degrees, and its coordinate reference system as one line of WKT (or
// "EPSG:N" when the WKT would not fit or holds ';' or '#'; "" = none).
typedef struct gdal_georef {
    double geotransform[6];
    int geographic;
    int mapped; // the band's scale and offset were applied: the samples are metres
    char crs[GDAL_CRS_MAX];
} gdal_georef;

// Whether the GDAL module can be loaded (why says why not).
int gdal_raster_available(char *why, size_t why_len);

// Band 1 as float: nodata samples as NaN, the band's scale and offset applied, feet
// converted to metres, and where it lies (geo). *kind: 0 unsigned, 1 signed, 2 float.
int gdal_raster_read(const char *path, int max_size, long long max_samples, float **samples,
                     int *width, int *height, int *kind, int *bits, gdal_georef *geo, char *desc,
                     size_t desc_len, og_error *err);

// A GeoTIFF of samples (float32, or uint16 when uint16: samples then hold whole numbers
// 0 .. 65535, and the band says metres = stored x scale + offset) with that
// geotransform and coordinate reference system (WKT or an authority code; "" = none:
// local metres), written atomically. Units: metres.
int gdal_raster_write_geotiff(const char *path, const float *samples, int width, int height,
                              int uint16, double scale, double offset, const double geotransform[6],
                              const char *crs, og_error *err);

#endif
