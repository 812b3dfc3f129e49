#include "renderer/clip_refine.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void clip_refine_cells_build(clip_refine_cells *c, const clip_window *level,
                             const clip_window *fine, int k) {
    const int n = level->size, cells = n / CLIP_CELL;
    c->cells = 0;
    if (!level->has_data || !fine->has_data || cells > CLIP_CELLS_MAX || n % CLIP_CELL != 0 ||
        k < 2)
        return;
    c->level = level, c->fine = fine, c->k = k;
    memset(c->measured, 0, (size_t)cells * cells);
    c->cells = cells;
    c->have[0] = level->have[0], c->have[1] = level->have[1];
}

// Measures cell (ci, cj): samples [ci, ci + 1] * CLIP_CELL (both ends) of the level.
static void measure(clip_refine_cells *c, int ci, int cj) {
    const clip_window *level = c->level, *fine = c->fine;
    const int n = level->size, mask = n - 1, k = c->k;
    const int fn = fine->size, fmask = fn - 1, half = k / 2;
    const float *h = (const float *)level->mirror, *f = (const float *)fine->mirror;
    float lo = INFINITY, hi = -INFINITY, error = 0.0f;
#define H(i, j)                                                                                    \
    h[(size_t)((level->have[1] + (j)) & mask) * n + (size_t)((level->have[0] + (i)) & mask)]
#define F(x, z)                                                                                    \
    f[(size_t)((fine->have[1] + (z)) & fmask) * fn + (size_t)((fine->have[0] + (x)) & fmask)]
    // Quad (i, j) of the level holds the refined vertices at its corner (i, j), its low
    // edges' midpoints and its centre (on the diagonal the base mesh splits it along);
    // the cell's quads and those whose corner is on its high edges.
    for (int j = cj * CLIP_CELL; j <= (cj + 1) * CLIP_CELL && j + 1 < n; j++) {
        const int64_t fz = (level->have[1] + j) * k - fine->have[1];
        if (fz < 0 || fz + half >= fn) continue;
        for (int i = ci * CLIP_CELL; i <= (ci + 1) * CLIP_CELL && i + 1 < n; i++) {
            const int64_t fx = (level->have[0] + i) * k - fine->have[0];
            if (fx < 0 || fx + half >= fn) continue;
            const float a = H(i, j), b = H(i + 1, j), d = H(i, j + 1), e = H(i + 1, j + 1);
            const float corner = F(fx, fz), mid_x = F(fx + half, fz), mid_z = F(fx, fz + half);
            const float centre = F(fx + half, fz + half);
            error = fmaxf(error, fabsf(corner - a));
            error = fmaxf(error, fabsf(mid_x - 0.5f * (a + b)));
            error = fmaxf(error, fabsf(mid_z - 0.5f * (a + d)));
            error = fmaxf(error, fabsf(centre - 0.5f * (b + d)));
            lo = fminf(lo, fminf(fminf(fminf(a, b), fminf(d, e)),
                                 fminf(fminf(corner, mid_x), fminf(mid_z, centre))));
            hi = fmaxf(hi, fmaxf(fmaxf(fmaxf(a, b), fmaxf(d, e)),
                                 fmaxf(fmaxf(corner, mid_x), fmaxf(mid_z, centre))));
        }
    }
#undef H
#undef F
    const size_t at = (size_t)cj * c->cells + ci;
    c->lo[at] = lo, c->hi[at] = hi, c->error[at] = error;
    c->measured[at] = 1;
}

size_t clip_refine_cell(clip_refine_cells *c, int i, int j) {
    const size_t at = (size_t)j * c->cells + i;
    if (!c->measured[at]) measure(c, i, j);
    return at;
}

int clip_refine_cells_range(clip_refine_cells *c, int64_t i0, int64_t j0, int64_t i1, int64_t j1,
                            float *lo, float *hi, float *error) {
    int a0, a1, b0, b1;
    if (c->cells == 0 || !clip_cell_span(i0 - c->have[0], i1 - c->have[0], c->cells, &a0, &a1) ||
        !clip_cell_span(j0 - c->have[1], j1 - c->have[1], c->cells, &b0, &b1))
        return 0;
    *lo = INFINITY, *hi = -INFINITY, *error = 0.0f;
    for (int j = b0; j <= b1; j++)
        for (int i = a0; i <= a1; i++) {
            size_t k = clip_refine_cell(c, i, j);
            *lo = fminf(*lo, c->lo[k]), *hi = fmaxf(*hi, c->hi[k]);
            *error = fmaxf(*error, c->error[k]);
        }
    return 1;
}

float clip_refine_weight(double error_m, double horizontal, double distance,
                         double pixels_per_radian, double pixels) {
    if (!(pixels > 0.0) || !(distance > 0.0) || !(error_m > 0.0)) return 0.0f;
    // A vertical move of e seen at distance d and elevation angle a spans about
    // e cos(a) / d radians; cos(a) = horizontal / d.
    double seen = error_m * pixels_per_radian * horizontal / (distance * distance);
    double w = (seen - pixels) / (0.5 * pixels);
    return (float)(w < 0.0 ? 0.0 : w > 1.0 ? 1.0 : w);
}

int clip_refine_map_init(clip_refine_map *m) {
    const size_t bytes = (size_t)CLIP_REFINE_SIDE * CLIP_REFINE_SIDE * RENDER_MAX_LEVELS;
    m->now = calloc(bytes, 1);
    m->sent = calloc(bytes, 1);
    if (!m->now || !m->sent) return -1;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &m->tex);
    glTextureStorage3D(m->tex, 1, GL_R8, CLIP_REFINE_SIDE, CLIP_REFINE_SIDE, RENDER_MAX_LEVELS);
    glTextureParameteri(m->tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(m->tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(m->tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(m->tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureSubImage3D(m->tex, 0, 0, 0, 0, CLIP_REFINE_SIDE, CLIP_REFINE_SIDE, RENDER_MAX_LEVELS,
                        GL_RED, GL_UNSIGNED_BYTE, m->sent);
    return 0;
}

void clip_refine_map_free(clip_refine_map *m) {
    if (m->tex) glDeleteTextures(1, &m->tex);
    free(m->now);
    free(m->sent);
    memset(m, 0, sizeof *m);
}

static unsigned char *layer(unsigned char *base, int level) {
    return base + (size_t)level * CLIP_REFINE_SIDE * CLIP_REFINE_SIDE;
}

void clip_refine_map_begin(clip_refine_map *m, int level, int h0, int h1) {
    memset(layer(m->now, level), 255, (size_t)CLIP_REFINE_SIDE * CLIP_REFINE_SIDE);
    clip_refine_map_limit(m, level, h0, h0, h1, h1, 0.0f);
}

void clip_refine_map_limit(clip_refine_map *m, int level, int x0, int z0, int x1, int z1, float w) {
    const unsigned char v = (unsigned char)lrintf(fminf(fmaxf(w, 0.0f), 1.0f) * 255.0f);
    x0 = x0 < 0 ? 0 : x0, z0 = z0 < 0 ? 0 : z0;
    x1 = x1 > CLIP_REFINE_SIDE - 1 ? CLIP_REFINE_SIDE - 1 : x1;
    z1 = z1 > CLIP_REFINE_SIDE - 1 ? CLIP_REFINE_SIDE - 1 : z1;
    for (int z = z0; z <= z1; z++) {
        unsigned char *row = layer(m->now, level) + (size_t)z * CLIP_REFINE_SIDE;
        for (int x = x0; x <= x1; x++)
            row[x] = row[x] < v ? row[x] : v;
    }
}

void clip_refine_map_upload(clip_refine_map *m, int level) {
    const size_t bytes = (size_t)CLIP_REFINE_SIDE * CLIP_REFINE_SIDE;
    if (!memcmp(layer(m->now, level), layer(m->sent, level), bytes)) return;
    memcpy(layer(m->sent, level), layer(m->now, level), bytes);
    glTextureSubImage3D(m->tex, 0, 0, 0, level, CLIP_REFINE_SIDE, CLIP_REFINE_SIDE, 1, GL_RED,
                        GL_UNSIGNED_BYTE, layer(m->sent, level));
}
