#include "editor/interchange/heightfield_simplify.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

// A triangle of the hierarchy: long edge a-b, right angle at c, corners on samples.
typedef struct tri {
    int64_t ax, az, bx, bz, cx, cz;
} tri;

static int splittable(tri t) {
    return llabs(t.ax - t.cx) + llabs(t.az - t.cz) > 1;
}

static tri child(tri t, int second) {
    int64_t mx = (t.ax + t.bx) / 2, mz = (t.az + t.bz) / 2;
    tri c = second ? (tri){t.bx, t.bz, t.cx, t.cz, mx, mz} : (tri){t.cx, t.cz, t.ax, t.az, mx, mz};
    return c;
}

// Where a triangle lies against the grid [0, w - 1] x [0, d - 1]: 0 outside (no area in
// it), 1 inside, 2 across its edge.
static int placement(const heightfield_rtin *r, tri t) {
    int64_t x0 = t.ax < t.bx ? t.ax : t.bx, x1 = t.ax > t.bx ? t.ax : t.bx;
    int64_t z0 = t.az < t.bz ? t.az : t.bz, z1 = t.az > t.bz ? t.az : t.bz;
    x0 = x0 < t.cx ? x0 : t.cx, x1 = x1 > t.cx ? x1 : t.cx;
    z0 = z0 < t.cz ? z0 : t.cz, z1 = z1 > t.cz ? z1 : t.cz;
    if (x0 >= r->w - 1 || z0 >= r->d - 1) return 0;
    return x1 <= r->w - 1 && z1 <= r->d - 1 ? 1 : 2;
}

typedef struct build {
    heightfield_rtin *r;
    const float *h;
    int level; // the depth being finished
} build;

// Finishes the errors of every triangle at depth b->level: its own midpoint's
// deviation and its children's (finished one level before), shared with the triangle
// across its long edge (the same depth); a triangle across the grid's edge must split.
static void finish_level(build *b, tri t, int depth) {
    heightfield_rtin *r = b->r;
    int where = placement(r, t);
    if (where == 0 || !splittable(t)) return;
    int64_t mx = (t.ax + t.bx) / 2, mz = (t.az + t.bz) / 2;
    int mid_inside = mx < r->w && mz < r->d;
    if (depth < b->level) {
        finish_level(b, child(t, 0), depth + 1);
        finish_level(b, child(t, 1), depth + 1);
        return;
    }
    if (!mid_inside) return; // only triangles across the edge reach it; they always split
    float e;
    if (where == 2) {
        e = INFINITY;
    } else {
        const float *h = b->h;
        double across = ((double)h[t.az * r->w + t.ax] + h[t.bz * r->w + t.bx]) / 2;
        e = (float)fabs(across - h[mz * r->w + mx]);
        for (int s = 0; s < 2; s++) {
            tri c = child(t, s);
            if (!splittable(c)) continue;
            float ce = r->error[((c.az + c.bz) / 2) * r->w + (c.ax + c.bx) / 2];
            if (ce > e) e = ce;
        }
    }
    float *slot = &r->error[mz * r->w + mx];
    if (e > *slot) *slot = e;
}

static void roots(const heightfield_rtin *r, tri out[2]) {
    int64_t n = r->tile;
    out[0] = (tri){0, 0, n, n, n, 0};
    out[1] = (tri){n, n, 0, 0, 0, n};
}

int heightfield_rtin_build(heightfield_rtin *r, const float *h, int64_t w, int64_t d) {
    memset(r, 0, sizeof *r);
    r->w = w, r->d = d, r->tile = 1;
    int levels = 0;
    while (r->tile < w - 1 || r->tile < d - 1)
        r->tile *= 2, levels += 2;
    r->error = calloc((size_t)(w * d), sizeof *r->error);
    if (!r->error) return -1;
    tri root[2];
    roots(r, root);
    build b = {r, h, 0};
    for (b.level = levels; b.level >= 0; b.level--)
        for (int k = 0; k < 2; k++)
            finish_level(&b, root[k], 0);
    return 0;
}

typedef struct emit {
    const heightfield_rtin *r;
    double threshold;
    uint32_t *idx;
    size_t n, cap;
    int failed;
} emit;

static void emit_tri(emit *e, tri t) {
    const heightfield_rtin *r = e->r;
    int where = placement(r, t);
    if (where == 0) return;
    int64_t mx = (t.ax + t.bx) / 2, mz = (t.az + t.bz) / 2;
    if (splittable(t) && (where == 2 || r->error[mz * r->w + mx] > e->threshold)) {
        emit_tri(e, child(t, 0));
        emit_tri(e, child(t, 1));
        return;
    }
    if (e->n + 3 > e->cap) {
        size_t cap = e->cap ? e->cap * 2 : 1 << 16;
        uint32_t *grown = realloc(e->idx, cap * sizeof *grown);
        if (!grown) {
            e->failed = 1;
            return;
        }
        e->idx = grown, e->cap = cap;
    }
    // The grid's winding: twice the signed area (x, z) negative.
    int64_t area = (t.bx - t.ax) * (t.cz - t.az) - (t.cx - t.ax) * (t.bz - t.az);
    uint32_t a = (uint32_t)(t.az * r->w + t.ax), b = (uint32_t)(t.bz * r->w + t.bx),
             c = (uint32_t)(t.cz * r->w + t.cx);
    e->idx[e->n++] = a;
    e->idx[e->n++] = area < 0 ? b : c;
    e->idx[e->n++] = area < 0 ? c : b;
}

int heightfield_rtin_mesh(const heightfield_rtin *r, double threshold, uint32_t **idx,
                          size_t *indices) {
    emit e = {r, threshold, NULL, 0, 0, 0};
    tri root[2];
    roots(r, root);
    for (int k = 0; k < 2; k++)
        emit_tri(&e, root[k]);
    if (e.failed) {
        free(e.idx);
        return -1;
    }
    *idx = e.idx;
    *indices = e.n;
    return 0;
}

void heightfield_rtin_free(heightfield_rtin *r) {
    free(r->error);
    memset(r, 0, sizeof *r);
}
