// The image functions load OpenImageIO only when first used: it pulls in some 260
// shared libraries (OpenCV, FFmpeg, GDAL, ...) that would otherwise cost every
// start of orogen ~0.3 s (several seconds under the sanitizers). io/image_read.cpp
// is built as the module liborogen_image.so and opened with dlopen here.
#include "io/image_read.h"

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef int (*read_fn)(const char *, float **, int *, int *, og_error *);
typedef int (*write_fn)(const char *, const float *, int, int, og_error *);
typedef int (*read_rgb8_fn)(const char *, unsigned char **, int *, int *, og_error *);
typedef int (*write_rgb8_fn)(const char *, const unsigned char *, int, int, og_error *);

static struct {
    pthread_once_t once;
    read_fn read;
    write_fn write;
    read_rgb8_fn read_rgb8;
    write_rgb8_fn write_rgb8;
    char why[1024];
} module = {.once = PTHREAD_ONCE_INIT};

static void *try_open(const char *path) {
    if (!path || !*path) return NULL;
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!h) snprintf(module.why, sizeof module.why, "%s", dlerror());
    return h;
}

static void load_module(void) {
    // $OROGEN_IMAGE_MODULE, then the installed lib/orogen beside bin/, then the build tree.
    char installed[PATH_MAX + 64] = "";
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) *slash = 0;
        snprintf(installed, sizeof installed, "%s/../lib/orogen/liborogen_image.so", exe);
    }
    const char *candidates[] = {getenv("OROGEN_IMAGE_MODULE"), installed,
#ifdef OROGEN_IMAGE_MODULE_PATH
                                OROGEN_IMAGE_MODULE_PATH
#else
                                NULL
#endif
    };
    snprintf(module.why, sizeof module.why, "liborogen_image.so not found");
    for (size_t i = 0; i < sizeof candidates / sizeof candidates[0]; i++) {
        if (!candidates[i] || access(candidates[i], R_OK) != 0) continue;
        void *h = try_open(candidates[i]);
        if (!h) continue;
        module.read = (read_fn)dlsym(h, "orogen_image_module_read_luminance");
        module.write = (write_fn)dlsym(h, "orogen_image_module_write_gray16");
        module.read_rgb8 = (read_rgb8_fn)dlsym(h, "orogen_image_module_read_rgb8");
        module.write_rgb8 = (write_rgb8_fn)dlsym(h, "orogen_image_module_write_rgb8");
        if (module.read && module.write && module.read_rgb8 && module.write_rgb8) return;
        // An older module lacks the newer entry points: all or nothing.
        snprintf(module.why, sizeof module.why, "%s is not Orogen's image module", candidates[i]);
        module.read = NULL;
        module.write = NULL;
        module.read_rgb8 = NULL;
        module.write_rgb8 = NULL;
    }
}

static int ready(const char *path, og_error *err) {
    pthread_once(&module.once, load_module);
    if (module.read) return 0;
    return og_error_set(err, "%s: image support is unavailable: %s", path ? path : "(no path)",
                        module.why);
}

int image_read_luminance(const char *path, float **pixels, int *width, int *height, og_error *err) {
    if (ready(path, err) != 0) return -1;
    return module.read(path, pixels, width, height, err);
}

int image_write_gray16(const char *path, const float *pixels, int width, int height,
                       og_error *err) {
    if (ready(path, err) != 0) return -1;
    return module.write(path, pixels, width, height, err);
}

int image_write_rgb8(const char *path, const unsigned char *rgb, int width, int height,
                     og_error *err) {
    if (ready(path, err) != 0) return -1;
    return module.write_rgb8(path, rgb, width, height, err);
}

int image_read_rgb8(const char *path, unsigned char **rgb, int *width, int *height, og_error *err) {
    *rgb = NULL;
    *width = *height = 0;
    if (ready(path, err) != 0) return -1;
    return module.read_rgb8(path, rgb, width, height, err);
}
