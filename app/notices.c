#include "app/notices.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

static void add(notices *n, const char *text, double passes_at) {
    if (n->count > 0 && strcmp(n->text[n->count - 1], text) == 0) {
        double *last = &n->passes_at[n->count - 1];
        if (*last != 0) *last = passes_at; // shown again: from now, or for good
        return;
    }
    if (n->count == NOTICES_MAX) notices_dismiss(n, 0);
    n->passes_at[n->count] = passes_at;
    snprintf(n->text[n->count++], sizeof n->text[0], "%s", text);
}

void notices_add(notices *n, const char *text) {
    add(n, text, 0);
}

// The commands that read or write files: their failures stay (a path to fix, a file
// that was not written).
static int file_command(const char *command) {
    static const char *const names[] = {"load", "save",    "import",  "export",
                                        "new",  "history", "recover", "stamp_add"};
    size_t len = strcspn(command, " \t;");
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strlen(names[i]) == len && strncmp(command, names[i], len) == 0) return 1;
    return 0;
}

void notices_add_failure(notices *n, const char *command, const char *text, double now) {
    while (*command == ' ')
        command++;
    add(n, text, file_command(command) ? 0 : now + NOTICES_PASS_SECONDS);
}

int notices_due(const notices *n, double now) {
    for (int i = 0; i < n->count; i++)
        if (n->passes_at[i] != 0 && n->passes_at[i] <= now) return 1;
    return 0;
}

// Drops the notices `gone` says, keeping the others' order.
static int drop_where(notices *n, double now, int all_passing) {
    int kept = 0, dropped = 0;
    for (int i = 0; i < n->count; i++) {
        int gone = n->passes_at[i] != 0 && (all_passing || n->passes_at[i] <= now);
        if (gone) {
            dropped = 1;
            continue;
        }
        if (kept != i) {
            memcpy(n->text[kept], n->text[i], sizeof n->text[0]);
            n->passes_at[kept] = n->passes_at[i];
        }
        kept++;
    }
    n->count = kept;
    return dropped;
}

int notices_expire(notices *n, double now) {
    return drop_where(n, now, 0);
}

void notices_clear_passing(notices *n) {
    drop_where(n, 0, 1);
}

int notices_user_action(const char *label) {
    return strcmp(label, "console") != 0 && strcmp(label, "radius") != 0 &&
           strcmp(label, "planet") != 0;
}

void notices_dismiss(notices *n, int i) {
    if (i < 0 || i >= n->count) return;
    memmove(n->text[i], n->text[i + 1], (size_t)(n->count - i - 1) * sizeof n->text[0]);
    memmove(n->passes_at + i, n->passes_at + i + 1,
            (size_t)(n->count - i - 1) * sizeof n->passes_at[0]);
    n->count--;
}

double notices_now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
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
