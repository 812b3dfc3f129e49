#ifndef OROGEN_BOX_ROWS_H
#define OROGEN_BOX_ROWS_H

#include <stdint.h>

// One box along a flat array of floats: dst[i + k] = the sum of src[i .. i + length
// - 1] times scale (length = 2k + 1 >= 3, below 2^BOX_ROWS_LEVELS) for every window
// inside [0, n); a scale of 1 multiplies nothing (the same bits: the blur's first pass
// leaves its sums whole and its second scales them to the mean of all four boxes).
// The window's sum is built from sums of power-of-two runs (runs of 2p from two runs
// of p), those of length's bits added high bit first, each starting where those
// before it end: the same additions, and so the same bits, for every window and on
// every path. Blocks of rows go through as one array
// (windows that run from one row into the next give values no result takes).
// scratch: (BOX_ROWS_LEVELS + 1) n floats (the plain pass's runs).
enum { BOX_ROWS_LEVELS = 12 };
void box_rows(const float *src, float *dst, int64_t n, int length, float scale, float *scratch);
// The plain C pass alone (for tests: the same bits).
void box_rows_plain(const float *src, float *dst, int64_t n, int length, float scale,
                    float *scratch);
// The pass in a single sweep with every partial sum held in AVX-512 registers.
// Returns 0, or -1 when this processor lacks AVX-512 or the length is outside 3..31
// (nothing written).
int box_rows_wide(const float *src, float *dst, int64_t n, int length, float scale);

#endif
