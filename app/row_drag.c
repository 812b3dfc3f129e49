#include "app/row_drag.h"

#include <math.h>

void row_drag_watch(row_drag *d, const ui_context *ui, int row) {
    const ui_input *in = ui_get_input(ui);
    if (!ui_last_hovered(ui) || !in->mouse_pressed[0]) return;
    d->pressed = row + 1;
    d->press_y = in->mouse_y;
    d->dragging = 0;
}

int row_drag_active(const row_drag *d) {
    return d->pressed && d->dragging;
}

int row_drag_update(row_drag *d, ui_context *ui, const ui_rect *rows, int count, int *from,
                    int *to) {
    const ui_input *in = ui_get_input(ui);
    int f = d->pressed - 1, t = -1;
    if (f < 0 || f >= count) {
        d->pressed = 0;
        return 0;
    }
    if (fabsf(in->mouse_y - d->press_y) > ui_em(ui, 0.6f)) d->dragging = 1;
    // The row whose span holds the pointer; between two rows, the nearer.
    float best = INFINITY;
    for (int i = 0; i < count; i++) {
        float mid = rows[i].y + rows[i].h * 0.5f, dist = fabsf(in->mouse_y - mid);
        if (dist < best) best = dist, t = i;
    }
    if (d->dragging && t >= 0 && t != f) { // a line on the side it would land on
        ui_rect r = rows[t];
        float y = rows[t].y < rows[f].y ? r.y - 1 : r.y + r.h + 1;
        ui_draw_rect(ui_draw_target(ui), (ui_rect){r.x, y - 1, r.w, 3},
                     ui_get_theme(ui)->accent_hot);
    }
    if (in->mouse_down[0]) return 0;
    int moved = d->dragging && t >= 0 && t != f;
    d->pressed = 0;
    d->dragging = 0;
    if (!moved) return 0;
    *from = f, *to = t;
    return 1;
}
