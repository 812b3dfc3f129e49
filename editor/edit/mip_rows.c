#include "editor/edit/mip_rows.h"

#include "io/avx2_clone.h"
#include "io/tile.h"

#include <stddef.h>

// Inlined into mip_rows_block (so compiled for each of its targets).
static inline void across(const float *restrict c, int n, float *restrict out) {
    for (int x = 0; x < n; x++)
        out[x] = 0.25f * c[2 * x] + 0.5f * c[2 * x + 1] + 0.25f * c[2 * x + 2];
}

static inline void down(const float *restrict a, const float *restrict b, const float *restrict g,
                        const float *before, float *dst, int n) {
    for (int x = 0; x < n; x++)
        dst[x] = before[x] + (0.25f * a[x] + 0.5f * b[x] + 0.25f * g[x]);
}

AVX2_CLONE void mip_rows_block(const float *win, int cw, int pw, int ph, const float *before,
                               float *dst, int stride) {
    // Rows rotating: each child row filtered across once.
    float rows[3][TILE_SIZE], *h0 = rows[0], *h1 = rows[1], *h2 = rows[2];
    across(win, pw, h0);
    for (int z = 0; z < ph; z++) {
        float *out = dst + (size_t)z * (size_t)stride;
        const float *was = before ? before + (size_t)z * (size_t)stride : out;
        across(win + (size_t)(2 * z + 1) * (size_t)cw, pw, h1);
        across(win + (size_t)(2 * z + 2) * (size_t)cw, pw, h2);
        down(h0, h1, h2, was, out, pw);
        float *next = h2;
        h2 = h0, h0 = next;
    }
}
