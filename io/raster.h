// Height rasters in: one channel of samples from an image (OpenImageIO), an
// elevation raster (GDAL: GeoTIFF, SRTM .hgt, ESRI ASCII grid, ...) or a headerless
// RAW / R16 file, as stored (never normalised), with what the file says about
// spacing, units and missing samples.
#ifndef OROGEN_IO_RASTER_H
#define OROGEN_IO_RASTER_H

#include "io/err.h"
#include "io/gdal_raster.h"

#include <stddef.h>
#include <stdint.h>

// The largest width or height a raster may have; checked before any large allocation.
#define RASTER_MAX_SIZE 65536
// And the most samples in all (4 GiB of floats).
#define RASTER_MAX_SAMPLES ((int64_t)1 << 30)

typedef enum raster_kind {
    RASTER_UNSIGNED, // unsigned integers: 0 .. 2^bits - 1 (a normalised format)
    RASTER_SIGNED,   // signed integers (DEMs store metres this way)
    RASTER_FLOAT     // half / float / double: values as stored
} raster_kind;

typedef enum raster_endian { RASTER_LITTLE, RASTER_BIG } raster_endian;

typedef struct raster_read_options {
    char channel[64]; // image channel by name (EXR "Y", "R", "height"...); "": the first
    // RAW / R16: sample format and size (0: inferred from the file length as a square).
    int raw_float;        // float32 instead of uint16
    raster_endian endian; // RAW byte order (little: Unity / Unreal / Godot)
    int width, height;
} raster_read_options;

typedef struct raster {
    float *samples; // width x height, row-major from the first stored row (malloc'd)
    int width, height;
    raster_kind kind;
    int bits;              // bits per stored sample: 8, 16, 32, 64
    double spacing_x;      // metres between columns from the file's georeferencing; 0: none
    double spacing_z;      // metres between rows; 0: none
    int64_t voids;         // missing samples (nodata, NaN) filled from their surroundings
    gdal_georef georef;    // GDAL's geotransform and CRS (zero / "" when not georeferenced)
    char reader[16];       // "image", "gdal" or "raw"
    char description[256]; // what was read: format, sample type, georeferencing, units
} raster;

// Reads path by its content and extension: .r16 / .raw as RAW; rasters GDAL knows
// (.hgt .tif .tiff .asc .dem .bil .bt .img .vrt ...) through GDAL; other images
// through OpenImageIO. Heights in feet are converted to metres; a band's scale and
// offset are applied. Voids are filled (raster_fill_voids) and counted.
// On failure nothing is allocated and err names the file and the problem.
int raster_read(const char *path, const raster_read_options *options, raster *out, og_error *err);
void raster_free(raster *r);

// RAW alone (also used by raster_read): see raster_read_options.
int raster_read_raw(const char *path, const raster_read_options *options, raster *out,
                    og_error *err);

// Fills NaN samples from the valid samples around them (push-pull: averages of the
// valid samples over a pyramid, pulled back down and blended across each hole).
// Returns the number filled, or -1 when no sample at all is valid.
int64_t raster_fill_voids(float *samples, int width, int height);

// Metres per degree of latitude and of longitude at a latitude (degrees), on the
// WGS84 ellipsoid: what a geographic raster's degree spacing is worth there.
void raster_metres_per_degree(double latitude, double *per_lat, double *per_lon);

#endif
