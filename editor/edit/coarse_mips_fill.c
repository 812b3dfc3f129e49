// Rebuilds the coarse mip levels a world saved without them lacks (coarse_mips_fill.h).
#include "editor/edit/coarse_mips_fill.h"

#include "editor/edit/edit.h"
#include "editor/edit/edit_commit.h"
#include "editor/edit/edit_mips.h"
#include "io/tile_store.h"

#include <stdio.h>

typedef struct saved_levels {
    int cover;                // the level where one tile covers the world
    int at_cover, past_cover; // composite coarse tiles saved at it and at the next
} saved_levels;

static int count(void *user, tile_key key) {
    saved_levels *s = user;
    if (tile_key_kind(key) != TILE_LAYER_COARSE || tile_key_slot(key) != 0 || key.face != 0)
        return 0;
    s->at_cover += key.level == s->cover;
    s->past_cover += key.level == s->cover + 1;
    return 0;
}

static int fill(world *w, og_error *err) {
    tile_store *store = world_store(w);
    const world_params *p = world_get_params(w);
    if (!store || p->kind == WORLD_PLANET || p->size <= 0) return 0;
    saved_levels s = {.cover = edit_mips_tile_cover_level(p)};
    if (s.cover >= edit_mips_top_level(p)) return 0;
    if (tile_store_each(store, count, &s, err) != 0) return -1;
    if (!s.at_cover || s.past_cover) return 0;
    edit *e = edit_begin(w, "coarse mips", err);
    if (!e) return -1;
    edit_set_starting_state(e);
    if (edit_mips_refilter_bounded(e, s.cover + 1, err) != 0) {
        edit_abort(e);
        return -1;
    }
    return edit_commit(e, err) != 0 ? -1 : 1;
}

int coarse_mips_fill_missing(world *w) {
    og_error err = {{0}};
    int n = fill(w, &err);
    if (n < 0) {
        char msg[1400];
        snprintf(msg, sizeof msg,
                 "%s: the heights' far levels could not be rebuilt (%s); from afar the world "
                 "shows its generated heights until it is edited again",
                 world_path(w), err.msg);
        world_warn(w, msg);
    }
    return n;
}
