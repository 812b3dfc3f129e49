#ifndef OROGEN_SMOOTH_ROW_H
#define OROGEN_SMOOTH_ROW_H

// The squares of the dab's columns' distances, dx2[i] = dx * dx with dx = fdx0 + i (in
// float, as the blend took them), i = 0 .. n - 1: the same for every row of a dab.
void smooth_row_squares(float *dx2, float fdx0, int n);

// The smooth dab's last step on one row span with the smooth falloff on a flat disc:
// for sample i, dx2[i] as smooth_row_squares gives it, t = min(sqrt(dx2[i] + dz2) * inv_r, 1),
// w = (1 - t^2 (3 - 2t)) * strength (negated when inverting), and where w > 0 the
// height h moves to h + w (smoothed[i] - h), kept finite (a NaN result keeps h) and
// within +-limit; elsewhere h keeps its bits. Float operations in that order without
// FMA: the bits of the weights' loop and the blend's loop it replaces, whichever path
// (AVX-512, AVX2 or plain C) runs.
void smooth_row_blend(float *row, const float *smoothed, const float *dx2, float dz2, float inv_r,
                      float strength, int invert, float limit, int n);

// The paths this processor can run (1 + the widest: 0 plain C, 1 AVX2, 2 AVX-512), and
// one of them by number (tests compare them).
int smooth_row_paths(void);
void smooth_row_blend_path(int path, float *row, const float *smoothed, const float *dx2, float dz2,
                           float inv_r, float strength, int invert, float limit, int n);

#endif
