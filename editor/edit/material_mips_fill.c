// Builds the material mip levels a world saved without them lacks (material_mips_fill.h).
#include "editor/edit/material_mips_fill.h"

#include "editor/edit/edit.h"
#include "editor/edit/edit_commit.h"
#include "editor/edit/edit_mips.h"
#include "io/tile_store.h"

#include <stdio.h>
#include <stdlib.h>

typedef struct painted_tiles {
    tile_key *keys; // the composite's level-0 material tiles
    size_t count, cap;
    int64_t mips; // composite material tiles above level 0
    int out_of_memory;
} painted_tiles;

static int collect(void *user, tile_key key) {
    painted_tiles *p = user;
    if (tile_key_kind(key) != TILE_LAYER_MATERIAL || tile_key_slot(key) != 0 || key.face != 0)
        return 0;
    if (key.level > 0) {
        p->mips++;
        return 0;
    }
    if (p->count == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 64;
        tile_key *k = realloc(p->keys, cap * sizeof *k);
        if (!k) return p->out_of_memory = 1;
        p->keys = k, p->cap = cap;
    }
    p->keys[p->count++] = key;
    return 0;
}

static int64_t fill(world *w, og_error *err) {
    tile_store *store = world_store(w);
    if (!store || world_get_params(w)->kind == WORLD_PLANET) return 0;
    painted_tiles p = {0};
    if (tile_store_each(store, collect, &p, err) != 0 || p.out_of_memory) {
        free(p.keys);
        if (p.out_of_memory) og_error_set(err, "out of memory listing the painted tiles");
        return -1;
    }
    if (p.count == 0 || p.mips > 0) {
        free(p.keys);
        return 0;
    }
    edit *e = edit_begin(w, "material mips", err);
    if (!e) {
        free(p.keys);
        return -1;
    }
    edit_set_starting_state(e);
    // A tile at a time: each call builds the levels over what changed since the last,
    // so paint far apart never makes one mip area spanning the space between.
    for (size_t i = 0; i < p.count; i++) {
        grid_rect r = {(int64_t)p.keys[i].tx * TILE_SIZE, (int64_t)p.keys[i].ty * TILE_SIZE,
                       ((int64_t)p.keys[i].tx + 1) * TILE_SIZE,
                       ((int64_t)p.keys[i].ty + 1) * TILE_SIZE};
        edit_dirty(e, TILE_LAYER_MATERIAL, 0, r);
        if (edit_mips_update(e, err) != 0) {
            edit_abort(e);
            free(p.keys);
            return -1;
        }
    }
    int64_t n = (int64_t)p.count;
    free(p.keys);
    return edit_commit(e, err) != 0 ? -1 : n;
}

int64_t material_mips_fill_missing(world *w) {
    og_error err = {{0}};
    int64_t n = fill(w, &err);
    if (n < 0) {
        char msg[1400];
        snprintf(msg, sizeof msg,
                 "%s: the paint's far levels could not be built (%s); it shows as painted "
                 "from near and as the automatic materials from afar until repainted",
                 world_path(w), err.msg);
        world_warn(w, msg);
    }
    return n;
}
