// The Layers panel: the world's edit layers top first, each a row with its eye and lock,
// its name (click: the tools' layer; double click: rename; drag: move it in the stack;
// right click: rename, duplicate, merge down, clear, delete, export), its blend and
// opacity, and a Mask button opening the mask editor (app/mask_editor.c): each term's
// range over a histogram of the composite's heights and slopes around the view, drawn
// live over the terrain while it is dragged. Every change runs a layer command (echoed,
// one undo step); nothing here writes world data. The histogram is a read-only query
// (editor/world/terrain_histogram.h), made while no job runs: the window builds its
// panels only then (app/work_queue.h).
#include "app/editor_ui_internal.h"

#include "app/layers_panel_state.h"

#include <unistd.h>

// The export dialog on layer name: NAME.exr in the folder of the last export or import
// (else the world's, else the working one), its change by default.
static void export_layer(editor_ui *e, cmd_context *ctx, const char *name) {
    char folder[4096] = "";
    const char *from =
        strchr(e->interchange.path, '/') ? e->interchange.path : world_path(ctx->world);
    const char *slash = strrchr(from, '/');
    if (slash)
        snprintf(folder, sizeof folder, "%.*s", (int)(slash - from), from);
    else if (!getcwd(folder, sizeof folder))
        snprintf(folder, sizeof folder, ".");
    char path[4200];
    snprintf(path, sizeof path, "%s/%s.exr", folder, name);
    const world_params *p = world_get_params(ctx->world);
    double bounded =
        p->kind != WORLD_PLANET && p->size > 0 ? (double)(p->size - 1) * p->spacing : 0;
    interchange_dialog *d = &e->interchange;
    interchange_dialog_show(d, 1, path, bounded, p->max_height, e->view_x, e->view_z);
    d->planet = 0;
    d->bits16 = 0;
    snprintf(d->layer_name, sizeof d->layer_name, "%s", name);
    d->layer_what = 0;
}

// As editor/edit/edit.c refuses a tool on the active layer: height tools on a paint
// layer, any tool on a hidden or locked one (paint on a height layer goes to the ground's
// own paint, refused never), mask painting without a painted mask.
int editor_ui_tool_refused(const cmd_context *ctx, char *why, size_t len) {
    const layer_table *t = &world_get_params(ctx->world)->layers;
    const brush *b = &ctx->brush;
    if (!t->count || brush_tool_is_volume(b->tool) || (b->target == TILE_LAYER_DETAIL && !b->mask))
        return 0;
    const layer_info *l = &t->layers[t->active];
    int paint = b->tool == BRUSH_PAINT && !b->mask;
    if (paint && l->kind != LAYER_KIND_PAINT) return 0;
    if (!paint && !b->mask && l->kind == LAYER_KIND_PAINT)
        snprintf(why, len, "layer %s holds paint: %s refused", l->name, current_tool(b));
    else if (!l->visible || l->locked)
        snprintf(why, len, "layer %s is %s: %s refused", l->name, l->visible ? "locked" : "hidden",
                 current_tool(b));
    else if (b->mask && !l->mask.painted)
        snprintf(why, len, "layer %s has no painted mask: %s refused", l->name, current_tool(b));
    else
        return 0;
    return 1;
}

// An eye (open: the layer shows; shut with a stroke: hidden) in box r.
static void eye_icon(ui_context *ui, ui_rect r, int open, ui_color c) {
    ui_draw_list *dl = ui_draw_target(ui);
    float cx = r.x + r.w * 0.5f, cy = r.y + r.h * 0.5f, w = r.h * 0.42f, h = r.h * 0.2f;
    ui_draw_triangle(dl, cx - w, cy, cx, cy - h, cx + w, cy, c);
    ui_draw_triangle(dl, cx - w, cy, cx + w, cy, cx, cy + h, c);
    float p = h * 0.9f;
    ui_draw_rect(dl, (ui_rect){cx - p * 0.5f, cy - p * 0.5f, p, p},
                 open ? ui_get_theme(ui)->panel : c);
    if (!open) ui_draw_line(dl, cx - w, cy + h * 1.6f, cx + w, cy - h * 1.6f, c, 1.5f);
}

// A padlock (shut: locked; the shackle raised: free) in box r.
static void lock_icon(ui_context *ui, ui_rect r, int shut, ui_color c) {
    ui_draw_list *dl = ui_draw_target(ui);
    float cx = r.x + r.w * 0.5f, s = r.h * 0.22f, top = r.y + r.h * 0.5f;
    ui_draw_rect(dl, (ui_rect){cx - s * 1.3f, top, s * 2.6f, s * 1.8f}, c);
    float lift = shut ? 0 : s * 0.7f, y0 = top - s * 1.4f - lift;
    ui_draw_line(dl, cx - s * 0.8f, top - (shut ? 0 : lift * 0.2f), cx - s * 0.8f, y0, c, 1.5f);
    ui_draw_line(dl, cx - s * 0.8f, y0, cx + s * 0.8f, y0, c, 1.5f);
    ui_draw_line(dl, cx + s * 0.8f, y0, cx + s * 0.8f, top - lift, c, 1.5f);
}

// A name `layer new` takes that no layer has: Layer_2, Layer_3, ...
static void fresh_name(const layer_table *t, char *name, size_t len) {
    for (int n = t->count + 1; n < 10000; n++) {
        snprintf(name, len, "Layer_%d", n);
        if (layer_table_find(t, name) < 0) return;
    }
}

// The name field while it is typed into: Enter renames, Esc or a click elsewhere
// leaves the name as it was.
static void rename_field(editor_ui *e, ui_context *ui, cmd_context *ctx, const layer_info *l) {
    layers_panel_state *s = &e->layers;
    int rc = ui_textbox_flags(ui, "Rename", s->rename, sizeof s->rename, UI_TEXTBOX_SELECT_ALL);
    ui_tooltip(ui, "The layer's new name (letters, digits, _ - .); Enter renames, Esc keeps it");
    int focused = ui_last_focused(ui);
    if (rc & UI_TEXT_SUBMIT) {
        if (strcmp(s->rename, l->name) != 0 && s->rename[0])
            runf(e, ctx, "layer set %s name=%s", l->name, s->rename);
        s->renaming = 0;
    } else if (focused) {
        s->rename_seen = 1;
    } else if (s->rename_seen) {
        s->renaming = 0; // the field lost the keyboard: nothing renamed
    }
}

// The right-click menu of a layer's name.
static void layer_menu(editor_ui *e, ui_context *ui, cmd_context *ctx, const layer_table *t,
                       int i) {
    const layer_info *l = &t->layers[i];
    if (!ui_context_menu_begin(ui, "Layer menu")) return;
    if (ui_menu_item(ui, "Rename", NULL, 1)) {
        e->layers.renaming = l->id;
        e->layers.rename_seen = 0;
        snprintf(e->layers.rename, sizeof e->layers.rename, "%s", l->name);
        ui_focus(ui, "Rename");
    }
    if (ui_menu_item(ui, "Duplicate", NULL, 1)) runf(e, ctx, "layer duplicate %s", l->name);
    if (ui_menu_item(ui, "Merge down", NULL, i > 0)) runf(e, ctx, "layer merge %s", l->name);
    if (ui_menu_item(ui, "Clear", NULL, 1)) runf(e, ctx, "layer clear %s", l->name);
    if (ui_menu_item(ui, "Delete", NULL, t->count > 1)) runf(e, ctx, "layer delete %s", l->name);
    // A heightmap of the layer: flat worlds (planets export whole, as meshes).
    int flat = world_get_params(ctx->world)->kind != WORLD_PLANET;
    if (ui_menu_item(ui, "Export...", NULL, l->kind == LAYER_KIND_HEIGHT && flat))
        export_layer(e, ctx, l->name);
    ui_context_menu_end(ui);
}

// One layer's two lines: eye, lock, name, Mask; then blend and opacity. Returns the
// rectangle of its name, where drags start and land.
static ui_rect layer_row(editor_ui *e, ui_context *ui, cmd_context *ctx, const layer_table *t,
                         int i) {
    layers_panel_state *s = &e->layers;
    const layer_info *l = &t->layers[i];
    const ui_theme *th = ui_get_theme(ui);
    float icon = ui_em(ui, 1.5f), mask_w = ui_em(ui, 3.2f);
    ui_push_scope(ui, l->name);
    float cols[4] = {icon, icon, 0, mask_w};
    ui_row(ui, 4, cols, 0);
    if (ui_toggle_button_indented(ui, "Visible", l->visible, 1e6f))
        runf(e, ctx, "layer set %s visible=%d", l->name, !l->visible);
    eye_icon(ui, ui_last_rect(ui), l->visible, th->text);
    ui_tooltip(ui, l->visible ? "Shown: click to hide the layer (the composite without it)"
                              : "Hidden: click to show the layer");
    if (ui_toggle_button_indented(ui, "Locked", l->locked, 1e6f))
        runf(e, ctx, "layer set %s locked=%d", l->name, !l->locked);
    lock_icon(ui, ui_last_rect(ui), l->locked, th->text);
    ui_tooltip(ui, l->locked ? "Locked: tools, clear, merge and delete refuse it (click to unlock)"
                             : "Click to lock the layer against edits");
    ui_rect name_rect;
    if (s->renaming == l->id) {
        rename_field(e, ui, ctx, l);
        name_rect = ui_last_rect(ui);
    } else {
        char label[LAYER_NAME_MAX + 8];
        snprintf(label, sizeof label, "%s##name", l->name);
        const ui_input *in = ui_get_input(ui);
        int clicked = ui_selectable(ui, label, i == t->active);
        name_rect = ui_last_rect(ui);
        row_drag_watch(&s->drag, ui, i);
        if (ui_last_hovered(ui) && in->double_click) {
            s->renaming = l->id;
            s->rename_seen = 0;
            snprintf(s->rename, sizeof s->rename, "%s", l->name);
            ui_focus(ui, "Rename");
        } else if (clicked && !row_drag_active(&s->drag) && i != t->active) {
            runf(e, ctx, "layer select %s", l->name);
        }
        ui_tooltip(ui, "Click: tools write to this layer; double click: rename; drag: move it "
                       "in the stack; right click: more");
        layer_menu(e, ui, ctx, t, i);
    }
    int editing = s->mask_layer == l->id;
    if (ui_toggle_button(ui, "Mask", editing)) {
        s->mask_layer = editing ? 0 : l->id;
        s->draft_live = 0;
    }
    if (layer_mask_active(&l->mask)) { // a dot: this layer has a mask
        ui_rect b = ui_last_rect(ui);
        float d = b.h * 0.22f;
        ui_draw_rect(ui_draw_target(ui), (ui_rect){b.x + b.w - d * 1.6f, b.y + d * 0.6f, d, d},
                     th->accent_hot);
    }
    ui_tooltip(ui, layer_mask_active(&l->mask)
                       ? "The layer has a mask (where it applies): click to edit it"
                       : "Give the layer a mask: where it applies by height, slope, curvature "
                         "and flow");
    float second[3] = {2 * icon + ui_em(ui, 0.2f), 0, 0};
    ui_row(ui, 3, second, 0);
    ui_next_cell(ui); // under the eye and the lock
    const char *blends[LAYER_BLEND_COUNT];
    for (int b = 0; b < LAYER_BLEND_COUNT; b++)
        blends[b] = layer_blend_name((layer_blend)b);
    int blend = (int)l->blend;
    if (l->kind == LAYER_KIND_PAINT)
        ui_label_colored(ui, "paint", th->text_dim);
    else if (ui_combo(ui, "##Blend", &blend, blends, LAYER_BLEND_COUNT))
        runf(e, ctx, "layer set %s blend=%s", l->name, blends[blend]);
    ui_tooltip(ui,
               "Blend: add: its heights add to the layers below; replace: its own heights; max, "
               "min: the higher or lower");
    double opacity = l->opacity * 100;
    if (ui_slider(ui, "##Opacity", &opacity, 0, 100, "%.0f%%"))
        runf(e, ctx, "layer set %s opacity=%.4g", l->name, opacity / 100);
    ui_tooltip(ui, "How much of the layer shows (0-100%)");
    ui_pop_scope(ui);
    return name_rect;
}

void layer_stack_panel(editor_ui *e, ui_context *ui, cmd_context *ctx, viewport *v) {
    const layer_table *t = &world_get_params(ctx->world)->layers;
    layers_panel_state *s = &e->layers;
    ui_rect names[LAYER_MAX];
    ui_push_scope(ui, "Stack");
    for (int i = t->count - 1; i >= 0; i--) // top first, as it covers the others
        names[i] = layer_row(e, ui, ctx, t, i);
    if (s->renaming && layer_table_find_id(t, s->renaming) < 0) s->renaming = 0;
    int from, to;
    if (row_drag_update(&s->drag, ui, names, t->count, &from, &to))
        runf(e, ctx, "layer move %s to=%d", t->layers[from].name, to);
    ui_pop_scope(ui);
    ui_row(ui, 1, NULL, 0);
    char line[160];
    if (editor_ui_tool_refused(ctx, line, sizeof line))
        ui_label_wrapped(ui, line, ui_get_theme(ui)->text_error);
    for (int paint = 0; paint < 2; paint++) {
        if (ui_button(ui, paint ? "New paint layer" : "New layer") && t->count < LAYER_MAX) {
            char name[LAYER_NAME_MAX];
            fresh_name(t, name, sizeof name);
            runf(e, ctx, "layer new %s%s", name, paint ? " kind=paint" : "");
        }
        ui_tooltip(ui, t->count >= LAYER_MAX ? "The stack is full (32 layers)"
                       : paint ? "A new empty paint layer above the active one: the paint "
                                 "tool writes materials to it"
                               : "A new empty height layer above the active one; the "
                                 "sculpting tools write to it");
    }
    int m = s->mask_layer ? layer_table_find_id(t, s->mask_layer) : -1;
    if (m < 0) {
        s->mask_layer = 0;
        v->settings.mask_terms = 0;
        return;
    }
    mask_editor(e, ui, ctx, v, &t->layers[m]);
}
