#include "editor/world/volume_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct mesh_builder {
    volume_mesh *m;
    size_t vertex_cap, index_cap;
} mesh_builder;

static int push_vertex(mesh_builder *b, const float p[3], const float n[3]) {
    volume_mesh *m = b->m;
    if (m->vertex_count == b->vertex_cap) {
        size_t cap = b->vertex_cap ? b->vertex_cap * 2 : 1024;
        float *pos = realloc(m->pos, cap * 3 * sizeof *pos);
        if (pos) m->pos = pos;
        float *nrm = realloc(m->normal, cap * 3 * sizeof *nrm);
        if (nrm) m->normal = nrm;
        if (!pos || !nrm) return -1;
        b->vertex_cap = cap;
    }
    memcpy(m->pos + 3 * m->vertex_count, p, 3 * sizeof *p);
    memcpy(m->normal + 3 * m->vertex_count, n, 3 * sizeof *n);
    m->vertex_count++;
    return 0;
}

static int push_quad(mesh_builder *b, uint32_t a, uint32_t c, uint32_t d, uint32_t e) {
    volume_mesh *m = b->m;
    if (m->index_count + 6 > b->index_cap) {
        size_t cap = b->index_cap ? b->index_cap * 2 : 4096;
        uint32_t *idx = realloc(m->index, cap * sizeof *idx);
        if (!idx) return -1;
        m->index = idx;
        b->index_cap = cap;
    }
    uint32_t q[6] = {a, c, d, a, d, e};
    memcpy(m->index + m->index_count, q, sizeof q);
    m->index_count += 6;
    return 0;
}

// The samples around the edges: one before their starts (the cells below and behind)
// and one past their ends.
typedef struct sample_box {
    volume_box box; // voxels sampled
    int64_t nx, ny, nz;
} sample_box;

static size_t at(const sample_box *s, int64_t x, int64_t y, int64_t z) {
    return (size_t)((y * s->nz + z) * s->nx + x);
}

// The combined distance at every sample, brick by brick (one pin per brick).
static int sample_field(world *w, const volume_grid *g, const sample_box *s, float *f,
                        og_error *err) {
    volume_heights vh;
    if (volume_heights_read(w, g, g->voxel, s->box.i0, s->box.k0, s->box.i1, s->box.k1, &vh, err) !=
        0)
        return -1;
    int rc = volume_field_read(w, g, &vh, s->box, f, err);
    volume_heights_free(&vh);
    return rc;
}

// The cell's vertex: the mean of its edges' zero crossings, with the field's
// gradient there (trilinear) as the normal.
static void cell_vertex(const float c[8], float out_p[3], float out_n[3]) {
    static const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                     {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    float sum[3] = {0, 0, 0};
    int n = 0;
    for (int e = 0; e < 12; e++) {
        float a = c[edges[e][0]], b = c[edges[e][1]];
        if ((a < 0) == (b < 0)) continue;
        float t = a / (a - b);
        for (int axis = 0; axis < 3; axis++) {
            float pa = (float)(edges[e][0] >> axis & 1), pb = (float)(edges[e][1] >> axis & 1);
            sum[axis] += pa + t * (pb - pa);
        }
        n++;
    }
    float p[3] = {sum[0] / n, sum[1] / n, sum[2] / n};
    // Corner bit 0 = x, 1 = y, 2 = z.
    float gx = (1 - p[1]) * (1 - p[2]) * (c[1] - c[0]) + p[1] * (1 - p[2]) * (c[3] - c[2]) +
               (1 - p[1]) * p[2] * (c[5] - c[4]) + p[1] * p[2] * (c[7] - c[6]);
    float gy = (1 - p[0]) * (1 - p[2]) * (c[2] - c[0]) + p[0] * (1 - p[2]) * (c[3] - c[1]) +
               (1 - p[0]) * p[2] * (c[6] - c[4]) + p[0] * p[2] * (c[7] - c[5]);
    float gz = (1 - p[0]) * (1 - p[1]) * (c[4] - c[0]) + p[0] * (1 - p[1]) * (c[5] - c[1]) +
               (1 - p[0]) * p[1] * (c[6] - c[2]) + p[0] * p[1] * (c[7] - c[3]);
    float len = sqrtf(gx * gx + gy * gy + gz * gz);
    if (len < 1e-12f) gx = 0, gy = 1, gz = 0, len = 1;
    memcpy(out_p, p, sizeof p);
    out_n[0] = gx / len, out_n[1] = gy / len, out_n[2] = gz / len;
}

static int inside_box(volume_box b, int64_t i, int64_t j, int64_t k) {
    return i >= b.i0 && i < b.i1 && j >= b.j0 && j < b.j1 && k >= b.k0 && k < b.k1;
}

// Samples outside the solid box become air, as far from the surface as the nearest
// sample inside it is (so the wall or floor lies half way between the two).
static void clip_to_solid(const sample_box *s, volume_box solid, float *f) {
    for (int64_t y = 0; y < s->ny; y++)
        for (int64_t z = 0; z < s->nz; z++)
            for (int64_t x = 0; x < s->nx; x++) {
                int64_t i = s->box.i0 + x, j = s->box.j0 + y, k = s->box.k0 + z;
                if (inside_box(solid, i, j, k)) continue;
                int64_t ci = i < solid.i0 ? solid.i0 : i >= solid.i1 ? solid.i1 - 1 : i;
                int64_t cj = j < solid.j0 ? solid.j0 : j >= solid.j1 ? solid.j1 - 1 : j;
                int64_t ck = k < solid.k0 ? solid.k0 : k >= solid.k1 ? solid.k1 - 1 : k;
                int64_t cx = ci - s->box.i0, cy = cj - s->box.j0, cz = ck - s->box.k0;
                float near = cx >= 0 && cx < s->nx && cy >= 0 && cy < s->ny && cz >= 0 && cz < s->nz
                                 ? f[at(s, cx, cy, cz)]
                                 : 1.0f;
                f[at(s, x, y, z)] = fmaxf(fabsf(near), 1e-6f);
            }
}

int volume_mesh_edges(world *w, const volume_grid *g, volume_box starts, volume_box within,
                      const volume_box *solid, const double origin[3], volume_mesh *out,
                      og_error *err) {
    memset(out, 0, sizeof *out);
    memcpy(out->origin, origin, sizeof out->origin);
    if (volume_box_empty(starts)) return 0;
    sample_box s;
    s.box = (volume_box){starts.i0 - 1, starts.j0 - 1, starts.k0 - 1,
                         starts.i1 + 1, starts.j1 + 1, starts.k1 + 1};
    s.nx = s.box.i1 - s.box.i0, s.ny = s.box.j1 - s.box.j0, s.nz = s.box.k1 - s.box.k0;
    size_t samples = (size_t)(s.nx * s.ny * s.nz);
    float *f = malloc(samples * sizeof *f);
    int32_t *cell = malloc(samples * sizeof *cell); // by the cell's lowest corner
    if (!f || !cell) {
        free(f);
        free(cell);
        return og_error_set(err, "out of memory meshing %lld voxels", (long long)samples);
    }
    int rc = sample_field(w, g, &s, f, err);
    if (rc == 0 && solid) clip_to_solid(&s, *solid, f);
    mesh_builder b = {out, 0, 0};
    double v = g->voxel;
    for (int64_t y = 0; y < s.ny && rc == 0; y++)
        for (int64_t z = 0; z < s.nz && rc == 0; z++)
            for (int64_t x = 0; x < s.nx; x++) {
                cell[at(&s, x, y, z)] = -1;
                if (x == s.nx - 1 || y == s.ny - 1 || z == s.nz - 1) continue;
                float c[8];
                int inside = 0;
                for (int k = 0; k < 8; k++) {
                    c[k] = f[at(&s, x + (k & 1), y + (k >> 1 & 1), z + (k >> 2 & 1))];
                    inside += c[k] < 0;
                }
                if (inside == 0 || inside == 8) continue;
                float p[3], n[3];
                cell_vertex(c, p, n);
                float local[3] = {(float)((s.box.i0 + x + p[0]) * v - origin[0]),
                                  (float)((s.box.j0 + y + p[1]) * v - origin[1]),
                                  (float)((s.box.k0 + z + p[2]) * v - origin[2])};
                if (push_vertex(&b, local, n) != 0) {
                    rc = og_error_set(err, "out of memory meshing");
                    break;
                }
                cell[at(&s, x, y, z)] = (int32_t)(out->vertex_count - 1);
            }
    // Each owned edge crossing the surface makes a quad of the four cells around it,
    // facing out of the solid.
    for (int64_t y = 1; y < s.ny - 1 && rc == 0; y++)
        for (int64_t z = 1; z < s.nz - 1 && rc == 0; z++)
            for (int64_t x = 1; x < s.nx - 1 && rc == 0; x++) {
                int64_t p[3] = {x, y, z};
                float here = f[at(&s, x, y, z)];
                for (int a = 0; a < 3; a++) {
                    int64_t q[3] = {x, y, z};
                    q[a]++;
                    if (!inside_box(within, s.box.i0 + q[0], s.box.j0 + q[1], s.box.k0 + q[2]) ||
                        !inside_box(within, s.box.i0 + x, s.box.j0 + y, s.box.k0 + z))
                        continue;
                    float there = f[at(&s, q[0], q[1], q[2])];
                    if ((here < 0) == (there < 0)) continue;
                    int bx = (a + 1) % 3, cx = (a + 2) % 3;
                    int64_t c00[3], c10[3], c11[3], c01[3];
                    memcpy(c00, p, sizeof p), c00[bx]--, c00[cx]--;
                    memcpy(c10, p, sizeof p), c10[cx]--;
                    memcpy(c11, p, sizeof p);
                    memcpy(c01, p, sizeof p), c01[bx]--;
                    int32_t v00 = cell[at(&s, c00[0], c00[1], c00[2])];
                    int32_t v10 = cell[at(&s, c10[0], c10[1], c10[2])];
                    int32_t v11 = cell[at(&s, c11[0], c11[1], c11[2])];
                    int32_t v01 = cell[at(&s, c01[0], c01[1], c01[2])];
                    if (v00 < 0 || v10 < 0 || v11 < 0 || v01 < 0) continue;
                    // (b, c) counter-clockwise faces +a: outward when the solid is at p.
                    int ok = here < 0 ? push_quad(&b, (uint32_t)v00, (uint32_t)v10, (uint32_t)v11,
                                                  (uint32_t)v01)
                                      : push_quad(&b, (uint32_t)v00, (uint32_t)v01, (uint32_t)v11,
                                                  (uint32_t)v10);
                    if (ok != 0) {
                        rc = og_error_set(err, "out of memory meshing");
                        break;
                    }
                }
            }
    free(f);
    free(cell);
    if (rc != 0) volume_mesh_free(out);
    return rc;
}

volume_box volume_box_everything(void) {
    volume_box b = {INT64_MIN / 4, INT64_MIN / 4, INT64_MIN / 4,
                    INT64_MAX / 4, INT64_MAX / 4, INT64_MAX / 4};
    return b;
}

int volume_mesh_brick(world *w, const volume_grid *g, tile_key key, volume_mesh *out,
                      og_error *err) {
    volume_box box = volume_brick_box(key);
    // Its own edges and a ring of one voxel around them, which the neighbours mesh too.
    volume_box starts = {box.i0 - 1, box.j0 - 1, box.k0 - 1, box.i1 + 1, box.j1 + 1, box.k1 + 1};
    double origin[3] = {box.i0 * g->voxel, box.j0 * g->voxel, box.k0 * g->voxel};
    return volume_mesh_edges(w, g, starts, volume_box_everything(), NULL, origin, out, err);
}

void volume_mesh_free(volume_mesh *m) {
    free(m->pos);
    free(m->normal);
    free(m->index);
    memset(m, 0, sizeof *m);
}
