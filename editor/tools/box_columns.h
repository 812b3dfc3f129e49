#ifndef OROGEN_BOX_COLUMNS_H
#define OROGEN_BOX_COLUMNS_H

#include <stdint.h>

// box_blur.c's two box means down the columns (radius k >= 1) on AVX-512 registers, a
// strip of 16 columns at a time from the top row to the bottom: the source's rows
// [y0, y1) (rows[y] + x: row y at column x; only columns [c0, c1) are read), results
// for columns [c0, c1) and rows [y0 + 2k, y1 - 2k) into out (w floats a row, row y
// at out + y w); nothing else is written there. Each column's additions are those of
// box_blur.c's sweep row by row, in the same order (in double: the same bits).
// ring: (2k + 2) x 16 doubles. Returns 0, or -1 when this processor lacks AVX-512
// (nothing written: the caller runs its own sweep).
int box_columns_wide(const float *const *rows, float *out, int64_t w, int k, double *ring,
                     int64_t c0, int64_t c1, int64_t y0, int64_t y1);
// Whether box_columns_wide runs here.
int box_columns_have_wide(void);

#endif
