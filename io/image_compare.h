// Comparing 8-bit RGB images: the RMSE that Tabakovic 2024 uses for visual accuracy (LOD vs
// full-resolution screenshots) and for Orogen's golden-image tests, and a visible
// difference image for when such a test fails.
#ifndef OROGEN_IO_IMAGE_COMPARE_H
#define OROGEN_IO_IMAGE_COMPARE_H

#include "io/err.h"

#include <stddef.h>

// Root mean square error between two 8-bit RGB images of the same size (pixels
// pixels, 3 bytes each), over every channel of every pixel: Tabakovic 2024's
// sqrt(1/(m n) sum (A-B)^2) with the sum over the 3 channels divided by 3 as well, so
// a uniform difference of d gives d. In 0..255; 0 for no pixels.
double image_rmse_rgb8(const unsigned char *a, const unsigned char *b, size_t pixels);

// Reads two images (any format image_read_rgb8 reads) and compares them. -1 with err
// if either is unreadable or their sizes differ ("a.png is 640x480 but b.png is
// 320x240"); else 0 and *rmse.
int image_rmse_files(const char *path_a, const char *path_b, double *rmse, og_error *err);

// Fills out (pixels x 3 bytes) with |a - b| * gain per channel, clamped to 255: small
// differences made visible.
void image_diff_rgb8(const unsigned char *a, const unsigned char *b, size_t pixels, int gain,
                     unsigned char *out);

// Box-filters a (width * k) x (height * k) 8-bit RGB image (rows top first) to width x
// height into out: each pixel the rounded mean of its k x k samples. Both images of a
// comparison rendered k times larger and reduced so are compared at k x k samples a
// pixel, where an edge or a ridge narrower than a pixel covers part of it instead of
// all or nothing (a full-resolution mesh seen from afar aliases).
void image_box_down_rgb8(const unsigned char *big, int width, int height, int k,
                         unsigned char *out);

#endif
