#ifndef OROGEN_BOX_COLUMNS_H
#define OROGEN_BOX_COLUMNS_H

#include <stdint.h>

// box_blur.c's two box means down the columns (radius k >= 1) of src (w wide, h rows)
// on AVX-512 registers, a strip of 16 columns at a time from the top row to the bottom:
// columns [c0, c1), rows [2k, h - 2k) of the result go to out (w wide); nothing else
// is written there. Each column's additions are those of box_blur.c's sweep row by
// row, in the same order (in double: the same bits). ring: (2k + 2) x 16 doubles.
// Returns 0, or -1 when this processor lacks AVX-512 (nothing written: the caller
// runs its own sweep).
int box_columns_wide(const float *src, float *out, int64_t w, int64_t h, int k, double *ring,
                     int64_t c0, int64_t c1);

#endif
