#include "editor/edit/layer_composite.h"

#include "editor/edit/parallel.h"
#include "editor/layers/layer_blend.h"
#include "editor/world/layer_grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

// The part of one tile to recompose: local sample columns [x0, x1), rows [z0, z1).
typedef struct tile_part {
    int face;
    int32_t tx, ty;
    int x0, z0, x1, z1;
} tile_part;

typedef struct compose_job {
    edit *e;
    layer_table table; // a copy: the world's may change only between edits
    int take;          // layer_take_edit: the tool's change goes into the active layer
    int stage;         // taking: 1 writes the active layer, 2 recomposes
    edit_layer_mode mode;
    int top_visible; // index of the highest visible layer (-1: none)
    const tile_part *parts;
} compose_job;

static tile_key slot_key(const tile_part *p, int32_t slot) {
    return (tile_key){.layer = tile_layer_in_slot(TILE_LAYER_COARSE, slot),
                      .face = p->face,
                      .tx = p->tx,
                      .ty = p->ty};
}

static grid_rect grow(grid_rect r, int by) {
    return (grid_rect){r.x0 - by, r.z0 - by, r.x1 + by, r.z1 + by};
}

static size_t rect_samples(grid_rect r) {
    return (size_t)((r.x1 - r.x0) * (r.z1 - r.z0));
}

// Samples of composite around a layer its mask reads (0 without a mask).
static int mask_border(const layer_info *l, double spacing) {
    return l->visible && layer_mask_active(&l->mask) ? layer_mask_border(&l->mask, spacing) : 0;
}

// The composite of the visible layers [0, upto) over r grown by extra (row-major, malloc'd
// into *out), from the base. A masked layer reads the composite below it around its part:
// the window starts wider by every such border and narrows layer by layer. When record is
// a layer index, *weights (r's size) gets its weight, opacity times mask.
static int compose_window(const compose_job *j, const layer_grid *grid, grid_rect r, int upto,
                          int extra, int record, float *weights, float **out, og_error *err) {
    world *w = edit_world(j->e);
    int margin = extra;
    for (int i = 0; i < upto; i++)
        margin += mask_border(&j->table.layers[i], grid->spacing);
    grid_rect outer = grow(r, margin);
    int ow = (int)(outer.x1 - outer.x0);
    size_t n = rect_samples(outer);
    float *acc = malloc(sizeof(float) * n), *val = malloc(sizeof(float) * n);
    float *below = malloc(sizeof(float) * n), *mask = malloc(sizeof(float) * n);
    int rc = acc && val && below && mask ? 0 : og_error_set(err, "out of memory composing layers");
    layer_grid g = *grid;
    g.layer = (tile_layer)tile_layer_in_slot(TILE_LAYER_COARSE, TILE_SLOT_BASE);
    if (rc == 0) rc = layer_grid_read(w, &g, outer, acc, err);
    for (int i = 0; i < upto && rc == 0; i++) {
        const layer_info *l = &j->table.layers[i];
        if (!l->visible) continue;
        int b = mask_border(l, grid->spacing), masked = layer_mask_active(&l->mask);
        grid_rect in = grow(r, margin), apply = grow(r, margin - b);
        int iw = (int)(in.x1 - in.x0), ih = (int)(in.z1 - in.z0);
        int aw = (int)(apply.x1 - apply.x0), ah = (int)(apply.z1 - apply.z0);
        g.layer = (tile_layer)tile_layer_in_slot(TILE_LAYER_COARSE, l->id);
        if ((rc = layer_grid_read(w, &g, apply, val, err)) != 0) break;
        float opacity = (float)l->opacity;
        if (masked) {
            for (int z = 0; z < ih; z++) // the composite below it, its window alone
                memcpy(below + (size_t)z * iw,
                       acc + (size_t)(z + in.z0 - outer.z0) * ow + (in.x0 - outer.x0),
                       sizeof(float) * (size_t)iw);
            layer_mask_evaluate(&l->mask, below, aw, ah, b, grid->spacing, NULL, mask);
        }
        for (int z = 0; z < ah; z++) {
            float *row = acc + (size_t)(z + apply.z0 - outer.z0) * ow + (apply.x0 - outer.x0);
            const float *v = val + (size_t)z * aw;
            if (!masked) {
                layer_blend_row(l->blend, opacity, row, v, row, aw);
                continue;
            }
            for (int x = 0; x < aw; x++)
                row[x] =
                    layer_blend_sample(l->blend, opacity * mask[(size_t)z * aw + x], row[x], v[x]);
        }
        if (i == record && weights) {
            int off = margin - b, rw = (int)(r.x1 - r.x0); // r within apply
            for (int z = 0; z < (int)(r.z1 - r.z0); z++)
                for (int x = 0; x < rw; x++)
                    weights[(size_t)z * rw + x] =
                        masked ? opacity * mask[(size_t)(z + off) * aw + x + off] : opacity;
        }
        margin -= b;
    }
    free(val);
    free(below);
    free(mask);
    if (rc != 0) {
        free(acc);
        return -1;
    }
    // Down to r grown by extra (margin == extra now).
    grid_rect want = grow(r, extra);
    int ww = (int)(want.x1 - want.x0);
    for (int z = 0; z < (int)(want.z1 - want.z0); z++)
        memmove(acc + (size_t)z * ww,
                acc + (size_t)(z + want.z0 - outer.z0) * ow + (want.x0 - outer.x0),
                sizeof(float) * (size_t)ww);
    *out = acc;
    return 0;
}

// Below this weight a result tool's change is not divided further (take_sample).
#define TAKE_MIN_WEIGHT 0.25f

// Moves the tool's change of one sample into the active layer's value v; returns v'.
static float take_sample(const compose_job *j, const layer_info *l, float weight, float below,
                         float v, float before, float now) {
    float shown = layer_blend_sample(l->blend, weight, below, v);
    float delta = now - before;
    if (j->mode == EDIT_LAYER_DELTA && !(l->blend == LAYER_BLEND_ADD && weight >= 1.0f))
        return (isnan(v) ? (l->blend == LAYER_BLEND_ADD ? 0.0f : shown) : v) + delta;
    // The top layer shows exactly what the tool made; one lower shows it moved by the
    // tool's change, which the layers above (adds) carry up.
    float target = j->table.active == j->top_visible ? now : shown + delta;
    if (weight < TAKE_MIN_WEIGHT) {
        // A faint sample (a mask's soft edge, a low opacity): dividing by its weight would
        // store a change many times the tool's, which shows the day the mask or opacity
        // changes. Solved at TAKE_MIN_WEIGHT, it shows weight / TAKE_MIN_WEIGHT of it.
        if (!(weight > 0.0f)) return v;
        return layer_blend_solve(l->blend, TAKE_MIN_WEIGHT, below, v, target);
    }
    return layer_blend_solve(l->blend, weight, below, v, target);
}

static int compose_task(void *user, int task, og_error *err) {
    compose_job *j = user;
    const tile_part *p = &j->parts[task];
    world *w = edit_world(j->e);
    tile_key ck = slot_key(p, 0);
    const float *before = NULL;
    if (j->take && !(before = edit_snapshot(j->e, ck))) return 0; // the tool left it alone
    layer_grid grid;
    if (layer_grid_init(&grid, world_get_params(w), TILE_LAYER_COARSE, p->face, err) != 0)
        return -1;
    int64_t gx = (int64_t)p->tx * TILE_SIZE, gz = (int64_t)p->ty * TILE_SIZE;
    // Only the world's own samples (a bounded world's edge tiles reach past it).
    grid_rect r =
        layer_grid_clip(&grid, (grid_rect){gx + p->x0, gz + p->z0, gx + p->x1, gz + p->z1});
    if (grid_rect_empty(r)) return 0;
    int x0 = (int)(r.x0 - gx), z0 = (int)(r.z0 - gz);
    int rw = (int)(r.x1 - r.x0), rh = (int)(r.z1 - r.z0);
    int active = j->take ? j->table.active : -1;
    float *acc = NULL, *weight = malloc(sizeof(float) * (size_t)rw * (size_t)rh);
    if (!weight) return og_error_set(err, "out of memory composing layers");
    tile_view cv;
    if (edit_tile_acquire(j->e, ck, &cv, err) != 0) {
        free(weight);
        return -1;
    }
    float *comp = cv.data;
    int rc = 0;
    grid_rect changed = {1, 1, 0, 0}; // part-local; empty
    if (j->stage == 1) { // the active layer takes the tool's change, over the layers below it
        const layer_info *l = &j->table.layers[active];
        int b = mask_border(l, grid.spacing);
        tile_view lv;
        rc = compose_window(j, &grid, r, active, b, -1, NULL, &acc, err);
        if (rc == 0 && layer_mask_active(&l->mask)) {
            float *mask = malloc(sizeof(float) * (size_t)rw * (size_t)rh);
            if (!mask)
                rc = og_error_set(err, "out of memory composing layers");
            else {
                layer_mask_evaluate(&l->mask, acc, rw, rh, b, grid.spacing, NULL, mask);
                for (int k = 0; k < rw * rh; k++)
                    weight[k] = (float)l->opacity * mask[k];
                free(mask);
            }
        } else {
            for (int k = 0; k < rw * rh; k++)
                weight[k] = (float)l->opacity;
        }
        if (rc == 0 && (rc = edit_tile_acquire(j->e, slot_key(p, l->id), &lv, err)) == 0) {
            float *val = lv.data;
            int bw = rw + 2 * b;
            for (int z = 0; z < rh; z++)
                for (int x = 0; x < rw; x++) {
                    int k = (z + z0) * TILE_SIZE + x + x0;
                    if (memcmp(&comp[k], &before[k], sizeof(float)) != 0)
                        val[k] =
                            take_sample(j, l, weight[z * rw + x], acc[(size_t)(z + b) * bw + x + b],
                                        val[k], before[k], comp[k]);
                }
            edit_tile_release(j->e, &lv);
        }
    } else {
        rc = compose_window(j, &grid, r, j->table.count, 0, active, weight, &acc, err);
        // On top at full weight, the composite keeps the tool's own result bit for bit,
        // as on a single heightfield, where base + layer rounds differently (a float sum
        // cannot always hit it: an ulp of the layer's value). Taking, samples the tool
        // left alone keep their composite.
        int exact = j->take && active == j->top_visible;
        for (int z = 0; z < rh && rc == 0; z++)
            for (int x = 0; x < rw; x++) {
                int k = (z + z0) * TILE_SIZE + x + x0;
                float next = acc[z * rw + x];
                if (before) {
                    if (!memcmp(&comp[k], &before[k], sizeof(float))) continue;
                    const layer_info *l = &j->table.layers[active];
                    if (exact && weight[z * rw + x] >= 1.0f &&
                        (j->mode == EDIT_LAYER_RESULT || l->blend == LAYER_BLEND_ADD))
                        continue; // kept
                }
                if (!memcmp(&comp[k], &next, sizeof next)) continue;
                comp[k] = next;
                // What changed now (the tool's own change was published as it was made).
                if (changed.x0 > changed.x1) changed = (grid_rect){x, z, x + 1, z + 1};
                if (x < changed.x0) changed.x0 = x;
                if (z < changed.z0) changed.z0 = z;
                if (x + 1 > changed.x1) changed.x1 = x + 1;
                if (z + 1 > changed.z1) changed.z1 = z + 1;
            }
    }
    free(acc);
    free(weight);
    edit_tile_release(j->e, &cv);
    if (rc == 0 && changed.x0 < changed.x1)
        edit_dirty(j->e, TILE_LAYER_COARSE, p->face,
                   (grid_rect){r.x0 + changed.x0, r.z0 + changed.z0, r.x0 + changed.x1,
                               r.z0 + changed.z1});
    return rc;
}

static int part_order(const void *a, const void *b) {
    const tile_part *x = a, *y = b;
    if (x->face != y->face) return x->face < y->face ? -1 : 1;
    if (x->ty != y->ty) return x->ty < y->ty ? -1 : 1;
    if (x->tx != y->tx) return x->tx < y->tx ? -1 : 1;
    return 0;
}

// Each tile once, covering every part of it (their bounding box).
static size_t merge_parts(tile_part *parts, size_t n) {
    if (!n) return 0;
    qsort(parts, n, sizeof *parts, part_order);
    size_t out = 0;
    for (size_t i = 1; i < n; i++) {
        tile_part *m = &parts[out];
        if (!part_order(m, &parts[i])) {
            if (parts[i].x0 < m->x0) m->x0 = parts[i].x0;
            if (parts[i].z0 < m->z0) m->z0 = parts[i].z0;
            if (parts[i].x1 > m->x1) m->x1 = parts[i].x1;
            if (parts[i].z1 > m->z1) m->z1 = parts[i].z1;
        } else {
            parts[++out] = parts[i];
        }
    }
    return out + 1;
}

typedef struct part_list {
    tile_part *parts;
    size_t count, cap;
} part_list;

static int add_rect(part_list *l, int face, grid_rect r) {
    if (grid_rect_empty(r)) return 0;
    int64_t tx0 = world_grid_floor_div(r.x0, TILE_SIZE),
            tx1 = world_grid_floor_div(r.x1 - 1, TILE_SIZE);
    int64_t tz0 = world_grid_floor_div(r.z0, TILE_SIZE),
            tz1 = world_grid_floor_div(r.z1 - 1, TILE_SIZE);
    for (int64_t tz = tz0; tz <= tz1; tz++)
        for (int64_t tx = tx0; tx <= tx1; tx++) {
            if (l->count == l->cap) {
                size_t cap = l->cap ? l->cap * 2 : 64;
                tile_part *grown = realloc(l->parts, cap * sizeof *grown);
                if (!grown) return -1;
                l->parts = grown;
                l->cap = cap;
            }
            int64_t gx = tx * TILE_SIZE, gz = tz * TILE_SIZE;
            tile_part p = {face,
                           (int32_t)tx,
                           (int32_t)tz,
                           (int)((r.x0 > gx ? r.x0 : gx) - gx),
                           (int)((r.z0 > gz ? r.z0 : gz) - gz),
                           (int)((r.x1 < gx + TILE_SIZE ? r.x1 : gx + TILE_SIZE) - gx),
                           (int)((r.z1 < gz + TILE_SIZE ? r.z1 : gz + TILE_SIZE) - gz)};
            l->parts[l->count++] = p;
        }
    return 0;
}

static int run(edit *e, part_list *l, int take, og_error *err) {
    compose_job j = {.e = e, .table = world_get_params(edit_world(e))->layers, .take = take};
    j.mode = edit_get_layer_mode(e);
    j.top_visible = -1;
    for (int i = 0; i < j.table.count; i++)
        if (j.table.layers[i].visible) j.top_visible = i;
    size_t n = merge_parts(l->parts, l->count);
    j.parts = l->parts;
    edit_layer_mode mode = edit_get_layer_mode(e);
    edit_set_layer_mode(e, EDIT_LAYER_COMPOSED); // composing writes the composite itself
    // Taking a tool's edit: first every part's active layer (reading only the layers
    // below it), then the composite (reading them all), so no part reads what another
    // is writing.
    int rc = 0;
    if (take) {
        j.stage = 1;
        rc = parallel_run((int)n, compose_task, &j, err);
        j.stage = 2;
    }
    if (rc == 0) rc = parallel_run((int)n, compose_task, &j, err);
    edit_set_layer_mode(e, mode);
    free(l->parts);
    return rc;
}

int layer_recompose(edit *e, int face, grid_rect r, og_error *err) {
    part_list l = {0};
    if (add_rect(&l, face, r) != 0) {
        free(l.parts);
        return og_error_set(err, "out of memory composing layers");
    }
    return run(e, &l, 0, err);
}

int layer_recompose_tiles(edit *e, const tile_key *keys, size_t count, og_error *err) {
    part_list l = {0};
    for (size_t i = 0; i < count; i++) {
        int64_t gx = (int64_t)keys[i].tx * TILE_SIZE, gz = (int64_t)keys[i].ty * TILE_SIZE;
        if (add_rect(&l, keys[i].face, (grid_rect){gx, gz, gx + TILE_SIZE, gz + TILE_SIZE}) != 0) {
            free(l.parts);
            return og_error_set(err, "out of memory composing layers");
        }
    }
    return run(e, &l, 0, err);
}

int layer_take_edit(edit *e, og_error *err) {
    if (edit_get_layer_mode(e) == EDIT_LAYER_COMPOSED) return 0;
    const layer_table *t = &world_get_params(edit_world(e))->layers;
    if (!t->count) return 0;
    const dirty_rect *rects;
    size_t count = edit_dirty_rects(e, &rects);
    part_list l = {0};
    for (size_t i = 0; i < count; i++)
        if (rects[i].layer == TILE_LAYER_COARSE &&
            add_rect(&l, rects[i].face, rects[i].rect) != 0) {
            free(l.parts);
            return og_error_set(err, "out of memory composing layers");
        }
    if (!l.count) return 0;
    return run(e, &l, 1, err);
}

// ---- a layer's tiles ----------------------------------------------------------------

typedef struct key_list {
    int32_t packed;
    tile_key *keys;
    size_t count, cap;
    int oom;
} key_list;

static int add_key(void *user, tile_key key) {
    key_list *l = user;
    if (key.layer != l->packed || key.level != 0) return 0;
    if (l->count == l->cap) {
        size_t cap = l->cap ? l->cap * 2 : 64;
        tile_key *grown = realloc(l->keys, cap * sizeof *grown);
        if (!grown) return l->oom = 1;
        l->keys = grown;
        l->cap = cap;
    }
    l->keys[l->count++] = key;
    return 0;
}

static int key_order(const void *a, const void *b) {
    const tile_key *x = a, *y = b;
    if (x->face != y->face) return x->face < y->face ? -1 : 1;
    if (x->ty != y->ty) return x->ty < y->ty ? -1 : 1;
    if (x->tx != y->tx) return x->tx < y->tx ? -1 : 1;
    return 0;
}

int layer_tiles(world *w, int32_t id, tile_key **keys, size_t *count, og_error *err) {
    key_list l = {.packed = tile_layer_in_slot(TILE_LAYER_COARSE, id)};
    *keys = NULL;
    *count = 0;
    size_t resident = tile_cache_edited_keys(world_cache(w), l.packed, NULL, 0);
    if (resident) {
        tile_key *r = malloc(resident * sizeof *r);
        if (!r) return og_error_set(err, "out of memory listing a layer's tiles");
        resident = tile_cache_edited_keys(world_cache(w), l.packed, r, resident);
        for (size_t i = 0; i < resident; i++)
            add_key(&l, r[i]);
        free(r);
    }
    tile_store *stores[2] = {world_journal(w), world_store(w)};
    for (int s = 0; s < 2; s++)
        if (stores[s] && tile_store_each(stores[s], add_key, &l, err) != 0) {
            free(l.keys);
            return -1;
        }
    if (l.oom) {
        free(l.keys);
        return og_error_set(err, "out of memory listing a layer's tiles");
    }
    if (l.count) qsort(l.keys, l.count, sizeof *l.keys, key_order);
    size_t n = 0;
    for (size_t i = 0; i < l.count; i++)
        if (!n || key_order(&l.keys[n - 1], &l.keys[i])) l.keys[n++] = l.keys[i];
    *keys = l.keys;
    *count = n;
    return 0;
}

int layer_count_filled(world *w, int32_t id, size_t *filled, og_error *err) {
    tile_key *keys;
    size_t n;
    *filled = 0;
    if (layer_tiles(w, id, &keys, &n, err) != 0) return -1;
    int rc = 0;
    for (size_t i = 0; i < n && rc == 0; i++) {
        tile_view v;
        if (tile_cache_acquire(world_cache(w), keys[i], &v, err) != 0) {
            rc = -1;
            break;
        }
        const float *f = v.data;
        for (size_t k = 0; k < TILE_SAMPLES; k++)
            if (f[k] == f[k]) {
                ++*filled;
                break;
            }
        tile_cache_release(world_cache(w), &v);
    }
    free(keys);
    return rc;
}

// ---- whole-layer operations ---------------------------------------------------------

typedef struct tiles_job {
    edit *e;
    const tile_key *keys;
    int32_t from, to; // slots: copy from -> to; clear to (from < 0)
    layer_table table;
    int below; // merge: the layer index merged into
} tiles_job;

static tile_key in_slot(tile_key k, int32_t slot) {
    k.layer = tile_layer_in_slot(TILE_LAYER_COARSE, slot);
    return k;
}

static int copy_task(void *user, int task, og_error *err) {
    tiles_job *j = user;
    tile_view dst;
    if (edit_tile_acquire(j->e, in_slot(j->keys[task], j->to), &dst, err) != 0) return -1;
    if (j->from < 0) {
        float *f = dst.data;
        for (size_t k = 0; k < TILE_SAMPLES; k++)
            f[k] = NAN;
    } else {
        tile_view src;
        tile_cache *cache = world_cache(edit_world(j->e));
        if (tile_cache_acquire(cache, in_slot(j->keys[task], j->from), &src, err) != 0) {
            edit_tile_release(j->e, &dst);
            return -1;
        }
        memcpy(dst.data, src.data, sizeof(float) * TILE_SAMPLES);
        tile_cache_release(cache, &src);
    }
    edit_tile_release(j->e, &dst);
    return 0;
}

int layer_copy_tiles(edit *e, int32_t from, int32_t to, const tile_key *keys, size_t count,
                     og_error *err) {
    tiles_job j = {.e = e, .keys = keys, .from = from, .to = to};
    return parallel_run((int)count, copy_task, &j, err);
}

// Folds layer below+1 into layer below over one tile: below's new value shows what the
// two showed together.
static int merge_task(void *user, int task, og_error *err) {
    tiles_job *j = user;
    world *w = edit_world(j->e);
    tile_cache *cache = world_cache(w);
    tile_key key = j->keys[task];
    const layer_info *lo = &j->table.layers[j->below], *hi = &j->table.layers[j->below + 1];
    tile_view bv, lv, hv;
    if (tile_cache_acquire(cache, in_slot(key, TILE_SLOT_BASE), &bv, err) != 0) return -1;
    float *acc = malloc(sizeof(float) * TILE_SAMPLES);
    if (!acc) {
        tile_cache_release(cache, &bv);
        return og_error_set(err, "out of memory merging layers");
    }
    memcpy(acc, bv.data, sizeof(float) * TILE_SAMPLES);
    tile_cache_release(cache, &bv);
    int rc = 0;
    for (int i = 0; i < j->below && rc == 0; i++) {
        const layer_info *l = &j->table.layers[i];
        if (!l->visible) continue;
        tile_view v;
        if (tile_cache_acquire(cache, in_slot(key, l->id), &v, err) != 0) {
            rc = -1;
            break;
        }
        if (v.edited) layer_blend_row(l->blend, (float)l->opacity, acc, v.data, acc, TILE_SAMPLES);
        tile_cache_release(cache, &v);
    }
    if (rc == 0 && edit_tile_acquire(j->e, in_slot(key, lo->id), &lv, err) != 0) rc = -1;
    if (rc == 0) {
        if (tile_cache_acquire(cache, in_slot(key, hi->id), &hv, err) != 0) {
            edit_tile_release(j->e, &lv);
            rc = -1;
        }
    }
    if (rc == 0) {
        float *lo_v = lv.data;
        const float *hi_v = hv.data;
        float wl = (float)lo->opacity, wh = (float)hi->opacity;
        for (size_t k = 0; k < TILE_SAMPLES; k++) {
            if (hi_v[k] != hi_v[k]) continue; // the upper layer has nothing here
            float shown = layer_blend_sample(lo->blend, wl, acc[k], lo_v[k]);
            float both = layer_blend_sample(hi->blend, wh, shown, hi_v[k]);
            lo_v[k] = layer_blend_solve(lo->blend, wl, acc[k], lo_v[k], both);
        }
        tile_cache_release(cache, &hv);
        edit_tile_release(j->e, &lv);
    }
    free(acc);
    return rc;
}

int layer_merge_tiles(edit *e, int below, const tile_key *keys, size_t count, og_error *err) {
    tiles_job j = {.e = e, .keys = keys, .below = below};
    j.table = world_get_params(edit_world(e))->layers;
    return parallel_run((int)count, merge_task, &j, err);
}
