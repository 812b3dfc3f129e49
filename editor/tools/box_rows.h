#ifndef OROGEN_BOX_ROWS_H
#define OROGEN_BOX_ROWS_H

#include <stdint.h>

// One box mean along a flat array of floats in a single sweep with every partial sum
// held in AVX-512 registers: dst[i + k] = mean of src[i .. i + length - 1] (length =
// 2k + 1, 3 to 31) for every window inside [0, n), with the additions of
// box_blur.c's pass of power-of-two runs in the same order (the same bits). Returns 0,
// or -1 when this processor lacks AVX-512 or the length is outside 3..31 (nothing
// written: the caller runs its own pass).
int box_rows_wide(const float *src, float *dst, int64_t n, int length);

#endif
