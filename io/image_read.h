// Image files in and out through OpenImageIO (a C++ library behind this C header):
// heightmaps and stamps read as one float channel, 16-bit grey PNGs written; 8-bit
// RGB read and written for screenshots, golden images and their diffs.
#ifndef OROGEN_IO_IMAGE_READ_H
#define OROGEN_IO_IMAGE_READ_H

#ifdef __cplusplus
extern "C" {
#endif

#include "io/err.h"
#include <stdint.h>

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

// Writes an 8-bit RGB PNG (rgb is width x height x 3 bytes, rows top-first) atomically,
// as image_write_gray16 does. Sizes 1..IMAGE_MAX_SIZE per side.
int image_write_rgb8(const char *path, const unsigned char *rgb, int width, int height,
                     og_error *err);

// Writes an 8-bit PNG of 1 to 4 channels (grey, grey + alpha, RGB, RGBA: alpha kept as
// stored, not premultiplied) atomically, as image_write_gray16 does.
int image_write_u8(const char *path, const unsigned char *data, int width, int height, int channels,
                   og_error *err);
// As image_write_u8 with 16-bit channels (host order in memory; PNG stores big-endian).
int image_write_u16(const char *path, const uint16_t *data, int width, int height, int channels,
                    og_error *err);

// Reads any image OpenImageIO can as 8-bit RGB, rows top-first: grey is replicated into
// the three channels, alpha is dropped (colour as stored, not premultiplied), 16-bit
// and float are converted to uint8 by OIIO (clamped to [0, 1], rounded). On success
// *rgb is malloc'd (width x height x 3 bytes; free() it); on failure it is NULL and
// err names the file, with the same checks as image_read_luminance.
int image_read_rgb8(const char *path, unsigned char **rgb, int *width, int *height, og_error *err);

typedef enum image_sample_kind {
    IMAGE_SAMPLES_UNSIGNED = 0,
    IMAGE_SAMPLES_SIGNED = 1,
    IMAGE_SAMPLES_FLOAT = 2
} image_sample_kind;

// Reads one channel (by name, or the first when channel is NULL or empty) as stored:
// integers keep their values (16-bit 40000 reads as 40000.0), half and float as they
// are, NaN and infinities included. Sizes up to max_size per side. *kind is an
// image_sample_kind, *bits the stored sample size; desc gets "FORMAT TYPE, channel
// NAME of N". On failure *samples is NULL and err names the file.
int image_read_channel(const char *path, const char *channel, int max_size, float **samples,
                       int *width, int *height, int *kind, int *bits, char *desc, size_t desc_len,
                       og_error *err);

typedef enum image_sample_format {
    IMAGE_WRITE_UINT16 = 0, // samples already in 0..65535, rounded
    IMAGE_WRITE_FLOAT = 1,
    IMAGE_WRITE_HALF = 2
} image_sample_format;

// Writes a one-channel image (.png: uint16 only; .tif/.tiff; .exr), the channel named
// `channel` (NULL: OIIO's default), atomically: temp file beside it, fsync, rename.
// Sizes 1..65536 per side.
int image_write_samples(const char *path, const float *samples, int width, int height,
                        image_sample_format format, const char *channel, og_error *err);

#ifdef __cplusplus
}
#endif

#endif
