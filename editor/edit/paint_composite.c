#include "editor/edit/paint_composite.h"

#include "editor/edit/height_window.h"
#include "editor/edit/parallel.h"
#include "editor/layers/paint_blend.h"

#include <stdlib.h>
#include <string.h>

// Below this share of a change showing through the paint layers above the target, the
// change is not divided further (as layer_composite.c's TAKE_MIN_WEIGHT).
#define TAKE_MIN_KEEP 0.25f

typedef struct paint_job {
    edit *e;
    layer_table table; // a copy: the world's may change only between edits
    int take;
    int target; // taking: the paint layer's index, or -1 for the base
    const tile_part *parts;
    // merging
    const tile_key *keys;
    int below;
} paint_job;

static tile_key material_key(int face, int32_t tx, int32_t ty, int32_t slot) {
    return (tile_key){
        .layer = tile_layer_in_slot(TILE_LAYER_MATERIAL, slot), .face = face, .tx = tx, .ty = ty};
}

// The weight of paint layer i over r (w x h samples): opacity times its mask, which reads
// the composite heights of the height layers below it.
static int layer_weights(edit *e, const layer_table *t, int i, int face, grid_rect r, float *out,
                         og_error *err) {
    const layer_info *l = &t->layers[i];
    size_t n = (size_t)((r.x1 - r.x0) * (r.z1 - r.z0));
    if (!layer_mask_active(&l->mask)) {
        for (size_t k = 0; k < n; k++)
            out[k] = (float)l->opacity;
        return 0;
    }
    layer_grid grid;
    if (layer_grid_init(&grid, world_get_params(edit_world(e)), TILE_LAYER_COARSE, face, err) != 0)
        return -1;
    int b = layer_mask_border(&l->mask, grid.spacing);
    float *heights;
    if (height_window_compose(edit_world(e), t, &grid, r, i, b, -1, NULL, &heights, err) != 0)
        return -1;
    int rc = height_window_mask(edit_world(e), l, &grid, r, heights, b, out, err);
    free(heights);
    if (rc != 0) return -1;
    for (size_t k = 0; k < n; k++)
        out[k] *= (float)l->opacity;
    return 0;
}

// What one part of a tile needs: the composite (as floats) with, when taking, the target's
// share: below it, its own output, its weight, and how the layers above pass it on
// (shown = X keep + add).
typedef struct paint_part {
    int rw, rh, x0, z0;
    float *acc, *below, *x, *weight, *keep, *add;
} paint_part;

static void part_free(paint_part *q) {
    free(q->acc);
    free(q->below);
    free(q->x);
    free(q->weight);
    free(q->keep);
    free(q->add);
}

// Lays a paint layer tile's samples of the part over q->acc (and the above-target sums).
static void lay(paint_part *q, const uint8_t *tile, const float *w, int above) {
    for (int z = 0; z < q->rh; z++)
        for (int x = 0; x < q->rw; x++) {
            size_t k = (size_t)z * q->rw + x;
            const uint8_t *l =
                tile + ((size_t)(z + q->z0) * TILE_SIZE + x + q->x0) * TILE_MATERIALS;
            paint_blend_sample(q->acc + k * TILE_MATERIALS, w[k], l);
            if (above) {
                int sum = 0;
                for (int c = 0; c < TILE_MATERIALS; c++)
                    sum += l[c];
                q->keep[k] *= 1.0f - w[k] * (float)sum / 255.0f;
                paint_blend_sample(q->add + k * TILE_MATERIALS, w[k], l);
            }
        }
}

static int compose_part(const paint_job *j, const tile_part *p, grid_rect r, paint_part *q,
                        og_error *err) {
    world *w = edit_world(j->e);
    tile_cache *cache = world_cache(w);
    size_t n = (size_t)q->rw * q->rh;
    q->acc = malloc(sizeof(float) * TILE_MATERIALS * n);
    q->weight = malloc(sizeof(float) * n);
    int ok = q->acc && q->weight;
    if (j->take) {
        q->below = malloc(sizeof(float) * TILE_MATERIALS * n);
        q->x = malloc(sizeof(float) * TILE_MATERIALS * n);
        q->keep = malloc(sizeof(float) * n);
        q->add = calloc(TILE_MATERIALS * n, sizeof(float));
        ok = ok && q->below && q->x && q->keep && q->add;
    }
    if (!ok) return og_error_set(err, "out of memory composing paint layers");
    tile_view bv;
    if (tile_cache_acquire(cache, material_key(p->face, p->tx, p->ty, TILE_SLOT_BASE), &bv, err) !=
        0)
        return -1;
    for (int z = 0; z < q->rh; z++)
        for (int x = 0; x < q->rw; x++)
            for (int c = 0; c < TILE_MATERIALS; c++)
                q->acc[((size_t)z * q->rw + x) * TILE_MATERIALS + c] =
                    ((const uint8_t *)bv
                         .data)[((size_t)(z + q->z0) * TILE_SIZE + x + q->x0) * TILE_MATERIALS + c];
    tile_cache_release(cache, &bv);
    if (j->take) {
        for (size_t k = 0; k < n; k++)
            q->keep[k] = 1.0f;
        if (j->target < 0) memcpy(q->x, q->acc, sizeof(float) * TILE_MATERIALS * n);
    }
    float *w8 = malloc(sizeof(float) * n);
    if (!w8) return og_error_set(err, "out of memory composing paint layers");
    int rc = 0;
    for (int i = 0; i < j->table.count && rc == 0; i++) {
        const layer_info *l = &j->table.layers[i];
        if (!l->visible || l->kind != LAYER_KIND_PAINT) continue;
        tile_view v;
        if (tile_cache_acquire(cache, material_key(p->face, p->tx, p->ty, l->id), &v, err) != 0) {
            rc = -1;
            break;
        }
        int is_target = j->take && i == j->target;
        if (v.edited || is_target) {
            rc = layer_weights(j->e, &j->table, i, p->face, r, w8, err);
            if (rc == 0 && is_target) {
                memcpy(q->below, q->acc, sizeof(float) * TILE_MATERIALS * n);
                memcpy(q->weight, w8, sizeof(float) * n);
            }
            if (rc == 0) lay(q, v.data, w8, j->take && i > j->target);
            if (rc == 0 && is_target) memcpy(q->x, q->acc, sizeof(float) * TILE_MATERIALS * n);
        }
        tile_cache_release(cache, &v);
    }
    free(w8);
    return rc;
}

// Moves the tool's change of the part's changed samples into the target (base or paint
// layer tile t) and writes the composite the stack now shows into comp.
// before holds only the samples of `touched` (tile-local, edit_snapshot): the tool
// changed none outside it.
static void take(const paint_job *j, paint_part *q, const uint8_t *before, grid_rect touched,
                 uint8_t *comp, uint8_t *t, int keep_tool, grid_rect *changed) {
    for (int z = 0; z < q->rh; z++)
        for (int x = 0; x < q->rw; x++) {
            size_t k = (size_t)z * q->rw + x;
            size_t at = ((size_t)(z + q->z0) * TILE_SIZE + x + q->x0) * TILE_MATERIALS;
            if (x + q->x0 < touched.x0 || x + q->x0 >= touched.x1 || z + q->z0 < touched.z0 ||
                z + q->z0 >= touched.z1 || !memcmp(comp + at, before + at, TILE_MATERIALS))
                continue;
            float keep = q->keep[k], *xk = q->x + k * TILE_MATERIALS;
            if (!(keep > 0.0f)) continue; // covered above: nothing the tool did can show
            float div = keep > TAKE_MIN_KEEP ? keep : TAKE_MIN_KEEP, want[TILE_MATERIALS];
            for (int c = 0; c < TILE_MATERIALS; c++) {
                want[c] = xk[c] + ((float)comp[at + c] - (float)before[at + c]) / div;
                if (want[c] < 0.0f) want[c] = 0.0f;
            }
            float now[TILE_MATERIALS];
            if (j->target < 0) {
                paint_blend_round(want, t + at);
                for (int c = 0; c < TILE_MATERIALS; c++)
                    now[c] = t[at + c];
            } else {
                paint_blend_solve(q->below + k * TILE_MATERIALS, q->weight[k], want, t + at,
                                  t + at);
                memcpy(now, q->below + k * TILE_MATERIALS, sizeof now);
                paint_blend_sample(now, q->weight[k], t + at);
            }
            if (keep_tool && (j->target < 0 || q->weight[k] >= 1.0f))
                continue; // on top at full weight the composite keeps the tool's own result
            for (int c = 0; c < TILE_MATERIALS; c++)
                now[c] = now[c] * keep + q->add[k * TILE_MATERIALS + c];
            uint8_t shown[TILE_MATERIALS];
            paint_blend_round(now, shown);
            if (memcmp(shown, comp + at, TILE_MATERIALS)) {
                memcpy(comp + at, shown, TILE_MATERIALS);
                tile_part_touch(changed, x, z);
            }
        }
}

static int paint_task(void *user, int task, og_error *err) {
    paint_job *j = user;
    const tile_part *p = &j->parts[task];
    tile_key ck = material_key(p->face, p->tx, p->ty, 0);
    const uint8_t *before = NULL;
    grid_rect touched = {0, 0, 0, 0};
    if (j->take && !(before = edit_snapshot(j->e, ck, &touched))) return 0; // left alone
    layer_grid grid;
    if (layer_grid_init(&grid, world_get_params(edit_world(j->e)), TILE_LAYER_MATERIAL, p->face,
                        err) != 0)
        return -1;
    int64_t gx = (int64_t)p->tx * TILE_SIZE, gz = (int64_t)p->ty * TILE_SIZE;
    grid_rect r =
        layer_grid_clip(&grid, (grid_rect){gx + p->x0, gz + p->z0, gx + p->x1, gz + p->z1});
    if (grid_rect_empty(r)) return 0;
    paint_part q = {.rw = (int)(r.x1 - r.x0),
                    .rh = (int)(r.z1 - r.z0),
                    .x0 = (int)(r.x0 - gx),
                    .z0 = (int)(r.z0 - gz)};
    int rc = compose_part(j, p, r, &q, err);
    tile_view cv, tv = {0};
    grid_rect local = {q.x0, q.z0, q.x0 + q.rw, q.z0 + q.rh};
    if (rc == 0) rc = edit_tile_acquire_part(j->e, ck, local, &cv, err);
    if (rc != 0) {
        part_free(&q);
        return -1;
    }
    uint8_t *comp = cv.data;
    grid_rect changed = {1, 1, 0, 0}; // part-local; empty
    if (j->take) {
        int32_t slot = j->target < 0 ? TILE_SLOT_BASE : j->table.layers[j->target].id;
        int above = 0; // a visible paint layer above the target
        for (int i = j->target + 1; i < j->table.count; i++)
            above |= j->table.layers[i].visible && j->table.layers[i].kind == LAYER_KIND_PAINT;
        rc = edit_tile_acquire_part(j->e, material_key(p->face, p->tx, p->ty, slot), local, &tv,
                                    err);
        if (rc == 0) {
            take(j, &q, before, touched, comp, tv.data, !above, &changed);
            edit_tile_release(j->e, &tv);
        }
    } else {
        for (int z = 0; z < q.rh; z++)
            for (int x = 0; x < q.rw; x++) {
                size_t at = ((size_t)(z + q.z0) * TILE_SIZE + x + q.x0) * TILE_MATERIALS;
                uint8_t shown[TILE_MATERIALS];
                paint_blend_round(q.acc + ((size_t)z * q.rw + x) * TILE_MATERIALS, shown);
                if (!memcmp(shown, comp + at, TILE_MATERIALS)) continue;
                memcpy(comp + at, shown, TILE_MATERIALS);
                tile_part_touch(&changed, x, z);
            }
    }
    edit_tile_release(j->e, &cv);
    part_free(&q);
    if (rc == 0) tile_part_publish(j->e, TILE_LAYER_MATERIAL, p->face, r, changed);
    return rc;
}

static int run(edit *e, tile_parts *parts, int take, og_error *err) {
    tile_parts_merge(parts);
    if (!parts->count) return 0;
    paint_job j = {.e = e, .table = world_get_params(edit_world(e))->layers, .take = take};
    j.target = j.table.count && j.table.layers[j.table.active].kind == LAYER_KIND_PAINT
                   ? j.table.active
                   : -1;
    j.parts = parts->parts;
    edit_layer_mode mode = edit_get_layer_mode(e);
    edit_set_layer_mode(e, EDIT_LAYER_COMPOSED); // composing writes the composite itself
    int rc = parallel_run((int)parts->count, paint_task, &j, err);
    edit_set_layer_mode(e, mode);
    return rc;
}

int paint_recompose(edit *e, tile_parts *parts, og_error *err) {
    return run(e, parts, 0, err);
}

int paint_take_edit(edit *e, tile_parts *parts, og_error *err) {
    return run(e, parts, 1, err);
}

int paint_recompose_masked(edit *e, const tile_part *parts, size_t count, og_error *err) {
    const world_params *params = world_get_params(edit_world(e));
    const layer_table *t = &params->layers;
    double spacing = 0.0;
    int border = -1;
    for (int i = 0; i < t->count; i++) {
        const layer_info *l = &t->layers[i];
        if (l->visible && l->kind == LAYER_KIND_PAINT && layer_mask_active(&l->mask)) {
            if (border < 0) {
                layer_grid g;
                if (layer_grid_init(&g, params, TILE_LAYER_COARSE, 0, err) != 0) return -1;
                spacing = g.spacing;
                border = 0;
            }
            int b = layer_mask_border(&l->mask, spacing);
            if (b > border) border = b;
        }
    }
    if (border < 0 || !count) return 0;
    tile_parts grown = {0};
    for (size_t i = 0; i < count; i++) {
        const tile_part *p = &parts[i];
        int64_t gx = (int64_t)p->tx * TILE_SIZE, gz = (int64_t)p->ty * TILE_SIZE;
        grid_rect r = {gx + p->x0 - border, gz + p->z0 - border, gx + p->x1 + border,
                       gz + p->z1 + border};
        if (tile_parts_add_rect(&grown, p->face, r) != 0) {
            tile_parts_free(&grown);
            return og_error_set(err, "out of memory composing paint layers");
        }
    }
    int rc = run(e, &grown, 0, err);
    tile_parts_free(&grown);
    return rc;
}

// ---- merging ------------------------------------------------------------------------

static int merge_task(void *user, int task, og_error *err) {
    paint_job *j = user;
    tile_key key = j->keys[task];
    const layer_info *lo = &j->table.layers[j->below], *hi = &j->table.layers[j->below + 1];
    int64_t gx = (int64_t)key.tx * TILE_SIZE, gz = (int64_t)key.ty * TILE_SIZE;
    layer_grid grid;
    if (layer_grid_init(&grid, world_get_params(edit_world(j->e)), TILE_LAYER_MATERIAL, key.face,
                        err) != 0)
        return -1;
    grid_rect r = layer_grid_clip(&grid, (grid_rect){gx, gz, gx + TILE_SIZE, gz + TILE_SIZE});
    if (grid_rect_empty(r)) return 0;
    int rw = (int)(r.x1 - r.x0), rh = (int)(r.z1 - r.z0), x0 = (int)(r.x0 - gx),
        z0 = (int)(r.z0 - gz);
    float *wl = malloc(sizeof(float) * (size_t)rw * rh),
          *wh = malloc(sizeof(float) * (size_t)rw * rh);
    int rc = wl && wh ? 0 : og_error_set(err, "out of memory merging paint layers");
    if (rc == 0) rc = layer_weights(j->e, &j->table, j->below, key.face, r, wl, err);
    if (rc == 0) rc = layer_weights(j->e, &j->table, j->below + 1, key.face, r, wh, err);
    tile_view lv, hv;
    tile_cache *cache = world_cache(edit_world(j->e));
    if (rc == 0 && (rc = edit_tile_acquire(j->e, material_key(key.face, key.tx, key.ty, lo->id),
                                           &lv, err)) == 0) {
        if ((rc = tile_cache_acquire(cache, material_key(key.face, key.tx, key.ty, hi->id), &hv,
                                     err)) == 0) {
            uint8_t *l8 = lv.data;
            const uint8_t *h8 = hv.data;
            for (int z = 0; z < rh; z++)
                for (int x = 0; x < rw; x++) {
                    size_t at = ((size_t)(z + z0) * TILE_SIZE + x + x0) * TILE_MATERIALS;
                    size_t k = (size_t)z * rw + x;
                    paint_blend_merge(l8 + at, wl[k], h8 + at, wh[k], l8 + at);
                }
            tile_cache_release(cache, &hv);
        }
        edit_tile_release(j->e, &lv);
    }
    free(wl);
    free(wh);
    return rc;
}

int paint_merge_tiles(edit *e, int below, const tile_key *keys, size_t count, og_error *err) {
    paint_job j = {.e = e, .keys = keys, .below = below};
    j.table = world_get_params(edit_world(e))->layers;
    return parallel_run((int)count, merge_task, &j, err);
}
