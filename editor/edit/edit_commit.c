#include "editor/edit/edit_commit.h"

#include "editor/edit/detail_pd.h"
#include "editor/edit/edit_mips.h"

int edit_commit(edit *e, og_error *err) {
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
    return edit_record(e, err);
}
