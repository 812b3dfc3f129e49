// The image functions load OpenImageIO only when first used: it pulls in some 260
// shared libraries (OpenCV, FFmpeg, GDAL, ...) that would otherwise cost every
// start of orogen ~0.3 s (several seconds under the sanitizers). io/image_read.cpp
// is built as the module liborogen_image.so and opened with dlopen here.
#include "io/image_read.h"

#include "io/file_kind.h"
#include "io/module_load.h"
#include "io/png_gray.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef int (*read_fn)(const char *, float **, int *, int *, og_error *);
typedef int (*write_fn)(const char *, const float *, int, int, og_error *);
typedef int (*read_rgb8_fn)(const char *, unsigned char **, int *, int *, og_error *);
typedef int (*write_rgb8_fn)(const char *, const unsigned char *, int, int, og_error *);
typedef int (*read_channel_fn)(const char *, const char *, int, float **, int *, int *, int *,
                               int *, char *, size_t, og_error *);
typedef int (*write_png_fn)(const char *, const void *, int, int, int, int, og_error *);
typedef int (*write_samples_fn)(const char *, const float *, int, int, int, const char *,
                                og_error *);

static struct {
    pthread_once_t once;
    read_fn read;
    write_fn write;
    read_rgb8_fn read_rgb8;
    write_rgb8_fn write_rgb8;
    read_channel_fn read_channel;
    write_samples_fn write_samples;
    write_png_fn write_png;
    char why[1024];
} module = {.once = PTHREAD_ONCE_INIT};

static void load_module(void) {
    void *h = module_open("OROGEN_IMAGE_MODULE", "liborogen_image.so",
#ifdef OROGEN_IMAGE_MODULE_PATH
                          OROGEN_IMAGE_MODULE_PATH,
#else
                          NULL,
#endif
                          module.why, sizeof module.why);
    if (!h) return;
    module.read = (read_fn)dlsym(h, "orogen_image_module_read_luminance");
    module.write = (write_fn)dlsym(h, "orogen_image_module_write_gray16");
    module.read_rgb8 = (read_rgb8_fn)dlsym(h, "orogen_image_module_read_rgb8");
    module.write_rgb8 = (write_rgb8_fn)dlsym(h, "orogen_image_module_write_rgb8");
    module.read_channel = (read_channel_fn)dlsym(h, "orogen_image_module_read_channel");
    module.write_samples = (write_samples_fn)dlsym(h, "orogen_image_module_write_samples");
    module.write_png = (write_png_fn)dlsym(h, "orogen_image_module_write_png");
    if (module.read && module.write && module.read_rgb8 && module.write_rgb8 &&
        module.read_channel && module.write_samples && module.write_png)
        return;
    // An older module lacks the newer entry points: all or nothing.
    snprintf(module.why, sizeof module.why, "liborogen_image.so is not Orogen's image module");
    module.read = NULL;
}

// Before a write: the module is there and path is no device, FIFO or socket.
static int ready_to_write(const char *path, og_error *err) {
    pthread_once(&module.once, load_module);
    if (file_kind_check_replace(path, err) != 0) return -1;
    if (module.read) return 0;
    return og_error_set(err, "%s: image support is unavailable: %s", path, module.why);
}

// Before a read: the module is there and path is no device, FIFO, socket or folder.
static int ready(const char *path, og_error *err) {
    pthread_once(&module.once, load_module);
    if (path && file_kind_check_read(path, err) != 0) return -1;
    if (module.read) return 0;
    return og_error_set(err, "%s: image support is unavailable: %s", path ? path : "(no path)",
                        module.why);
}

int image_read_luminance(const char *path, float **pixels, int *width, int *height, og_error *err) {
    *pixels = NULL;
    *width = *height = 0;
    if (ready(path, err) != 0) return -1;
    return module.read(path, pixels, width, height, err);
}

int image_write_gray16(const char *path, const float *pixels, int width, int height,
                       og_error *err) {
    if (ready_to_write(path, err) != 0) return -1;
    return module.write(path, pixels, width, height, err);
}

int image_write_rgb8(const char *path, const unsigned char *rgb, int width, int height,
                     og_error *err) {
    if (ready_to_write(path, err) != 0) return -1;
    return module.write_rgb8(path, rgb, width, height, err);
}

int image_read_rgb8(const char *path, unsigned char **rgb, int *width, int *height, og_error *err) {
    *rgb = NULL;
    *width = *height = 0;
    if (ready(path, err) != 0) return -1;
    return module.read_rgb8(path, rgb, width, height, err);
}

int image_read_channel(const char *path, const char *channel, int max_size, float **samples,
                       int *width, int *height, int *kind, int *bits, char *desc, size_t desc_len,
                       og_error *err) {
    *samples = NULL;
    *width = *height = 0;
    // A greyscale PNG (its one channel OIIO names Y) needs no OpenImageIO.
    if (path && file_kind_check_read(path, err) != 0) return -1;
    if (path && (!channel || !*channel || !strcmp(channel, "Y")) &&
        png_gray_read(path, max_size, samples, width, height, bits)) {
        *kind = IMAGE_SAMPLES_UNSIGNED;
        snprintf(desc, desc_len, "png uint%d, channel Y of 1", *bits);
        return 0;
    }
    if (ready(path, err) != 0) return -1;
    return module.read_channel(path, channel, max_size, samples, width, height, kind, bits, desc,
                               desc_len, err);
}

int image_write_samples(const char *path, const float *samples, int width, int height,
                        image_sample_format format, const char *channel, og_error *err) {
    if (ready_to_write(path, err) != 0) return -1;
    return module.write_samples(path, samples, width, height, (int)format, channel, err);
}

int image_write_u8(const char *path, const unsigned char *data, int width, int height, int channels,
                   og_error *err) {
    if (ready_to_write(path, err) != 0) return -1;
    return module.write_png(path, data, width, height, channels, 8, err);
}

int image_write_u16(const char *path, const uint16_t *data, int width, int height, int channels,
                    og_error *err) {
    if (ready_to_write(path, err) != 0) return -1;
    return module.write_png(path, data, width, height, channels, 16, err);
}
