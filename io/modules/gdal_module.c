// GDAL bridge, built as the module liborogen_gdal.so and opened on first use by
// io/gdal_raster.c (GDAL pulls in hundreds of libraries; most runs never need it).
// Reads band 1 of any raster GDAL knows as float, nodata as NaN, with its
// geotransform; writes float GeoTIFFs.
#include "io/err.h"
#include "io/gdal_raster.h"

#include <gdal.h>
#include <ogr_srs_api.h>

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#define EXPORT __attribute__((visibility("default")))

static pthread_once_t registered = PTHREAD_ONCE_INIT;

static void register_drivers(void) {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler); // errors come back through CPLGetLastErrorMsg
}

static const char *last_error(void) {
    const char *m = CPLGetLastErrorMsg();
    return m && *m ? m : "no details";
}

// Unit names GDAL drivers report for feet.
static int unit_is_feet(const char *u) {
    return u && (!strcasecmp(u, "ft") || !strcasecmp(u, "foot") || !strcasecmp(u, "feet") ||
                 !strcasecmp(u, "us survey foot") || !strcasecmp(u, "ft_us"));
}

// kind: 0 unsigned, 1 signed, 2 float (as io/raster.h's raster_kind).
static void describe_type(GDALDataType t, int *kind, int *bits) {
    *bits = GDALGetDataTypeSizeBits(t);
    *kind = GDALDataTypeIsFloating(t) ? 2 : GDALDataTypeIsSigned(t) ? 1 : 0;
}

// The dataset's coordinate reference system as one line a world file keeps: its WKT
// when that fits and holds no ';' or '#', else its authority code; "" when it has none
// (or neither form fits).
static void crs_text(GDALDatasetH ds, char *out, size_t len, int *geographic) {
    out[0] = 0;
    *geographic = 0;
    const char *wkt = GDALGetProjectionRef(ds);
    if (!wkt || !*wkt) return;
    OGRSpatialReferenceH srs = OSRNewSpatialReference(wkt);
    if (!srs) return;
    *geographic = OSRIsGeographic(srs);
    if (strlen(wkt) < len && !strpbrk(wkt, ";#\n\r")) {
        snprintf(out, len, "%s", wkt);
    } else {
        const char *root = OSRIsProjected(srs) ? "PROJCS" : "GEOGCS";
        const char *name = OSRGetAuthorityName(srs, root), *code = OSRGetAuthorityCode(srs, root);
        if (name && code) snprintf(out, len, "%s:%s", name, code);
    }
    OSRDestroySpatialReference(srs);
}

EXPORT int orogen_gdal_module_read_georef(const char *path, int max_size, long long max_samples,
                                          float **samples, int *width, int *height, int *kind,
                                          int *bits, gdal_georef *geo, char *desc, size_t desc_len,
                                          og_error *err) {
    double *geotransform = geo->geotransform;
    *samples = NULL;
    *width = *height = 0;
    pthread_once(&registered, register_drivers);
    struct stat st;
    if (stat(path, &st) != 0)
        return og_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    if (S_ISDIR(st.st_mode)) return og_error_set(err, "%s: is a folder, not a raster", path);
    CPLErrorReset();
    GDALDatasetH ds = GDALOpen(path, GA_ReadOnly);
    if (!ds) return og_error_set(err, "%s: not a raster GDAL can read (%s)", path, last_error());
    int rc = -1;
    float *out = NULL;
    const int w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
    if (GDALGetRasterCount(ds) < 1) {
        og_error_set(err, "%s: the raster has no bands", path);
        goto done;
    }
    if (w <= 0 || h <= 0) {
        og_error_set(err, "%s: the raster has zero size (%d x %d)", path, w, h);
        goto done;
    }
    if (w > max_size || h > max_size || (long long)w * h > max_samples) {
        og_error_set(err,
                     "%s: the raster is %d x %d, over the limit of %d per side and %lld "
                     "samples",
                     path, w, h, max_size, max_samples);
        goto done;
    }
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    describe_type(GDALGetRasterDataType(band), kind, bits);
    if (GDALDataTypeIsComplex(GDALGetRasterDataType(band))) {
        og_error_set(err, "%s: complex samples are not heights", path);
        goto done;
    }
    // GDAL reads whole blocks, of every band at once when they are interleaved: a
    // damaged header can claim blocks of gigabytes for a small raster (found by
    // fuzzing: thousands of bands of 256 x 256), which GDAL would allocate.
    int block_w = 0, block_h = 0;
    GDALGetBlockSize(band, &block_w, &block_h);
    const long long bands = GDALGetRasterCount(ds), sample_bytes = (*bits + 7) / 8;
    const long long block_bytes = (long long)block_w * block_h * bands * sample_bytes;
    // What it may take: a few times the band we read (one strip of a whole big DEM is
    // fine), not the other bands' share of an interleaved block.
    if (block_w <= 0 || block_h <= 0 ||
        (block_bytes > (1LL << 28) && block_bytes > 4 * (long long)w * h * sample_bytes)) {
        og_error_set(err,
                     "%s: the raster is %d x %d but its %lld band%s claim blocks of %d x %d "
                     "samples (a damaged file?)",
                     path, w, h, bands, bands == 1 ? "" : "s", block_w, block_h);
        goto done;
    }
    out = malloc(sizeof(float) * (size_t)w * (size_t)h);
    if (!out) {
        og_error_set(err, "%s: out of memory for %d x %d samples", path, w, h);
        goto done;
    }
    CPLErrorReset();
    if (GDALRasterIO(band, GF_Read, 0, 0, w, h, out, w, h, GDT_Float32, 0, 0) != CE_None) {
        og_error_set(err, "%s: cannot read the samples (%s)", path, last_error());
        goto done;
    }
    int has_nodata = 0;
    double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
    int has_scale = 0, has_offset = 0;
    double scale = GDALGetRasterScale(band, &has_scale);
    double offset = GDALGetRasterOffset(band, &has_offset);
    if (!has_scale) scale = 1.0;
    if (!has_offset) offset = 0.0;
    geo->mapped = scale != 1.0 || offset != 0.0;
    const char *units = GDALGetRasterUnitType(band);
    const double to_metres = unit_is_feet(units) ? 0.3048 : 1.0;
    const float nodata_f = (float)nodata;
    const size_t n = (size_t)w * (size_t)h;
    for (size_t i = 0; i < n; i++) {
        float v = out[i];
        if (has_nodata && (v == nodata_f || (isnan(nodata) && isnan(v)))) {
            out[i] = NAN;
            continue;
        }
        out[i] = (float)((v * scale + offset) * to_metres);
    }
    if (GDALGetGeoTransform(ds, geotransform) != CE_None) {
        geotransform[0] = geotransform[2] = geotransform[3] = geotransform[4] = 0.0;
        geotransform[1] = geotransform[5] = 0.0; // no georeferencing
    }
    crs_text(ds, geo->crs, sizeof geo->crs, &geo->geographic);
    char mapping[96] = "";
    if (geo->mapped)
        snprintf(mapping, sizeof mapping, ", x %.9g + %.9g (the band's scale and offset)", scale,
                 offset);
    snprintf(desc, desc_len, "%s %s%s%s%s%s", GDALGetDriverShortName(GDALGetDatasetDriver(ds)),
             GDALGetDataTypeName(GDALGetRasterDataType(band)), has_nodata ? ", nodata " : "",
             has_nodata ? "set" : "", mapping,
             to_metres != 1.0 ? ", feet converted to metres" : "");
    *samples = out;
    out = NULL;
    *width = w;
    *height = h;
    rc = 0;
done:
    free(out);
    GDALClose(ds);
    return rc;
}

// A float32 or uint16 GeoTIFF (deflate, tiled) with the given geotransform and
// coordinate reference system, written to a temp file beside path and renamed into place.
// A uint16 band carries scale and offset (metres = stored x scale + offset), as GDAL
// readers apply them.
EXPORT int orogen_gdal_module_write_geotiff_mapped(const char *path, const float *samples,
                                                   int width, int height, int uint16, double scale,
                                                   double offset, const double geotransform[6],
                                                   const char *crs, og_error *err) {
    pthread_once(&registered, register_drivers);
    GDALDriverH drv = GDALGetDriverByName("GTiff");
    if (!drv) return og_error_set(err, "%s: GDAL has no GeoTIFF driver", path);
    char tmp[4200];
    if (snprintf(tmp, sizeof tmp, "%s.tmp-%d", path, (int)getpid()) >= (int)sizeof tmp)
        return og_error_set(err, "%s: path too long", path);
    OGRSpatialReferenceH srs = NULL;
    if (crs && *crs) {
        srs = OSRNewSpatialReference(NULL);
        if (!srs || OSRSetFromUserInput(srs, crs) != OGRERR_NONE) {
            if (srs) OSRDestroySpatialReference(srs);
            return og_error_set(err, "%s: GDAL does not know the world's geo_crs '%.80s'", path,
                                crs);
        }
    }
    char *options[] = {"COMPRESS=DEFLATE", "TILED=YES", uint16 ? "PREDICTOR=2" : "PREDICTOR=3",
                       NULL};
    CPLErrorReset();
    GDALDatasetH ds =
        GDALCreate(drv, tmp, width, height, 1, uint16 ? GDT_UInt16 : GDT_Float32, options);
    if (!ds) {
        if (srs) OSRDestroySpatialReference(srs);
        return og_error_set(err, "%s: cannot create (%s)", path, last_error());
    }
    int ok = GDALSetGeoTransform(ds, (double *)geotransform) == CE_None;
    if (srs) {
        ok = ok && GDALSetSpatialRef(ds, srs) == CE_None;
        OSRDestroySpatialReference(srs);
    }
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    GDALSetRasterUnitType(band, "m");
    if (uint16)
        ok = ok && GDALSetRasterScale(band, scale) == CE_None &&
             GDALSetRasterOffset(band, offset) == CE_None;
    ok = ok && GDALRasterIO(band, GF_Write, 0, 0, width, height, (void *)samples, width, height,
                            GDT_Float32, 0, 0) == CE_None;
    GDALClose(ds); // flushes; errors land in CPLGetLastErrorMsg
    if (!ok || CPLGetLastErrorType() >= CE_Failure) {
        og_error_set(err, "%s: cannot write (%s)", path, last_error());
        unlink(tmp);
        return -1;
    }
    int fd = open(tmp, O_RDONLY);
    int synced = fd >= 0 && fsync(fd) == 0;
    if (fd >= 0) close(fd);
    if (!synced) {
        og_error_set(err, "%s: cannot sync: %s", path, strerror(errno));
        unlink(tmp);
        return -1;
    }
    if (rename(tmp, path) != 0) {
        og_error_set(err, "%s: cannot rename the temp file into place: %s", path, strerror(errno));
        unlink(tmp);
        return -1;
    }
    return 0;
}
