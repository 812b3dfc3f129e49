#include "renderer/clip_skyline.h"

#include <math.h>
#include <string.h>

void clip_skyline_begin(clip_skyline *k, const double eye[3], const double forward[3],
                        const double right[3], const double up[3], double tan_half_x,
                        double tan_half_y) {
    memcpy(k->eye, eye, sizeof k->eye);
    memcpy(k->forward, forward, sizeof k->forward);
    memcpy(k->right, right, sizeof k->right);
    memcpy(k->up, up, sizeof k->up);
    k->tan_half_x = tan_half_x, k->tan_half_y = tan_half_y;
    for (int i = 0; i < CLIP_SKYLINE_COLUMNS; i++)
        k->top[i] = -INFINITY;
}

// Cell (ci, cj)'s top on the screen: its highest sample at its centre, over the columns
// [*c0, *c1] its width covers; 0 when it is behind the camera or off the screen's sides.
static int cell_top(const clip_skyline *k, const clip_cells *c, double spacing, int ci, int cj,
                    float *y, int *c0, int *c1) {
    const float hi = c->hi[(size_t)cj * c->cells + ci];
    if (!(hi > -INFINITY)) return 0;
    const double side = CLIP_CELL * spacing;
    const double p[3] = {((double)c->have[0] + (ci + 0.5) * CLIP_CELL) * spacing - k->eye[0],
                         (double)hi - k->eye[1],
                         ((double)c->have[1] + (cj + 0.5) * CLIP_CELL) * spacing - k->eye[2]};
    const double depth = p[0] * k->forward[0] + p[1] * k->forward[1] + p[2] * k->forward[2];
    if (!(depth > 0.5 * side)) return 0; // behind the camera or around it: no top of its own
    const double x =
        (p[0] * k->right[0] + p[1] * k->right[1] + p[2] * k->right[2]) / (depth * k->tan_half_x);
    const double half = 0.7072 * side / (depth * k->tan_half_x);
    const double a = (x - half + 1.0) * 0.5 * CLIP_SKYLINE_COLUMNS,
                 b = (x + half + 1.0) * 0.5 * CLIP_SKYLINE_COLUMNS;
    if (b < 0.0 || a >= CLIP_SKYLINE_COLUMNS) return 0;
    *c0 = a < 0.0 ? 0 : (int)a;
    *c1 = b >= CLIP_SKYLINE_COLUMNS ? CLIP_SKYLINE_COLUMNS - 1 : (int)b;
    *y = (float)((p[0] * k->up[0] + p[1] * k->up[1] + p[2] * k->up[2]) / (depth * k->tan_half_y));
    return 1;
}

void clip_skyline_add_level(clip_skyline *k, const clip_cells *c, double spacing, int64_t i0,
                            int64_t j0, int64_t i1, int64_t j1, int64_t h_i0, int64_t h_j0,
                            int64_t h_i1, int64_t h_j1) {
    int a0, a1, b0, b1;
    if (c->cells == 0 || !clip_cell_span(i0 - c->have[0], i1 - c->have[0], c->cells, &a0, &a1) ||
        !clip_cell_span(j0 - c->have[1], j1 - c->have[1], c->cells, &b0, &b1))
        return;
    for (int cj = b0; cj <= b1; cj++) {
        const int64_t z0 = c->have[1] + (int64_t)cj * CLIP_CELL, z1 = z0 + CLIP_CELL;
        const int rows_inside = z0 >= h_j0 && z1 <= h_j1;
        for (int ci = a0; ci <= a1; ci++) {
            const int64_t x0 = c->have[0] + (int64_t)ci * CLIP_CELL, x1 = x0 + CLIP_CELL;
            if (rows_inside && x0 >= h_i0 && x1 <= h_i1) continue; // the finer level's
            float y;
            int c0, c1;
            if (!cell_top(k, c, spacing, ci, cj, &y, &c0, &c1)) continue;
            for (int col = c0; col <= c1; col++)
                k->top[col] = k->top[col] > y ? k->top[col] : y;
        }
    }
}

// How far under the skyline cell (ci, cj)'s top projects (screen units); infinite when
// it has no top of its own on the screen.
static double cell_gap(const clip_skyline *k, const clip_cells *c, double spacing, int ci, int cj) {
    float y;
    int c0, c1;
    if (!cell_top(k, c, spacing, ci, cj, &y, &c0, &c1)) return INFINITY;
    double gap = INFINITY;
    for (int col = c0; col <= c1; col++)
        gap = fmin(gap, (double)k->top[col] - y);
    return gap;
}

int clip_skyline_near(const clip_skyline *k, const clip_cells *c, double spacing, int64_t i0,
                      int64_t j0, int64_t i1, int64_t j1, double band) {
    int a0, a1, b0, b1;
    if (c->cells == 0 || !clip_cell_span(i0 - c->have[0], i1 - c->have[0], c->cells, &a0, &a1) ||
        !clip_cell_span(j0 - c->have[1], j1 - c->have[1], c->cells, &b0, &b1))
        return 0;
    for (int cj = b0; cj <= b1; cj++)
        for (int ci = a0; ci <= a1; ci++)
            if (cell_gap(k, c, spacing, ci, cj) < 2.0 * band) return 1;
    return 0;
}

float clip_skyline_weight(const clip_skyline *k, const clip_cells *c, clip_refine_cells *e,
                          double spacing, int64_t i0, int64_t j0, int64_t i1, int64_t j1,
                          double band, double pixels_per_radian, double pixels) {
    int a0, a1, b0, b1;
    if (c->cells == 0 || e->cells != c->cells || e->have[0] != c->have[0] ||
        e->have[1] != c->have[1] || !(band > 0.0) ||
        !clip_cell_span(i0 - c->have[0], i1 - c->have[0], c->cells, &a0, &a1) ||
        !clip_cell_span(j0 - c->have[1], j1 - c->have[1], c->cells, &b0, &b1))
        return 0.0f;
    float w = 0.0f;
    for (int cj = b0; cj <= b1; cj++)
        for (int ci = a0; ci <= a1; ci++) {
            double near = (2.0 * band - cell_gap(k, c, spacing, ci, cj)) / band;
            if (!(near > 0.0)) continue;
            // Its own error as seen from its nearest point.
            const size_t at = clip_refine_cell(e, ci, cj);
            const double x0 = ((double)c->have[0] + ci * CLIP_CELL) * spacing - k->eye[0],
                         z0 = ((double)c->have[1] + cj * CLIP_CELL) * spacing - k->eye[2],
                         side = CLIP_CELL * spacing;
            const double dx = fmax(fmax(x0, -(x0 + side)), 0.0),
                         dz = fmax(fmax(z0, -(z0 + side)), 0.0),
                         dy = fmax(fmax((double)e->lo[at] - k->eye[1], k->eye[1] - e->hi[at]), 0.0);
            float cw =
                clip_refine_weight(e->error[at], hypot(dx, dz), sqrt(dx * dx + dy * dy + dz * dz),
                                   pixels_per_radian, pixels);
            cw *= (float)(near > 1.0 ? 1.0 : near);
            w = w > cw ? w : cw;
        }
    return w;
}
