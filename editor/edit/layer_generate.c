#include "editor/edit/layer_generate.h"

#include "editor/edit/edit_commit.h"
#include "editor/edit/layer_composite.h"

#include <stdlib.h>
#include <string.h>

int layer_generate(world *w, const world_params *wanted, og_error *err) {
    world_params next = *wanted;
    next.layers = world_get_params(w)->layers;
    if (edit_generate_check(w, &next, err) != 0) return -1;
    // Every visible layer's tiles, before the switch (the store is the same after it).
    tile_key *all = NULL;
    size_t count = 0;
    for (int i = 0; i < next.layers.count; i++) {
        if (!next.layers.layers[i].visible) continue;
        tile_key *keys;
        size_t n;
        if (layer_tiles(w, next.layers.layers[i].id, &keys, &n, err) != 0) {
            free(all);
            return -1;
        }
        tile_key *grown = n ? realloc(all, (count + n) * sizeof *grown) : all;
        if (n && !grown) {
            free(keys);
            free(all);
            return og_error_set(err, "out of memory listing the layers' tiles");
        }
        all = grown;
        if (n) memcpy(all + count, keys, n * sizeof *keys);
        count += n;
        free(keys);
    }
    edit *e = edit_begin(w, "generate", err);
    int rc = e ? 0 : -1;
    if (e) edit_set_layer_mode(e, EDIT_LAYER_COMPOSED);
    if (rc == 0) rc = edit_set_params(e, &next, err);
    if (rc == 0) rc = layer_recompose_tiles(e, all, count, err); // each tile once (merge_parts)
    free(all);
    if (!e) return -1;
    if (rc != 0) {
        edit_abort(e);
        return -1;
    }
    return edit_commit(e, err);
}
