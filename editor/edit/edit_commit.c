#include "editor/edit/edit_commit.h"

#include "editor/edit/detail_pd.h"
#include "editor/edit/edit_mips.h"
#include "editor/edit/layer_composite.h"

int edit_commit(edit *e, og_error *err) {
    if (layer_take_edit(e, err) != 0) {
        edit_abort(e);
        return -1;
    }
    edit_record_start(e); // the level-0 deltas, on the other core while the mips follow
    if (edit_mips_update(e, err) != 0) {
        edit_abort(e);
        return -1;
    }
    const dirty_rect *rects;
    size_t count = edit_dirty_rects(e, &rects);
    if (detail_pd_update(edit_world(e), rects, count, err) != 0) {
        edit_abort(e);
        return -1;
    }
    // The detail areas were published as they changed; their slopes (the PD map, which
    // readers of the detail layer take with it) change only now.
    for (size_t i = 0; i < count; i++)
        if (rects[i].layer == TILE_LAYER_DETAIL)
            world_publish_area(edit_world(e), rects[i].layer, rects[i].face, rects[i].rect);
    return edit_record(e, err);
}
