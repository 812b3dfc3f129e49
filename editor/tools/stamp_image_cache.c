#include "editor/tools/stamp_image_cache.h"

#include "editor/tools/stamp_image.h"
#include "io/image_read.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

// Larger images are read every time rather than kept (a 4096² stamp is 64 MiB).
#define KEPT_BYTES_MAX ((size_t)64 << 20)

typedef struct file_identity {
    dev_t dev;
    ino_t ino;
    off_t size;
    struct timespec mtime;
} file_identity;

static struct {
    pthread_mutex_t lock;
    char *path;
    file_identity id;
    float *pixels;
    int width, height;
    double support;
} kept = {.lock = PTHREAD_MUTEX_INITIALIZER};

static int identity_of(const char *path, file_identity *id) {
    struct stat st;
    if (stat(path, &st) != 0) return -1;
    memset(id, 0, sizeof *id);
    id->dev = st.st_dev, id->ino = st.st_ino, id->size = st.st_size, id->mtime = st.st_mtim;
    return 0;
}

static int same_identity(const file_identity *a, const file_identity *b) {
    return a->dev == b->dev && a->ino == b->ino && a->size == b->size &&
           a->mtime.tv_sec == b->mtime.tv_sec && a->mtime.tv_nsec == b->mtime.tv_nsec;
}

static void forget_locked(void) {
    free(kept.path);
    free(kept.pixels);
    kept.path = NULL, kept.pixels = NULL;
}

static float *copy_pixels(const float *pixels, size_t bytes) {
    float *copy = malloc(bytes);
    if (copy) memcpy(copy, pixels, bytes);
    return copy;
}

int stamp_image_cache_read(const char *path, float **pixels, int *width, int *height,
                           double *support, og_error *err) {
    *pixels = NULL;
    file_identity before;
    int known = identity_of(path, &before) == 0;
    pthread_mutex_lock(&kept.lock);
    if (known && kept.path && strcmp(kept.path, path) == 0 && same_identity(&kept.id, &before)) {
        size_t bytes = (size_t)kept.width * kept.height * sizeof(float);
        *pixels = copy_pixels(kept.pixels, bytes);
        *width = kept.width, *height = kept.height, *support = kept.support;
        pthread_mutex_unlock(&kept.lock);
        if (!*pixels) return og_error_set(err, "%s: out of memory", path);
        return 0;
    }
    pthread_mutex_unlock(&kept.lock);

    if (image_read_luminance(path, pixels, width, height, err) != 0) return -1;
    *support = stamp_image_support(*pixels, *width, *height);
    // Kept only if the file did not change while it was read.
    file_identity after;
    size_t bytes = (size_t)*width * *height * sizeof(float);
    if (!known || identity_of(path, &after) != 0 || !same_identity(&before, &after) ||
        bytes > KEPT_BYTES_MAX)
        return 0;
    float *copy = copy_pixels(*pixels, bytes);
    char *name = strdup(path);
    pthread_mutex_lock(&kept.lock);
    forget_locked();
    if (copy && name) {
        kept.path = name, kept.pixels = copy, kept.id = before;
        kept.width = *width, kept.height = *height, kept.support = *support;
    } else {
        free(copy), free(name);
    }
    pthread_mutex_unlock(&kept.lock);
    return 0;
}

void stamp_image_cache_clear(void) {
    pthread_mutex_lock(&kept.lock);
    forget_locked();
    pthread_mutex_unlock(&kept.lock);
}
