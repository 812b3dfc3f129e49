#include "editor/edit/layer_composite.h"

#include "editor/edit/parallel.h"
#include "editor/layers/layer_blend.h"

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

// Moves the tool's change of one sample into the active layer's value v; returns v'.
static float take_sample(const compose_job *j, const layer_info *l, float below, float v,
                         float before, float now) {
    float weight = (float)l->opacity;
    float shown = layer_blend_sample(l->blend, weight, below, v);
    float delta = now - before;
    if (j->mode == EDIT_LAYER_DELTA && !(l->blend == LAYER_BLEND_ADD && weight >= 1.0f))
        return (isnan(v) ? (l->blend == LAYER_BLEND_ADD ? 0.0f : shown) : v) + delta;
    // The top layer shows exactly what the tool made; one lower shows it moved by the
    // tool's change, which the layers above (adds) carry up.
    float target = j->table.active == j->top_visible ? now : shown + delta;
    return layer_blend_solve(l->blend, weight, below, v, target);
}

static int compose_task(void *user, int task, og_error *err) {
    compose_job *j = user;
    const tile_part *p = &j->parts[task];
    world *w = edit_world(j->e);
    tile_cache *cache = world_cache(w);
    tile_key ck = slot_key(p, 0);
    const float *before = NULL;
    if (j->take && !(before = edit_snapshot(j->e, ck))) return 0; // the tool left it alone
    tile_view cv, bv;
    if (edit_tile_acquire(j->e, ck, &cv, err) != 0) return -1;
    if (tile_cache_acquire(cache, slot_key(p, TILE_SLOT_BASE), &bv, err) != 0) {
        edit_tile_release(j->e, &cv);
        return -1;
    }
    float *acc = malloc(sizeof(float) * TILE_SAMPLES);
    int rc = acc ? 0 : og_error_set(err, "out of memory composing layers");
    float *comp = cv.data;
    const float *base = bv.data;
    for (int z = p->z0; z < p->z1 && acc; z++)
        memcpy(acc + z * TILE_SIZE + p->x0, base + z * TILE_SIZE + p->x0,
               sizeof(float) * (size_t)(p->x1 - p->x0));
    for (int i = 0; i < j->table.count && rc == 0; i++) {
        const layer_info *l = &j->table.layers[i];
        if (!l->visible) continue;
        tile_view lv;
        float weight = (float)l->opacity;
        if (j->take && i == j->table.active) {
            if (edit_tile_acquire(j->e, slot_key(p, l->id), &lv, err) != 0) {
                rc = -1;
                break;
            }
            float *val = lv.data;
            int exact = i == j->top_visible && (j->mode == EDIT_LAYER_RESULT ||
                                                (l->blend == LAYER_BLEND_ADD && weight >= 1.0f));
            for (int z = p->z0; z < p->z1; z++)
                for (int x = p->x0; x < p->x1; x++) {
                    int k = z * TILE_SIZE + x;
                    int changed = memcmp(&comp[k], &before[k], sizeof(float)) != 0;
                    if (changed) val[k] = take_sample(j, l, acc[k], val[k], before[k], comp[k]);
                    // On top, the composite keeps the tool's own result, bit for bit as
                    // on a single heightfield, where base + layer rounds differently
                    // (a float sum cannot always hit it: an ulp of the layer's value).
                    acc[k] = changed && exact
                                 ? comp[k]
                                 : layer_blend_sample(l->blend, weight, acc[k], val[k]);
                }
            edit_tile_release(j->e, &lv);
            continue;
        }
        if (tile_cache_acquire(cache, slot_key(p, l->id), &lv, err) != 0) {
            rc = -1;
            break;
        }
        if (lv.edited) { // a tile the layer never wrote holds nothing
            const float *val = lv.data;
            for (int z = p->z0; z < p->z1; z++) {
                int k = z * TILE_SIZE + p->x0;
                layer_blend_row(l->blend, weight, acc + k, val + k, acc + k, p->x1 - p->x0);
            }
        }
        tile_cache_release(cache, &lv);
    }
    // Taking a tool's edit, samples it left alone keep their composite (a rectangle's
    // edge, and every sample a top layer holds exactly: see take_sample).
    if (rc == 0)
        for (int z = p->z0; z < p->z1; z++) {
            int k = z * TILE_SIZE + p->x0;
            if (!before) {
                memcpy(comp + k, acc + k, sizeof(float) * (size_t)(p->x1 - p->x0));
                continue;
            }
            for (int x = p->x0; x < p->x1; x++, k++)
                if (memcmp(&comp[k], &before[k], sizeof(float)) != 0) comp[k] = acc[k];
        }
    free(acc);
    tile_cache_release(cache, &bv);
    edit_tile_release(j->e, &cv);
    if (rc == 0) {
        int64_t gx = (int64_t)p->tx * TILE_SIZE, gz = (int64_t)p->ty * TILE_SIZE;
        edit_dirty(j->e, TILE_LAYER_COARSE, p->face,
                   (grid_rect){gx + p->x0, gz + p->z0, gx + p->x1, gz + p->z1});
    }
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
    int rc = parallel_run((int)n, compose_task, &j, err);
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
