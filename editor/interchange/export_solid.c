#include "editor/interchange/export_solid.h"

#include "editor/interchange/mesh_manifold.h"
#include "editor/world/volume_grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

// The region's voxel columns: [c0, c1) in x and z.
static int region_columns(world *w, grid_rect rect, volume_grid *g, int64_t c0[2], int64_t c1[2],
                          og_error *err) {
    if (volume_grid_init(g, world_get_params(w), err) != 0) return -1;
    c0[0] = rect.x0 * g->ratio, c0[1] = rect.z0 * g->ratio;
    c1[0] = (rect.x1 - 1) * g->ratio + 1, c1[1] = (rect.z1 - 1) * g->ratio + 1;
    return 0;
}

// Bricks whose columns come within a voxel of [c0, c1).
static int bricks_over(world *w, const int64_t c0[2], const int64_t c1[2], tile_key **keys,
                       size_t *count, og_error *err) {
    if (volume_list_bricks(w, keys, count, err) != 0) return -1;
    size_t n = 0;
    for (size_t i = 0; i < *count; i++) {
        volume_box b = volume_brick_box((*keys)[i]);
        if (b.i1 >= c0[0] - 1 && b.i0 <= c1[0] && b.k1 >= c0[1] - 1 && b.k0 <= c1[1])
            (*keys)[n++] = (*keys)[i];
    }
    *count = n;
    return 0;
}

int export_solid_has_volume(world *w, grid_rect rect, int *has, og_error *err) {
    *has = 0;
    if (world_get_params(w)->kind != WORLD_FLAT) return 0;
    volume_grid g;
    int64_t c0[2], c1[2];
    tile_key *keys;
    size_t n;
    if (region_columns(w, rect, &g, c0, c1, err) != 0 || bricks_over(w, c0, c1, &keys, &n, err))
        return -1;
    free(keys);
    *has = n > 0;
    return 0;
}

// Welding: one vertex per distinct position (blocks compute shared vertices from the
// same samples, so they are bit-identical).
typedef struct welder {
    uint32_t *slots; // vertex index + 1; 0 = empty
    size_t size;     // power of two
} welder;

static uint64_t position_hash(const float p[3]) {
    uint32_t b[3];
    memcpy(b, p, sizeof b);
    uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (int i = 0; i < 3; i++)
        h = (h ^ b[i]) * 0xff51afd7ed558ccdULL, h ^= h >> 33;
    return h;
}

static int weld_grow(welder *wd, const volume_mesh *m) {
    size_t size = wd->size ? wd->size * 2 : 1 << 16;
    uint32_t *slots = calloc(size, sizeof *slots);
    if (!slots) return -1;
    for (size_t i = 0; i < wd->size; i++) {
        if (!wd->slots[i]) continue;
        size_t s = position_hash(m->pos + 3 * (wd->slots[i] - 1)) & (size - 1);
        while (slots[s])
            s = (s + 1) & (size - 1);
        slots[s] = wd->slots[i];
    }
    free(wd->slots);
    wd->slots = slots;
    wd->size = size;
    return 0;
}

// Appends block b's triangles to out, reusing out's vertices at the same positions.
static int append_welded(volume_mesh *out, welder *wd, size_t *vcap, size_t *icap,
                         const volume_mesh *b) {
    uint32_t *remap = malloc((b->vertex_count + 1) * sizeof *remap);
    if (!remap) return -1;
    for (size_t v = 0; v < b->vertex_count; v++) {
        if ((out->vertex_count + 1) * 2 > wd->size && weld_grow(wd, out) != 0) goto fail;
        const float *p = b->pos + 3 * v;
        size_t s = position_hash(p) & (wd->size - 1);
        uint32_t found = 0;
        while (wd->slots[s]) {
            if (memcmp(out->pos + 3 * (wd->slots[s] - 1), p, 3 * sizeof *p) == 0) {
                found = wd->slots[s];
                break;
            }
            s = (s + 1) & (wd->size - 1);
        }
        if (!found) {
            if (out->vertex_count == *vcap) {
                size_t cap = *vcap ? *vcap * 2 : 1 << 16;
                float *pos = realloc(out->pos, cap * 3 * sizeof *pos);
                if (pos) out->pos = pos;
                float *nrm = realloc(out->normal, cap * 3 * sizeof *nrm);
                if (nrm) out->normal = nrm;
                if (!pos || !nrm) goto fail;
                *vcap = cap;
            }
            memcpy(out->pos + 3 * out->vertex_count, p, 3 * sizeof *p);
            memcpy(out->normal + 3 * out->vertex_count, b->normal + 3 * v, 3 * sizeof *p);
            found = (uint32_t)++out->vertex_count;
            wd->slots[s] = found;
        }
        remap[v] = found - 1;
    }
    if (out->index_count + b->index_count > *icap) {
        size_t cap = *icap ? *icap : 1 << 16;
        while (cap < out->index_count + b->index_count)
            cap *= 2;
        uint32_t *idx = realloc(out->index, cap * sizeof *idx);
        if (!idx) goto fail;
        out->index = idx;
        *icap = cap;
    }
    for (size_t i = 0; i < b->index_count; i++)
        out->index[out->index_count++] = remap[b->index[i]];
    free(remap);
    return 0;
fail:
    free(remap);
    return -1;
}

int export_solid_surface(world *w, grid_rect rect, int closed, volume_mesh *out, og_error *err) {
    memset(out, 0, sizeof *out);
    volume_grid g;
    int64_t c0[2], c1[2];
    tile_key *keys;
    size_t n;
    if (region_columns(w, rect, &g, c0, c1, err) != 0 || bricks_over(w, c0, c1, &keys, &n, err))
        return -1;
    volume_heights vh;
    if (volume_heights_read(w, &g, g.voxel, c0[0] - 1, c0[1] - 1, c1[0] + 1, c1[1] + 1, &vh, err) !=
        0) {
        free(keys);
        return -1;
    }
    welder wd = {0};
    size_t vcap = 0, icap = 0;
    int rc = 0;
    double v = g.voxel, origin[3] = {0, 0, 0};
    volume_box within = volume_box_everything();
    within.i0 = c0[0], within.i1 = c1[0], within.k0 = c0[1], within.k1 = c1[1];
    // Closed: the solid box's sides and floor are surface too, so the edges reach one
    // voxel past the region on every side.
    volume_box solid = within;
    const int64_t pad = closed ? 1 : 0;
    if (closed) {
        double lo = INFINITY, hi = -INFINITY;
        for (int64_t c = 0; c < vh.w * vh.h; c++)
            lo = fmin(lo, vh.height[c]), hi = fmax(hi, vh.height[c]);
        for (size_t b = 0; b < n; b++)
            lo = fmin(lo, (double)volume_brick_box(keys[b]).j0 * v);
        solid.j0 = (int64_t)floor((lo - fmax(1.0, 0.05 * (hi - lo))) / v);
        within.i0--, within.k0--, within.i1++, within.k1++;
    }
    for (int64_t bz = c0[1] - pad; bz < c1[1] + pad && rc == 0; bz += VOLUME_BRICK_Z)
        for (int64_t bx = c0[0] - pad; bx < c1[0] + pad && rc == 0; bx += VOLUME_BRICK_X) {
            int64_t ex = bx + VOLUME_BRICK_X < c1[0] + pad ? bx + VOLUME_BRICK_X : c1[0] + pad;
            int64_t ez = bz + VOLUME_BRICK_Z < c1[1] + pad ? bz + VOLUME_BRICK_Z : c1[1] + pad;
            // Heights over the block's columns and the cells around them, a voxel spare,
            // and the volume bricks over them: where the surface can cross an edge.
            double lo = INFINITY, hi = -INFINITY;
            for (int64_t k = bz - 1 < c0[1] - 1 ? c0[1] - 1 : bz - 1; k <= ez && k < c1[1] + 1; k++)
                for (int64_t i = bx - 1 < c0[0] - 1 ? c0[0] - 1 : bx - 1;
                     i <= ex && i < c0[0] + (c1[0] - c0[0]) + 1; i++) {
                    double h = vh.height[(size_t)((k - vh.k0) * vh.w + (i - vh.i0))];
                    lo = fmin(lo, h), hi = fmax(hi, h);
                }
            int64_t j0 = (int64_t)floor(lo / v) - 2, j1 = (int64_t)ceil(hi / v) + 3;
            for (size_t b = 0; b < n; b++) {
                volume_box box = volume_brick_box(keys[b]);
                if (box.i1 < bx - 1 || box.i0 > ex || box.k1 < bz - 1 || box.k0 > ez) continue;
                if (box.j0 - 1 < j0) j0 = box.j0 - 1;
                if (box.j1 + 1 > j1) j1 = box.j1 + 1;
            }
            if (closed && solid.j0 - 1 < j0) j0 = solid.j0 - 1;
            volume_box starts = {bx, j0, bz, ex, j1, ez};
            volume_mesh block;
            if (volume_mesh_edges(w, &g, starts, within, closed ? &solid : NULL, origin, &block,
                                  err) != 0) {
                rc = -1;
                break;
            }
            if (append_welded(out, &wd, &vcap, &icap, &block) != 0)
                rc = og_error_set(err, "out of memory for the mesh");
            volume_mesh_free(&block);
        }
    free(wd.slots);
    free(keys);
    volume_heights_free(&vh);
    mesh_manifold_report manifold;
    if (rc == 0) rc = mesh_make_manifold(out, &manifold, err);
    if (rc != 0) volume_mesh_free(out);
    return rc;
}
