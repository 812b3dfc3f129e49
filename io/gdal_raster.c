#include "io/gdal_raster.h"

#include "io/file_kind.h"
#include "io/module_load.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>

typedef int (*read_fn)(const char *, int, long long, float **, int *, int *, int *, int *,
                       gdal_georef *, char *, size_t, og_error *);
typedef int (*write_fn)(const char *, const float *, int, int, int, double, double, const double[6],
                        const char *, og_error *);

static struct {
    pthread_once_t once;
    read_fn read;
    write_fn write;
    char why[1024];
} module = {.once = PTHREAD_ONCE_INIT};

static void load_module(void) {
    void *h = module_open("OROGEN_GDAL_MODULE", "liborogen_gdal.so",
#ifdef OROGEN_GDAL_MODULE_PATH
                          OROGEN_GDAL_MODULE_PATH,
#else
                          NULL,
#endif
                          module.why, sizeof module.why);
    if (!h) return;
    module.read = (read_fn)dlsym(h, "orogen_gdal_module_read_georef");
    module.write = (write_fn)dlsym(h, "orogen_gdal_module_write_geotiff_mapped");
    if (module.read && module.write) return;
    snprintf(module.why, sizeof module.why, "liborogen_gdal.so is not Orogen's GDAL module");
    module.read = NULL;
}

int gdal_raster_available(char *why, size_t why_len) {
    pthread_once(&module.once, load_module);
    if (!module.read && why) snprintf(why, why_len, "%s", module.why);
    return module.read != NULL;
}

int gdal_raster_read(const char *path, int max_size, long long max_samples, float **samples,
                     int *width, int *height, int *kind, int *bits, gdal_georef *geo, char *desc,
                     size_t desc_len, og_error *err) {
    *samples = NULL;
    if (file_kind_check_read(path, err) != 0) return -1;
    if (!gdal_raster_available(NULL, 0))
        return og_error_set(err, "%s: elevation rasters need GDAL, which is unavailable: %s", path,
                            module.why);
    return module.read(path, max_size, max_samples, samples, width, height, kind, bits, geo, desc,
                       desc_len, err);
}

int gdal_raster_write_geotiff(const char *path, const float *samples, int width, int height,
                              int uint16, double scale, double offset, const double geotransform[6],
                              const char *crs, og_error *err) {
    if (file_kind_check_replace(path, err) != 0) return -1;
    if (!gdal_raster_available(NULL, 0))
        return og_error_set(err, "%s: GeoTIFF export needs GDAL, which is unavailable: %s", path,
                            module.why);
    return module.write(path, samples, width, height, uint16, scale, offset, geotransform,
                        crs ? crs : "", err);
}
