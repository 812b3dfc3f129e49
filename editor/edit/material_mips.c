#include "editor/edit/material_mips.h"

#include "editor/edit/parallel.h"
#include "editor/params/world_grid.h"

#include <stdlib.h>
#include <string.h>

#define M TILE_MATERIALS

static int64_t floor_div(int64_t a, int64_t b) {
    return world_grid_floor_div(a, b);
}

void material_mips_filter(const uint8_t *const children[9], uint8_t out[]) {
    static const int tent[9] = {1, 2, 1, 2, 4, 2, 1, 2, 1}; // sums to 16
    int acc[M] = {0};
    for (int k = 0; k < 9; k++)
        for (int c = 0; c < M; c++)
            acc[c] += tent[k] * children[k][c];
    int total = 0, rem[M];
    for (int c = 0; c < M; c++) {
        out[c] = (uint8_t)(acc[c] >> 4);
        rem[c] = acc[c] & 15;
        total += out[c];
    }
    while (total < 255) { // the units rounding lost, to the largest remainders
        int best = 0;
        for (int c = 1; c < M; c++)
            if (rem[c] > rem[best]) best = c;
        out[best]++;
        rem[best] = -1;
        total++;
    }
}

typedef struct material_level_job {
    edit *e;
    int level;               // the parent level being written
    int64_t child_extent[2]; // children along X and Z at the child level; 0: unbounded
    grid_rect parents;
    int64_t ptx0, ptz0, ptw;
} material_level_job;

// Fills win (w x h samples from cx0, cz0 at the child level) from the cache; samples
// past a bounded world's edge read as the edge sample (as the coarse mips do).
static int read_children(const material_level_job *j, int64_t cx0, int64_t cz0, int64_t w,
                         int64_t h, uint8_t *win, og_error *err) {
    tile_cache *cache = world_cache(edit_world(j->e));
    int64_t nx = j->child_extent[0], nz = j->child_extent[1];
    grid_rect in = {cx0, cz0, cx0 + w, cz0 + h};
    if (nx > 0) in = grid_rect_intersect(in, (grid_rect){0, 0, nx, nz});
    if (grid_rect_empty(in)) return og_error_set(err, "material mips: nothing under a parent");
    for (int64_t ty = floor_div(in.z0, TILE_SIZE); ty <= floor_div(in.z1 - 1, TILE_SIZE); ty++)
        for (int64_t tx = floor_div(in.x0, TILE_SIZE); tx <= floor_div(in.x1 - 1, TILE_SIZE);
             tx++) {
            tile_key key = {TILE_LAYER_MATERIAL, 0, j->level - 1, (int32_t)tx, (int32_t)ty};
            tile_view v;
            if (tile_cache_acquire(cache, key, &v, err) != 0) return -1;
            const uint8_t *t = v.data;
            int64_t x0 = tx * TILE_SIZE > in.x0 ? tx * TILE_SIZE : in.x0;
            int64_t x1 = (tx + 1) * TILE_SIZE < in.x1 ? (tx + 1) * TILE_SIZE : in.x1;
            int64_t z0 = ty * TILE_SIZE > in.z0 ? ty * TILE_SIZE : in.z0;
            int64_t z1 = (ty + 1) * TILE_SIZE < in.z1 ? (ty + 1) * TILE_SIZE : in.z1;
            for (int64_t z = z0; z < z1; z++)
                memcpy(win + ((z - cz0) * w + (x0 - cx0)) * M,
                       t + ((z - ty * TILE_SIZE) * TILE_SIZE + (x0 - tx * TILE_SIZE)) * M,
                       (size_t)(x1 - x0) * M);
            tile_cache_release(cache, &v);
        }
    if (in.x0 == cx0 && in.z0 == cz0 && in.x1 == cx0 + w && in.z1 == cz0 + h) return 0;
    for (int64_t z = 0; z < h; z++) {
        int64_t sz = cz0 + z < in.z0 ? in.z0 : cz0 + z >= in.z1 ? in.z1 - 1 : cz0 + z;
        for (int64_t x = 0; x < w; x++) {
            int64_t sx = cx0 + x < in.x0 ? in.x0 : cx0 + x >= in.x1 ? in.x1 - 1 : cx0 + x;
            if (sx != cx0 + x || sz != cz0 + z)
                memcpy(win + (z * w + x) * M, win + ((sz - cz0) * w + (sx - cx0)) * M, M);
        }
    }
    return 0;
}

static int parent_tile_task(void *user, int task, og_error *err) {
    material_level_job *j = user;
    int64_t tx = j->ptx0 + task % j->ptw, tz = j->ptz0 + task / j->ptw;
    grid_rect sub =
        grid_rect_intersect(j->parents, (grid_rect){tx * TILE_SIZE, tz * TILE_SIZE,
                                                    (tx + 1) * TILE_SIZE, (tz + 1) * TILE_SIZE});
    if (grid_rect_empty(sub)) return 0;
    int64_t pw = sub.x1 - sub.x0, ph = sub.z1 - sub.z0;
    int64_t cw = 2 * pw + 1, ch = 2 * ph + 1; // parent p filters children 2p-1 .. 2p+1
    uint8_t *win = malloc((size_t)(cw * ch) * M);
    if (!win) return og_error_set(err, "out of memory updating the material mip levels");
    int rc = read_children(j, 2 * sub.x0 - 1, 2 * sub.z0 - 1, cw, ch, win, err);
    tile_key key = {TILE_LAYER_MATERIAL, 0, j->level, (int32_t)tx, (int32_t)tz};
    tile_view v;
    if (rc == 0 && (rc = edit_tile_acquire(j->e, key, &v, err)) == 0) {
        uint8_t *t = v.data;
        for (int64_t z = 0; z < ph; z++) {
            uint8_t *dst =
                t + ((sub.z0 + z - tz * TILE_SIZE) * TILE_SIZE + (sub.x0 - tx * TILE_SIZE)) * M;
            for (int64_t x = 0; x < pw; x++) {
                const uint8_t *c = win + ((2 * z) * cw + 2 * x) * M;
                const uint8_t *const kids[9] = {c,
                                                c + M,
                                                c + 2 * M,
                                                c + cw * M,
                                                c + (cw + 1) * M,
                                                c + (cw + 2) * M,
                                                c + 2 * cw * M,
                                                c + (2 * cw + 1) * M,
                                                c + (2 * cw + 2) * M};
                material_mips_filter(kids, dst + x * M);
            }
        }
        edit_tile_release(j->e, &v);
    }
    free(win);
    return rc;
}

int material_mips_update_from(edit *e, size_t first, og_error *err) {
    const world_params *p = world_get_params(edit_world(e));
    if (p->kind == WORLD_PLANET) return 0;
    const dirty_rect *d;
    size_t n = edit_dirty_rects(e, &d);
    if (first >= n) return 0;
    grid_rect r = {0, 0, 0, 0};
    int have = 0;
    for (size_t i = first; i < n; i++) {
        if (d[i].layer != TILE_LAYER_MATERIAL || d[i].face != 0) continue;
        r = have ? grid_rect_union(r, d[i].rect) : d[i].rect;
        have = 1;
    }
    if (!have) return 0;
    int64_t extent = p->size, extent_z = world_params_size_z(p);
    // Every level the viewport can draw, also past the one where a tile covers a bounded
    // world (edit_mips_top_level): the paint must show from however far away.
    int top = EDIT_MIP_LEVELS_UNBOUNDED;
    for (int level = 1; level <= top; level++) {
        grid_rect pr = {-floor_div(-(r.x0 - 1), 2), -floor_div(-(r.z0 - 1), 2),
                        floor_div(r.x1, 2) + 1, floor_div(r.z1, 2) + 1};
        material_level_job job = {.e = e, .level = level};
        if (extent > 0) {
            pr = grid_rect_intersect(
                pr, (grid_rect){0, 0, ((extent - 1) >> level) + 1, ((extent_z - 1) >> level) + 1});
            job.child_extent[0] = ((extent - 1) >> (level - 1)) + 1;
            job.child_extent[1] = ((extent_z - 1) >> (level - 1)) + 1;
        }
        if (grid_rect_empty(pr)) break;
        job.parents = pr;
        job.ptx0 = floor_div(pr.x0, TILE_SIZE);
        job.ptz0 = floor_div(pr.z0, TILE_SIZE);
        job.ptw = floor_div(pr.x1 - 1, TILE_SIZE) - job.ptx0 + 1;
        int64_t pth = floor_div(pr.z1 - 1, TILE_SIZE) - job.ptz0 + 1;
        if (parallel_run((int)(job.ptw * pth), parent_tile_task, &job, err) != 0) return -1;
        r = pr;
    }
    return 0;
}
