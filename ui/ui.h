// Orogen's immediate-mode UI (after microui and Dear ImGui): the UI is a function of
// the editor's state, called every frame. Widgets are identified by ids hashed from
// their label and the enclosing scopes ("Label##suffix" disambiguates; only "Label"
// is shown; a label that shows nothing, "##Opacity", is named by its suffix and a slider
// or combo box then shows only its value). The library keeps only what must survive a frame: the
// hot, active and focused widgets, drag and text-edit state, scroll offsets, open menus and
// sections. It produces a draw list (ui_draw.h) and knows nothing of OpenGL, windows or terrain.
//
// Sizes in layouts: > 0 pixels (use ui_em for sizes that follow the font and the UI
// scale), < 0 a fraction of the row (-0.5 = half), 0 fills what is left (shared).
#ifndef OROGEN_UI_H
#define OROGEN_UI_H

#include "ui/ui_draw.h"
#include "ui/ui_font.h"

#include <stddef.h>
#include <stdint.h>

typedef uint32_t ui_id;

typedef enum ui_key {
    UI_KEY_TAB,
    UI_KEY_ENTER,
    UI_KEY_ESCAPE,
    UI_KEY_BACKSPACE,
    UI_KEY_DELETE,
    UI_KEY_LEFT,
    UI_KEY_RIGHT,
    UI_KEY_UP,
    UI_KEY_DOWN,
    UI_KEY_HOME,
    UI_KEY_END,
    UI_KEY_A,
    UI_KEY_C,
    UI_KEY_V,
    UI_KEY_X,
    UI_KEY_Z,
    UI_KEY_COUNT
} ui_key;

enum { UI_MOD_SHIFT = 1, UI_MOD_CTRL = 2, UI_MOD_ALT = 4 };

// One input event as the window system delivers it (see ui_input_queue).
typedef enum ui_event_kind {
    UI_EVENT_MOVE,   // the pointer moved to (x, y)
    UI_EVENT_BUTTON, // button went down or up at (x, y)
    UI_EVENT_WHEEL,  // wheel notches
    UI_EVENT_KEY,    // a key went down (or repeated) or up
    UI_EVENT_TEXT,   // a typed code point (UTF-8 in text)
} ui_event_kind;

typedef struct ui_event {
    ui_event_kind kind;
    float x, y;   // MOVE, BUTTON: the pointer (pixels)
    int button;   // BUTTON: 0 left, 1 right, 2 middle
    int down;     // BUTTON, KEY: 1 pressed (or repeated), 0 released
    int repeat;   // KEY: an auto-repeat of a held key
    int key;      // KEY: a ui_key, or -1 for a key the UI does not use
    int code;     // KEY: the window system's key code, for the caller's shortcuts
    int mods;     // BUTTON, KEY: UI_MOD_* held
    float wheel;  // WHEEL: notches, + away from the user
    char text[8]; // TEXT: one code point, UTF-8
    double time;  // seconds
} ui_event;

enum { UI_FRAME_EVENTS_MAX = 64 };

// One frame's input, filled by the window (pixels, origin top left), or made from
// queued events by ui_input_queue_frame.
typedef struct ui_input {
    float mouse_x, mouse_y;
    int mouse_down[3];             // left, right, middle held now
    int mouse_pressed[3];          // went down this frame
    int mouse_released[3];         // went up this frame
    int double_click;              // the left press this frame was a double click
    float wheel;                   // notches, + away from the user
    int key_pressed[UI_KEY_COUNT]; // pressed or repeated this frame
    int mods;                      // UI_MOD_* held
    char text[64];                 // UTF-8 typed this frame
    double time;                   // seconds
    // The events this frame was made of, in order (from ui_input_queue_frame): what the
    // UI did not take (ui_took_keys, ui_captures_point) is the caller's to use.
    ui_event events[UI_FRAME_EVENTS_MAX];
    int event_count;
} ui_input;

// Events queued as they arrive and handed out frame by frame, so that none is lost or
// seen twice however slow a frame is (as Dear ImGui's input queue "trickles" them): a
// frame takes events in order until one would change what an earlier one meant, i.e. a
// second button change, a move after a button change (the press is seen where it
// happened), a key after another key or text, text after a key the UI uses. The rest
// waits for the next frame. Typed text stays together while a field has the keyboard.
enum { UI_QUEUE_MAX = 4096 };
typedef struct ui_input_queue {
    ui_event events[UI_QUEUE_MAX];
    size_t head, count;
    size_t merged;  // moves merged because the queue was full (no button or key is ever)
    ui_input state; // the pointer, held buttons and modifiers between frames
    double last_press_time;
    float last_press_x, last_press_y;
} ui_input_queue;

void ui_input_queue_init(ui_input_queue *q);
void ui_input_queue_push(ui_input_queue *q, const ui_event *e);
// Fills in with the next frame's share of the queue; typing: a text field has the
// keyboard (ui_wants_keyboard), so keys and text of plain typing go in one frame.
// Returns how many events still wait (draw another frame while > 0).
size_t ui_input_queue_frame(ui_input_queue *q, int typing, ui_input *in);

typedef struct ui_theme {
    ui_color bg, panel, panel_alt, border, text, text_dim, text_error, accent, accent_hot, widget,
        widget_hot, widget_active, selection;
} ui_theme;

// Clipboard through the window system (GLFW's); tests inject their own.
typedef struct ui_clipboard {
    const char *(*get)(void *user);
    void (*set)(void *user, const char *text);
    void *user;
} ui_clipboard;

typedef struct ui_context ui_context;

// font: made by the caller at the UI's pixel size (owned by the caller).
ui_context *ui_create(const ui_font *font);
void ui_destroy(ui_context *ui);
// Another font (a new UI scale); the caller frees the old one.
void ui_set_font(ui_context *ui, const ui_font *font);
void ui_set_clipboard(ui_context *ui, ui_clipboard cb);
const ui_theme *ui_get_theme(const ui_context *ui);
const ui_font *ui_get_font(const ui_context *ui);

// A frame: begin with the input and the window's size, build widgets, end.
void ui_begin(ui_context *ui, const ui_input *in, float width, float height);
// The frame's draw list, valid until the next ui_begin.
const ui_draw_list *ui_end(ui_context *ui);

// Whether the UI wants the mouse (the pointer is over a widget or panel, or a widget
// is being dragged) or the keyboard (a text field has focus): the viewport must not
// take those events then. Valid after ui_end, for the next frame's events.
int ui_wants_mouse(const ui_context *ui);
// Whether the UI would take a press at (x, y) now: the point is on a panel, menu bar,
// open popup or modal dialog of the last frame, or a widget is being dragged. Unlike
// ui_wants_mouse it uses the given point, not where the pointer was at the last frame.
int ui_captures_point(const ui_context *ui, float x, float y);
int ui_wants_keyboard(const ui_context *ui);
// The last frame's keys went to a text field (one had the keyboard when the frame began
// or has it at its end) or closed a popup: the caller must not use them as shortcuts too.
int ui_took_keys(const ui_context *ui);
// A text field (a slider being typed into) that refused its text on Enter says why
// here (it stays open); "" when none does. Valid after ui_end.
const char *ui_field_error(const ui_context *ui);

// The messages the last frame showed the user: every label drawn in the theme's error
// colour and a field's refusal (ui_field_error), each named by where it is ("Import
// options", "Dock/Radius"), for tests and the console's ui_messages.
typedef struct ui_message_info {
    char where[128];
    char text[512];
} ui_message_info;
size_t ui_message_count(const ui_context *ui);
const ui_message_info *ui_message_at(const ui_context *ui, size_t i);
// Something animates or waits (a tooltip delay, a caret blink): draw another frame.
int ui_needs_frame(const ui_context *ui);

// Pixels for n lines of the font (the unit editor code sizes things in).
float ui_em(const ui_context *ui, float n);

// --- ids and scopes ---------------------------------------------------------------
// An id is the label's hash within the scope stack: panels, pushed scopes, tree nodes
// and sections (the widgets after a ui_section header, up to the next one at the same
// level or the end of the enclosing scope, are scoped by it). Two widgets claiming one
// id in one frame are a conflict (they would share hover, drags and typing): the
// library records it, and in strict mode (debug builds, or OROGEN_UI_STRICT=1 in the
// environment, as the tests set) prints both widgets' paths and aborts.
ui_id ui_get_id(ui_context *ui, const char *label);
void ui_push_scope(ui_context *ui, const char *name);
// Pops the last pushed scope (and any section opened inside it).
void ui_pop_scope(ui_context *ui);
void ui_set_strict_ids(ui_context *ui, int strict);
// The last frame's id conflicts: each the paths of the two widgets (sections shown as
// path segments too), e.g. "Dock/Raise/Radius" and "Dock/World/Radius".
size_t ui_id_conflict_count(const ui_context *ui);
const char *ui_id_conflict(const ui_context *ui, size_t i, int which);

// Named widgets: every widget's rectangle of the last frame under its path of scope
// names and label ("Tools/Raise"), for tests that click widgets by name.
typedef struct ui_widget_info {
    char name[128];
    ui_rect rect;
} ui_widget_info;
size_t ui_widget_count(const ui_context *ui);
const ui_widget_info *ui_widget_at(const ui_context *ui, size_t i);
const ui_widget_info *ui_widget_find(const ui_context *ui, const char *name);

// --- layout -----------------------------------------------------------------------
// A region (a panel's inside): widgets flow top to bottom in rows.
void ui_row(ui_context *ui, int columns, const float *widths, float height);
// The next cell of the current row (starting a new row like the last when full).
ui_rect ui_next_cell(ui_context *ui);
// Splits r into n cells along x (or y) with the same size rules; returns cells in out.
void ui_split(const ui_context *ui, ui_rect r, int horizontal, int n, const float *sizes,
              ui_rect *out);

// A panel: a rectangle with a background, its own scope and a vertical scroll bar
// when the content is taller than it.
void ui_panel_begin(ui_context *ui, const char *name, ui_rect r);
void ui_panel_end(ui_context *ui);
// Scrolls the open panel so the widget just placed shows, from the next frame (the
// History list following its current step).
void ui_reveal_last(ui_context *ui);

// --- widgets (each takes the next layout cell) -------------------------------------
void ui_label(ui_context *ui, const char *text);
void ui_label_colored(ui_context *ui, const char *text, ui_color c);
// The whole text over as many full-width rows as it needs, broken between words (a
// message must never be cut at the panel's edge); in the error colour it is one message.
// Each row is a named widget (its text); rows after it are single full-width ones.
void ui_label_wrapped(ui_context *ui, const char *text, ui_color c);
int ui_button(ui_context *ui, const char *label); // 1 when clicked
int ui_toggle_button(ui_context *ui, const char *label, int on);
// The same with its label left-aligned after indent pixels (room for an icon); with
// an indent of the cell's whole width no text is drawn (an icon-only button, still
// named by its label).
int ui_toggle_button_indented(ui_context *ui, const char *label, int on,
                              float indent);                    // a button shown pressed when on
int ui_checkbox(ui_context *ui, const char *label, int *value); // 1 when changed
// A button showing a texture of the renderer's (0: none yet) with its label across the
// bottom; drawn selected when on. 1 when clicked.
int ui_image_button(ui_context *ui, const char *label, uint32_t texture, int on);
int ui_radio(ui_context *ui, const char *label, int *value, int option);
// A line of a list, left-aligned, highlighted when on. 1 when clicked.
int ui_selectable(ui_context *ui, const char *label, int on);
// A slider over [lo, hi], as Unreal's and Blender's number fields: a drag scrubs from
// the value (Shift: 10x finer); a click, double click or Ctrl+click opens a text field
// without changing the value; while it is open every key goes to it; Enter sets a
// number in [lo, hi] (other text keeps the field open, ui_field_error says why), Esc or
// a click elsewhere leaves the value as it was. fmt formats the value ("%.1f m").
// 1 when changed.
int ui_slider(ui_context *ui, const char *label, double *value, double lo, double hi,
              const char *fmt);
// A combo box: items[0..count); 1 when *index changed.
int ui_combo(ui_context *ui, const char *label, int *index, const char *const *items, int count);
// Single-line text input in buf (size bytes, NUL-terminated). Returns UI_TEXT_CHANGED
// and/or UI_TEXT_SUBMIT (Enter); Esc while editing restores the text it had on focus.
enum { UI_TEXT_CHANGED = 1, UI_TEXT_SUBMIT = 2 };
int ui_textbox(ui_context *ui, const char *label, char *buf, size_t size);
// The same; with UI_TEXTBOX_OWN_TAB, Tab does not move the focus (the caller uses it,
// e.g. for completion); with UI_TEXTBOX_SELECT_ALL a click that focuses the field
// selects all its text, so typing replaces it (number fields, paths, as an address bar).
enum { UI_TEXTBOX_OWN_TAB = 1, UI_TEXTBOX_SELECT_ALL = 2 };
int ui_textbox_flags(ui_context *ui, const char *label, char *buf, size_t size, int flags);
// A row of a form: the label in a fixed column, then a text box (named name, clicking
// selects its text) filling the rest, with a tooltip.
void ui_form_field(ui_context *ui, const char *label, const char *name, char *buf, size_t size,
                   const char *tip);
// Whether the last widget has the keyboard focus.
int ui_last_focused(const ui_context *ui);
// This frame's input (for widgets built on top of the library).
const ui_input *ui_get_input(const ui_context *ui);
// Gives keyboard focus to the text box with this label in the current scope next frame.
void ui_focus(ui_context *ui, const char *label);
void ui_separator(ui_context *ui);
// A curve editor filling the next cell: points (t[i], v[i]) in [0, 1] with t rising,
// joined by straight lines and held flat beyond the ends (as brush falloff curves are
// read). Drag a point to move it (the two ends only up and down, the others between
// their neighbours); double-click the square to add a point; right-click a point to
// remove it (never an end). The arrays change, and 1 is returned, only when a change
// is done (a drag released, a point added or removed); max is the arrays' room.
int ui_curve(ui_context *ui, const char *label, float *t, float *v, int *count, int max);
void ui_progress(ui_context *ui, double fraction, const char *text);
// A range [*lo, *hi] within [min, max] drawn over a histogram (bars[0..count) spread
// across the cell, scaled to the highest; NULL for none), with a soft edge of `edge`
// units each side shown lighter (as masks and material rules weigh them). A press
// moves the nearer end to the pointer and a drag moves it on (never past the other
// end). Returns UI_RANGE_DRAGGING while the ends follow a drag (*lo, *hi changed live)
// and UI_RANGE_DONE on the frame the drag is released; 0 otherwise.
enum { UI_RANGE_DRAGGING = 1, UI_RANGE_DONE = 2 };
int ui_range(ui_context *ui, const char *label, double *lo, double *hi, double edge, double min,
             double max, const float *bars, int count);
// A collapsible section header; returns 1 while open (starts open when default_open).
int ui_section(ui_context *ui, const char *label, int default_open);
// A tree node: a row with an arrow that opens and closes it. While open (returns 1) the
// rows after it are indented and named below it (NODE/child) until ui_tree_pop, which
// is called only when it returned 1.
int ui_tree_push(ui_context *ui, const char *label, int default_open);
void ui_tree_pop(ui_context *ui);
// A colour swatch with its label beside it, shown selected when on; 1 when clicked.
int ui_color_swatch(ui_context *ui, const char *label, ui_color color, int on);
// Opens or closes the section with this label (in the current scope) from the next frame.
void ui_section_set(ui_context *ui, const char *label, int open);
// Shows text near the pointer after a short hover over the last widget.
void ui_tooltip(ui_context *ui, const char *text);
// The list this frame draws into, for custom drawing inside a widget's rectangle
// (icons); drawing there follows the current clip.
ui_draw_list *ui_draw_target(ui_context *ui);
// The last widget's rectangle and whether the pointer is over it.
ui_rect ui_last_rect(const ui_context *ui);
int ui_last_hovered(const ui_context *ui);

// Read-only multi-line text (a log) of count lines from line(user, i), scrolled to the
// bottom while it was at the bottom; height in pixels.
typedef struct ui_log_line {
    const char *text;
    ui_color color;
} ui_log_line;
void ui_log(ui_context *ui, const char *name, size_t count,
            ui_log_line (*line)(void *user, size_t i), void *user, float height);

// A modal dialog over r for the rest of this frame: widgets outside r ignore the
// pointer. Call before building anything (the dialog's rectangle is known up front).
void ui_modal(ui_context *ui, ui_rect r);
// Whether a modal dialog is up in this frame (what is drawn after it would cover it).
int ui_modal_open(const ui_context *ui);
// Darkens everything drawn so far (behind a modal dialog).
void ui_dim(ui_context *ui);

// --- menus --------------------------------------------------------------------------
// A menu bar across r; menus open on click and close on a pick, Esc or a click outside.
void ui_menubar_begin(ui_context *ui, ui_rect r);
void ui_menubar_end(ui_context *ui);
int ui_menu_begin(ui_context *ui, const char *label); // 1 while open: add items
void ui_menu_end(ui_context *ui);
// An item with an optional shortcut text; disabled items are shown dim and return 0.
int ui_menu_item(ui_context *ui, const char *label, const char *shortcut, int enabled);
void ui_menu_separator(ui_context *ui);
// A context menu: a right click on the widget built just before it opens it at the
// pointer (above it when there is no room below). 1 while open: add ui_menu_item's,
// then call ui_context_menu_end. Closes on a pick, Esc or a click elsewhere.
int ui_context_menu_begin(ui_context *ui, const char *label);
void ui_context_menu_end(ui_context *ui);

#endif
