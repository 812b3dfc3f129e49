// libFuzzer target: the heightmap importers' readers: RAW/R16 (sizes, byte orders,
// float32), GDAL's (SRTM .hgt, ESRI ASCII grid, GeoTIFF) and OpenImageIO's (PNG, EXR,
// PGM) with their void filling.
// The first byte picks the format and RAW options.
#include "fuzz_support.h"
#include "io/raster.h"

#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < 1 || size > (1u << 20)) return 0;
    static const char *const names[] = {"r.r16", "r.raw", "N10E010.hgt", "r.asc",
                                        "r.tif", "r.png", "r.exr",       "r.pgm"};
    const char *path = fuzz_file(names[data[0] % 8], data + 1, size - 1);
    raster_read_options o;
    memset(&o, 0, sizeof o);
    o.raw_float = (data[0] >> 3) & 1;
    o.endian = (data[0] >> 4) & 1 ? RASTER_BIG : RASTER_LITTLE;
    raster r;
    og_error err;
    if (raster_read(path, &o, &r, &err) == 0) raster_free(&r);
    return 0;
}
