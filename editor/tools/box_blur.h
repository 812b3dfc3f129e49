#ifndef OROGEN_BOX_BLUR_H
#define OROGEN_BOX_BLUR_H

#include <stdint.h>

// Two box blurs of radius k >= 1 down columns, then two along rows, of a w x h area
// of floats (row-major), into out (w x h; it may be in). Only its samples at least 2k
// from every edge of the area are written (the others would need samples past it).
// Down columns in float with running sums re-anchored every 2k + 1 rows
// (box_columns.h), along rows each sum of 2k + 1 samples added in a tree whose shape
// depends on k alone: a sample's result is the same float whichever results are
// asked for (the tiled and the plain-array path agree), and on every processor path.
// Within a few float roundings of the exact blur (test_box_blur_exact says how few).
// The buffers are the calling thread's, kept between calls.
// 0, or -1: out of memory.
int box_blur_twice(const float *in, float *out, int64_t w, int64_t h, int k);

// The same with the area's rows read where they lie: at(user, y, x, &end) points at row
// y's sample at column x, contiguous up to column end (the same end for every row: a
// tile's edge, or w). need (NULL: every result): per row z, the columns [need[z][0],
// need[z][1]) whose results are wanted; only what those take is computed, and other
// results may be left unwritten.
typedef const float *(*box_row_at)(void *user, int64_t y, int64_t x, int64_t *end);
int box_blur_twice_rows(box_row_at at, void *user, const int64_t (*need)[2], float *out, int64_t w,
                        int64_t h, int k);
// The same with the results left where the last pass writes them (no copy): out (w x h
// floats) holds them packed, row z's column x at out[row_at[z] + x] for the columns
// need[z] asks for (need as above; row_at: h entries, set for rows that want any).
int box_blur_twice_packed(box_row_at at, void *user, const int64_t (*need)[2], float *out,
                          int64_t *row_at, int64_t w, int64_t h, int k);

#endif
