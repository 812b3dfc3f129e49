#ifndef OROGEN_BOX_COLUMNS_H
#define OROGEN_BOX_COLUMNS_H

#include <stdint.h>

// One row's step down box_blur.c's two column boxes, for columns [c0, c1): the first
// box's row mid = (float)(sum1 * inv) goes into the ring row m (as a double), the
// second box's sum takes it and drops the ring row `old` (sum2 += mid - old), its row
// (float)(sum2 * inv) goes to `row`, and sum1 moves on (sum1 += a - r). In double, in
// that order: the same bits whichever path runs.
void box_column_step(double *sum1, double *sum2, double *m, const double *old, const float *a,
                     const float *r, double inv, float *row, int64_t c0, int64_t c1);

// The paths this processor can run (1 + the widest: 0 the compiler's loop, 1 AVX-512
// intrinsics), and one of them by number (tests compare them).
int box_column_paths(void);
void box_column_step_path(int path, double *sum1, double *sum2, double *m, const double *old,
                          const float *a, const float *r, double inv, float *row, int64_t c0,
                          int64_t c1);

#endif
