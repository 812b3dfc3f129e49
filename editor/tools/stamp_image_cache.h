#pragma once
// The last stamp image read, kept decoded. A user stamping the same image again and
// again (a click each) would otherwise decode it every time: 4.5 ms for a 512² PNG,
// about twice the stamp's own undo step. A file counts as unchanged while its device,
// inode, size and modification time are; a file replaced or rewritten is read again.

#include "io/err.h"

// As image_read_luminance (io/image_read.h): on success *pixels is malloc'd (free() it,
// it is the caller's copy) and *support is stamp_image_support's value for the image.
// Thread-safe.
int stamp_image_cache_read(const char *path, float **pixels, int *width, int *height,
                           double *support, og_error *err);

// Forgets the kept image (its memory is freed).
void stamp_image_cache_clear(void);
