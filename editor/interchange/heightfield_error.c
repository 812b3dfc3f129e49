#include "editor/interchange/heightfield_error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int heightfield_error_measure(const heightfield_grid *g, const float *pos, size_t stride,
                              const uint32_t *idx, size_t indices, heightfield_error *out) {
    memset(out, 0, sizeof *out);
    unsigned char *covered = calloc((size_t)(g->w * g->d), 1);
    if (!covered) return -1;
    for (size_t k = 0; k + 2 < indices; k += 3) {
        // Corners are grid samples: their (i, j) exactly, whatever float rounding did to
        // positions far from the origin, so the tests below are exact.
        int64_t u[3], v[3];
        double y[3];
        for (int c = 0; c < 3; c++) {
            const float *p = pos + (size_t)idx[k + c] * stride;
            u[c] = llround(((double)p[0] - g->origin_x) / g->spacing);
            v[c] = llround(((double)p[2] - g->origin_z) / g->spacing);
            y[c] = p[1];
        }
        // Twice the area seen from above, in samples; the grid's own triangles have -1
        // (counter-clockwise from +Y with Z toward the viewer).
        int64_t area = (u[1] - u[0]) * (v[2] - v[0]) - (u[2] - u[0]) * (v[1] - v[0]);
        if (area >= 0) {
            out->folded++;
            continue;
        }
        int64_t i0 = u[0] < u[1] ? u[0] : u[1], i1 = u[0] > u[1] ? u[0] : u[1];
        int64_t j0 = v[0] < v[1] ? v[0] : v[1], j1 = v[0] > v[1] ? v[0] : v[1];
        i0 = i0 < u[2] ? i0 : u[2], i1 = i1 > u[2] ? i1 : u[2];
        j0 = j0 < v[2] ? j0 : v[2], j1 = j1 > v[2] ? j1 : v[2];
        if (i0 < 0) i0 = 0;
        if (j0 < 0) j0 = 0;
        if (i1 > g->w - 1) i1 = g->w - 1;
        if (j1 > g->d - 1) j1 = g->d - 1;
        for (int64_t j = j0; j <= j1; j++)
            for (int64_t i = i0; i <= i1; i++) {
                // Barycentric weights times area (all <= 0 inside, as area is).
                int64_t w1 = (i - u[0]) * (v[2] - v[0]) - (u[2] - u[0]) * (j - v[0]);
                int64_t w2 = (u[1] - u[0]) * (j - v[0]) - (i - u[0]) * (v[1] - v[0]);
                int64_t w0 = area - w1 - w2;
                if (w0 > 0 || w1 > 0 || w2 > 0) continue;
                double at = ((double)w0 * y[0] + (double)w1 * y[1] + (double)w2 * y[2]) / area;
                double dev = fabs(at - g->h[j * g->w + i]);
                if (dev > out->max_deviation) out->max_deviation = dev;
                covered[j * g->w + i] = 1;
            }
    }
    for (int64_t s = 0; s < g->w * g->d; s++)
        out->uncovered += !covered[s];
    free(covered);
    return 0;
}
