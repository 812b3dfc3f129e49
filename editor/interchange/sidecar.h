// The sidecar FILE.json written beside every exported heightmap: what a sample
// means (height = stored value x scale + offset, metres), where the first sample
// sits (origin, metres) and how far apart samples are, so the file goes back in at
// true scale and place. Import reads it when present.
#ifndef OROGEN_EDITOR_INTERCHANGE_SIDECAR_H
#define OROGEN_EDITOR_INTERCHANGE_SIDECAR_H

#include "io/err.h"

#include <stdio.h>

typedef struct sidecar {
    double spacing;            // metres between samples (both axes, unless spacing_z)
    double spacing_z;          // metres between rows when not spacing (0: spacing)
    double origin_x, origin_z; // world position of row 0, column 0 (metres)
    int width, height;         // samples
    double scale, offset;      // height = stored value x scale + offset
    double min, max;           // metres: the heights the file holds
    char format[32];           // "png16", "tiff16", "tiff32", "exr32", "r16", ...
    char layer[16];            // "coarse", "detail"
    // A georeferenced export's place (sidecar_georef): GDAL's geotransform of the image
    // and its coordinate reference system; has_georef 0 when the sidecar has none.
    int has_georef;
    double geotransform[6];
    char crs[3584];
} sidecar;

// Writes path + ".json" atomically. extra (may be NULL) is inserted as more
// members (already formatted `"key": value` lines joined by ",\n").
int sidecar_write(const char *image_path, const sidecar *s, const char *extra, og_error *err);
// Formats the members a georeferenced export adds to its sidecar ("crs": the
// coordinate reference system as given, "geotransform": GDAL's six numbers) into out,
// after a comma when comma is set.
void sidecar_georef(char *out, size_t len, int comma, const char *crs, const double gt[6]);
// Reads image_path + ".json": 1 when read, 0 when there is none, -1 when it is there
// but unreadable or missing a field (err names the file and field).
int sidecar_read(const char *image_path, sidecar *s, og_error *err);

#endif
