#include "renderer/clip_cells.h"

#include <math.h>
#include <string.h>

void clip_cells_build(clip_cells *c, const clip_window *w) {
    const float *h = (const float *)w->mirror;
    const int n = w->size, mask = n - 1, cells = n / CLIP_CELL;
    c->cells = 0;
    if (!w->has_data || cells > CLIP_CELLS_MAX || n % CLIP_CELL != 0) return;
    const int x0 = (int)(w->have[0] & mask), z0 = (int)(w->have[1] & mask);
    // Per row: each cell's bounds over its samples and the next cell's first one.
    float row_lo[CLIP_CELLS_MAX], row_hi[CLIP_CELLS_MAX], line[CLIP_CELLS_MAX * CLIP_CELL + 1];
    for (int k = 0; k < cells * cells; k++)
        c->lo[k] = INFINITY, c->hi[k] = -INFINITY;
    for (int j = 0; j < n; j++) {
        // The row in window order (the mirror's is rotated by the origin), then each
        // cell's samples and the next cell's first one (none after the last).
        const float *row = h + (size_t)((z0 + j) & mask) * n;
        memcpy(line, row + x0, (size_t)(n - x0) * sizeof *line);
        memcpy(line + (n - x0), row, (size_t)x0 * sizeof *line);
        line[n] = line[n - 1];
        for (int ci = 0; ci < cells; ci++) {
            const float *v = line + ci * CLIP_CELL;
            float lo = v[CLIP_CELL], hi = v[CLIP_CELL];
            for (int i = 0; i < CLIP_CELL; i++)
                lo = v[i] < lo ? v[i] : lo, hi = v[i] > hi ? v[i] : hi;
            row_lo[ci] = lo, row_hi[ci] = hi;
        }
        // Row j lies in cell row j / CLIP_CELL, and in the one before on a cell's edge.
        const int cj = j / CLIP_CELL;
        for (int r = cj - (j % CLIP_CELL == 0 && cj > 0); r <= cj && r < cells; r++)
            for (int ci = 0; ci < cells; ci++) {
                float *lo = &c->lo[r * cells + ci], *hi = &c->hi[r * cells + ci];
                *lo = fminf(*lo, row_lo[ci]), *hi = fmaxf(*hi, row_hi[ci]);
            }
    }
    c->have[0] = w->have[0], c->have[1] = w->have[1];
    c->cells = cells;
}

int clip_cell_span(int64_t a, int64_t b, int cells, int *c0, int *c1) {
    const int64_t n = (int64_t)cells * CLIP_CELL;
    if (b < 0 || a > n - 1 || a > b) return 0;
    a = a < 0 ? 0 : a, b = b > n - 1 ? n - 1 : b;
    *c0 = (int)(a / CLIP_CELL);
    *c1 = (int)(b > a ? (b - 1) / CLIP_CELL : a / CLIP_CELL); // cell k holds sample (k+1)*CELL
    if (*c1 >= cells) *c1 = cells - 1;
    return 1;
}

int clip_cells_range(const clip_cells *c, int64_t i0, int64_t j0, int64_t i1, int64_t j1, float *lo,
                     float *hi) {
    int a0, a1, b0, b1;
    if (c->cells == 0 || !clip_cell_span(i0 - c->have[0], i1 - c->have[0], c->cells, &a0, &a1) ||
        !clip_cell_span(j0 - c->have[1], j1 - c->have[1], c->cells, &b0, &b1))
        return 0;
    *lo = INFINITY, *hi = -INFINITY;
    for (int j = b0; j <= b1; j++)
        for (int i = a0; i <= a1; i++)
            *lo = fminf(*lo, c->lo[j * c->cells + i]), *hi = fmaxf(*hi, c->hi[j * c->cells + i]);
    return 1;
}
