#include "app/notices.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void notices_add(notices *n, const char *text) {
    if (n->count > 0 && strcmp(n->text[n->count - 1], text) == 0) return;
    if (n->count == NOTICES_MAX) notices_dismiss(n, 0);
    snprintf(n->text[n->count++], sizeof n->text[0], "%s", text);
}

void notices_dismiss(notices *n, int i) {
    if (i < 0 || i >= n->count) return;
    memmove(n->text[i], n->text[i + 1], (size_t)(n->count - i - 1) * sizeof n->text[0]);
    n->count--;
}

// Rows a notice needs at width w (as ui_label_wrapped breaks it), to size the panel.
static int rows_for(const ui_context *ui, const char *text, float w) {
    float tw = ui_font_text_width(ui_get_font(ui), UI_FACE_SANS, text, strlen(text));
    int rows = (int)(tw / (w > 1 ? w : 1)) + 1;
    return rows + rows / 3; // breaks between words leave some of each row empty
}

void notices_draw(notices *n, ui_context *ui, ui_rect area) {
    if (n->count == 0) return;
    float pad = ui_em(ui, 0.3f), button = ui_em(ui, 4.5f);
    float row = ui_em(ui, 1.4f) + ui_em(ui, 0.2f);
    float text_w = area.w - 4 * pad;
    int rows = 0;
    for (int i = 0; i < n->count; i++)
        rows += rows_for(ui, n->text[i], text_w) + 1; // and its button's
    float h = fminf(rows * row + 2 * pad, area.h * 0.5f);
    ui_panel_begin(ui, "Notices", (ui_rect){area.x + pad, area.y + pad, area.w - 2 * pad, h});
    const ui_theme *theme = ui_get_theme(ui);
    int dismissed = -1;
    for (int i = 0; i < n->count; i++) {
        char name[32];
        snprintf(name, sizeof name, "Dismiss##%d", i);
        ui_label_wrapped(ui, n->text[i], theme->text_error);
        float widths[2] = {0, button};
        ui_row(ui, 2, widths, 0);
        ui_next_cell(ui); // the button at the right, under its text
        if (ui_button(ui, name)) dismissed = i;
        ui_tooltip(ui, "Close this message");
    }
    ui_panel_end(ui);
    notices_dismiss(n, dismissed);
}
