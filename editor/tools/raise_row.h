#ifndef OROGEN_RAISE_ROW_H
#define OROGEN_RAISE_ROW_H

// The raise (and lower) dab's inner loop with the smooth falloff on a flat disc: for
// sample i of a row span, dx2[i] the square of its column's distance from the centre
// (smooth_row_squares' floats), t = min(sqrt(dx2[i] + dz2) * inv_r, 1),
// w = (1 - t^2 (3 - 2t)) * strength, and the height h becomes h + w * amount, kept
// finite (a NaN result keeps h) and within +-limit. Float operations in that order
// without FMA: the same bits whichever path (AVX-512, AVX2 or plain C) runs, for any
// heights (NaN and infinities included) as long as strength * amount is finite.
void raise_row_smooth(float *row, const float *dx2, float dz2, float inv_r, float strength,
                      float amount, float limit, int n);

// The paths this processor can run (1 + the widest: 0 plain C, 1 AVX2, 2 AVX-512), and
// one of them by number (tests compare them).
int raise_row_paths(void);
void raise_row_smooth_path(int path, float *row, const float *dx2, float dz2, float inv_r,
                           float strength, float amount, float limit, int n);

#endif
