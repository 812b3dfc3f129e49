#include "editor/edit/edit.h"

#include "editor/world/volume_grid.h"

#include "editor/edit/detail_pd.h"
#include "editor/edit/parallel.h"
#include "editor/edit/snapshot_pool.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct snapshot {
    tile_key key;
    int pristine;   // the tile had never been edited (it was generated)
    void *before;   // a whole tile's bytes, of which only `part`'s are copied
    grid_rect part; // tile-local samples acquired for writing (a bounding box)
    int early;      // its delta is edit_record_start's job's
} snapshot;

// Undo deltas to encode: copies of some of an edit's snapshots (adding a snapshot can
// move the edit's array) and where each one's delta goes in the step.
typedef struct encode_job {
    world *world;
    snapshot *snaps;
    size_t *at; // each one's index in the edit's snapshots
    void **deltas;
    size_t *sizes;
    size_t count;
} encode_job;

struct edit {
    world *world;
    char label[128];
    pthread_mutex_t lock;
    snapshot *snaps;
    size_t count, cap;
    size_t *index; // open addressing into snaps (+1; 0 = empty), power-of-two size
    size_t index_size;
    dirty_rect *dirty;
    size_t dirty_count, dirty_cap;
    // Dirty areas [0, this) have reached the mip levels and been published; a coarse
    // area past it is still open (later dabs that touch it grow it).
    size_t mips_current;
    edit_layer_mode layer_mode;
    int starting_state; // edit_set_starting_state: no undo step
    // A change of the world's parameters within the edit (the layer table): applied at
    // once, part of the step, undone by abort.
    int has_params;
    history_params *params; // apart: a zeroed 28 KB per edit (each dab's) otherwise
    // edit_record_start's job, running in the pool while the commit goes on.
    encode_job early;
    int early_open;
};

// Two areas of one grid that overlap or touch (a stroke's dabs): kept as their union.
static int joins(const dirty_rect *a, const dirty_rect *b) {
    return a->layer == b->layer && a->face == b->face && a->rect.x0 <= b->rect.x1 &&
           b->rect.x0 <= a->rect.x1 && a->rect.z0 <= b->rect.z1 && b->rect.z0 <= a->rect.z1;
}

static snapshot *find_snap(edit *e, tile_key key) {
    if (!e->index_size) return NULL;
    for (size_t i = tile_key_hash(key) & (e->index_size - 1);; i = (i + 1) & (e->index_size - 1)) {
        if (!e->index[i]) return NULL;
        snapshot *s = &e->snaps[e->index[i] - 1];
        if (tile_key_equal(s->key, key)) return s;
    }
}

static int reindex(edit *e, size_t size) {
    size_t *index = calloc(size, sizeof *index);
    if (!index) return -1;
    free(e->index);
    e->index = index;
    e->index_size = size;
    for (size_t n = 0; n < e->count; n++) {
        size_t i = tile_key_hash(e->snaps[n].key) & (size - 1);
        while (index[i])
            i = (i + 1) & (size - 1);
        index[i] = n + 1;
    }
    return 0;
}

static snapshot *add_snap(edit *e, tile_key key, int pristine, void *before) {
    if (e->count == e->cap) {
        size_t cap = e->cap ? e->cap * 2 : 64;
        snapshot *s = realloc(e->snaps, cap * sizeof *s);
        if (!s) return NULL;
        e->snaps = s;
        e->cap = cap;
    }
    e->snaps[e->count++] = (snapshot){key, pristine, before, {0, 0, 0, 0}, 0};
    if (e->count * 2 > e->index_size) { // grow: reindex places the new one too
        if (reindex(e, e->index_size ? e->index_size * 2 : 256) != 0) {
            e->count--;
            return NULL;
        }
    } else {
        size_t i = tile_key_hash(key) & (e->index_size - 1);
        while (e->index[i])
            i = (i + 1) & (e->index_size - 1);
        e->index[i] = e->count;
    }
    return &e->snaps[e->count - 1];
}

edit *edit_begin(world *w, const char *label, og_error *err) {
    edit *e = calloc(1, sizeof *e);
    if (!e) {
        og_error_set(err, "out of memory");
        return NULL;
    }
    e->world = w;
    snprintf(e->label, sizeof e->label, "%s", label);
    pthread_mutex_init(&e->lock, NULL);
    return e;
}

world *edit_world(edit *e) {
    return e->world;
}

const void *edit_snapshot(edit *e, tile_key key, grid_rect *part) {
    pthread_mutex_lock(&e->lock);
    snapshot *s = find_snap(e, key);
    const void *before = s ? s->before : NULL;
    if (part) *part = s ? s->part : (grid_rect){0, 0, 0, 0};
    pthread_mutex_unlock(&e->lock);
    return before;
}

void edit_snapshots(edit *e, const tile_key *keys, size_t n, const void **before, grid_rect *part) {
    if (!n) return;
    pthread_mutex_lock(&e->lock);
    for (size_t i = 0; i < n; i++) {
        snapshot *s = find_snap(e, keys[i]);
        before[i] = s ? s->before : NULL;
        part[i] = s ? s->part : (grid_rect){0, 0, 0, 0};
    }
    pthread_mutex_unlock(&e->lock);
}

edit_layer_mode edit_get_layer_mode(const edit *e) {
    return e->layer_mode;
}

void edit_set_starting_state(edit *e) {
    e->starting_state = 1;
}

void edit_set_layer_mode(edit *e, edit_layer_mode mode) {
    e->layer_mode = mode;
}

int edit_set_params(edit *e, const world_params *params, og_error *err) {
    if (!e->params && !(e->params = malloc(sizeof *e->params)))
        return og_error_set(err, "out of memory");
    world_params before = *world_get_params(e->world);
    if (world_regenerate(e->world, params, err) != 0) return -1;
    if (!e->has_params) e->params->before = before;
    e->has_params = 1;
    e->params->after = *world_get_params(e->world);
    return 0;
}

// Tools change the composite; the active layer takes the change (layer_composite.h),
// unless it is hidden or locked: then the tool is refused before it changes anything.
// Heights go into a height layer; paint goes into a paint layer, or with a height layer
// active into the ground's own paint (the base, under every paint layer).
static int check_active_layer(edit *e, tile_key key, og_error *err) {
    if (e->layer_mode == EDIT_LAYER_COMPOSED || key.level != 0 ||
        (key.layer != TILE_LAYER_COARSE && key.layer != TILE_LAYER_MATERIAL))
        return 0;
    const layer_table *t = &world_get_params(e->world)->layers;
    if (!t->count) return 0;
    const layer_info *l = &t->layers[t->active];
    if (key.layer == TILE_LAYER_MATERIAL && l->kind != LAYER_KIND_PAINT) return 0;
    if (key.layer == TILE_LAYER_COARSE && l->kind == LAYER_KIND_PAINT)
        return og_error_set(err,
                            "layer '%s' is a paint layer: it holds materials, not heights "
                            "(select a height layer with 'layer select NAME' to sculpt)",
                            l->name);
    if (!l->visible)
        return og_error_set(err,
                            "layer '%s' is hidden: edits to it would not show (show it with "
                            "'layer set %s visible=1', or select another layer)",
                            l->name, l->name);
    if (l->locked)
        return og_error_set(err,
                            "layer '%s' is locked against edits (unlock it with 'layer set %s "
                            "locked=0', or select another layer)",
                            l->name, l->name);
    return 0;
}

// Copies the tile's samples in part but not yet in s->part into the snapshot (they
// are unchanged: every write of the edit stays inside what it acquired), and grows
// s->part to the bounding box of both.
static void capture(snapshot *s, const void *data, grid_rect part) {
    grid_rect had = s->part, now = grid_rect_empty(had) ? part : grid_rect_union(had, part);
    if (!memcmp(&now, &had, sizeof now)) return;
    size_t el = tile_layer_bytes((tile_layer)s->key.layer) / TILE_SAMPLES;
    uint8_t *dst = s->before;
    const uint8_t *src = data;
    // Rows `had` spans gain only what grew at their sides: often nothing (a stroke's
    // parts grow a strip at a time), so those rows are skipped, not copied 0 bytes twice.
    int sides = had.x0 > now.x0 || now.x1 > had.x1;
    for (int64_t z = now.z0; z < now.z1; z++) {
        size_t row = (size_t)z * TILE_SIZE * el;
        if (grid_rect_empty(had) || z < had.z0 || z >= had.z1) {
            size_t at = row + (size_t)now.x0 * el;
            memcpy(dst + at, src + at, (size_t)(now.x1 - now.x0) * el);
            continue;
        }
        if (!sides) {
            z = had.z1 - 1;
            continue;
        }
        size_t left = row + (size_t)now.x0 * el, right = row + (size_t)had.x1 * el;
        if (had.x0 > now.x0) memcpy(dst + left, src + left, (size_t)(had.x0 - now.x0) * el);
        if (now.x1 > had.x1) memcpy(dst + right, src + right, (size_t)(now.x1 - had.x1) * el);
    }
    s->part = now;
}

int edit_tile_acquire_part(edit *e, tile_key key, grid_rect part, tile_view *view, og_error *err) {
    const void *before;
    grid_rect kept;
    return edit_tile_acquire_snapshot(e, key, part, view, &before, &kept, err);
}

int edit_tile_acquire_snapshot(edit *e, tile_key key, grid_rect part, tile_view *view,
                               const void **before, grid_rect *kept, og_error *err) {
    part = grid_rect_intersect(part, (grid_rect){0, 0, TILE_SIZE, TILE_SIZE});
    if (check_active_layer(e, key, err) != 0) return -1;
    if (tile_cache_acquire_write(world_cache(e->world), key, view, err) != 0) return -1;
    pthread_mutex_lock(&e->lock);
    int rc = 0;
    snapshot *s = find_snap(e, key);
    if (!s) {
        size_t bytes = tile_layer_bytes((tile_layer)key.layer);
        void *copy = snapshot_pool_take(bytes);
        if (!copy || !(s = add_snap(e, key, !view->edited, copy))) {
            snapshot_pool_give(copy, bytes);
            rc = og_error_set(err, "out of memory keeping the undo copy of a tile");
        }
    }
    if (s && !grid_rect_empty(part)) capture(s, view->data, part);
    *before = s ? s->before : NULL;
    *kept = s ? s->part : (grid_rect){0, 0, 0, 0};
    pthread_mutex_unlock(&e->lock);
    if (rc != 0) tile_cache_release(world_cache(e->world), view);
    return rc;
}

int edit_tile_acquire(edit *e, tile_key key, tile_view *view, og_error *err) {
    return edit_tile_acquire_part(e, key, (grid_rect){0, 0, TILE_SIZE, TILE_SIZE}, view, err);
}

void edit_tile_release(edit *e, tile_view *view) {
    tile_cache_release(world_cache(e->world), view);
}

// Layers whose level-0 changes reach mip levels (edit_mips_update): their areas are
// published once those are current.
static int has_mips(tile_layer layer) {
    return layer == TILE_LAYER_COARSE || layer == TILE_LAYER_MATERIAL;
}

void edit_dirty(edit *e, tile_layer layer, int face, grid_rect r) {
    if (grid_rect_empty(r)) return;
    dirty_rect d = {layer, face, r};
    pthread_mutex_lock(&e->lock);
    // Coalesce with the previous rect of the same layer when they touch (a stroke's dabs),
    // unless that is a coarse area whose mips are done: its successor is only the new part.
    dirty_rect *last = e->dirty_count ? &e->dirty[e->dirty_count - 1] : NULL;
    if (last && has_mips(layer) && e->dirty_count <= e->mips_current) last = NULL;
    if (last && joins(last, &d)) {
        last->rect = grid_rect_union(last->rect, r);
    } else {
        if (e->dirty_count == e->dirty_cap) {
            size_t cap = e->dirty_cap ? e->dirty_cap * 2 : 16;
            dirty_rect *grown = realloc(e->dirty, cap * sizeof *grown);
            if (grown) {
                e->dirty = grown;
                e->dirty_cap = cap;
            }
        }
        // Out of memory: the area is still reported live below, only not kept for the step.
        if (e->dirty_count < e->dirty_cap) e->dirty[e->dirty_count++] = d;
    }
    pthread_mutex_unlock(&e->lock);
    // Live: the viewport shows the stroke. Coarse and material areas wait for their mip
    // levels (edit_mips_update publishes them), so the coarser levels are read once, current.
    if (!has_mips(layer)) world_publish_area(e->world, layer, face, r);
}

void edit_publish_from(edit *e, size_t first) {
    for (size_t i = first; i < e->dirty_count; i++)
        if (has_mips(e->dirty[i].layer))
            world_publish_area(e->world, e->dirty[i].layer, e->dirty[i].face, e->dirty[i].rect);
}

size_t edit_mips_current(const edit *e) {
    return e->mips_current;
}

void edit_set_mips_current(edit *e, size_t count) {
    e->mips_current = count;
}

size_t edit_dirty_rects(edit *e, const dirty_rect **rects) {
    *rects = e->dirty;
    return e->dirty_count;
}

static void free_edit(edit *e) {
    for (size_t i = 0; i < e->count; i++)
        snapshot_pool_give(e->snaps[i].before, tile_layer_bytes((tile_layer)e->snaps[i].key.layer));
    free(e->snaps);
    free(e->index);
    free(e->dirty);
    free(e->params);
    pthread_mutex_destroy(&e->lock);
    free(e);
}

static void publish_areas(world *w, const dirty_rect *rects, size_t count) {
    for (size_t i = 0; i < count; i++)
        world_publish_area(w, rects[i].layer, rects[i].face, rects[i].rect);
}

// Puts every snapshot back (writing the tiles' bytes as they were).
static void restore(edit *e) {
    tile_cache *cache = world_cache(e->world);
    for (size_t i = 0; i < e->count; i++) {
        tile_view v;
        og_error err;
        if (tile_cache_acquire_write(cache, e->snaps[i].key, &v, &err) != 0) {
            world_warn(e->world, err.msg);
            continue;
        }
        const snapshot *s = &e->snaps[i];
        size_t el = tile_layer_bytes((tile_layer)s->key.layer) / TILE_SAMPLES;
        for (int64_t z = s->part.z0; z < s->part.z1; z++) {
            size_t at = ((size_t)z * TILE_SIZE + (size_t)s->part.x0) * el;
            memcpy((uint8_t *)v.data + at, (const uint8_t *)s->before + at,
                   (size_t)(s->part.x1 - s->part.x0) * el);
        }
        tile_cache_release(cache, &v);
    }
    og_error err;
    if (e->has_params && world_regenerate(e->world, &e->params->before, &err) != 0)
        world_warn(e->world, err.msg);
    publish_areas(e->world, e->dirty, e->dirty_count);
}

static int early_finish(edit *e, og_error *err);
static void encode_job_free(encode_job *j);

void edit_abort(edit *e) {
    if (!e) return;
    early_finish(e, NULL); // its tasks read the tiles restore writes
    encode_job_free(&e->early);
    restore(e);
    free_edit(e);
}

static void encode_job_free(encode_job *j) {
    for (size_t k = 0; j->deltas && k < j->count; k++)
        free(j->deltas[k]);
    free(j->snaps), free(j->at), free(j->deltas), free(j->sizes);
    *j = (encode_job){0};
}

// The job of e's snapshots whose early flag is `early`; -1 when out of memory.
static int encode_job_init(encode_job *j, const edit *e, int early) {
    *j = (encode_job){.world = e->world};
    size_t n = 0;
    for (size_t i = 0; i < e->count; i++)
        n += e->snaps[i].early == early;
    j->snaps = malloc((n ? n : 1) * sizeof *j->snaps);
    j->at = malloc((n ? n : 1) * sizeof *j->at);
    j->deltas = calloc(n ? n : 1, sizeof *j->deltas);
    j->sizes = calloc(n ? n : 1, sizeof *j->sizes);
    if (!j->snaps || !j->at || !j->deltas || !j->sizes) {
        encode_job_free(j);
        return -1;
    }
    for (size_t i = 0; i < e->count; i++)
        if (e->snaps[i].early == early) j->snaps[j->count] = e->snaps[i], j->at[j->count++] = i;
    return 0;
}

// Moves the job's deltas to their places in the step's.
static void encode_job_take(encode_job *j, void **deltas, size_t *sizes) {
    for (size_t k = 0; k < j->count; k++) {
        deltas[j->at[k]] = j->deltas[k], sizes[j->at[k]] = j->sizes[k];
        j->deltas[k] = NULL;
    }
}

static int encode_task(void *user, int task, og_error *err) {
    encode_job *j = user;
    const snapshot *s = &j->snaps[task];
    tile_view v;
    if (tile_cache_acquire(world_cache(j->world), s->key, &v, err) != 0) return -1;
    int rc = history_delta_encode_part_quick((tile_layer)s->key.layer, s->before, v.data, s->part,
                                             &j->deltas[task], &j->sizes[task]);
    tile_cache_release(world_cache(j->world), &v);
    return rc != 0 ? og_error_set(err, "out of memory recording the undo step") : 0;
}

// The early job finished (its deltas dropped unless taken).
static int early_finish(edit *e, og_error *err) {
    if (!e->early_open) return 0;
    int rc = parallel_finish(err);
    e->early_open = 0;
    return rc;
}

// Level-0 height tiles: once the layer take is done, nothing later in a commit writes
// them (the mip levels are above them), a dab's two largest deltas (the composite's and
// the active layer's). Up to a few tiles: a stamp's many keep the pool for its mips.
enum { EARLY_MAX_TILES = 8 };

void edit_record_start(edit *e) {
    if (e->starting_state || e->early_open) return;
    size_t n = 0;
    for (size_t i = 0; i < e->count; i++)
        n += tile_key_kind(e->snaps[i].key) == TILE_LAYER_COARSE && e->snaps[i].key.level == 0;
    if (!n || n > EARLY_MAX_TILES) return;
    for (size_t i = 0; i < e->count; i++)
        e->snaps[i].early =
            tile_key_kind(e->snaps[i].key) == TILE_LAYER_COARSE && e->snaps[i].key.level == 0;
    if (encode_job_init(&e->early, e, 1) != 0) {
        for (size_t i = 0; i < e->count; i++)
            e->snaps[i].early = 0;
        return;
    }
    e->early_open = 1;
    parallel_start((int)e->early.count, encode_task, &e->early);
}

static void report_dropped(world *w, size_t dropped) {
    if (!dropped) return;
    history *h = world_history(w);
    char msg[256];
    snprintf(msg, sizeof msg,
             "history: dropped the %zu oldest undo step%s to stay within the %zu MiB history "
             "budget (%zu steps left)",
             dropped, dropped == 1 ? "" : "s", history_budget(h) >> 20, history_count(h));
    world_warn(w, msg);
}

int edit_record(edit *e, og_error *err) {
    if (e->starting_state) { // nothing to go back to: no deltas to encode or keep
        edit_publish_from(e, e->mips_current);
        free_edit(e);
        return 0;
    }
    history_step *step = history_step_new(e->label);
    void **deltas = calloc(e->count ? e->count : 1, sizeof *deltas);
    size_t *sizes = calloc(e->count ? e->count : 1, sizeof *sizes);
    encode_job job = {0};
    int failed = !step || !deltas || !sizes || encode_job_init(&job, e, 0) != 0;
    if (failed) og_error_set(err, "out of memory recording the undo step");
    // The rest while the early job's level-0 tiles finish beside it.
    if (!failed) failed = parallel_run((int)job.count, encode_task, &job, err) != 0;
    og_error early_err;
    if (early_finish(e, &early_err) != 0 && !failed) failed = 1, *err = early_err;
    if (!failed) {
        encode_job_take(&job, deltas, sizes);
        encode_job_take(&e->early, deltas, sizes);
    }
    encode_job_free(&job);
    encode_job_free(&e->early);
    for (size_t i = 0; i < e->count && !failed; i++)
        if (deltas[i] && history_step_add_delta(step, e->snaps[i].key, e->snaps[i].pristine,
                                                deltas[i], sizes[i]) != 0)
            failed = og_error_set(err, "out of memory recording the undo step");
        else
            deltas[i] = NULL;
    for (size_t i = 0; i < e->dirty_count && !failed; i++) {
        // The step holds a stroke's touching areas as one, as edit_dirty kept them
        // before the mip levels split them.
        dirty_rect *last = step->dirty_count ? &step->dirty[step->dirty_count - 1] : NULL;
        if (last && joins(last, &e->dirty[i]))
            last->rect = grid_rect_union(last->rect, e->dirty[i].rect);
        else if (history_step_add_dirty(step, e->dirty[i]) != 0)
            failed = og_error_set(err, "out of memory recording the undo step");
    }
    if (!failed && e->has_params &&
        history_step_set_params(step, &e->params->before, &e->params->after) != 0)
        failed = og_error_set(err, "out of memory recording the undo step");
    if (failed) {
        for (size_t i = 0; i < e->count; i++)
            free(deltas ? deltas[i] : NULL);
        free(deltas);
        free(sizes);
        history_step_free(step);
        edit_abort(e);
        return -1;
    }
    // A never-edited tile the edit touched without changing (the brush's edge): back to
    // generated terrain, as if untouched, so a later `generate` changes it like its
    // neighbours; the undo step has no record of it, so a replay (recover) agrees. It
    // keeps its samples (they are the generated ones): discarded, the next edit there
    // generated it again (a 512^2 stamp regenerated the 8 tiles its edges graze, 40% of
    // its CPU time). The journal rarely holds such a tile: look before deleting (a delete
    // is a synchronous write, milliseconds per tile on every stamp that grazes one).
    tile_cache *cache = world_cache(e->world);
    tile_store *journal = world_journal(e->world);
    for (size_t i = 0; i < e->count; i++) {
        og_error ignored;
        if (!sizes[i] && e->snaps[i].pristine &&
            tile_cache_mark_generated(cache, e->snaps[i].key) == 0 && journal &&
            tile_store_has(journal, e->snaps[i].key))
            tile_store_put(journal, e->snaps[i].key, NULL, &ignored);
    }
    free(deltas);
    free(sizes);
    // Every area was published once already, as it changed (edit_dirty) or when its mip
    // levels were (edit_mips_update); only coarse and material areas no mip update saw are left.
    edit_publish_from(e, e->mips_current);
    world *w = e->world;
    free_edit(e);
    if (step->tile_count == 0 && !step->has_params) { // nothing changed: no step
        history_step_free(step);
        return 0;
    }
    report_dropped(w, history_push(world_history(w), step));
    world_journal_record(w, RECOVERY_STEP, step);
    world_publish(w, &(world_event){.kind = WORLD_EVENT_HISTORY});
    return 0;
}

// ---- replay ----------------------------------------------------------------------

typedef struct replay_job {
    world *world;
    const history_step *step;
    int undo;
} replay_job;

static int replay_task(void *user, int task, og_error *err) {
    replay_job *j = user;
    const history_tile *t = &j->step->tiles[task];
    tile_cache *cache = world_cache(j->world);
    tile_view v;
    if (tile_cache_acquire_write(cache, t->key, &v, err) != 0) return -1;
    int rc = 0;
    if (history_tile_apply(t, v.data) != 0)
        rc = og_error_set(err, "undo data of a tile is damaged (out of memory?)");
    tile_cache_release(cache, &v);
    // Back to never-edited terrain: the tile holds its generated heights again and
    // counts as generated (a later `generate` changes it like any untouched tile). It
    // stays in memory: forgetting it would leave the viewport a gap until it
    // regenerated. A tile saved since then is not pristine any more: the saved store
    // holds it.
    tile_store *saved = world_store(j->world);
    og_error ignored;
    if (j->undo && t->was_pristine && !(saved && tile_store_has(saved, t->key)) &&
        tile_cache_mark_generated(cache, t->key) == 0)
        tile_store_put(world_journal(j->world), t->key, NULL, &ignored);
    return rc;
}

// Whether a step with parameters changed what the terrain is (else only its look).
static int step_regenerates(const history_step *s) {
    world_params a = s->params->before, b = s->params->after;
    a.material_rules = b.material_rules;
    char *ta = world_params_format(&a), *tb = world_params_format(&b);
    int differ = !ta || !tb || strcmp(ta, tb) != 0;
    free(ta), free(tb);
    return differ;
}

int edit_apply_step(world *w, const history_step *s, int undo, og_error *err) {
    const world_params *to = !s->has_params ? NULL : undo ? &s->params->before : &s->params->after;
    if (s->has_params && step_regenerates(s) && world_regenerate(w, to, err) != 0) return -1;
    if (s->has_params) world_set_material_rules(w, &to->material_rules);
    replay_job job = {w, s, undo};
    if (parallel_run((int)s->tile_count, replay_task, &job, err) != 0) return -1;
    if (detail_pd_update(w, s->dirty, s->dirty_count, err) != 0) return -1;
    publish_areas(w, s->dirty, s->dirty_count);
    return 0;
}

int edit_undo(world *w, og_error *err) {
    history *h = world_history(w);
    history_step *s = history_undo_peek(h);
    if (!s) return 0;
    if (edit_apply_step(w, s, 1, err) != 0) return -1;
    history_undo_done(h);
    world_journal_record(w, RECOVERY_UNDO, s);
    world_publish(w, &(world_event){.kind = WORLD_EVENT_HISTORY});
    return 1;
}

int edit_redo(world *w, og_error *err) {
    history *h = world_history(w);
    history_step *s = history_redo_peek(h);
    if (!s) return 0;
    if (edit_apply_step(w, s, 0, err) != 0) return -1;
    history_redo_done(h);
    world_journal_record(w, RECOVERY_REDO, s);
    world_publish(w, &(world_event){.kind = WORLD_EVENT_HISTORY});
    return 1;
}

int edit_material_rules(world *w, const material_rules *rules, const char *label, og_error *err) {
    history_step *s = history_step_new(label);
    world_params before = *world_get_params(w);
    if (!s || history_step_set_params(s, &before, &before) != 0) {
        history_step_free(s);
        return og_error_set(err, "out of memory recording the undo step");
    }
    world_set_material_rules(w, rules);
    s->params->after = *world_get_params(w);
    report_dropped(w, history_push(world_history(w), s));
    world_journal_record(w, RECOVERY_STEP, s);
    world_publish(w, &(world_event){.kind = WORLD_EVENT_HISTORY});
    return 0;
}

static double voxel_size(const world_params *p) {
    return p->spacing / (p->volume_ratio > 0 ? p->volume_ratio : 1);
}

int edit_generate_check(world *w, const world_params *params, og_error *err) {
    const world_params *before = world_get_params(w);
    // Volume edits are stored per voxel: a new voxel size would move and stretch them.
    if (params->kind == WORLD_FLAT && before->kind == WORLD_FLAT &&
        voxel_size(params) != voxel_size(before)) {
        int has = 0;
        if (volume_has_edits(w, &has, err) != 0) return -1;
        if (has)
            return og_error_set(err,
                                "spacing / volume_ratio: the world has volume edits (caves, "
                                "overhangs) on %g m voxels; keep spacing / volume_ratio at %g m",
                                voxel_size(before), voxel_size(before));
    }
    return 0;
}

int edit_generate(world *w, const world_params *wanted, og_error *err) {
    world_params before = *world_get_params(w);
    // The layers are the world's, whatever parameters the caller started from.
    world_params next = *wanted;
    next.layers = before.layers;
    const world_params *params = &next;
    if (edit_generate_check(w, params, err) != 0) return -1;
    if (world_regenerate(w, params, err) != 0) return -1;
    history_step *s = history_step_new("generate");
    if (!s || history_step_set_params(s, &before, world_get_params(w)) != 0) {
        history_step_free(s);
        return og_error_set(err, "out of memory recording the undo step");
    }
    report_dropped(w, history_push(world_history(w), s));
    world_journal_record(w, RECOVERY_STEP, s);
    world_publish(w, &(world_event){.kind = WORLD_EVENT_HISTORY});
    return 0;
}
