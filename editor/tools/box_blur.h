#ifndef OROGEN_BOX_BLUR_H
#define OROGEN_BOX_BLUR_H

#include <stdint.h>

// Two box blurs of radius k >= 1 along rows, then two along columns, of a w x h area
// of floats (row-major), into out (w x h; it may be in). Only its samples at least 2k
// from every edge of the area are written (the others would need samples past it).
// Along rows each sum of 2k + 1 samples is added in a tree whose shape depends on k
// alone, down columns in double (exact), so a sample's result is the same float
// wherever the area starts (the tiled and the plain-array path agree). The buffers
// are the calling thread's, kept between calls.
// 0, or -1: out of memory.
int box_blur_twice(const float *in, float *out, int64_t w, int64_t h, int k);

// The same with the area's rows read as the blur needs them (each once, in order):
// read(user, y, x0, n, dst) copies n samples of row y from column x0 to dst. From
// tiles this saves a copy of the whole area through the second-level cache. need
// (NULL: every result): per row z, the columns [need[z][0], need[z][1]) whose results
// are wanted (rows 2k .. h - 2k - 1 are read); where AVX-512 runs, only what those
// take is computed, and other results may be left unwritten.
typedef void (*box_row_reader)(void *user, int64_t y, int64_t x0, int64_t n, float *dst);
int box_blur_twice_rows(box_row_reader read, void *user, const int64_t (*need)[2], float *out,
                        int64_t w, int64_t h, int k);

#endif
