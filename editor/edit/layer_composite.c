#include "editor/edit/layer_composite.h"

#include "editor/edit/height_window.h"
#include "editor/edit/paint_composite.h"
#include "editor/edit/parallel.h"
#include "editor/edit/tile_parts.h"
#include "io/avx2_clone.h"
#include "editor/layers/layer_blend.h"
#include "editor/world/layer_grid.h"
#include "editor/world/thread_scratch.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct compose_job {
    edit *e;
    layer_table table; // a copy: the world's may change only between edits
    int take;          // layer_take_edit: the tool's change goes into the active layer
    int stage;         // taking: 1 writes the active layer, 2 recomposes
    edit_layer_mode mode;
    int top_visible; // index of the highest visible height layer (-1: none)
    const tile_part *parts;
    // Taking with no masked height layer above the active one: stage 1's composite of
    // the layers below it (the part grown by its mask border) and its weights, per part,
    // which stage 2 lays the layers from the active one up over (NULL: compose all).
    float **below, **below_weight;
} compose_job;

static tile_key slot_key(const tile_part *p, int32_t slot) {
    return (tile_key){.layer = tile_layer_in_slot(TILE_LAYER_COARSE, slot),
                      .face = p->face,
                      .tx = p->tx,
                      .ty = p->ty};
}

// Below this weight a result tool's change is not divided further (take_sample).
#define TAKE_MIN_WEIGHT 0.25f

// Moves the tool's change of one sample into the active layer's value v; returns v'.
static float take_sample(const compose_job *j, const layer_info *l, float weight, float below,
                         float v, float before, float now) {
    if (l->blend == LAYER_BLEND_ADD && weight >= 1.0f && !isnan(v)) {
        // The common layer, inline: what layer_blend_solve returns when no ulp step is
        // needed (the value kept if it already shows the target, else target - below).
        float target = j->table.active == j->top_visible ? now : (below + v) + (now - before);
        if (isnan(target) || below + v == target) return v;
        float solved = target - below;
        if (below + solved == target) return solved;
    }
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

// The samples take_row_add_top's inline case missed, gathered over rows for one
// layer_blend_solve_add_row call: a row's few misses (a tenth to a fifth of a tall
// stroke's samples) left the solve's vector loop mostly in its scalar tail.
enum { TAKE_MISSES = 2048 };
typedef struct take_misses {
    float below[TAKE_MISSES], value[TAKE_MISSES], target[TAKE_MISSES];
    float *at[TAKE_MISSES];
    int count;
} take_misses;

static void take_misses_solve(take_misses *t) {
    layer_blend_solve_add_row(t->below, t->value, t->target, t->value, t->count);
    for (int i = 0; i < t->count; i++)
        *t->at[i] = t->value[i];
    t->count = 0;
}

// take_sample over a row span for the common layer: an add layer at full weight, the top
// visible one (its target is the tool's own result). The inline case take_sample tries
// first, for the whole span without branches (vectorised; it nearly always succeeds),
// then for the samples it missed what take_sample does for them there (its ulp search,
// layer_blend_solve), gathered into misses for take_misses_solve: the same values.
// Samples whose composite the tool left as it was (bit for bit) keep their value, as
// kept() says. An empty sample (NaN: the layer's first edit there) shows below: it stays
// empty where the target is below, else it takes target - below when that hits it, as
// layer_blend_solve does (a first stamp on a new layer sent all its samples to the
// search, 190k of them for a 512^2 stamp: 30 ms).
AVX2_CLONE static void take_row_add_top(float *val, const float *below, const float *before,
                                        const float *now, int n, take_misses *misses) {
    uint8_t miss[TILE_SIZE];
    int32_t missed[TILE_SIZE]; // as wide as the floats: the step below vectorises
    int any = 0;
    for (int x = 0; x < n; x++) {
        uint32_t a, c;
        memcpy(&a, &now[x], sizeof a);
        memcpy(&c, &before[x], sizeof c);
        float v = val[x], b = below[x], t = now[x], solved = t - b;
        int keep = (a == c) | ((v == v) & ((t != t) | (b + v == t))) | ((v != v) & (t == b));
        int hit = b + solved == t;
        val[x] = keep | !hit ? v : solved;
        missed[x] = !keep & !hit;
        any |= missed[x];
    }
    if (!any) return;
    // The search's first step, inline (step_toward's bits; a zero steps to the smallest
    // subnormal), which decides it for nearly every miss (a target finer than the sums
    // around it: below and the value larger than it, of opposite signs). The value an ulp
    // toward the target makes the sum hit it: the search ends there. It makes a worse
    // miss: the search ends at once with the value as solved. It lands as far on the
    // other side: the search steps back and forth for its 8 steps and ends where it
    // began, as solved (the values nonzero: a step back from a zero is not the way it
    // came). The rest (a NaN target or sum, an infinite value, a step that leaves the
    // sum as it was) go to the search.
    any = 0;
    for (int x = 0; x < n; x++) {
        float b = below[x], t = now[x], solved = t - b, got = b + solved;
        uint32_t u;
        memcpy(&u, &solved, sizeof u);
        int32_t up = got < t;
        uint32_t zero = up ? 1u : 0x80000001u;
        uint32_t moved = (u & 0x7fffffffu) == 0 ? zero : ((u >> 31) == 0) == up ? u + 1 : u - 1;
        float next;
        memcpy(&next, &moved, sizeof next);
        // Finite and nonzero, this value and the next (an ulp from it): the value is
        // neither zero, an infinity nor NaN, and neither the smallest nor largest.
        float size = solved < 0.0f ? -solved : solved;
        int32_t finite = (size > 0x1p-149f) & (size < 0x1.fffffep+127f);
        float again = b + next;
        int32_t known = missed[x] & (t == t) & (got == got) & finite;
        int32_t stepped = known & (again == t);
        float off = got - t, off_next = again - t; // compared as fabsf's (not a call here)
        off = off < 0.0f ? -off : off;
        off_next = off_next < 0.0f ? -off_next : off_next;
        int32_t stays = known & ((off_next > off) | ((off_next == off) & (again != got)));
        val[x] = stepped ? next : stays ? solved : val[x];
        miss[x] = (uint8_t)(missed[x] & !stepped & !stays);
        any |= miss[x];
    }
    if (!any) return;
    take_misses *t = misses;
    if (t->count > TAKE_MISSES - n) take_misses_solve(t);
    // Gathered from the miss flags 8 at a time, a flag's lowest set bit after another:
    // a loop over every sample (branch-free) spent most of its time on loads of values
    // the loop above had just stored, 32 bytes at a time.
    int m = t->count, x = 0;
    for (; x + 8 <= n; x += 8) {
        uint64_t flags;
        memcpy(&flags, miss + x, sizeof flags);
        for (; flags; flags &= flags - 1) {
            int k = x + __builtin_ctzll(flags) / 8;
            t->below[m] = below[k], t->value[m] = val[k], t->target[m] = now[k];
            t->at[m++] = &val[k];
        }
    }
    for (; x < n; x++)
        if (miss[x])
            t->below[m] = below[x], t->value[m] = val[x], t->target[m] = now[x],
            t->at[m++] = &val[x];
    t->count = m;
}

// Whether no visible height layer lies below the active one (the composite below it
// is the base).
static int base_alone(const layer_table *t, int active) {
    for (int i = 0; i < active; i++)
        if (t->layers[i].visible && t->layers[i].kind == LAYER_KIND_HEIGHT) return 0;
    return 1;
}

// Whether the tool left the sample at (x, z) of a tile as it was: outside the part
// it acquired (where the snapshot holds nothing), or bit for bit the same.
static int kept(grid_rect touched, int x, int z, const float *now, const float *before) {
    if (x < touched.x0 || x >= touched.x1 || z < touched.z0 || z >= touched.z1) return 1;
    return !memcmp(now, before, sizeof *now);
}

// Copies a row of the new composite over the old where they differ bit for bit (NaN
// payloads and signed zeros included), widening changed by the span that did.
static void store_row(float *comp, const float *next, int n, int z, grid_rect *changed) {
    if (!memcmp(comp, next, sizeof *comp * (size_t)n)) return;
    int first = 0, last = n - 1;
    while (!memcmp(&comp[first], &next[first], sizeof *comp))
        first++;
    while (!memcmp(&comp[last], &next[last], sizeof *comp))
        last--;
    memcpy(comp + first, next + first, sizeof *comp * (size_t)(last + 1 - first));
    tile_part_touch(changed, first, z);
    tile_part_touch(changed, last, z);
}

// Stage 2 from stage 1's composite below the active layer (j->below): the part's
// composite of the visible height layers from the active one up, laid as
// height_window_compose lays them (none of them reads a mask border), so the result is
// the same bit for bit. weight gets the active layer's weights.
static int compose_from_active(compose_job *j, int task, const layer_grid *grid, grid_rect r,
                               float *weight, float **out, og_error *err) {
    const int active = j->table.active, rw = (int)(r.x1 - r.x0), rh = (int)(r.z1 - r.z0);
    const layer_info *a = &j->table.layers[active];
    const int b = height_window_mask_border(a, grid->spacing), bw = rw + 2 * b;
    const size_t n = (size_t)rw * (size_t)rh;
    float *acc = malloc(sizeof(float) * n), *val = malloc(sizeof(float) * n);
    if (!acc || !val) {
        free(acc), free(val);
        return og_error_set(err, "out of memory composing layers");
    }
    for (int z = 0; z < rh; z++)
        memcpy(acc + (size_t)z * rw, j->below[task] + (size_t)(z + b) * bw + b,
               sizeof(float) * (size_t)rw);
    memcpy(weight, j->below_weight[task], sizeof(float) * n);
    layer_grid g = *grid;
    int rc = 0;
    for (int i = active; i < j->table.count && rc == 0; i++) {
        const layer_info *l = &j->table.layers[i];
        if (!l->visible || l->kind != LAYER_KIND_HEIGHT) continue;
        g.layer = (tile_layer)tile_layer_in_slot(TILE_LAYER_COARSE, l->id);
        if ((rc = layer_grid_read(edit_world(j->e), &g, r, val, err)) != 0) break;
        if (i == active && layer_mask_active(&l->mask)) {
            for (size_t k = 0; k < n; k++)
                acc[k] = layer_blend_sample(l->blend, weight[k], acc[k], val[k]);
            continue;
        }
        for (int z = 0; z < rh; z++)
            layer_blend_row(l->blend, (float)l->opacity, acc + (size_t)z * rw, val + (size_t)z * rw,
                            acc + (size_t)z * rw, rw);
    }
    free(val);
    if (rc != 0) {
        free(acc);
        return -1;
    }
    *out = acc;
    return 0;
}

static int compose_task(void *user, int task, og_error *err) {
    compose_job *j = user;
    const tile_part *p = &j->parts[task];
    world *w = edit_world(j->e);
    tile_key ck = slot_key(p, 0);
    const float *before = NULL;
    grid_rect touched = {0, 0, 0, 0}; // tile-local: the only samples the tool can have changed
    if (j->take && !(before = edit_snapshot(j->e, ck, &touched))) return 0; // left alone
    layer_grid grid;
    if (layer_grid_init(&grid, world_get_params(w), TILE_LAYER_COARSE, p->face, err) != 0)
        return -1;
    int64_t gx = (int64_t)p->tx * TILE_SIZE, gz = (int64_t)p->ty * TILE_SIZE;
    // Only the world's own samples (a bounded world's edge tiles reach past it).
    grid_rect r =
        layer_grid_clip(&grid, (grid_rect){gx + p->x0, gz + p->z0, gx + p->x1, gz + p->z1});
    // Taking, the rest of the part keeps its samples (kept()): a rotated stamp's tile
    // part is often much larger than what its footprint touched there.
    if (j->take)
        r = grid_rect_intersect(
            r, (grid_rect){gx + touched.x0, gz + touched.z0, gx + touched.x1, gz + touched.z1});
    if (grid_rect_empty(r)) return 0;
    int x0 = (int)(r.x0 - gx), z0 = (int)(r.z0 - gz);
    int rw = (int)(r.x1 - r.x0), rh = (int)(r.z1 - r.z0);
    int active = j->take ? j->table.active : -1;
    // The take's common case (add_top) over the base alone reads no weights: none are
    // allocated (a fresh 66 KB per dab tile came from the heap's top and went back to
    // the system at its free, a page fault per 4 KB every time).
    const layer_info *taking = j->stage == 1 ? &j->table.layers[active] : NULL;
    int add_top = taking && taking->blend == LAYER_BLEND_ADD && !layer_mask_active(&taking->mask) &&
                  (float)taking->opacity >= 1.0f && active == j->top_visible;
    int no_weights = add_top && !j->below;
    float *acc = NULL,
          *weight = no_weights ? NULL : malloc(sizeof(float) * (size_t)rw * (size_t)rh);
    if (!weight && !no_weights) return og_error_set(err, "out of memory composing layers");
    grid_rect local = {x0, z0, x0 + rw, z0 + rh};
    tile_view cv;
    if (edit_tile_acquire_part(j->e, ck, local, &cv, err) != 0) {
        free(weight);
        return -1;
    }
    float *comp = cv.data;
    int rc = 0;
    grid_rect changed = {1, 1, 0, 0}; // part-local; empty
    if (j->stage == 1) { // the active layer takes the tool's change, over the layers below it
        const layer_info *l = taking;
        int b = height_window_mask_border(l, grid.spacing);
        tile_view lv, base = {0};
        // The common layer over the base alone: the composite below it is the base
        // tile's own rows (a window copied from them cost as much as the take's rows).
        const float *below = NULL;
        int below_stride = 0;
        if (no_weights && base_alone(&j->table, active)) {
            tile_key bk = {.layer = tile_layer_in_slot(TILE_LAYER_COARSE, TILE_SLOT_BASE),
                           .face = p->face,
                           .tx = p->tx,
                           .ty = p->ty};
            rc = tile_cache_acquire(world_cache(w), bk, &base, err);
            below = rc == 0 ? (const float *)base.data + (size_t)z0 * TILE_SIZE + x0 : NULL;
            below_stride = TILE_SIZE;
        } else {
            rc = height_window_compose(edit_world(j->e), &j->table, &grid, r, active, b, -1, NULL,
                                       &acc, err);
            below = rc == 0 ? acc + (size_t)b * (rw + 2 * b) + b : NULL;
            below_stride = rw + 2 * b;
        }
        if (rc == 0 && layer_mask_active(&l->mask)) {
            float *mask = malloc(sizeof(float) * (size_t)rw * (size_t)rh);
            if (!mask)
                rc = og_error_set(err, "out of memory composing layers");
            else if ((rc = height_window_mask(w, l, &grid, r, acc, b, mask, err)) == 0) {
                for (int k = 0; k < rw * rh; k++)
                    weight[k] = (float)l->opacity * mask[k];
            }
            free(mask);
        } else if (!add_top || j->below) { // add_top reads no weights; stage 2 may
            for (int k = 0; k < rw * rh; k++)
                weight[k] = (float)l->opacity;
        }
        if (rc == 0 &&
            (rc = edit_tile_acquire_part(j->e, slot_key(p, l->id), local, &lv, err)) == 0) {
            float *val = lv.data;
            take_misses *misses =
                add_top ? thread_scratch(SCRATCH_TAKE_MISSES, sizeof *misses) : NULL;
            if (add_top && !misses) rc = og_error_set(err, "out of memory composing layers");
            if (misses) misses->count = 0;
            for (int z = 0; misses && z < rh; z++) {
                int tz = z + z0, xa = x0 > touched.x0 ? x0 : (int)touched.x0;
                int xb = x0 + rw < touched.x1 ? x0 + rw : (int)touched.x1;
                if (tz < touched.z0 || tz >= touched.z1 || xa >= xb) continue;
                int k = tz * TILE_SIZE + xa;
                take_row_add_top(val + k, below + (size_t)z * below_stride + (xa - x0), before + k,
                                 comp + k, xb - xa, misses);
            }
            if (misses) take_misses_solve(misses);
            for (int z = 0; !add_top && z < rh; z++)
                for (int x = 0; x < rw; x++) {
                    int k = (z + z0) * TILE_SIZE + x + x0;
                    if (!kept(touched, x + x0, z + z0, comp + k, before + k))
                        val[k] = take_sample(j, l, weight[z * rw + x],
                                             below[(size_t)z * below_stride + x], val[k], before[k],
                                             comp[k]);
                }
            edit_tile_release(j->e, &lv);
        }
        if (base.data) tile_cache_release(world_cache(w), &base);
    } else {
        if (j->below && j->below[task])
            rc = compose_from_active(j, task, &grid, r, weight, &acc, err);
        else
            rc = height_window_compose(edit_world(j->e), &j->table, &grid, r, j->table.count, 0,
                                       active, weight, &acc, err);
        // On top at full weight, the composite keeps the tool's own result bit for bit,
        // as on a single heightfield, where base + layer rounds differently (a float sum
        // cannot always hit it: an ulp of the layer's value). Taking, samples the tool
        // left alone keep their composite.
        int exact = j->take && active == j->top_visible;
        if (!before && rc == 0) // recomposing: whole rows at memory speed
            for (int z = 0; z < rh; z++)
                store_row(comp + (size_t)(z + z0) * TILE_SIZE + x0, acc + (size_t)z * rw, rw, z,
                          &changed);
        for (int z = 0; z < rh && rc == 0 && before; z++)
            for (int x = 0; x < rw; x++) {
                int k = (z + z0) * TILE_SIZE + x + x0;
                float next = acc[z * rw + x];
                if (kept(touched, x + x0, z + z0, comp + k, before + k)) continue;
                const layer_info *l = &j->table.layers[active];
                if (exact && weight[z * rw + x] >= 1.0f &&
                    (j->mode == EDIT_LAYER_RESULT || l->blend == LAYER_BLEND_ADD))
                    continue; // kept
                if (!memcmp(&comp[k], &next, sizeof next)) continue;
                comp[k] = next;
                // What changed now (the tool's own change was published as it was made).
                tile_part_touch(&changed, x, z);
            }
    }
    if (j->stage == 1 && j->below && rc == 0) { // kept for stage 2 (run frees them)
        j->below[task] = acc, j->below_weight[task] = weight;
        acc = weight = NULL;
    }
    free(acc);
    free(weight);
    edit_tile_release(j->e, &cv);
    if (rc == 0) tile_part_publish(j->e, TILE_LAYER_COARSE, p->face, r, changed);
    return rc;
}

// Whether stage 2 can start from stage 1's composite below the active layer: no visible
// height layer above it reads a mask border (the active layer's own mask is stage 1's).
static int reuse_below(const layer_table *t) {
    if (t->active < 0 || t->layers[t->active].kind != LAYER_KIND_HEIGHT) return 0;
    for (int i = t->active + 1; i < t->count; i++) {
        const layer_info *l = &t->layers[i];
        if (l->visible && l->kind == LAYER_KIND_HEIGHT && layer_mask_active(&l->mask)) return 0;
    }
    return 1;
}

// Whether taking a tool's change leaves the composite as the tool made it everywhere, so
// stage 2 would change no sample: the active layer is the top visible one, unmasked,
// at full opacity, and shows the tool's result exactly (compose_task's `exact` case
// for every weight, which is the opacity).
static int take_keeps_composite(const compose_job *j) {
    if (j->table.active < 0 || j->table.active != j->top_visible) return 0;
    const layer_info *l = &j->table.layers[j->table.active];
    return !layer_mask_active(&l->mask) && (float)l->opacity >= 1.0f &&
           (j->mode == EDIT_LAYER_RESULT || l->blend == LAYER_BLEND_ADD);
}

// Runs over l's parts (frees them): the composite's heights, taking a tool's change
// first when take; then the materials where a paint layer's mask reads those heights.
static int run(edit *e, tile_parts *l, int take, og_error *err) {
    compose_job j = {.e = e, .table = world_get_params(edit_world(e))->layers, .take = take};
    j.mode = edit_get_layer_mode(e);
    j.top_visible = layer_table_top_visible(&j.table, LAYER_KIND_HEIGHT);
    tile_parts_merge(l);
    size_t n = l->count;
    j.parts = l->parts;
    edit_layer_mode mode = edit_get_layer_mode(e);
    edit_set_layer_mode(e, EDIT_LAYER_COMPOSED); // composing writes the composite itself
    // Taking a tool's edit: first every part's active layer (reading only the layers
    // below it), then the composite (reading them all), so no part reads what another
    // is writing.
    int rc = 0;
    int compose = !take || !take_keeps_composite(&j);
    if (take && compose && n &&
        reuse_below(&j.table)) { // without memory: every part composes it all
        j.below = calloc(n, sizeof *j.below), j.below_weight = calloc(n, sizeof *j.below);
        if (!j.below || !j.below_weight) {
            free(j.below), free(j.below_weight);
            j.below = j.below_weight = NULL;
        }
    }
    if (take) {
        j.stage = 1;
        rc = parallel_run((int)n, compose_task, &j, err);
        j.stage = 2;
    }
    if (rc == 0 && compose) rc = parallel_run((int)n, compose_task, &j, err);
    for (size_t i = 0; j.below && i < n; i++)
        free(j.below[i]), free(j.below_weight[i]);
    free(j.below), free(j.below_weight);
    edit_set_layer_mode(e, mode);
    if (rc == 0) rc = paint_recompose_masked(e, l->parts, n, err);
    tile_parts_free(l);
    return rc;
}

int layer_recompose(edit *e, int face, grid_rect r, og_error *err) {
    tile_parts l = {0};
    if (tile_parts_add_rect(&l, face, r) != 0) {
        tile_parts_free(&l);
        return og_error_set(err, "out of memory composing layers");
    }
    return run(e, &l, 0, err);
}

int layer_recompose_tiles(edit *e, const tile_key *keys, size_t count, og_error *err) {
    tile_parts heights = {0}, paint = {0};
    for (size_t i = 0; i < count; i++) {
        int64_t gx = (int64_t)keys[i].tx * TILE_SIZE, gz = (int64_t)keys[i].ty * TILE_SIZE;
        tile_parts *l = tile_key_kind(keys[i]) == TILE_LAYER_MATERIAL ? &paint : &heights;
        if (tile_parts_add_rect(l, keys[i].face,
                                (grid_rect){gx, gz, gx + TILE_SIZE, gz + TILE_SIZE}) != 0) {
            tile_parts_free(&heights);
            tile_parts_free(&paint);
            return og_error_set(err, "out of memory composing layers");
        }
    }
    int rc = paint_recompose(e, &paint, err);
    tile_parts_free(&paint);
    if (rc != 0) {
        tile_parts_free(&heights);
        return -1;
    }
    return heights.count ? run(e, &heights, 0, err) : 0;
}

// Keeps painted coverage within 0..1 over one dirty area of it.
static int clamp_coverage(edit *e, const dirty_rect *d, og_error *err) {
    tile_parts l = {0};
    if (tile_parts_add_rect(&l, d->face, d->rect) != 0) {
        tile_parts_free(&l);
        return og_error_set(err, "out of memory painting a mask");
    }
    int rc = 0;
    for (size_t i = 0; i < l.count && rc == 0; i++) {
        const tile_part *p = &l.parts[i];
        tile_view v;
        tile_key key = {.layer = (int32_t)d->layer, .face = p->face, .tx = p->tx, .ty = p->ty};
        if ((rc = edit_tile_acquire(e, key, &v, err)) != 0) break;
        float *f = v.data;
        for (int z = p->z0; z < p->z1; z++)
            for (int x = p->x0; x < p->x1; x++) {
                float *c = &f[z * TILE_SIZE + x];
                *c = !(*c > 0.0f) ? 0.0f : *c > 1.0f ? 1.0f : *c;
            }
        edit_tile_release(e, &v);
    }
    tile_parts_free(&l);
    return rc;
}

// A tool painted a layer's mask coverage (brush target=mask) over rects (a copy): kept
// within 0..1, and the composite recomposed where it changed (and where the masks above
// read that).
static int take_coverage(edit *e, const dirty_rect *rects, size_t count, og_error *err) {
    const world_params *params = world_get_params(edit_world(e));
    const layer_table *t = &params->layers;
    int rc = 0;
    for (size_t i = 0; i < count && rc == 0; i++) {
        int32_t slot = tile_key_slot((tile_key){.layer = (int32_t)rects[i].layer});
        int li = layer_table_find_id(t, slot - LAYER_ID_MAX - 1);
        if (li < 0 || (rc = clamp_coverage(e, &rects[i], err)) != 0) continue;
        tile_parts parts = {0};
        layer_grid g;
        if ((rc = layer_grid_init(&g, params, TILE_LAYER_COARSE, rects[i].face, err)) != 0) break;
        int grow = 0;
        for (int k = li + 1; k < t->count; k++)
            grow += height_window_mask_border(&t->layers[k], g.spacing);
        if (t->layers[li].kind == LAYER_KIND_PAINT) {
            if (tile_parts_add_rect(&parts, rects[i].face, rects[i].rect) != 0)
                rc = og_error_set(err, "out of memory painting a mask");
            else
                rc = paint_recompose(e, &parts, err);
            tile_parts_free(&parts);
        } else {
            rc = layer_recompose(e, rects[i].face, height_window_grow(rects[i].rect, grow), err);
        }
    }
    return rc;
}

int layer_take_edit(edit *e, og_error *err) {
    if (edit_get_layer_mode(e) == EDIT_LAYER_COMPOSED) return 0;
    const layer_table *t = &world_get_params(edit_world(e))->layers;
    if (!t->count) return 0;
    const dirty_rect *rects;
    size_t count = edit_dirty_rects(e, &rects);
    // Everything the tool changed is gathered first: composing adds areas of its own.
    tile_parts l = {0}, paint = {0};
    dirty_rect *coverage = malloc((count ? count : 1) * sizeof *coverage);
    size_t covered = 0;
    int rc = coverage ? 0 : og_error_set(err, "out of memory composing layers");
    for (size_t i = 0; i < count && rc == 0; i++) {
        tile_key probe = {.layer = (int32_t)rects[i].layer};
        if (tile_key_kind(probe) == TILE_LAYER_COARSE && tile_key_slot(probe) > LAYER_ID_MAX)
            coverage[covered++] = rects[i];
        tile_parts *to = rects[i].layer == TILE_LAYER_COARSE     ? &l
                         : rects[i].layer == TILE_LAYER_MATERIAL ? &paint
                                                                 : NULL;
        if (to && tile_parts_add_rect(to, rects[i].face, rects[i].rect) != 0)
            rc = og_error_set(err, "out of memory composing layers");
    }
    if (rc == 0 && paint.count) rc = paint_take_edit(e, &paint, err);
    if (rc == 0 && l.count)
        rc = run(e, &l, 1, err);
    else
        tile_parts_free(&l);
    if (rc == 0) rc = take_coverage(e, coverage, covered, err);
    tile_parts_free(&paint);
    free(coverage);
    return rc;
}

// ---- a layer's tiles ----------------------------------------------------------------

typedef struct key_list {
    int32_t slot;
    tile_key *keys;
    size_t count, cap;
    int oom;
} key_list;

static int add_key(void *user, tile_key key) {
    key_list *l = user;
    tile_layer kind = tile_key_kind(key);
    if (tile_key_slot(key) != l->slot || key.level != 0 ||
        (kind != TILE_LAYER_COARSE && kind != TILE_LAYER_MATERIAL))
        return 0;
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
    return (x->layer > y->layer) - (x->layer < y->layer);
}

int layer_tiles(world *w, int32_t id, tile_key **keys, size_t *count, og_error *err) {
    key_list l = {.slot = id};
    *keys = NULL;
    *count = 0;
    const tile_layer kinds[2] = {TILE_LAYER_COARSE, TILE_LAYER_MATERIAL};
    for (int k = 0; k < 2; k++) {
        int32_t packed = tile_layer_in_slot(kinds[k], id);
        size_t resident = tile_cache_edited_keys(world_cache(w), packed, NULL, 0);
        if (!resident) continue;
        tile_key *r = malloc(resident * sizeof *r);
        if (!r) {
            free(l.keys);
            return og_error_set(err, "out of memory listing a layer's tiles");
        }
        resident = tile_cache_edited_keys(world_cache(w), packed, r, resident);
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
        if (tile_key_kind(keys[i]) == TILE_LAYER_MATERIAL) { // painted: any coverage
            const uint8_t *m = v.data;
            for (size_t k = 0; k < (size_t)TILE_SAMPLES * TILE_MATERIALS; k++)
                if (m[k]) {
                    ++*filled;
                    break;
                }
        } else {
            const float *f = v.data;
            for (size_t k = 0; k < TILE_SAMPLES; k++)
                if (f[k] == f[k]) {
                    ++*filled;
                    break;
                }
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
    int below;      // merge: the layer index merged into
    float **merged; // merge: each tile's new values, written once all are computed
} tiles_job;

// The same place and kind in another slot.
static tile_key in_slot(tile_key k, int32_t slot) {
    k.layer = tile_layer_in_slot(tile_key_kind(k), slot);
    return k;
}

static int copy_task(void *user, int task, og_error *err) {
    tiles_job *j = user;
    tile_view dst;
    if (edit_tile_acquire(j->e, in_slot(j->keys[task], j->to), &dst, err) != 0) return -1;
    if (j->from < 0 &&
        (tile_key_kind(j->keys[task]) == TILE_LAYER_MATERIAL || j->to > LAYER_ID_MAX)) {
        memset(dst.data, 0, tile_layer_bytes(tile_key_kind(j->keys[task]))); // no coverage
    } else if (j->from < 0) {
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
        memcpy(dst.data, src.data, tile_layer_bytes(tile_key_kind(j->keys[task])));
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
// two showed together. When either is masked, both weights (opacity x mask) are baked in:
// the merged layer becomes an add layer at full opacity without a mask (the caller sets
// that) holding the difference the two made.
static int merge_task(void *user, int task, og_error *err) {
    tiles_job *j = user;
    world *w = edit_world(j->e);
    tile_key key = j->keys[task];
    const layer_info *lo = &j->table.layers[j->below], *hi = &j->table.layers[j->below + 1];
    layer_grid grid;
    if (layer_grid_init(&grid, world_get_params(w), TILE_LAYER_COARSE, key.face, err) != 0)
        return -1;
    int64_t gx = (int64_t)key.tx * TILE_SIZE, gz = (int64_t)key.ty * TILE_SIZE;
    grid_rect r = layer_grid_clip(&grid, (grid_rect){gx, gz, gx + TILE_SIZE, gz + TILE_SIZE});
    if (grid_rect_empty(r)) return 0;
    int rw = (int)(r.x1 - r.x0), rh = (int)(r.z1 - r.z0), x0 = (int)(r.x0 - gx),
        z0 = (int)(r.z0 - gz);
    int bl = height_window_mask_border(lo, grid.spacing),
        bh = height_window_mask_border(hi, grid.spacing);
    int lo_masked = layer_mask_active(&lo->mask), hi_masked = layer_mask_active(&hi->mask);
    int bake = lo_masked || hi_masked;
    // Below the two over r grown by both borders; the lower one's weight and what it shows
    // over r grown by the upper one's border (what the upper mask reads).
    grid_rect mid = height_window_grow(r, bh);
    int mw = rw + 2 * bh, mh = rh + 2 * bh;
    size_t nm = (size_t)mw * mh;
    float *below = NULL, *lov = malloc(sizeof(float) * nm), *wl = malloc(sizeof(float) * nm),
          *shown = malloc(sizeof(float) * nm), *wh = malloc(sizeof(float) * (size_t)rw * rh);
    int rc = lov && wl && shown && wh ? 0 : og_error_set(err, "out of memory merging layers");
    if (rc == 0)
        rc = height_window_compose(edit_world(j->e), &j->table, &grid, r, j->below, bl + bh, -1,
                                   NULL, &below, err);
    layer_grid g = grid;
    g.layer = (tile_layer)tile_layer_in_slot(TILE_LAYER_COARSE, lo->id);
    if (rc == 0) rc = layer_grid_read(w, &g, mid, lov, err);
    if (rc == 0) {
        int bw = mw + 2 * bl; // below's width
        if (lo_masked) rc = height_window_mask(w, lo, &grid, mid, below, bl, wl, err);
        for (size_t k = 0; k < nm; k++) {
            wl[k] = lo_masked ? wl[k] * (float)lo->opacity : (float)lo->opacity;
            int z = (int)(k / (size_t)mw), x = (int)(k % (size_t)mw);
            shown[k] =
                layer_blend_sample(lo->blend, wl[k], below[(size_t)(z + bl) * bw + x + bl], lov[k]);
        }
        if (hi_masked && rc == 0) rc = height_window_mask(w, hi, &grid, r, shown, bh, wh, err);
        for (size_t k = 0; k < (size_t)rw * rh; k++)
            wh[k] = hi_masked ? wh[k] * (float)hi->opacity : (float)hi->opacity;
    }
    // The new values go aside: a neighbour's upper mask reads this tile's lower layer as
    // it was (merge_write_task writes them when every tile is done).
    tile_view lv, hv;
    tile_cache *cache = world_cache(w);
    if (rc == 0 && !(j->merged[task] = malloc(sizeof(float) * TILE_SAMPLES)))
        rc = og_error_set(err, "out of memory merging layers");
    if (rc == 0 && (rc = tile_cache_acquire(cache, in_slot(key, lo->id), &lv, err)) == 0) {
        memcpy(j->merged[task], lv.data, sizeof(float) * TILE_SAMPLES);
        tile_cache_release(cache, &lv);
        if ((rc = tile_cache_acquire(cache, in_slot(key, hi->id), &hv, err)) == 0) {
            float *lo_v = j->merged[task];
            const float *hi_v = hv.data;
            int bw = mw + 2 * bl;
            for (int z = 0; z < rh; z++)
                for (int x = 0; x < rw; x++) {
                    size_t k = (size_t)(z + z0) * TILE_SIZE + x + x0,
                           m = (size_t)(z + bh) * mw + x + bh;
                    float b = below[(size_t)(z + bh + bl) * bw + x + bh + bl];
                    float vh = hi_v[k], whk = wh[(size_t)z * rw + x];
                    if (!bake) {
                        if (vh != vh) continue; // the upper layer has nothing here
                        float both = layer_blend_sample(hi->blend, whk, shown[m], vh);
                        lo_v[k] = layer_blend_solve(lo->blend, wl[m], b, lo_v[k], both);
                        continue;
                    }
                    int lo_none = lo_v[k] != lo_v[k] || !(wl[m] > 0.0f);
                    int hi_none = vh != vh || !(whk > 0.0f);
                    if (lo_none && hi_none) {
                        lo_v[k] = NAN;
                        continue;
                    }
                    float both = layer_blend_sample(hi->blend, whk, shown[m], vh);
                    lo_v[k] = layer_blend_solve(LAYER_BLEND_ADD, 1.0f, b, NAN, both);
                }
            tile_cache_release(cache, &hv);
        }
    }
    free(below);
    free(lov);
    free(wl);
    free(shown);
    free(wh);
    return rc;
}

static int merge_write_task(void *user, int task, og_error *err) {
    tiles_job *j = user;
    tile_view v;
    if (!j->merged[task]) return 0; // outside the world
    if (edit_tile_acquire(j->e, in_slot(j->keys[task], j->table.layers[j->below].id), &v, err) != 0)
        return -1;
    memcpy(v.data, j->merged[task], sizeof(float) * TILE_SAMPLES);
    edit_tile_release(j->e, &v);
    return 0;
}

int layer_merge_tiles(edit *e, int below, const tile_key *keys, size_t count, og_error *err) {
    tiles_job j = {.e = e, .keys = keys, .below = below};
    j.table = world_get_params(edit_world(e))->layers;
    if (!(j.merged = calloc(count ? count : 1, sizeof *j.merged)))
        return og_error_set(err, "out of memory merging layers");
    int rc = parallel_run((int)count, merge_task, &j, err);
    if (rc == 0) rc = parallel_run((int)count, merge_write_task, &j, err);
    for (size_t i = 0; i < count; i++)
        free(j.merged[i]);
    free(j.merged);
    return rc;
}
