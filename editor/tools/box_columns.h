#ifndef OROGEN_BOX_COLUMNS_H
#define OROGEN_BOX_COLUMNS_H

#include <stdint.h>
// The most columns the AVX-512 sweep takes at once (4 strips of 16); its ring holds
// this many floats a row.
enum { BOX_COLUMNS_WIDTH = 64 };

// Two box sums of radius k >= 1 down the columns [c0, c1) of an area (not divided:
// the means times (2k + 1)^2; the row boxes' last pass scales), in float with running
// sums re-anchored every 2k + 1 rows: the first box's sum of rows [i - k, i + k] is, at
// the anchors (i - k a multiple of 2k + 1), those rows added in order; between them
// the anchor's sum plus the changes since (each the row entering minus the row
// leaving, added up on their own: small where the ground is smooth, so the running
// part rounds far less than a sum of whole heights). The second box the same over the
// first's results (anchors where j - 2k is a multiple of 2k + 1). So a result depends
// on the rows and k alone, not on which rows were asked for: the strips a disc needs
// and the whole area give the same bits.
//
// rows[y] + x: the area's row y at column x (only columns [c0, c1) are read). Results
// for rows [y0, y1) (2k <= y0 < y1 <= h - 2k) go to out[y] + x; rows from the anchor
// at or above y0 may be written too, nothing else; keep (NULL: all of them): per row y,
// only its columns [keep[y][0], keep[y][1]) are written. Rows from that anchor's - 2k to
// y1 + 2k are read. ring: (2k + 2) x BOX_COLUMNS_WIDTH floats.
// Every path (AVX-512 here, the plain C loop elsewhere) gives the same bits.
void box_columns(const float *const *rows, float *const *out, const int64_t (*keep)[2], int k,
                 float *ring, int64_t c0, int64_t c1, int64_t y0, int64_t y1);
// The plain C loop alone (for tests: the same bits as box_columns).
void box_columns_plain(const float *const *rows, float *const *out, const int64_t (*keep)[2], int k,
                       float *ring, int64_t c0, int64_t c1, int64_t y0, int64_t y1);
// The anchor at or above result row y0 (the first row box_columns may write).
int64_t box_columns_anchor(int64_t y0, int k);
// Whether box_columns runs on AVX-512 here.
int box_columns_have_wide(void);

#endif
