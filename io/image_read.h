// Image files in and out through OpenImageIO (a C++ library behind this C header):
// heightmaps and stamps read as one float channel, 16-bit grey PNGs written.
#ifndef OROGEN_IO_IMAGE_READ_H
#define OROGEN_IO_IMAGE_READ_H

#ifdef __cplusplus
extern "C" {
#endif

#include "io/err.h"

// The largest width or height either function accepts.
#define IMAGE_MAX_SIZE 16384

// Reads any image OpenImageIO can (8/16-bit, half/float; PNG, TIFF, EXR, ...) as one
// float channel, row-major from the top row: grey as is, colour as the Rec. 709
// luminance (0.2126 R + 0.7152 G + 0.0722 B) of the first three channels; alpha is
// ignored. Unsigned integer formats map to [0, 1] (signed ones to [-1, 1], OIIO's
// convention); float stays as is. The first subimage of a multi-image file is read.
// On success *pixels is malloc'd (free() it); on failure it is NULL and err names the
// file: unreadable, not an image, zero or huge size, or a pixel that is NaN or
// infinite ("path: pixel (x, y) is not finite").
int image_read_luminance(const char *path, float **pixels, int *width, int *height, og_error *err);

// Writes a 16-bit greyscale PNG (values clamped to [0, 1], rounded to the nearest
// 1/65535) atomically: temp file in the same folder, fsync, rename. NaN is an error.
int image_write_gray16(const char *path, const float *pixels, int width, int height, og_error *err);

#ifdef __cplusplus
}
#endif

#endif
