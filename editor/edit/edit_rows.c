#include "editor/edit/edit_rows.h"

#include "editor/edit/parallel.h"
#include "editor/params/world_grid.h"
#include "io/progress.h"

#include <stdatomic.h>

static size_t sample_bytes(tile_layer layer) {
    return layer == TILE_LAYER_MATERIAL ? TILE_MATERIALS : sizeof(float);
}

typedef struct rows_job {
    edit *e;
    const layer_grid *g;
    grid_rect r;
    int64_t tx0, tz0, tw;
    edit_row_fn fn;
    edit_rows_wanted_fn wanted;
    edit_rows_narrow_fn narrow;
    void *user;
    og_progress *progress; // the calling thread's (tasks run on the pool's threads)
    atomic_long tiles_done;
    long tiles;
} rows_job;

static int rows_task(void *user, int task, og_error *err) {
    rows_job *j = user;
    if (og_progress_cancelled(j->progress)) return og_error_set(err, "cancelled");
    int64_t tx = j->tx0 + task % j->tw, tz = j->tz0 + task / j->tw;
    grid_rect t =
        grid_rect_intersect(j->r, (grid_rect){tx * TILE_SIZE, tz * TILE_SIZE, (tx + 1) * TILE_SIZE,
                                              (tz + 1) * TILE_SIZE});
    if (grid_rect_empty(t) || (j->wanted && !j->wanted(j->user, t))) return 0;
    if (j->narrow && (!j->narrow(j->user, &t) || grid_rect_empty(t))) return 0;
    tile_key key = {j->g->layer, j->g->face, 0, (int32_t)tx, (int32_t)tz};
    tile_view v;
    grid_rect local = {t.x0 - tx * TILE_SIZE, t.z0 - tz * TILE_SIZE, t.x1 - tx * TILE_SIZE,
                       t.z1 - tz * TILE_SIZE};
    if (edit_tile_acquire_part(j->e, key, local, &v, err) != 0) return -1;
    size_t bytes = sample_bytes(j->g->layer);
    for (int64_t z = t.z0; z < t.z1; z++) {
        size_t at = (size_t)((z - tz * TILE_SIZE) * TILE_SIZE + (t.x0 - tx * TILE_SIZE));
        j->fn(j->user, (uint8_t *)v.data + at * bytes, z, t.x0, t.x1);
    }
    edit_tile_release(j->e, &v);
    long done = atomic_fetch_add(&j->tiles_done, 1) + 1;
    // The bar is written from whichever thread finished a tile: only its fraction grows.
    if (j->progress) og_progress_report(j->progress, done, j->tiles);
    return 0;
}

static int apply(edit *e, const layer_grid *g, grid_rect r, edit_row_fn fn,
                 edit_rows_wanted_fn wanted, edit_rows_narrow_fn narrow, void *user,
                 og_error *err) {
    if (grid_rect_empty(r)) return 0;
    rows_job job = {
        .e = e, .g = g, .r = r, .fn = fn, .wanted = wanted, .narrow = narrow, .user = user};
    job.tx0 = world_grid_floor_div(r.x0, TILE_SIZE);
    job.tz0 = world_grid_floor_div(r.z0, TILE_SIZE);
    job.tw = world_grid_floor_div(r.x1 - 1, TILE_SIZE) - job.tx0 + 1;
    int64_t th = world_grid_floor_div(r.z1 - 1, TILE_SIZE) - job.tz0 + 1;
    job.progress = og_progress_current();
    job.tiles = (long)(job.tw * th);
    atomic_init(&job.tiles_done, 0);
    if (parallel_run((int)(job.tw * th), rows_task, &job, err) != 0) return -1;
    edit_dirty(e, g->layer, g->face, r);
    return 0;
}

int edit_rows_apply(edit *e, const layer_grid *g, grid_rect r, edit_row_fn fn,
                    edit_rows_wanted_fn wanted, void *user, og_error *err) {
    return apply(e, g, r, fn, wanted, NULL, user, err);
}

int edit_rows_apply_narrowed(edit *e, const layer_grid *g, grid_rect r, edit_row_fn fn,
                             edit_rows_narrow_fn narrow, void *user, og_error *err) {
    return apply(e, g, r, fn, NULL, narrow, user, err);
}

void edit_rows_apply_array(tile_layer layer, void *data, grid_rect area, grid_rect r,
                           edit_row_fn fn, void *user) {
    size_t bytes = sample_bytes(layer);
    int64_t aw = area.x1 - area.x0;
    for (int64_t z = r.z0; z < r.z1; z++)
        fn(user, (uint8_t *)data + ((z - area.z0) * aw + (r.x0 - area.x0)) * bytes, z, r.x0, r.x1);
}
