#include "ui/ui.h"

#include "ui/log_rows.h"

#include <locale.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SCOPE_MAX 32
#define LAYOUT_MAX 16
#define COLUMNS_MAX 16
#define WIDGETS_MAX 1024
#define SLOTS_MAX 512
#define EDIT_MAX 1024
#define UNDO_MAX 16
#define FOCUSABLE_MAX 256
#define TOOLTIP_DELAY 0.5
#define CLAIMS_MAX 2048 // a power of two above WIDGETS_MAX: the open-addressed id table
#define CONFLICTS_MAX 8
#define PATH_MAX_LEN 192
#define MESSAGES_MAX 32

typedef struct layout {
    ui_rect body;      // the region widgets flow in (screen pixels, scrolled)
    float y;           // top of the next row
    float content_top; // body.y at scroll 0, for measuring the content's height
    int columns, col;
    float widths[COLUMNS_MAX];
    float row_height;
    ui_rect cells[COLUMNS_MAX];
} layout;

// What survives frames per widget id: scroll offsets, open sections, sizes.
typedef struct slot {
    ui_id id;
    float scroll, content, size_w, size_h;
    float at_x, at_y; // a context menu: where it opened
    int open, initialised, at_bottom;
    uint64_t frame; // last frame it was used
} slot;

struct ui_context {
    const ui_font *font;
    ui_theme theme;
    ui_draw_list dl, overlay, *target;
    ui_input in;
    float width, height;
    uint64_t frame;

    ui_id hot, active, focus, hot_next;
    ui_id focus_request;

    ui_id scope_ids[SCOPE_MAX];
    char scope_names[SCOPE_MAX][64];
    int scope_section[SCOPE_MAX]; // the entry is a section's (ends at the next section)
    int scope_depth;

    // Ids claimed by widgets this frame, to find two widgets with one id.
    struct {
        ui_id id;
        uint64_t frame;
        char path[PATH_MAX_LEN];
    } claims[CLAIMS_MAX];
    char conflicts[2][CONFLICTS_MAX][2][PATH_MAX_LEN];
    ui_message_info messages[2][MESSAGES_MAX];
    size_t message_count[2];
    size_t conflict_count[2];
    int strict_ids;
    layout layouts[LAYOUT_MAX];
    int layout_depth;

    ui_widget_info widgets[2][WIDGETS_MAX];
    size_t widget_count[2];
    int cur;   // widgets[cur] is being written; the other is the last frame's
    int shown; // the last finished frame's: ui_end sets it to cur

    ui_rect last_rect;
    ui_id last_id;
    int last_hovered;

    ui_id tip_id;
    double tip_since;

    // Text editing (text boxes, and sliders being typed into).
    ui_id edit_id;
    char edit_restore[EDIT_MAX];
    float select_all_press_x; // where the click that selected all (or a word) was
    int keep_selection;       // and its selection holds until the pointer moves away
    size_t cursor, anchor;
    char undo[UNDO_MAX][EDIT_MAX];
    int undo_count, typing_run;
    size_t edit_len; // the text's length after the last edit: a different one was set by the caller
    double caret_time;
    ui_id focusables[FOCUSABLE_MAX];
    int focusable_count;
    int focus_seen;   // the focused widget was drawn this frame
    int tab_pending;  // Tab was pressed with a field focused
    ui_id tab_from;   // the field Tab leaves: the next field drawn takes the focus
    int tab_to_first; // Tab on the last field: the first field next frame

    // Sliders.
    ui_id typing_id; // a slider in typing mode
    char typing_buf[64];
    double drag_start_value;
    float drag_start_x;
    int drag_fine;
    int drag_moved; // the pointer left the press's spot: a scrub, not a click
    char field_error[PATH_MAX_LEN];
    ui_id field_error_id;
    // Keys: whether a field had the keyboard as the frame began, and whether Esc was
    // spent closing a popup (ui_took_keys).
    int focus_at_begin, keys_spent, took_keys;

    // Curve editors: the point being dragged, where it is now (the caller's arrays
    // change only when the drag ends).
    int curve_point;
    float curve_t, curve_v;

    // Range widgets: the end being dragged (0 low, 1 high).
    int range_end;

    // Menus and combos: one popup open at a time.
    ui_id open_popup;
    ui_rect popup_rect, popup_rect_prev;
    float popup_y, popup_w_needed;
    // A popup taller than the room below it wraps into columns of popup_col_w.
    float popup_top, popup_bottom, popup_col_x, popup_col_w, popup_y_max;
    int in_popup;
    ui_rect menubar;
    float menubar_x;
    int popup_just_opened;
    // A list item took this frame's click: what was under the list (drawn after it,
    // once the list closed) does not see the click too (a press and its release in one
    // slow frame), nor does the viewport.
    int press_taken;

    ui_rect modal;    // w > 0: only widgets inside it take the pointer this frame
    int modal_before; // a modal dialog was up last frame
    ui_rect panel_rects[2][64];
    int panel_count[2];
    // The innermost panel under the pointer that can scroll, by frame: the wheel scrolls
    // the one the last frame found, not every panel around it (the dock scrolled with
    // the History list inside it). 0: none.
    ui_id wheel_panel[2];

    slot slots[SLOTS_MAX];
    ui_clipboard clipboard;
    int wants_mouse, wants_keyboard, needs_frame;
    ui_id panel_ids[LAYOUT_MAX]; // the open panels, innermost last (ui_reveal_last)
    int panel_depth;
    locale_t c_locale;
};

// ---- small helpers ---------------------------------------------------------------

static ui_id hash_bytes(ui_id h, const void *data, size_t n) {
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 16777619u;
    return h;
}

// The shown part of a label: up to "##".
static size_t label_len(const char *label) {
    const char *hash = strstr(label, "##");
    return hash ? (size_t)(hash - label) : strlen(label);
}

static slot *get_slot(ui_context *ui, ui_id id) {
    size_t i = id % SLOTS_MAX, oldest = i;
    for (size_t k = 0; k < 16; k++) {
        slot *s = &ui->slots[(i + k) % SLOTS_MAX];
        if (s->id == id) {
            s->frame = ui->frame;
            return s;
        }
        if (s->frame < ui->slots[oldest].frame) oldest = (i + k) % SLOTS_MAX;
        if (!s->id) {
            oldest = (i + k) % SLOTS_MAX;
            break;
        }
    }
    slot *s = &ui->slots[oldest]; // reuse the least recently used nearby slot
    memset(s, 0, sizeof *s);
    s->id = id;
    s->frame = ui->frame;
    return s;
}

static int mouse_pressed(const ui_context *ui) {
    return ui->in.mouse_pressed[0];
}

// A press a widget may take: one outside an open popup only closes it (ui_end), unless
// it lands on what opened it.
static int press_for(const ui_context *ui, ui_id id) {
    return mouse_pressed(ui) && (ui->in_popup || !ui->open_popup || ui->open_popup == id);
}

// The pointer is over r and nothing covers it (an open popup over a base widget).
static int over(const ui_context *ui, ui_rect r) {
    if (ui->press_taken && !ui->in_popup) return 0;
    if (!ui_rect_contains(ui_rect_intersect(r, ui_draw_clip(ui->target)), ui->in.mouse_x,
                          ui->in.mouse_y))
        return 0;
    if (!ui->in_popup && ui->open_popup &&
        ui_rect_contains(ui->popup_rect_prev, ui->in.mouse_x, ui->in.mouse_y))
        return 0;
    // A popup open during a dialog was opened from it (a combo box) and belongs to it.
    if (ui->modal.w > 0 && !ui->in_popup &&
        !(r.x >= ui->modal.x && r.y >= ui->modal.y && r.x + r.w <= ui->modal.x + ui->modal.w &&
          r.y + r.h <= ui->modal.y + ui->modal.h))
        return 0;
    return 1;
}

// The scope path and label in out ("Dock/Radius"); with sections, their headers too
// ("Dock/World/Radius"). A long path is cut.
// The part of a label that names it in widget paths: what it shows, or, for a label
// that shows nothing ("##Opacity": a value without its name), its suffix.
static const char *path_name(const char *label, size_t *len) {
    *len = label_len(label);
    if (*len == 0 && label[0] == '#' && label[1] == '#') label += 2, *len = strlen(label);
    return label;
}

static void widget_path(const ui_context *ui, const char *label, int sections, char *out,
                        size_t size) {
    size_t n = 0;
    out[0] = 0;
    for (int i = 0; i < ui->scope_depth && n < size; i++)
        if (sections || !ui->scope_section[i])
            n += (size_t)snprintf(out + n, size - n, "%s/", ui->scope_names[i]);
    size_t shown;
    label = path_name(label, &shown);
    if (n < size) snprintf(out + n, size - n, "%.*s", (int)shown, label);
}

// A message shown this frame, where the current scope is (label: a widget it is about).
static void record_message(ui_context *ui, const char *label, const char *text, size_t n) {
    size_t *count = &ui->message_count[ui->cur];
    if (*count == MESSAGES_MAX) return;
    ui_message_info *m = &ui->messages[ui->cur][(*count)++];
    char where[PATH_MAX_LEN];
    widget_path(ui, label, 0, where, sizeof where);
    size_t len = strlen(where);
    if (len > 0 && where[len - 1] == '/') where[len - 1] = 0; // no label: the scope
    snprintf(m->where, sizeof m->where, "%s", where);
    snprintf(m->text, sizeof m->text, "%.*s", (int)n, text);
}

size_t ui_message_count(const ui_context *ui) {
    return ui->message_count[ui->shown];
}
const ui_message_info *ui_message_at(const ui_context *ui, size_t i) {
    return i < ui_message_count(ui) ? &ui->messages[ui->shown][i] : NULL;
}

// Widgets are named by their scopes without sections, as tests have always found them.
static void record_widget(ui_context *ui, const char *label, ui_rect r) {
    if (ui->widget_count[ui->cur] == WIDGETS_MAX) return;
    ui_widget_info *w = &ui->widgets[ui->cur][ui->widget_count[ui->cur]++];
    widget_path(ui, label, 0, w->name, sizeof w->name);
    w->rect = r;
}

// A widget takes id for this frame; a second one with the same id is a conflict.
static void claim_id(ui_context *ui, ui_id id, const char *label) {
    size_t i = id & (CLAIMS_MAX - 1);
    for (size_t k = 0; k < CLAIMS_MAX; k++, i = (i + 1) & (CLAIMS_MAX - 1)) {
        if (ui->claims[i].frame != ui->frame) { // free this frame: take it
            ui->claims[i].id = id;
            ui->claims[i].frame = ui->frame;
            widget_path(ui, label, 1, ui->claims[i].path, sizeof ui->claims[i].path);
            return;
        }
        if (ui->claims[i].id != id) continue;
        char path[PATH_MAX_LEN];
        widget_path(ui, label, 1, path, sizeof path);
        if (ui->strict_ids) {
            fprintf(stderr,
                    "ui: two widgets share one id in one frame: \"%s\" and \"%s\" (give one "
                    "a \"##suffix\" or a scope)\n",
                    ui->claims[i].path, path);
            abort(); // a programmer's mistake, caught where the tests run strict
        }
        size_t *count = &ui->conflict_count[ui->cur];
        if (*count < CONFLICTS_MAX) {
            memcpy(ui->conflicts[ui->cur][*count][0], ui->claims[i].path, PATH_MAX_LEN);
            memcpy(ui->conflicts[ui->cur][*count][1], path, PATH_MAX_LEN);
            (*count)++;
        }
        return;
    }
}

static void record_claim(ui_context *ui, ui_id id, const char *label, ui_rect r) {
    claim_id(ui, id, label);
    record_widget(ui, label, r);
}

// Hover and press handling shared by clickable widgets; returns 1 on a click
// (press and release over it).
static int behave(ui_context *ui, ui_id id, ui_rect r) {
    int hovered = over(ui, r);
    if (hovered) ui->hot_next = id;
    int clicked = 0;
    if (hovered && press_for(ui, id)) {
        ui->active = id;
        if (ui->focus && ui->focus != id) ui->focus = ui->edit_id = ui->typing_id = 0;
    }
    if (ui->active == id && ui->in.mouse_released[0]) {
        clicked = hovered;
        ui->active = 0;
    }
    ui->last_id = id;
    ui->last_rect = r;
    ui->last_hovered = hovered;
    return clicked;
}

static float text_width(const ui_context *ui, const char *s, size_t n) {
    return ui_font_text_width(ui->font, UI_FACE_SANS, s, n);
}

static void text_in(ui_context *ui, ui_rect r, const char *s, size_t n, ui_color c, int centred) {
    float w = text_width(ui, s, n), pad = ui_em(ui, 0.3f);
    // Text wider than the box starts at its left edge and ends in an ellipsis.
    int fits = w <= r.w - 2 * pad;
    float x = centred && fits ? r.x + (r.w - w) * 0.5f : r.x + pad;
    float y = r.y + (r.h - ui_font_line_height(ui->font)) * 0.5f;
    ui_draw_push_clip(ui->target, r);
    if (fits) {
        ui_draw_text(ui->target, UI_FACE_SANS, x, y, s, n, c);
    } else {
        static const char dots[] = "\xe2\x80\xa6";
        float room = r.w - 2 * pad - text_width(ui, dots, 3);
        size_t cut = ui_font_offset_at(ui->font, UI_FACE_SANS, s, n, room);
        while (cut > 0 && text_width(ui, s, cut) > room)
            cut--;
        while (cut > 0 && ((unsigned char)s[cut] & 0xC0) == 0x80) // whole characters
            cut--;
        float drawn = ui_draw_text(ui->target, UI_FACE_SANS, x, y, s, cut, c);
        ui_draw_text(ui->target, UI_FACE_SANS, x + drawn, y, dots, 3, c);
    }
    ui_draw_pop_clip(ui->target);
}

// ---- context ---------------------------------------------------------------------

ui_context *ui_create(const ui_font *font) {
    ui_context *ui = calloc(1, sizeof *ui);
    if (!ui) return NULL;
    ui->font = font;
    ui->c_locale = newlocale(LC_ALL_MASK, "C", (locale_t)0);
#ifndef NDEBUG
    ui->strict_ids = 1;
#endif
    const char *strict = getenv("OROGEN_UI_STRICT");
    if (strict && *strict) ui->strict_ids = strcmp(strict, "0") != 0;
    // A dark theme in the manner of Blender's and Unreal's editors.
    ui->theme = (ui_theme){
        .bg = UI_RGBA(30, 30, 33, 255),
        .panel = UI_RGBA(43, 43, 47, 245),
        .panel_alt = UI_RGBA(52, 52, 57, 255),
        .border = UI_RGBA(20, 20, 22, 255),
        .text = UI_RGBA(222, 222, 222, 255),
        .text_dim = UI_RGBA(140, 140, 145, 255),
        .text_error = UI_RGBA(255, 110, 100, 255),
        .accent = UI_RGBA(72, 118, 196, 255),
        .accent_hot = UI_RGBA(92, 140, 220, 255),
        .widget = UI_RGBA(64, 64, 70, 255),
        .widget_hot = UI_RGBA(80, 80, 88, 255),
        .widget_active = UI_RGBA(98, 98, 108, 255),
        .selection = UI_RGBA(60, 100, 170, 255),
    };
    return ui;
}

void ui_destroy(ui_context *ui) {
    if (!ui) return;
    ui_draw_free(&ui->dl);
    ui_draw_free(&ui->overlay);
    if (ui->c_locale) freelocale(ui->c_locale);
    free(ui);
}

void ui_set_clipboard(ui_context *ui, ui_clipboard cb) {
    ui->clipboard = cb;
}
void ui_set_font(ui_context *ui, const ui_font *font) {
    ui->font = font;
}
const ui_theme *ui_get_theme(const ui_context *ui) {
    return &ui->theme;
}
const ui_font *ui_get_font(const ui_context *ui) {
    return ui->font;
}
float ui_em(const ui_context *ui, float n) {
    return roundf(n * ui_font_line_height(ui->font));
}

void ui_begin(ui_context *ui, const ui_input *in, float width, float height) {
    ui->in = *in;
    ui->width = width;
    ui->height = height;
    ui->frame++;
    ui->hot = ui->hot_next;
    ui->hot_next = 0;
    ui->cur ^= 1;
    ui->widget_count[ui->cur] = 0;
    ui->conflict_count[ui->cur] = 0;
    ui->message_count[ui->cur] = 0;
    ui->panel_count[ui->cur] = 0;
    ui->wheel_panel[ui->cur] = 0;
    ui->focus_at_begin = ui->focus != 0;
    ui->keys_spent = 0;
    ui->scope_depth = 0;
    ui->layout_depth = 0;
    ui->panel_depth = 0;
    ui->needs_frame = 0;
    ui->popup_rect_prev = ui->popup_rect;
    ui->popup_rect = (ui_rect){0, 0, 0, 0};
    ui->in_popup = 0;
    ui->press_taken = 0;
    ui->focusable_count = 0;
    ui->focus_seen = 0;
    ui->modal_before = ui->modal.w > 0;
    ui->modal = (ui_rect){0, 0, 0, 0};
    ui->last_id = 0;
    ui->last_hovered = 0;
    ui_draw_reset(&ui->dl, ui->font, width, height);
    ui_draw_reset(&ui->overlay, ui->font, width, height);
    ui->target = &ui->dl;
    // A click that lands on no widget drops the keyboard focus (checked in ui_end).
    if (in->key_pressed[UI_KEY_ESCAPE] && ui->open_popup && !ui->edit_id) {
        ui->open_popup = 0;
        ui->in.key_pressed[UI_KEY_ESCAPE] = 0; // spent: the dialog under the popup stays
        ui->keys_spent = 1;
    }
    ui->tab_pending = in->key_pressed[UI_KEY_TAB] && ui->focus;
}

// Popups and tooltips are drawn into their own list and appended last: on top.
static void append_overlay(ui_context *ui) {
    ui_draw_list *d = &ui->dl, *o = &ui->overlay;
    uint32_t base = d->vtx_count;
    // Raw copy: vertices appended, indices offset, commands appended.
    if (!o->cmd_count) return;
    uint32_t nv = d->vtx_count + o->vtx_count, ni = d->idx_count + o->idx_count,
             nc = d->cmd_count + o->cmd_count;
    ui_vertex *vtx = realloc(d->vtx, (size_t)(nv ? nv : 1) * sizeof *vtx);
    if (!vtx) return (void)(d->out_of_memory = 1);
    d->vtx = vtx, d->vtx_cap = nv;
    uint32_t *idx = realloc(d->idx, (size_t)(ni ? ni : 1) * sizeof *idx);
    if (!idx) return (void)(d->out_of_memory = 1);
    d->idx = idx, d->idx_cap = ni;
    ui_draw_cmd *cmds = realloc(d->cmds, (size_t)nc * sizeof *cmds);
    if (!cmds) return (void)(d->out_of_memory = 1);
    d->cmds = cmds, d->cmd_cap = nc;
    memcpy(d->vtx + d->vtx_count, o->vtx, o->vtx_count * sizeof *vtx);
    for (uint32_t i = 0; i < o->idx_count; i++)
        d->idx[d->idx_count + i] = o->idx[i] + base;
    for (uint32_t c = 0; c < o->cmd_count; c++) {
        ui_draw_cmd cmd = o->cmds[c];
        cmd.first_index += d->idx_count;
        d->cmds[d->cmd_count + c] = cmd;
    }
    d->vtx_count = nv, d->idx_count = ni, d->cmd_count = nc;
}

const ui_draw_list *ui_end(ui_context *ui) {
    // Tooltip delay and caret blink keep frames coming.
    if (ui->tip_id) ui->needs_frame = 1;
    if (ui->focus) ui->needs_frame = 1;
    // A press outside the open popup (and not on what opened it) closes it.
    if (ui->open_popup && mouse_pressed(ui) && !ui->popup_just_opened &&
        !ui_rect_contains(ui->popup_rect, ui->in.mouse_x, ui->in.mouse_y) &&
        ui->hot_next != ui->open_popup)
        ui->open_popup = 0;
    ui->popup_just_opened = 0;
    if (ui->tab_from) { // Tab on the last field wraps to the first
        ui->tab_from = 0;
        ui->tab_to_first = 1;
    }
    // A focused field that was not drawn (its panel closed) holds no keys any more.
    if (ui->focus && !ui->focus_seen && !ui->focus_request) {
        ui->focus = 0;
        ui->edit_id = 0;
        ui->typing_id = 0;
    }
    // A press on nothing focusable drops the focus.
    if (mouse_pressed(ui) && ui->focus && ui->hot_next != ui->focus) {
        ui->focus = 0;
        ui->edit_id = 0;
        ui->typing_id = 0;
    }
    if (ui->in.mouse_released[0] && ui->active) ui->active = 0;
    int over_panel = 0;
    for (int i = 0; i < ui->panel_count[ui->cur]; i++)
        over_panel |= ui_rect_contains(ui->panel_rects[ui->cur][i], ui->in.mouse_x, ui->in.mouse_y);
    over_panel |=
        ui->open_popup && ui_rect_contains(ui->popup_rect, ui->in.mouse_x, ui->in.mouse_y);
    ui->wants_mouse = over_panel || ui->active != 0 || ui->press_taken;
    ui->wants_keyboard = ui->focus != 0;
    ui->took_keys = ui->focus_at_begin || ui->focus != 0 || ui->keys_spent;
    if (ui->field_error_id && ui->typing_id != ui->field_error_id) ui->field_error_id = 0;
    ui->shown = ui->cur;
    append_overlay(ui);
    return &ui->dl;
}

int ui_captures_point(const ui_context *ui, float x, float y) {
    if (ui->active || ui->modal.w > 0) return 1;
    if (ui->open_popup && ui_rect_contains(ui->popup_rect, x, y)) return 1;
    for (int i = 0; i < ui->panel_count[ui->cur]; i++)
        if (ui_rect_contains(ui->panel_rects[ui->cur][i], x, y)) return 1;
    return 0;
}

int ui_wants_mouse(const ui_context *ui) {
    return ui->wants_mouse;
}
int ui_wants_keyboard(const ui_context *ui) {
    return ui->wants_keyboard;
}
int ui_took_keys(const ui_context *ui) {
    return ui->took_keys;
}
const char *ui_field_error(const ui_context *ui) {
    return ui->field_error_id ? ui->field_error : "";
}
int ui_needs_frame(const ui_context *ui) {
    return ui->needs_frame;
}

void ui_modal(ui_context *ui, ui_rect r) {
    ui->modal = r;
    if (!ui->modal_before) ui->open_popup = 0; // a menu open when the dialog came up
}

int ui_modal_open(const ui_context *ui) {
    return ui->modal.w > 0;
}

void ui_dim(ui_context *ui) {
    ui_draw_rect(ui->target, (ui_rect){0, 0, ui->width, ui->height}, UI_RGBA(0, 0, 0, 110));
}

// ---- ids, scopes, named widgets -------------------------------------------------------

static ui_id id_at_depth(const ui_context *ui, int depth, const char *label) {
    ui_id h = depth ? ui->scope_ids[depth - 1] : 2166136261u;
    h = hash_bytes(h, label, strlen(label));
    return h ? h : 1;
}

ui_id ui_get_id(ui_context *ui, const char *label) {
    return id_at_depth(ui, ui->scope_depth, label);
}

static void push_scope(ui_context *ui, const char *name, int section) {
    if (ui->scope_depth == SCOPE_MAX) return;
    ui->scope_ids[ui->scope_depth] = hash_bytes(ui_get_id(ui, name), "", 1); // a NUL after it
    size_t shown; // a combo's "##Blend" names its items' scope "Blend", not ""
    const char *named = path_name(name, &shown);
    snprintf(ui->scope_names[ui->scope_depth], sizeof ui->scope_names[0], "%.*s", (int)shown,
             named);
    ui->scope_section[ui->scope_depth] = section;
    ui->scope_depth++;
}

void ui_push_scope(ui_context *ui, const char *name) {
    push_scope(ui, name, 0);
}

// The depth below the sections open at the current level.
static int depth_below_sections(const ui_context *ui) {
    int d = ui->scope_depth;
    while (d > 0 && ui->scope_section[d - 1])
        d--;
    return d;
}

void ui_pop_scope(ui_context *ui) {
    ui->scope_depth = depth_below_sections(ui);
    if (ui->scope_depth > 0) ui->scope_depth--;
}

void ui_set_strict_ids(ui_context *ui, int strict) {
    ui->strict_ids = strict;
}
size_t ui_id_conflict_count(const ui_context *ui) {
    return ui->conflict_count[ui->shown];
}
const char *ui_id_conflict(const ui_context *ui, size_t i, int which) {
    if (i >= ui_id_conflict_count(ui) || which < 0 || which > 1) return NULL;
    return ui->conflicts[ui->shown][i][which];
}

size_t ui_widget_count(const ui_context *ui) {
    return ui->widget_count[ui->shown];
}
const ui_widget_info *ui_widget_at(const ui_context *ui, size_t i) {
    return i < ui_widget_count(ui) ? &ui->widgets[ui->shown][i] : NULL;
}
const ui_widget_info *ui_widget_find(const ui_context *ui, const char *name) {
    for (size_t i = 0; i < ui_widget_count(ui); i++)
        if (strcmp(ui->widgets[ui->shown][i].name, name) == 0) return &ui->widgets[ui->shown][i];
    return NULL;
}

// ---- layout ----------------------------------------------------------------------

void ui_split(const ui_context *ui, ui_rect r, int horizontal, int n, const float *sizes,
              ui_rect *out) {
    (void)ui;
    float total = horizontal ? r.w : r.h, fixed = 0;
    int fills = 0;
    for (int i = 0; i < n; i++) {
        float s = sizes ? sizes[i] : 0;
        if (s > 0)
            fixed += s;
        else if (s < 0)
            fixed += -s * total;
        else
            fills++;
    }
    float fill = fills ? fmaxf(0.0f, (total - fixed) / fills) : 0, at = horizontal ? r.x : r.y;
    for (int i = 0; i < n; i++) {
        float s = sizes ? sizes[i] : 0;
        float len = s > 0 ? s : s < 0 ? -s * total : fill;
        float a0 = i ? roundf(at) : at, a1 = i + 1 < n ? roundf(at + len) : at + len;
        out[i] = horizontal ? (ui_rect){a0, r.y, a1 - a0, r.h} : (ui_rect){r.x, a0, r.w, a1 - a0};
        at += len;
    }
}

static layout *top_layout(ui_context *ui) {
    if (ui->layout_depth == 0) { // no panel: the whole window
        ui->layouts[0] = (layout){.body = {0, 0, ui->width, ui->height}};
        ui->layout_depth = 1;
    }
    return &ui->layouts[ui->layout_depth - 1];
}

void ui_row(ui_context *ui, int columns, const float *widths, float height) {
    layout *l = top_layout(ui);
    if (columns < 1) columns = 1;
    if (columns > COLUMNS_MAX) columns = COLUMNS_MAX;
    l->columns = columns;
    for (int i = 0; i < columns; i++)
        l->widths[i] = widths ? widths[i] : 0;
    l->row_height = height > 0 ? height : ui_em(ui, 1.4f);
    l->col = columns; // the next cell starts a row
}

ui_rect ui_next_cell(ui_context *ui) {
    layout *l = top_layout(ui);
    if (l->columns == 0) ui_row(ui, 1, NULL, 0);
    if (l->col >= l->columns) {
        float gap = ui_em(ui, 0.2f);
        ui_rect row = {l->body.x, l->y, l->body.w, l->row_height};
        ui_split(ui, row, 1, l->columns, l->widths, l->cells);
        for (int i = 0; i < l->columns; i++) { // a small gap between cells
            if (i + 1 < l->columns) l->cells[i].w -= gap;
        }
        l->y += l->row_height + gap;
        l->col = 0;
    }
    return l->cells[l->col++];
}

void ui_panel_begin(ui_context *ui, const char *name, ui_rect r) {
    ui_push_scope(ui, name);
    ui_id id = ui->scope_ids[ui->scope_depth - 1];
    slot *s = get_slot(ui, id);
    if (ui->panel_count[ui->cur] < 64) ui->panel_rects[ui->cur][ui->panel_count[ui->cur]++] = r;
    ui_draw_rect(ui->target, r, ui->theme.panel);
    // Wheel over the panel scrolls it.
    float pad = ui_em(ui, 0.3f), bar = ui_em(ui, 0.45f);
    float max_scroll = fmaxf(0.0f, s->content - (r.h - 2 * pad));
    int hovered = over(ui, r);
    if (hovered && max_scroll > 0) ui->wheel_panel[ui->cur] = id; // inner panels begin later
    ui_id wheel_to = ui->wheel_panel[ui->cur ^ 1];
    if (ui->in.wheel != 0 && hovered && (wheel_to == id || wheel_to == 0))
        s->scroll -= ui->in.wheel * ui_em(ui, 3);
    s->scroll = fminf(fmaxf(s->scroll, 0.0f), max_scroll);
    ui_draw_push_clip(ui->target, r);
    if (ui->layout_depth < LAYOUT_MAX) {
        layout *l = &ui->layouts[ui->layout_depth++];
        memset(l, 0, sizeof *l);
        l->body = (ui_rect){r.x + pad, r.y + pad - s->scroll,
                            r.w - 2 * pad - (max_scroll > 0 ? bar : 0), r.h - 2 * pad};
        l->y = l->body.y;
        l->content_top = l->body.y;
    }
    claim_id(ui, id, "");
    record_widget(ui, "", r);
    if (ui->panel_depth < LAYOUT_MAX) ui->panel_ids[ui->panel_depth] = id;
    ui->panel_depth++;
}

void ui_reveal_last(ui_context *ui) {
    if (ui->layout_depth == 0 || ui->panel_depth == 0 || ui->panel_depth > LAYOUT_MAX) return;
    const layout *l = &ui->layouts[ui->layout_depth - 1];
    if (l->col == 0) return;
    ui_rect c = l->cells[l->col - 1], view = ui_draw_clip(ui->target);
    float pad = ui_em(ui, 0.3f), below = c.y + c.h - (view.y + view.h - pad),
          above = view.y + pad - c.y;
    slot *s = get_slot(ui, ui->panel_ids[ui->panel_depth - 1]);
    if (below > 0.5f)
        s->scroll += below;
    else if (above > 0.5f)
        s->scroll -= above;
    else
        return;
    ui->needs_frame = 1; // the panel scrolls on the next frame
}

void ui_panel_end(ui_context *ui) {
    if (ui->panel_depth > 0) ui->panel_depth--;
    ui->scope_depth = depth_below_sections(ui); // the panel's last section ends
    if (ui->scope_depth == 0) return;
    ui_id id = ui->scope_ids[ui->scope_depth - 1];
    slot *s = get_slot(ui, id);
    ui_rect clip = ui_draw_clip(ui->target);
    if (ui->layout_depth > 0) {
        layout *l = &ui->layouts[--ui->layout_depth];
        s->content = fmaxf(0.0f, l->y - l->content_top - ui_em(ui, 0.2f)); // less the last gap
        float pad = ui_em(ui, 0.3f), bar = ui_em(ui, 0.45f), view = clip.h - 2 * pad;
        if (s->content > view && view > 0) { // a scroll bar with a draggable thumb
            ui_rect track = {clip.x + clip.w - bar, clip.y, bar, clip.h};
            float th = fmaxf(ui_em(ui, 1), track.h * view / s->content);
            float max_scroll = s->content - view;
            ui_rect thumb = {track.x, track.y + (track.h - th) * (s->scroll / max_scroll), bar, th};
            ui_id tid = id ^ 0x5c5c5c5cu;
            behave(ui, tid, track);
            if (ui->active == tid && ui->in.mouse_down[0])
                s->scroll = fminf(
                    fmaxf((ui->in.mouse_y - track.y - th * 0.5f) / (track.h - th) * max_scroll,
                          0.0f),
                    max_scroll);
            ui_draw_rect(ui->target, track, ui->theme.panel_alt);
            ui_draw_rect(ui->target, thumb,
                         ui->hot == tid || ui->active == tid ? ui->theme.widget_active
                                                             : ui->theme.widget_hot);
        }
    }
    ui_draw_pop_clip(ui->target);
    ui_pop_scope(ui);
}

// ---- widgets -----------------------------------------------------------------------

void ui_label_colored(ui_context *ui, const char *text, ui_color c) {
    ui_rect r = ui_next_cell(ui);
    if (c == ui->theme.text_error) record_message(ui, "", text, label_len(text));
    text_in(ui, r, text, label_len(text), c, 0);
    record_widget(ui, text, r);
    ui->last_rect = r;
    ui->last_id = ui_get_id(ui, text);
    ui->last_hovered = over(ui, r);
}

static size_t next_char(const char *s, size_t n, size_t i);

// The bytes of text's next row at most w wide: the longest run of whole words that fits,
// at least one word; a word longer than a row (a path) is cut between characters.
static size_t fitting_words(const ui_context *ui, const char *at, float w) {
    size_t n = strlen(at), fit = 0, i = 0;
    while (i < n) {
        size_t next = i;
        while (next < n && at[next] == ' ')
            next++;
        while (next < n && at[next] != ' ')
            next++;
        if (fit > 0 && text_width(ui, at, next) > w) break;
        fit = i = next;
    }
    if (text_width(ui, at, fit) > w) {
        size_t cut = ui_font_offset_at(ui->font, UI_FACE_SANS, at, fit, w);
        while (cut > 0 && text_width(ui, at, cut) > w)
            cut--;
        while (cut > 0 && ((unsigned char)at[cut] & 0xC0) == 0x80)
            cut--;
        fit = cut > 0 ? cut : next_char(at, fit, 0);
    }
    return fit;
}

void ui_label_wrapped(ui_context *ui, const char *text, ui_color c) {
    if (c == ui->theme.text_error) record_message(ui, "", text, strlen(text));
    ui_rect all = {0, 0, 0, 0}; // its rows, for a tooltip on it (not on what came before)
    layout *l = top_layout(ui);
    if (l->col < l->columns) l->col = l->columns; // full-width rows
    float w = l->body.w - ui_em(ui, 0.6f) - 1;    // text_in's padding
    const char *at = text;
    do {
        size_t fit = fitting_words(ui, at, w);
        ui_row(ui, 1, NULL, 0);
        ui_rect r = ui_next_cell(ui);
        text_in(ui, r, at, fit, c, 0);
        char row[PATH_MAX_LEN]; // each row is named by its text, as labels are
        snprintf(row, sizeof row, "%.*s", (int)(fit < sizeof row ? fit : sizeof row - 1), at);
        record_widget(ui, row, r);
        all = all.w > 0 ? (ui_rect){all.x, all.y, all.w, r.y + r.h - all.y} : r;
        at += fit;
        while (*at == ' ')
            at++;
    } while (*at);
    ui->last_id = ui_get_id(ui, text);
    ui->last_rect = all;
    ui->last_hovered = over(ui, all);
}

void ui_label(ui_context *ui, const char *text) {
    ui_label_colored(ui, text, ui->theme.text);
}

static ui_color widget_colour(const ui_context *ui, ui_id id) {
    if (ui->active == id) return ui->theme.widget_active;
    if (ui->hot == id) return ui->theme.widget_hot;
    return ui->theme.widget;
}

// A button shown pressed when on; its label centred, or left-aligned after indent.
static int toggle(ui_context *ui, const char *label, int on, float indent, int centred) {
    ui_id id = ui_get_id(ui, label);
    ui_rect r = ui_next_cell(ui);
    int clicked = behave(ui, id, r);
    ui_color bg =
        on ? (ui->hot == id ? ui->theme.accent_hot : ui->theme.accent) : widget_colour(ui, id);
    ui_draw_rect(ui->target, r, bg);
    if (indent < r.w) // an indent of the whole width: an icon button (the caller draws it)
        text_in(ui, (ui_rect){r.x + indent, r.y, r.w - indent, r.h}, label, label_len(label),
                ui->theme.text, centred);
    record_claim(ui, id, label, r);
    return clicked;
}

int ui_toggle_button(ui_context *ui, const char *label, int on) {
    return toggle(ui, label, on, 0, 1);
}

int ui_selectable(ui_context *ui, const char *label, int on) {
    ui_id id = ui_get_id(ui, label);
    ui_rect r = ui_next_cell(ui);
    int clicked = behave(ui, id, r);
    if (on || ui->hot == id)
        ui_draw_rect(ui->target, r, on ? ui->theme.selection : ui->theme.widget_hot);
    text_in(ui, r, label, label_len(label), ui->theme.text, 0);
    record_claim(ui, id, label, r);
    return clicked;
}

int ui_image_button(ui_context *ui, const char *label, uint32_t texture, int on) {
    ui_id id = ui_get_id(ui, label);
    ui_rect r = ui_next_cell(ui);
    int clicked = behave(ui, id, r);
    ui_draw_rect(ui->target, r, on ? ui->theme.accent : widget_colour(ui, id));
    float pad = ui_em(ui, 0.15f), lh = ui_font_line_height(ui->font);
    ui_rect img = {r.x + pad, r.y + pad, r.w - 2 * pad, r.h - 2 * pad};
    ui_draw_image(ui->target, texture, img, 0, 0, 1, 1,
                  ui->hot == id ? UI_RGBA(255, 255, 255, 255) : UI_RGBA(225, 225, 225, 255));
    ui_rect strip = {img.x, img.y + img.h - lh, img.w, lh};
    ui_draw_rect(ui->target, strip, UI_RGBA(0, 0, 0, 150));
    text_in(ui, strip, label, label_len(label), ui->theme.text, 1);
    record_claim(ui, id, label, r);
    return clicked;
}

int ui_toggle_button_indented(ui_context *ui, const char *label, int on, float indent) {
    return toggle(ui, label, on, indent, 0);
}

int ui_button(ui_context *ui, const char *label) {
    return ui_toggle_button(ui, label, 0);
}

int ui_checkbox(ui_context *ui, const char *label, int *value) {
    ui_id id = ui_get_id(ui, label);
    ui_rect r = ui_next_cell(ui);
    int clicked = behave(ui, id, r);
    float box = fminf(r.h, ui_em(ui, 0.9f));
    ui_rect b = {r.x, r.y + (r.h - box) * 0.5f, box, box};
    ui_draw_rect(ui->target, b, widget_colour(ui, id));
    if (*value) {
        float m = box * 0.22f;
        ui_draw_rect(ui->target, (ui_rect){b.x + m, b.y + m, box - 2 * m, box - 2 * m},
                     ui->theme.accent_hot);
    }
    text_in(ui, (ui_rect){r.x + box, r.y, r.w - box, r.h}, label, label_len(label), ui->theme.text,
            0);
    record_claim(ui, id, label, r);
    if (clicked) *value = !*value;
    return clicked;
}

int ui_radio(ui_context *ui, const char *label, int *value, int option) {
    int on = *value == option;
    if (ui_toggle_button(ui, label, on) && !on) {
        *value = option;
        return 1;
    }
    return 0;
}

void ui_separator(ui_context *ui) {
    layout *l = top_layout(ui);
    float gap = ui_em(ui, 0.3f);
    if (l->col < l->columns) l->col = l->columns; // finish the row
    ui_draw_rect(ui->target, (ui_rect){l->body.x, l->y + gap, l->body.w, 1}, ui->theme.border);
    l->y += 2 * gap + 1;
}

void ui_progress(ui_context *ui, double fraction, const char *text) {
    ui_rect r = ui_next_cell(ui);
    double f = fraction < 0 ? 0 : fraction > 1 ? 1 : fraction;
    ui_draw_rect(ui->target, r, ui->theme.widget);
    ui_draw_rect(ui->target, (ui_rect){r.x, r.y, roundf(r.w * (float)f), r.h}, ui->theme.accent);
    if (text) text_in(ui, r, text, label_len(text), ui->theme.text, 1);
    record_widget(ui, text ? text : "progress", r);
}

int ui_section(ui_context *ui, const char *label, int default_open) {
    ui->scope_depth = depth_below_sections(ui); // the section before it ends here
    ui_id id = ui_get_id(ui, label);
    slot *s = get_slot(ui, id);
    if (!s->initialised) s->open = default_open, s->initialised = 1;
    layout *l = top_layout(ui);
    if (l->col < l->columns) l->col = l->columns;
    int cols = l->columns;
    float widths[COLUMNS_MAX], height = l->row_height;
    memcpy(widths, l->widths, sizeof widths);
    ui_row(ui, 1, NULL, ui_em(ui, 1.3f));
    ui_rect r = ui_next_cell(ui);
    if (behave(ui, id, r)) s->open = !s->open;
    ui_draw_rect(ui->target, r, ui->hot == id ? ui->theme.widget_hot : ui->theme.panel_alt);
    char head[256];
    snprintf(head, sizeof head, "%s %.*s", s->open ? "\xe2\x96\xbc" : "\xe2\x96\xb6",
             (int)label_len(label), label);
    text_in(ui, r, head, strlen(head), ui->theme.text, 0);
    record_claim(ui, id, label, r);
    if (cols > 0) ui_row(ui, cols, widths, height);
    push_scope(ui, label, 1); // what follows, open or not, is named in it
    return s->open;
}

int ui_tree_push(ui_context *ui, const char *label, int default_open) {
    ui_id id = ui_get_id(ui, label);
    slot *s = get_slot(ui, id);
    if (!s->initialised) s->open = default_open, s->initialised = 1;
    ui_rect r = ui_next_cell(ui);
    if (behave(ui, id, r)) s->open = !s->open;
    if (ui->hot == id) ui_draw_rect(ui->target, r, ui->theme.widget_hot);
    char head[256];
    snprintf(head, sizeof head, "%s %.*s", s->open ? "\xe2\x96\xbe" : "\xe2\x96\xb8",
             (int)label_len(label), label);
    text_in(ui, r, head, strlen(head), ui->theme.text, 0);
    record_claim(ui, id, label, r);
    if (!s->open) return 0;
    layout *l = top_layout(ui); // children are indented and named below the node
    float indent = ui_em(ui, 1.0f);
    l->body.x += indent;
    l->body.w -= indent;
    l->col = l->columns; // they start a new row
    ui_push_scope(ui, label);
    return 1;
}

void ui_tree_pop(ui_context *ui) {
    ui_pop_scope(ui);
    layout *l = top_layout(ui);
    float indent = ui_em(ui, 1.0f);
    l->body.x -= indent;
    l->body.w += indent;
    l->col = l->columns;
}

int ui_color_swatch(ui_context *ui, const char *label, ui_color color, int on) {
    ui_id id = ui_get_id(ui, label);
    ui_rect r = ui_next_cell(ui);
    int clicked = behave(ui, id, r);
    if (on || ui->hot == id)
        ui_draw_rect(ui->target, r, on ? ui->theme.selection : ui->theme.widget_hot);
    float side = r.h - ui_em(ui, 0.3f), pad = (r.h - side) * 0.5f;
    ui_rect sw = {r.x + pad, r.y + pad, side * 1.6f, side};
    ui_draw_rect(ui->target, sw, color);
    ui_draw_rect_outline(ui->target, sw, ui->theme.border, 1.0f);
    float text_x = sw.x + sw.w + ui_em(ui, 0.2f);
    text_in(ui, (ui_rect){text_x, r.y, r.x + r.w - text_x, r.h}, label, label_len(label),
            ui->theme.text, 0);
    record_claim(ui, id, label, r);
    return clicked;
}

void ui_section_set(ui_context *ui, const char *label, int open) {
    slot *s = get_slot(ui, id_at_depth(ui, depth_below_sections(ui), label)); // as ui_section
    s->open = open;
    s->initialised = 1;
}

ui_draw_list *ui_draw_target(ui_context *ui) {
    return ui->target;
}

ui_rect ui_last_rect(const ui_context *ui) {
    return ui->last_rect;
}
int ui_last_hovered(const ui_context *ui) {
    return ui->last_hovered;
}

// Below the pointer; for a widget in the right part of the window (the dock), left of
// its panel, level with it, so it covers none of the panel's rows (at a large UI scale
// the box below a layer's opacity hid the next layer's name). A long text is broken
// between words into rows at most 32 em wide and never wider than the window (or than
// the room left of the panel), so no tooltip runs past the window's edge.
static void tooltip_box(ui_context *ui, const char *text, ui_rect anchor) {
    ui_draw_list *keep = ui->target;
    ui->target = &ui->overlay;
    enum { MAX_ROWS = 12 };
    float pad = ui_em(ui, 0.3f), line = ui_font_line_height(ui->font);
    float left = ui->layout_depth > 0 ? fminf(anchor.x, ui->layouts[0].body.x) : anchor.x;
    int beside = anchor.x > ui->width * 0.5f && left - pad > ui_em(ui, 12.0f);
    float room = beside ? left - 3 * pad : ui->width - 2 * pad;
    float wrap = fmaxf(fminf(ui_em(ui, 32.0f), room), ui_em(ui, 4.0f));
    size_t start[MAX_ROWS], len[MAX_ROWS];
    int rows = 0;
    float widest = 0;
    for (const char *at = text; *at && rows < MAX_ROWS; rows++) {
        size_t fit = fitting_words(ui, at, wrap);
        start[rows] = (size_t)(at - text), len[rows] = fit;
        widest = fmaxf(widest, text_width(ui, at, fit));
        at += fit;
        while (*at == ' ')
            at++;
    }
    float w = widest + 2 * pad, h = rows * line + 2 * pad;
    float x = fminf(ui->in.mouse_x + ui_em(ui, 0.8f), ui->width - w);
    float y = ui->in.mouse_y + ui_em(ui, 1.0f);
    if (y + h > ui->height) y = ui->in.mouse_y - h - pad;
    if (beside && left - w - pad >= 0) { // left of the panel: clear of it
        x = left - w - pad;
        y = fminf(fmaxf(anchor.y + (anchor.h - h) * 0.5f, 0), ui->height - h);
    }
    ui_rect r = {fmaxf(0, x), fmaxf(0, y), w, h};
    ui_draw_rect(ui->target, r, ui->theme.panel_alt);
    ui_draw_rect_outline(ui->target, r, ui->theme.border, 1);
    for (int i = 0; i < rows; i++)
        ui_draw_text(ui->target, UI_FACE_SANS, r.x + pad, r.y + pad + i * line, text + start[i],
                     len[i], ui->theme.text);
    ui->target = keep;
}

void ui_tooltip(ui_context *ui, const char *text) {
    // Not over a field being typed into: its text and its refusal stay readable.
    if (!ui->last_hovered || ui->active || (ui->last_id && ui->last_id == ui->typing_id)) {
        if (ui->tip_id == ui->last_id) ui->tip_id = 0;
        return;
    }
    if (ui->tip_id != ui->last_id) {
        ui->tip_id = ui->last_id;
        ui->tip_since = ui->in.time;
    }
    if (ui->in.time - ui->tip_since >= TOOLTIP_DELAY) tooltip_box(ui, text, ui->last_rect);
}

// ---- sliders ------------------------------------------------------------------------

static int parse_double_c(ui_context *ui, const char *s, double *out) {
    char *end;
    double v = strtod_l(s, &end, ui->c_locale);
    while (*end == ' ')
        end++;
    if (end == s || *end || !isfinite(v)) return -1; // "42abc" is not a number
    *out = v;
    return 0;
}

static int text_edit(ui_context *ui, ui_id id, ui_rect r, char *buf, size_t size, int flags);

// Opens the slider's text field on its value, as "%.17g" prints it: the text reads back
// as the same double, so Enter on it unchanged changes nothing.
static void slider_open_typing(ui_context *ui, ui_id id, double value) {
    ui->typing_id = id;
    ui->focus_seen = 1; // its text field is drawn from the next frame
    snprintf(ui->typing_buf, sizeof ui->typing_buf, "%.15g", value);
    double back;
    if (parse_double_c(ui, ui->typing_buf, &back) != 0 || back != value)
        snprintf(ui->typing_buf, sizeof ui->typing_buf, "%.17g", value);
    ui->focus = id;
    ui->edit_id = 0; // text_edit starts editing next frame (all selected)
    ui->active = 0;
    ui->field_error_id = 0;
}

// The slider's open text field: Enter with a number in range sets it; other text keeps
// the field open with the reason; Esc or a click elsewhere closes it, the value untouched.
static int slider_typing(ui_context *ui, ui_id id, const char *label, ui_rect r, double *value,
                         double lo, double hi) {
    int rc = text_edit(ui, id, r, ui->typing_buf, sizeof ui->typing_buf, UI_TEXTBOX_SELECT_ALL);
    ui->keys_spent = 1; // every key while it is open is its own
    if (rc & UI_TEXT_CHANGED) ui->field_error_id = 0;
    if (ui->focus != id) { // Esc or a click elsewhere
        ui->typing_id = 0;
        ui->field_error_id = 0;
        return 0;
    }
    if (rc & UI_TEXT_SUBMIT) {
        double v;
        const char *fail = NULL;
        char why[PATH_MAX_LEN];
        if (parse_double_c(ui, ui->typing_buf, &v) != 0) {
            snprintf(why, sizeof why, "\"%.40s\" is not a number", ui->typing_buf);
            fail = why;
        } else if (v < lo || v > hi) {
            snprintf(why, sizeof why, "%.10g is outside %.10g .. %.10g", v, lo, hi);
            fail = why;
        }
        if (fail) {
            snprintf(ui->field_error, sizeof ui->field_error, "%s", fail);
            ui->field_error_id = id;
        } else {
            ui->typing_id = ui->focus = ui->edit_id = 0;
            ui->field_error_id = 0;
            if (v != *value) return *value = v, 1;
            return 0;
        }
    }
    if (ui->field_error_id == id) { // the reason, under the field, until the text changes
        record_message(ui, label, ui->field_error, strlen(ui->field_error));
        ui_draw_list *base = ui->target;
        ui->target = &ui->overlay;
        float pad = ui_em(ui, 0.3f), w = text_width(ui, ui->field_error, strlen(ui->field_error));
        ui_rect box = {r.x, r.y + r.h, fmaxf(r.w, w + 2 * pad), ui_em(ui, 1.3f)};
        if (box.y + box.h > ui->height) box.y = r.y - box.h;
        ui_draw_rect(ui->target, box, ui->theme.panel_alt);
        ui_draw_rect_outline(ui->target, box, ui->theme.text_error, 1);
        text_in(ui, (ui_rect){box.x + pad, box.y, box.w - 2 * pad, box.h}, ui->field_error,
                strlen(ui->field_error), ui->theme.text_error, 0);
        ui->target = base;
    }
    return 0;
}

int ui_slider(ui_context *ui, const char *label, double *value, double lo, double hi,
              const char *fmt) {
    ui_id id = ui_get_id(ui, label);
    ui_rect r = ui_next_cell(ui);
    record_claim(ui, id, label, r);
    if (ui->typing_id == id) return slider_typing(ui, id, label, r, value, lo, hi);
    int hovered = over(ui, r);
    if (hovered) ui->hot_next = id;
    int changed = 0;
    if (hovered && press_for(ui, id)) {
        if (ui->focus && ui->focus != id) ui->focus = ui->edit_id = ui->typing_id = 0;
        if ((ui->in.mods & UI_MOD_CTRL) || ui->in.double_click) { // type a value
            slider_open_typing(ui, id, *value);
        } else { // a scrub from the value, or a click (opens the field on release)
            ui->active = id;
            // From the value as shown: one outside the range (a sea under all the ground)
            // moves from the end it is shown at.
            ui->drag_start_value = *value < lo ? lo : *value > hi ? hi : *value;
            ui->drag_start_x = ui->in.mouse_x;
            ui->drag_fine = ui->in.mods & UI_MOD_SHIFT;
            ui->drag_moved = 0;
        }
    }
    if (ui->active == id) {
        // The pointer's last place counts in the frame the button is let go in too.
        if (ui->in.mouse_down[0] || ui->in.mouse_released[0]) {
            int fine = ui->in.mods & UI_MOD_SHIFT;
            if (!ui->drag_moved && fabsf(ui->in.mouse_x - ui->drag_start_x) >= ui_em(ui, 0.25f))
                ui->drag_moved = 1;
            if (fine != ui->drag_fine) { // re-base when Shift changes mid-drag
                ui->drag_start_value = *value;
                ui->drag_start_x = ui->in.mouse_x;
                ui->drag_fine = fine;
            }
            double per_px = (hi - lo) / (r.w > 1 ? r.w : 1) * (fine ? 0.1 : 1.0);
            double v = ui->drag_start_value + (ui->in.mouse_x - ui->drag_start_x) * per_px;
            v = v < lo ? lo : v > hi ? hi : v;
            if (ui->drag_moved && v != *value) *value = v, changed = 1;
        }
        if (!ui->in.mouse_down[0]) {
            ui->active = 0;
            if (!ui->drag_moved && hovered) slider_open_typing(ui, id, *value);
        }
    }
    ui->last_id = id, ui->last_rect = r, ui->last_hovered = hovered;
    ui_draw_rect(ui->target, r, widget_colour(ui, id));
    double t = hi > lo ? (*value - lo) / (hi - lo) : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    ui_draw_rect(ui->target, (ui_rect){r.x, r.y, roundf(r.w * (float)t), r.h},
                 ui->hot == id || ui->active == id ? ui->theme.accent_hot : ui->theme.accent);
    char text[192], num[64];
    snprintf(num, sizeof num, fmt ? fmt : "%.3g", *value);
    if (label_len(label))
        snprintf(text, sizeof text, "%.*s: %s", (int)label_len(label), label, num);
    else
        snprintf(text, sizeof text, "%s", num);
    text_in(ui, r, text, strlen(text), ui->theme.text, 1);
    return changed;
}

// ---- combos and menus (popups) ---------------------------------------------------------

// A popup's slot keeps its column's width (size_w), its height (size_h) and how many
// columns it took (content) on the last frame, to place it before its items are known.
static void popup_begin(ui_context *ui, ui_id id, float x, float y, float min_w) {
    slot *s = get_slot(ui, id);
    float col_w = fmaxf(min_w, s->size_w), h = s->size_h;
    int cols = s->content > 1 ? (int)s->content : 1;
    float w = col_w * (float)cols;
    if (x + w > ui->width) x = fmaxf(0, ui->width - w);
    ui->target = &ui->overlay;
    ui->in_popup = 1;
    ui->popup_rect = (ui_rect){x, y, w, h};
    ui->popup_top = ui->popup_y = y + ui_em(ui, 0.2f);
    ui->popup_bottom = fmaxf(ui->popup_top + ui_em(ui, 2.6f), ui->height - ui_em(ui, 0.2f));
    ui->popup_col_x = 0;
    ui->popup_col_w = col_w;
    ui->popup_y_max = ui->popup_y;
    ui->popup_w_needed = min_w;
    ui_draw_rect(ui->target, ui->popup_rect, ui->theme.panel_alt);
    ui_draw_rect_outline(ui->target, ui->popup_rect, ui->theme.border, 1);
    if (h == 0) ui->needs_frame = 1; // sized from this frame's items on the next
}

// The next line of height h in the popup: below the last, or atop a new column when it
// would pass the window's bottom (a long menu at a small window or a large UI scale).
static ui_rect popup_line(ui_context *ui, float h) {
    if (ui->popup_y + h > ui->popup_bottom && ui->popup_y > ui->popup_top) {
        ui->popup_col_x += ui->popup_col_w;
        ui->popup_y = ui->popup_top;
    }
    ui_rect r = {ui->popup_rect.x + ui->popup_col_x + 1, ui->popup_y, ui->popup_col_w - 2, h};
    ui->popup_y += h;
    ui->popup_y_max = fmaxf(ui->popup_y_max, ui->popup_y);
    return r;
}

static void popup_end(ui_context *ui, ui_id id) {
    slot *s = get_slot(ui, id);
    float h = ui->popup_y_max + ui_em(ui, 0.2f) - ui->popup_rect.y;
    float cols = ui->popup_col_x / fmaxf(ui->popup_col_w, 1) + 1;
    if (s->size_h != h || s->size_w != ui->popup_w_needed || s->content != cols)
        ui->needs_frame = 1;
    s->size_h = h;
    s->size_w = ui->popup_w_needed;
    s->content = cols;
    ui->popup_rect.h = h;
    ui->popup_rect.w = fmaxf(ui->popup_rect.w, ui->popup_w_needed * cols);
    ui->target = &ui->dl;
    ui->in_popup = 0;
}

// One line of a popup; returns 1 when picked.
static int popup_item(ui_context *ui, const char *label, const char *right, int enabled,
                      int checked) {
    ui_id id = ui_get_id(ui, label);
    float h = ui_em(ui, 1.3f), pad = ui_em(ui, 0.6f);
    float need = text_width(ui, label, label_len(label)) + 3 * pad +
                 (right ? text_width(ui, right, strlen(right)) + 2 * pad : 0);
    ui->popup_w_needed = fmaxf(ui->popup_w_needed, need);
    ui_rect r = popup_line(ui, h);
    int clicked = enabled && behave(ui, id, r);
    if (clicked) ui->press_taken = 1;
    if (enabled && ui->hot == id) ui_draw_rect(ui->target, r, ui->theme.selection);
    ui_color c = enabled ? ui->theme.text : ui->theme.text_dim;
    if (checked)
        ui_draw_text(ui->target, UI_FACE_SANS, r.x + pad * 0.3f,
                     r.y + (h - ui_font_line_height(ui->font)) * 0.5f, "\xe2\x9c\x93", 3, c);
    ui_draw_text(ui->target, UI_FACE_SANS, r.x + pad,
                 r.y + (h - ui_font_line_height(ui->font)) * 0.5f, label, label_len(label), c);
    if (right) {
        float rw = text_width(ui, right, strlen(right));
        ui_draw_text(ui->target, UI_FACE_SANS, r.x + r.w - rw - pad,
                     r.y + (h - ui_font_line_height(ui->font)) * 0.5f, right, strlen(right),
                     ui->theme.text_dim);
    }
    record_claim(ui, id, label, r);
    return clicked;
}

int ui_combo(ui_context *ui, const char *label, int *index, const char *const *items, int count) {
    ui_id id = ui_get_id(ui, label);
    ui_rect r = ui_next_cell(ui);
    record_claim(ui, id, label, r);
    if (behave(ui, id, r)) {
        ui->open_popup = ui->open_popup == id ? 0 : id;
        ui->popup_just_opened = 1;
    }
    ui_draw_rect(ui->target, r, widget_colour(ui, id));
    char text[256];
    const char *item = *index >= 0 && *index < count ? items[*index] : "";
    if (label_len(label))
        snprintf(text, sizeof text, "%.*s: %s", (int)label_len(label), label, item);
    else
        snprintf(text, sizeof text, "%s", item);
    text_in(ui, (ui_rect){r.x, r.y, r.w - ui_em(ui, 0.8f), r.h}, text, strlen(text), ui->theme.text,
            0);
    ui_draw_text(ui->target, UI_FACE_SANS, r.x + r.w - ui_em(ui, 0.8f),
                 r.y + (r.h - ui_font_line_height(ui->font)) * 0.5f, "\xe2\x96\xbc", 3,
                 ui->theme.text_dim);
    if (ui->open_popup != id) return 0;
    int changed = 0;
    ui_push_scope(ui, label);
    popup_begin(ui, id, r.x, r.y + r.h, r.w);
    for (int i = 0; i < count; i++)
        if (popup_item(ui, items[i], NULL, 1, i == *index)) {
            changed = i != *index;
            *index = i;
            ui->open_popup = 0;
        }
    popup_end(ui, id);
    ui_pop_scope(ui);
    return changed;
}

void ui_menubar_begin(ui_context *ui, ui_rect r) {
    ui->menubar = r;
    ui->menubar_x = r.x + ui_em(ui, 0.3f);
    ui_draw_rect(ui->target, r, ui->theme.panel);
    if (ui->panel_count[ui->cur] < 64) ui->panel_rects[ui->cur][ui->panel_count[ui->cur]++] = r;
    ui_push_scope(ui, "Menu");
}

void ui_menubar_end(ui_context *ui) {
    ui_pop_scope(ui);
}

int ui_menu_begin(ui_context *ui, const char *label) {
    ui_id id = ui_get_id(ui, label);
    float w = text_width(ui, label, label_len(label)) + ui_em(ui, 1.0f);
    ui_rect r = {ui->menubar_x, ui->menubar.y, w, ui->menubar.h};
    ui->menubar_x += w;
    int hovered = over(ui, r);
    if (hovered) ui->hot_next = id;
    if (hovered && mouse_pressed(ui)) {
        ui->open_popup = ui->open_popup == id ? 0 : id;
        ui->popup_just_opened = 1;
    }
    // Moving along the bar while a menu is open opens the one under the pointer.
    if (hovered && ui->open_popup && ui->open_popup != id && !mouse_pressed(ui))
        ui->open_popup = id;
    int open = ui->open_popup == id;
    if (open || ui->hot == id)
        ui_draw_rect(ui->target, r, open ? ui->theme.selection : ui->theme.widget_hot);
    text_in(ui, r, label, label_len(label), ui->theme.text, 1);
    record_claim(ui, id, label, r);
    ui->last_id = id, ui->last_rect = r, ui->last_hovered = hovered;
    if (!open) return 0;
    ui_push_scope(ui, label);
    popup_begin(ui, id, r.x, r.y + r.h, ui_em(ui, 8));
    return 1;
}

void ui_menu_end(ui_context *ui) {
    popup_end(ui, ui->open_popup);
    ui_pop_scope(ui);
}

int ui_menu_item(ui_context *ui, const char *label, const char *shortcut, int enabled) {
    if (popup_item(ui, label, shortcut, enabled, 0)) {
        ui->open_popup = 0;
        return 1;
    }
    return 0;
}

int ui_context_menu_begin(ui_context *ui, const char *label) {
    int opens = ui->last_hovered && ui->in.mouse_pressed[1];
    ui_id id = ui_get_id(ui, label);
    slot *s = get_slot(ui, id);
    if (opens) {
        ui->open_popup = id;
        ui->popup_just_opened = 1;
        s->at_x = ui->in.mouse_x, s->at_y = ui->in.mouse_y;
    }
    if (ui->open_popup != id) return 0;
    ui_push_scope(ui, label);
    // Kept in the window: above the pointer when there is no room below it.
    float y = s->at_y + s->size_h > ui->height ? fmaxf(0, s->at_y - s->size_h) : s->at_y;
    popup_begin(ui, id, s->at_x, y, ui_em(ui, 6));
    return 1;
}

void ui_context_menu_end(ui_context *ui) {
    ui_menu_end(ui);
}

void ui_menu_separator(ui_context *ui) {
    ui_rect line = popup_line(ui, ui_em(ui, 0.4f) + 1);
    float y = line.y + ui_em(ui, 0.2f);
    ui_draw_rect(ui->target, (ui_rect){line.x + 3, y, line.w - 6, 1}, ui->theme.border);
}

// ---- ranges ------------------------------------------------------------------------------

int ui_range(ui_context *ui, const char *label, double *lo, double *hi, double edge, double min,
             double max, const float *bars, int count) {
    ui_id id = ui_get_id(ui, label);
    ui_rect r = ui_next_cell(ui);
    int hovered = over(ui, r);
    if (hovered) ui->hot_next = id;
    double span = max > min ? max - min : 1;
#define RANGE_X(v) (r.x + (float)((fmin(fmax((v), min), max) - min) / span) * r.w)
    int result = 0;
    if (hovered && press_for(ui, id)) { // the nearer end follows the pointer
        ui->active = id;
        if (ui->focus && ui->focus != id) ui->focus = ui->edit_id = ui->typing_id = 0;
        float m = ui->in.mouse_x;
        ui->range_end = fabsf(m - RANGE_X(*hi)) < fabsf(m - RANGE_X(*lo)) ||
                        (RANGE_X(*hi) == RANGE_X(*lo) && m > RANGE_X(*hi));
    }
    if (ui->active == id) {
        double v = min + (double)((ui->in.mouse_x - r.x) / fmaxf(r.w, 1)) * span;
        v = fmin(fmax(v, min), max);
        double *end = ui->range_end ? hi : lo;
        if (ui->range_end ? v < *lo : v > *hi) v = ui->range_end ? *lo : *hi;
        if (v != *end) *end = v;
        result = UI_RANGE_DRAGGING;
        if (ui->in.mouse_released[0]) {
            ui->active = 0;
            result = UI_RANGE_DONE;
        }
    }
    ui->last_id = id, ui->last_rect = r, ui->last_hovered = hovered;
    ui_draw_rect(ui->target, r, ui->theme.widget);
    float top = 0;
    for (int i = 0; i < count; i++)
        top = fmaxf(top, bars[i]);
    for (int i = 0; i < count && top > 0; i++) { // the histogram, scaled to its highest bar
        float bh = (r.h - 2) * bars[i] / top, x0 = r.x + r.w * (float)i / (float)count;
        float x1 = r.x + r.w * (float)(i + 1) / (float)count;
        if (bh > 0)
            ui_draw_rect(ui->target, (ui_rect){x0, r.y + r.h - 1 - bh, fmaxf(x1 - x0, 1), bh},
                         ui->theme.text_dim);
    }
    ui_color sel = ui->theme.accent, soft = ui->theme.accent;
    sel = (sel & 0x00ffffffu) | 0x70000000u; // the range and its soft edges over the bars
    soft = (soft & 0x00ffffffu) | 0x30000000u;
    float xl = RANGE_X(*lo), xh = RANGE_X(*hi);
    float el = RANGE_X(*lo - edge), eh = RANGE_X(*hi + edge);
    ui_draw_rect(ui->target, (ui_rect){el, r.y, xl - el, r.h}, soft);
    ui_draw_rect(ui->target, (ui_rect){xh, r.y, eh - xh, r.h}, soft);
    ui_draw_rect(ui->target, (ui_rect){xl, r.y, fmaxf(xh - xl, 1), r.h}, sel);
    ui_color handle = ui->active == id || ui->hot == id ? ui->theme.accent_hot : ui->theme.text;
    ui_draw_rect(ui->target, (ui_rect){xl - 1, r.y, 2, r.h}, handle);
    ui_draw_rect(ui->target, (ui_rect){xh - 1, r.y, 2, r.h}, handle);
    ui_draw_rect_outline(ui->target, r, ui->theme.border, 1);
#undef RANGE_X
    record_claim(ui, id, label, r);
    return result;
}

// ---- text editing ----------------------------------------------------------------------

static int is_word(char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' ||
           (unsigned char)c >= 0x80;
}

static size_t prev_char(const char *s, size_t i) {
    if (i == 0) return 0;
    i--;
    while (i > 0 && ((unsigned char)s[i] & 0xC0) == 0x80)
        i--;
    return i;
}

static size_t next_char(const char *s, size_t n, size_t i) {
    if (i >= n) return n;
    i++;
    while (i < n && ((unsigned char)s[i] & 0xC0) == 0x80)
        i++;
    return i;
}

static size_t word_left(const char *s, size_t i) {
    while (i > 0 && !is_word(s[i - 1]))
        i--;
    while (i > 0 && is_word(s[i - 1]))
        i--;
    return i;
}

static size_t word_right(const char *s, size_t n, size_t i) {
    while (i < n && !is_word(s[i]))
        i++;
    while (i < n && is_word(s[i]))
        i++;
    return i;
}

static void push_undo(ui_context *ui, const char *buf) {
    if (ui->undo_count == UNDO_MAX) {
        memmove(ui->undo[0], ui->undo[1], (UNDO_MAX - 1) * sizeof ui->undo[0]);
        ui->undo_count--;
    }
    snprintf(ui->undo[ui->undo_count++], EDIT_MAX, "%s", buf);
}

// Deletes the selection; returns whether there was one.
static int delete_selection(ui_context *ui, char *buf) {
    if (ui->cursor == ui->anchor) return 0;
    size_t a = ui->cursor < ui->anchor ? ui->cursor : ui->anchor;
    size_t b = ui->cursor < ui->anchor ? ui->anchor : ui->cursor;
    memmove(buf + a, buf + b, strlen(buf + b) + 1);
    ui->cursor = ui->anchor = a;
    return 1;
}

static void insert_text(ui_context *ui, char *buf, size_t size, const char *text) {
    delete_selection(ui, buf);
    size_t n = strlen(buf), add = 0;
    for (const char *t = text; *t && *t != '\n' && *t != '\r'; t++)
        add++;
    if (n + add + 1 > size) add = size - 1 - n;
    while (add > 0 && ((unsigned char)text[add] & 0xC0) == 0x80)
        add--; // whole code points
    memmove(buf + ui->cursor + add, buf + ui->cursor, n - ui->cursor + 1);
    memcpy(buf + ui->cursor, text, add);
    ui->cursor += add;
    ui->anchor = ui->cursor;
}

// The editing behaviour of a focused text field; draws the field. Returns UI_TEXT_*.
static int text_edit(ui_context *ui, ui_id id, ui_rect r, char *buf, size_t size, int flags) {
    int hovered = over(ui, r), rc = 0;
    if (hovered) ui->hot_next = id;
    if (ui->focusable_count < FOCUSABLE_MAX) ui->focusables[ui->focusable_count++] = id;
    float pad = ui_em(ui, 0.3f);
    size_t n = strlen(buf);
    if (hovered && press_for(ui, id)) {
        if (ui->focus != id) {
            ui->focus = id;
            ui->edit_id = 0;
        }
        ui->active = id;
    }
    if (ui->focus == id && ui->edit_id != id) { // gaining focus
        ui->edit_id = id;
        ui->edit_len = n;
        snprintf(ui->edit_restore, sizeof ui->edit_restore, "%s", buf);
        ui->undo_count = 0;
        ui->typing_run = 0;
        ui->cursor = n;
        ui->anchor = 0; // all selected, as most editors do on focus
        ui->caret_time = ui->in.time;
        ui->keep_selection = 0;
        if (hovered && press_for(ui, id) && (flags & UI_TEXTBOX_SELECT_ALL))
            ui->select_all_press_x = ui->in.mouse_x, // keep all selected: typing replaces
                ui->keep_selection = 1;
        else if (hovered && press_for(ui, id))
            ui->cursor = ui->anchor =
                ui_font_offset_at(ui->font, UI_FACE_SANS, buf, n, ui->in.mouse_x - r.x - pad);
    } else if (ui->focus == id && hovered && press_for(ui, id) && ui->in.double_click) {
        // A double click selects the word under it (a number field: all of it).
        size_t at = ui_font_offset_at(ui->font, UI_FACE_SANS, buf, n, ui->in.mouse_x - r.x - pad);
        ui->anchor = (flags & UI_TEXTBOX_SELECT_ALL) ? 0 : word_left(buf, at);
        ui->cursor = (flags & UI_TEXTBOX_SELECT_ALL) ? n : word_right(buf, n, at);
        ui->select_all_press_x = ui->in.mouse_x;
        ui->keep_selection = 1;
    } else if (ui->focus == id && ui->active == id && ui->in.mouse_down[0] &&
               !(ui->keep_selection && !mouse_pressed(ui) &&
                 fabsf(ui->in.mouse_x - ui->select_all_press_x) < ui_em(ui, 0.3f))) {
        ui->keep_selection = 0;
        // Click/drag selects (a select-all field keeps its selection until a drag).
        size_t at = ui_font_offset_at(ui->font, UI_FACE_SANS, buf, n, ui->in.mouse_x - r.x - pad);
        if (mouse_pressed(ui) && !(ui->in.mods & UI_MOD_SHIFT)) ui->anchor = at;
        ui->cursor = at;
    }
    if (ui->focus == id && ui->edit_id == id && n != ui->edit_len) // replaced from outside
        ui->cursor = ui->anchor = n;
    if (ui->focus == id) ui->focus_seen = 1;
    if (ui->focus == id) {
        const ui_input *in = &ui->in;
        int shift = in->mods & UI_MOD_SHIFT, ctrl = in->mods & UI_MOD_CTRL;
        if (ui->cursor > n) ui->cursor = n;
        if (ui->anchor > n) ui->anchor = n;
        size_t before = ui->cursor;
        if (in->key_pressed[UI_KEY_LEFT])
            ui->cursor = ctrl ? word_left(buf, ui->cursor) : prev_char(buf, ui->cursor);
        if (in->key_pressed[UI_KEY_RIGHT])
            ui->cursor = ctrl ? word_right(buf, n, ui->cursor) : next_char(buf, n, ui->cursor);
        if (in->key_pressed[UI_KEY_HOME]) ui->cursor = 0;
        if (in->key_pressed[UI_KEY_END]) ui->cursor = n;
        if (ui->cursor != before && !shift) ui->anchor = ui->cursor;
        if (ui->cursor != before) ui->typing_run = 0;
        if (ctrl && in->key_pressed[UI_KEY_A]) ui->anchor = 0, ui->cursor = n;
        if (ctrl && (in->key_pressed[UI_KEY_C] || in->key_pressed[UI_KEY_X]) &&
            ui->cursor != ui->anchor && ui->clipboard.set) {
            size_t a = ui->cursor < ui->anchor ? ui->cursor : ui->anchor;
            size_t b = ui->cursor < ui->anchor ? ui->anchor : ui->cursor;
            char tmp[EDIT_MAX];
            snprintf(tmp, sizeof tmp, "%.*s", (int)(b - a), buf + a);
            ui->clipboard.set(ui->clipboard.user, tmp);
            if (in->key_pressed[UI_KEY_X]) {
                push_undo(ui, buf);
                delete_selection(ui, buf);
                rc |= UI_TEXT_CHANGED;
            }
        }
        if (ctrl && in->key_pressed[UI_KEY_V] && ui->clipboard.get) {
            const char *clip = ui->clipboard.get(ui->clipboard.user);
            if (clip && *clip) {
                push_undo(ui, buf);
                insert_text(ui, buf, size, clip);
                rc |= UI_TEXT_CHANGED;
                ui->typing_run = 0;
            }
        }
        if (ctrl && in->key_pressed[UI_KEY_Z] && ui->undo_count > 0) {
            snprintf(buf, size, "%s", ui->undo[--ui->undo_count]);
            ui->cursor = ui->anchor = strlen(buf);
            ui->typing_run = 0;
            rc |= UI_TEXT_CHANGED;
        }
        if (in->text[0] && !ctrl) {
            if (!ui->typing_run) push_undo(ui, buf); // one undo step per run of typing
            ui->typing_run = 1;
            insert_text(ui, buf, size, in->text);
            rc |= UI_TEXT_CHANGED;
        }
        if (in->key_pressed[UI_KEY_BACKSPACE] || in->key_pressed[UI_KEY_DELETE]) {
            size_t len = strlen(buf);
            if (ui->cursor == ui->anchor) {
                if (in->key_pressed[UI_KEY_BACKSPACE])
                    ui->anchor = ctrl ? word_left(buf, ui->cursor) : prev_char(buf, ui->cursor);
                else
                    ui->anchor =
                        ctrl ? word_right(buf, len, ui->cursor) : next_char(buf, len, ui->cursor);
            }
            if (ui->cursor != ui->anchor) {
                push_undo(ui, buf);
                delete_selection(ui, buf);
                ui->typing_run = 0;
                rc |= UI_TEXT_CHANGED;
            }
        }
        if (in->key_pressed[UI_KEY_ENTER]) rc |= UI_TEXT_SUBMIT;
        if (in->key_pressed[UI_KEY_ESCAPE]) { // cancel: back to the text it had on focus
            if (strcmp(buf, ui->edit_restore) != 0) rc |= UI_TEXT_CHANGED;
            snprintf(buf, size, "%s", ui->edit_restore);
            ui->focus = 0;
            ui->edit_id = 0;
        }
        if (ui->tab_pending &&
            !(flags &
              UI_TEXTBOX_OWN_TAB)) { // Tab: the next field in drawing order (Shift+Tab: previous)
            ui->tab_pending = 0;
            if (shift) {
                if (ui->focusable_count >= 2) {
                    ui->focus = ui->focusables[ui->focusable_count - 2];
                    ui->edit_id = 0;
                }
            } else {
                ui->tab_from = id;
            }
        }
        if (rc & UI_TEXT_CHANGED) ui->caret_time = in->time;
    }
    ui->last_id = id, ui->last_rect = r, ui->last_hovered = hovered;
    // Draw: field, selection, text scrolled so the caret shows, caret.
    n = strlen(buf);
    if (ui->focus == id) ui->edit_len = n;
    ui_draw_rect(ui->target, r, ui->focus == id ? ui->theme.panel_alt : widget_colour(ui, id));
    if (ui->focus == id) ui_draw_rect_outline(ui->target, r, ui->theme.accent, 1);
    ui_draw_push_clip(ui->target, r);
    float caret_x =
        ui_font_text_width(ui->font, UI_FACE_SANS, buf, ui->focus == id ? ui->cursor : 0);
    float shift_x = fmaxf(0.0f, caret_x - (r.w - 3 * pad));
    float tx = r.x + pad - shift_x, ty = r.y + (r.h - ui_font_line_height(ui->font)) * 0.5f;
    if (ui->focus == id && ui->cursor != ui->anchor) {
        size_t a = ui->cursor < ui->anchor ? ui->cursor : ui->anchor;
        size_t b = ui->cursor < ui->anchor ? ui->anchor : ui->cursor;
        float xa = ui_font_text_width(ui->font, UI_FACE_SANS, buf, a);
        float xb = ui_font_text_width(ui->font, UI_FACE_SANS, buf, b);
        ui_draw_rect(ui->target, (ui_rect){tx + xa, ty, xb - xa, ui_font_line_height(ui->font)},
                     ui->theme.selection);
    }
    ui_draw_text(ui->target, UI_FACE_SANS, tx, ty, buf, n, ui->theme.text);
    if (ui->focus == id && fmod(ui->in.time - ui->caret_time, 1.0) < 0.6)
        ui_draw_rect(ui->target, (ui_rect){tx + caret_x, ty, 1, ui_font_line_height(ui->font)},
                     ui->theme.text);
    ui_draw_pop_clip(ui->target);
    return rc;
}

int ui_textbox(ui_context *ui, const char *label, char *buf, size_t size) {
    return ui_textbox_flags(ui, label, buf, size, 0);
}

int ui_last_focused(const ui_context *ui) {
    return ui->last_id && ui->focus == ui->last_id;
}
const ui_input *ui_get_input(const ui_context *ui) {
    return &ui->in;
}

void ui_form_field(ui_context *ui, const char *label, const char *name, char *buf, size_t size,
                   const char *tip) {
    float w[2] = {ui_em(ui, 7), 0};
    ui_row(ui, 2, w, 0);
    ui_label(ui, label);
    ui_textbox_flags(ui, name, buf, size, UI_TEXTBOX_SELECT_ALL);
    ui_tooltip(ui, tip);
}

int ui_textbox_flags(ui_context *ui, const char *label, char *buf, size_t size, int flags) {
    ui_id id = ui_get_id(ui, label);
    if (ui->focus_request == id) {
        ui->focus = id;
        ui->edit_id = 0;
        ui->focus_request = 0;
    }
    // Tab from the previous field lands here; after the last, on the first.
    if ((ui->tab_from && ui->tab_from != id) || (ui->tab_to_first && ui->focusable_count == 0)) {
        ui->focus = id;
        ui->edit_id = 0;
        ui->tab_from = 0;
        ui->tab_to_first = 0;
    }
    ui_rect r = ui_next_cell(ui);
    record_claim(ui, id, label, r);
    return text_edit(ui, id, r, buf, size, flags);
}

void ui_focus(ui_context *ui, const char *label) {
    ui->focus_request = ui_get_id(ui, label);
}

// ---- log view ---------------------------------------------------------------------------

void ui_log(ui_context *ui, const char *name, size_t count,
            ui_log_line (*line)(void *user, size_t i), void *user, float height) {
    ui_id id = ui_get_id(ui, name);
    slot *s = get_slot(ui, id);
    layout *l = top_layout(ui);
    if (l->col < l->columns) l->col = l->columns;
    ui_rect r = {l->body.x, l->y, l->body.w, height};
    l->y += height + ui_em(ui, 0.2f);
    record_claim(ui, id, name, r);
    float lh = ui_font_line_height(ui->font), pad = ui_em(ui, 0.3f), bar = ui_em(ui, 0.3f);
    // Long lines fold into rows as wide as the log (beside its scroll bar).
    float advance = ui_font_text_width(ui->font, UI_FACE_MONO, "M", 1);
    float fit = advance > 0 ? (r.w - 2 * pad - bar) / advance : 1;
    size_t cols = fit >= 1 ? (size_t)fit : 1, rows = 0;
    for (size_t i = 0; i < count; i++)
        rows += log_rows(line(user, i).text, cols);
    float content = (float)rows * lh, view = r.h - 2 * pad,
          max_scroll = fmaxf(0.0f, content - view);
    if (!s->initialised) s->initialised = 1, s->at_bottom = 1;
    if (ui->in.wheel != 0 && over(ui, r)) {
        s->scroll -= ui->in.wheel * 3 * lh;
        s->at_bottom = 0;
    }
    if (s->at_bottom) s->scroll = max_scroll;
    s->scroll = fminf(fmaxf(s->scroll, 0.0f), max_scroll);
    if (s->scroll >= max_scroll - 0.5f) s->at_bottom = 1;
    ui_draw_rect(ui->target, r, ui->theme.bg);
    ui_draw_push_clip(ui->target, r);
    size_t first = (size_t)(s->scroll / lh), row = 0;
    for (size_t i = 0; i < count && r.y + pad + (float)row * lh - s->scroll <= r.y + r.h; i++) {
        ui_log_line ln = line(user, i);
        const char *at = ln.text;
        do {
            size_t n = log_row_bytes(at, cols);
            float y = r.y + pad + (float)row * lh - s->scroll;
            if (row >= first && y <= r.y + r.h)
                ui_draw_text(ui->target, UI_FACE_MONO, r.x + pad, y, at, n, ln.color);
            at += n, row++;
        } while (*at);
    }
    if (max_scroll > 0) {
        float th = fmaxf(ui_em(ui, 1), r.h * view / content);
        ui_draw_rect(
            ui->target,
            (ui_rect){r.x + r.w - bar, r.y + (r.h - th) * (s->scroll / max_scroll), bar, th},
            ui->theme.widget_hot);
    }
    ui_draw_pop_clip(ui->target);
    ui->last_id = id, ui->last_rect = r, ui->last_hovered = over(ui, r);
}

// ---- curve editor ----------------------------------------------------------------------

static float clampf(float x, float lo, float hi) {
    return x < lo ? lo : x > hi ? hi : x;
}

int ui_curve(ui_context *ui, const char *label, float *t, float *v, int *count, int max) {
    ui_id id = ui_get_id(ui, label);
    ui_rect r = ui_next_cell(ui);
    record_claim(ui, id, label, r);
    float pad = ui_em(ui, 0.45f);
    ui_rect a = {r.x + pad, r.y + pad, r.w - 2 * pad, r.h - 2 * pad}; // the unit square
    if (a.w < 1 || a.h < 1 || *count < 2) return 0;
    int n = *count, done = 0;
    const float mx = ui->in.mouse_x, my = ui->in.mouse_y;
    int hovered = over(ui, r);
    if (hovered) ui->hot_next = id;
    // The point under the pointer, within half an em of its handle.
    int near = -1;
    float best = ui_em(ui, 0.5f) * ui_em(ui, 0.5f);
    for (int k = 0; k < n; k++) {
        float dx = mx - (a.x + t[k] * a.w), dy = my - (a.y + (1 - v[k]) * a.h);
        if (dx * dx + dy * dy <= best) best = dx * dx + dy * dy, near = k;
    }
    float pt = clampf((mx - a.x) / a.w, 0, 1), pv = clampf(1 - (my - a.y) / a.h, 0, 1);
    if (hovered && press_for(ui, id) && near >= 0 && !ui->in.double_click) {
        ui->active = id;
        ui->curve_point = near;
        ui->curve_t = t[near], ui->curve_v = v[near];
    } else if (hovered && press_for(ui, id) && ui->in.double_click && near < 0 && n < max &&
               pt > t[0] && pt < t[n - 1]) { // a new point where the double click was
        int at = 1;
        while (at < n - 1 && t[at] < pt)
            at++;
        if (pt > t[at - 1] && pt < t[at]) {
            memmove(t + at + 1, t + at, (size_t)(n - at) * sizeof *t);
            memmove(v + at + 1, v + at, (size_t)(n - at) * sizeof *v);
            t[at] = pt, v[at] = pv;
            *count = ++n;
            done = 1;
        }
    }
    if (hovered && ui->in.mouse_pressed[1] && near > 0 && near < n - 1 && n > 2) {
        memmove(t + near, t + near + 1, (size_t)(n - near - 1) * sizeof *t);
        memmove(v + near, v + near + 1, (size_t)(n - near - 1) * sizeof *v);
        *count = --n;
        done = 1;
    }
    int dragged = ui->active == id && ui->curve_point < n ? ui->curve_point : -1;
    if (dragged >= 0) { // ends move up and down only; inner points stay between neighbours
        const float gap = 1e-3f;
        ui->curve_v = pv;
        ui->curve_t = dragged == 0       ? t[0]
                      : dragged == n - 1 ? t[n - 1]
                                         : clampf(pt, t[dragged - 1] + gap, t[dragged + 1] - gap);
        if (!ui->in.mouse_down[0]) {
            ui->active = 0;
            done = t[dragged] != ui->curve_t || v[dragged] != ui->curve_v;
            t[dragged] = ui->curve_t, v[dragged] = ui->curve_v;
            dragged = -1;
        }
    }
    ui->last_id = id, ui->last_rect = r, ui->last_hovered = hovered;
    // The square, quarter lines, the curve and its handles (the dragged one where it is).
    ui_draw_rect(ui->target, r, ui->theme.widget);
    for (int q = 1; q < 4; q++) {
        float gx = a.x + a.w * q / 4, gy = a.y + a.h * q / 4;
        ui_draw_line(ui->target, gx, a.y, gx, a.y + a.h, ui->theme.panel_alt, 1);
        ui_draw_line(ui->target, a.x, gy, a.x + a.w, gy, ui->theme.panel_alt, 1);
    }
    float px = 0, py = 0;
    for (int k = 0; k < n; k++) {
        float tk = k == dragged ? ui->curve_t : t[k], vk = k == dragged ? ui->curve_v : v[k];
        float x = a.x + tk * a.w, y = a.y + (1 - vk) * a.h;
        if (k == 0 && tk > 0) px = a.x, py = y; // flat before the first point
        if (k > 0 || tk > 0) ui_draw_line(ui->target, px, py, x, y, ui->theme.accent, 2);
        px = x, py = y;
    }
    if (px < a.x + a.w) ui_draw_line(ui->target, px, py, a.x + a.w, py, ui->theme.accent, 2);
    float h = ui_em(ui, 0.22f);
    for (int k = 0; k < n; k++) {
        float tk = k == dragged ? ui->curve_t : t[k], vk = k == dragged ? ui->curve_v : v[k];
        float x = a.x + tk * a.w, y = a.y + (1 - vk) * a.h;
        ui_color c = k == dragged || (k == near && hovered) ? ui->theme.accent_hot : ui->theme.text;
        ui_draw_rect(ui->target, (ui_rect){x - h, y - h, 2 * h, 2 * h}, c);
    }
    return done;
}
