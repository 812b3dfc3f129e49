#include "editor/cmd/base_pending.h"

#include "editor/edit/edit_commit.h"
#include "editor/edit/edit_mips.h"
#include "editor/world/layer_grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct base_pending {
    world *world;
    char path[4096];
    import_source src;
    import_options options;
    int journal_paused;
    int copies; // the import is a copy of the raster's samples (no blend, no falloff)
    layer_grid grid;
    int64_t tiles_x, tiles_z; // world tiles (TILE_SIZE samples) over the grid
    unsigned char *done;      // per world tile: imported
    int64_t left;             // tiles not imported yet
    int imports;              // imports made so far
};

base_pending *base_pending_new(world *w, const char *path, import_source *src,
                               const import_options *o, int journal_paused) {
    base_pending *b = calloc(1, sizeof *b);
    og_error ignored;
    if (!b || layer_grid_init(&b->grid, world_get_params(w), TILE_LAYER_COARSE, 0, &ignored) != 0) {
        free(b);
        return NULL;
    }
    b->tiles_x = world_grid_floor_div(b->grid.extent - 1, TILE_SIZE) + 1;
    b->tiles_z = world_grid_floor_div(b->grid.extent_z - 1, TILE_SIZE) + 1;
    b->done = calloc((size_t)(b->tiles_x * b->tiles_z), 1);
    if (!b->done) {
        free(b);
        return NULL;
    }
    b->left = b->tiles_x * b->tiles_z;
    b->world = w;
    snprintf(b->path, sizeof b->path, "%s", path);
    b->src = *src;
    memset(src, 0, sizeof *src);
    b->options = *o;
    b->journal_paused = journal_paused;
    b->copies = o->blend == IMPORT_REPLACE && !(o->falloff > 0);
    return b;
}

// The mip levels past the one where a tile covers the world, summed part by part, differ
// from a whole import's in float rounding (up to that level the filtered sums are exact);
// once the last part is in they are made again as one import of the whole makes them.
static int refilter_deep_levels(base_pending *b, og_error *err) {
    edit *e = edit_begin(b->world, "import (far levels)", err);
    if (!e) return -1;
    edit_set_starting_state(e);
    world_journal_pause(b->world, b->journal_paused);
    int first = edit_mips_tile_cover_level(world_get_params(b->world)) + 1;
    if (edit_mips_refilter_bounded(e, first, err) != 0) {
        edit_abort(e);
        world_journal_pause(b->world, 0);
        return -1;
    }
    int rc = edit_commit(e, err);
    world_journal_pause(b->world, 0);
    return rc;
}

// Imports world tiles [tx0, tx1) x [tz0, tz1), none of them imported yet.
static int import_tiles(base_pending *b, int64_t tx0, int64_t tz0, int64_t tx1, int64_t tz1,
                        og_error *err) {
    import_options o = b->options;
    o.has_limit = 1;
    o.limit = (grid_rect){tx0 * TILE_SIZE, tz0 * TILE_SIZE, tx1 * TILE_SIZE, tz1 * TILE_SIZE};
    world_journal_pause(b->world, b->journal_paused);
    int rc = import_apply_source(b->world, b->path, &b->src, &o, NULL, err);
    world_journal_pause(b->world, 0);
    if (rc != 0) return -1;
    for (int64_t tz = tz0; tz < tz1; tz++)
        memset(b->done + tz * b->tiles_x + tx0, 1, (size_t)(tx1 - tx0));
    b->left -= (tx1 - tx0) * (tz1 - tz0);
    b->imports++;
    return b->left == 0 && b->imports > 1 ? refilter_deep_levels(b, err) : 0;
}

int base_pending_require(base_pending *b, grid_rect r, og_error *err) {
    r = layer_grid_clip(&b->grid, r);
    if (grid_rect_empty(r) || !b->left) return 0;
    const int64_t tx0 = world_grid_floor_div(r.x0, TILE_SIZE),
                  tx1 = world_grid_floor_div(r.x1 - 1, TILE_SIZE) + 1,
                  tz0 = world_grid_floor_div(r.z0, TILE_SIZE),
                  tz1 = world_grid_floor_div(r.z1 - 1, TILE_SIZE) + 1;
    // None of them imported yet: one import (an edit: its compositing and mip levels
    // cover what it wrote). Else one per run of missing tiles along a tile row.
    int none = 1;
    for (int64_t tz = tz0; tz < tz1 && none; tz++)
        for (int64_t tx = tx0; tx < tx1 && none; tx++)
            none = !b->done[tz * b->tiles_x + tx];
    if (none) return import_tiles(b, tx0, tz0, tx1, tz1, err);
    for (int64_t tz = tz0; tz < tz1; tz++)
        for (int64_t tx = tx0; tx < tx1;) {
            if (b->done[tz * b->tiles_x + tx]) {
                tx++;
                continue;
            }
            int64_t end = tx + 1;
            while (end < tx1 && !b->done[tz * b->tiles_x + end])
                end++;
            if (import_tiles(b, tx, tz, end, tz + 1, err) != 0) return -1;
            tx = end;
        }
    return 0;
}

int base_pending_range(const base_pending *b, grid_rect r, double *lo, double *hi) {
    if (!b->copies) return 0;
    r = layer_grid_clip(&b->grid, r);
    const raster *s = &b->src.raster;
    // The world is the raster, sample for sample (cmd_world_from_raster): sample (x, z)
    // is the raster's.
    r = grid_rect_intersect(r, (grid_rect){0, 0, s->width, s->height});
    if (grid_rect_empty(r)) return 0;
    float l = INFINITY, h = -INFINITY;
    for (int64_t z = r.z0; z < r.z1; z++) {
        const float *row = s->samples + (size_t)z * (size_t)s->width;
        for (int64_t x = r.x0; x < r.x1; x++) {
            l = fminf(l, row[x]);
            h = fmaxf(h, row[x]);
        }
    }
    *lo = l, *hi = h;
    return 1;
}

int base_pending_finish(base_pending *b, og_error *err) {
    return base_pending_require(b, (grid_rect){0, 0, b->grid.extent, b->grid.extent_z}, err);
}

void base_pending_free(base_pending *b) {
    if (!b) return;
    import_source_free(&b->src);
    free(b->done);
    free(b);
}

int cmd_base_settle(cmd_context *ctx, og_error *err) {
    if (!ctx->base_pending) return 0;
    if (base_pending_finish(ctx->base_pending, err) != 0) return -1;
    cmd_base_drop(ctx);
    return 0;
}

void cmd_base_drop(cmd_context *ctx) {
    base_pending_free(ctx->base_pending);
    ctx->base_pending = NULL;
}
