#include "editor/interchange/mesh_distance.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void corner(const mesh_distance *d, uint32_t face, int c, double out[3]) {
    const float *p = d->pos + 3 * (size_t)d->index[3 * (size_t)face + c];
    out[0] = p[0], out[1] = p[1], out[2] = p[2];
}

static int64_t cell_of(const mesh_distance *d, int axis, double x) {
    int64_t i = (int64_t)floor((x - d->lo[axis]) / d->cell);
    return i < 0 ? 0 : i >= d->n[axis] ? d->n[axis] - 1 : i;
}

// The faces' bounds split into cells about as wide as a face, at most a few per face.
int mesh_distance_build(mesh_distance *d, const float *pos, const uint32_t *index,
                        size_t triangles) {
    memset(d, 0, sizeof *d);
    d->pos = pos, d->index = index;
    double hi[3] = {-INFINITY, -INFINITY, -INFINITY}, edges = 0;
    for (int k = 0; k < 3; k++)
        d->lo[k] = INFINITY;
    for (size_t f = 0; f < triangles; f++)
        for (int c = 0; c < 3; c++) {
            double a[3], b[3];
            corner(d, (uint32_t)f, c, a);
            corner(d, (uint32_t)f, (c + 1) % 3, b);
            edges += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                          (a[2] - b[2]) * (a[2] - b[2]));
            for (int k = 0; k < 3; k++)
                d->lo[k] = fmin(d->lo[k], a[k]), hi[k] = fmax(hi[k], a[k]);
        }
    if (triangles == 0) return 0;
    d->cell = fmax(edges / (3.0 * (double)triangles), 1e-3);
    for (;;) { // no more cells than a few per face
        double cells = 1;
        for (int k = 0; k < 3; k++)
            cells *= floor((hi[k] - d->lo[k]) / d->cell) + 1;
        if (cells <= 4.0 * (double)triangles + 64) break;
        d->cell *= 1.25;
    }
    size_t total = 1;
    for (int k = 0; k < 3; k++) {
        d->n[k] = (int64_t)floor((hi[k] - d->lo[k]) / d->cell) + 1;
        total *= (size_t)d->n[k];
    }
    d->start = calloc(total + 1, sizeof *d->start);
    if (!d->start) return -1;
    // Two passes over each face's cells: count, then place.
    for (int pass = 0; pass < 2; pass++) {
        for (size_t f = 0; f < triangles; f++) {
            int64_t c0[3], c1[3];
            for (int k = 0; k < 3; k++) {
                double a[3], lo = INFINITY, h = -INFINITY;
                for (int c = 0; c < 3; c++) {
                    corner(d, (uint32_t)f, c, a);
                    lo = fmin(lo, a[k]), h = fmax(h, a[k]);
                }
                c0[k] = cell_of(d, k, lo), c1[k] = cell_of(d, k, h);
            }
            for (int64_t z = c0[2]; z <= c1[2]; z++)
                for (int64_t y = c0[1]; y <= c1[1]; y++)
                    for (int64_t x = c0[0]; x <= c1[0]; x++) {
                        size_t c = (size_t)((z * d->n[1] + y) * d->n[0] + x);
                        if (pass == 0)
                            d->start[c + 1]++;
                        else
                            d->face[d->start[c]++] = (uint32_t)f;
                    }
        }
        if (pass == 0) {
            for (size_t c = 0; c < total; c++)
                d->start[c + 1] += d->start[c];
            d->face = malloc((d->start[total] ? d->start[total] : 1) * sizeof *d->face);
            if (!d->face) {
                mesh_distance_free(d);
                return -1;
            }
        } else { // start[c] now holds the end of cell c: shift back
            memmove(d->start + 1, d->start, total * sizeof *d->start);
            d->start[0] = 0;
        }
    }
    return 0;
}

static double dot(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Squared distance from p to triangle (a, b, c): the nearest point by its Voronoi region
// (Ericson, Real-Time Collision Detection, 5.1.5).
static double triangle_distance2(const double p[3], const double a[3], const double b[3],
                                 const double c[3]) {
    double ab[3], ac[3], ap[3], q[3];
    for (int k = 0; k < 3; k++)
        ab[k] = b[k] - a[k], ac[k] = c[k] - a[k], ap[k] = p[k] - a[k];
    double d1 = dot(ab, ap), d2 = dot(ac, ap), v, w;
    if (d1 <= 0 && d2 <= 0) {
        memcpy(q, a, sizeof q);
        goto done;
    }
    double bp[3], cp[3];
    for (int k = 0; k < 3; k++)
        bp[k] = p[k] - b[k], cp[k] = p[k] - c[k];
    double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) {
        memcpy(q, b, sizeof q);
        goto done;
    }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        v = d1 / (d1 - d3);
        for (int k = 0; k < 3; k++)
            q[k] = a[k] + v * ab[k];
        goto done;
    }
    double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) {
        memcpy(q, c, sizeof q);
        goto done;
    }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        w = d2 / (d2 - d6);
        for (int k = 0; k < 3; k++)
            q[k] = a[k] + w * ac[k];
        goto done;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (int k = 0; k < 3; k++)
            q[k] = b[k] + w * (c[k] - b[k]);
        goto done;
    }
    double denom = va + vb + vc;
    if (denom == 0) { // no area: the nearest of its corners will do
        memcpy(q, a, sizeof q);
        goto done;
    }
    v = vb / denom, w = vc / denom;
    for (int k = 0; k < 3; k++)
        q[k] = a[k] + ab[k] * v + ac[k] * w;
done:
    return (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
           (p[2] - q[2]) * (p[2] - q[2]);
}

// Rings of cells around p's cell, outwards, until no nearer face can lie beyond (or one
// lies within enough, squared): the squared distance to the nearest face found.
static double search(const mesh_distance *d, const double p[3], double enough, uint32_t *nearest) {
    if (!d->start) return INFINITY;
    int64_t c[3], reach = 0;
    for (int k = 0; k < 3; k++) {
        c[k] = cell_of(d, k, p[k]);
        reach = d->n[k] > reach ? d->n[k] : reach;
    }
    double best = INFINITY;
    uint32_t found = UINT32_MAX;
    for (int64_t r = 0; r <= reach; r++) {
        double bound = (double)(r - 1) * d->cell; // p to any cell r rings out, at least
        if (r > 0 && (best <= bound * bound || (enough >= 0 && bound * bound > enough))) break;
        for (int64_t z = c[2] - r; z <= c[2] + r; z++) {
            if (z < 0 || z >= d->n[2]) continue;
            for (int64_t y = c[1] - r; y <= c[1] + r; y++) {
                if (y < 0 || y >= d->n[1]) continue;
                int shell = z == c[2] - r || z == c[2] + r || y == c[1] - r || y == c[1] + r;
                for (int64_t x = c[0] - r; x <= c[0] + r; x += shell ? 1 : 2 * r) {
                    if (x >= 0 && x < d->n[0]) {
                        size_t cell = (size_t)((z * d->n[1] + y) * d->n[0] + x);
                        for (uint32_t i = d->start[cell]; i < d->start[cell + 1]; i++) {
                            double a[3], b[3], e[3];
                            corner(d, d->face[i], 0, a);
                            corner(d, d->face[i], 1, b);
                            corner(d, d->face[i], 2, e);
                            double d2 = triangle_distance2(p, a, b, e);
                            if (d2 < best) best = d2, found = d->face[i];
                            if (best <= enough) goto found;
                        }
                    }
                    if (r == 0) break;
                }
            }
        }
    }
found:
    if (nearest) *nearest = found;
    return best;
}

double mesh_distance_to(const mesh_distance *d, const double p[3], uint32_t *nearest) {
    return sqrt(search(d, p, -1, nearest));
}

int mesh_distance_within(const mesh_distance *d, const double p[3], double limit,
                         uint32_t *nearest) {
    return search(d, p, limit * limit, nearest) <= limit * limit;
}

void mesh_distance_free(mesh_distance *d) {
    free(d->start);
    free(d->face);
    d->start = d->face = NULL;
}
