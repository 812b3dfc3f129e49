#include "editor/edit/mip_rows.h"

#include "io/avx2_clone.h"

AVX2_CLONE void mip_rows_across(const float *restrict c, int n, float *restrict out) {
    for (int x = 0; x < n; x++)
        out[x] = 0.25f * c[2 * x] + 0.5f * c[2 * x + 1] + 0.25f * c[2 * x + 2];
}

AVX2_CLONE void mip_rows_down(const float *a, const float *b, const float *g, const float *before,
                              float *dst, int n) {
    for (int x = 0; x < n; x++)
        dst[x] = before[x] + (0.25f * a[x] + 0.5f * b[x] + 0.25f * g[x]);
}
