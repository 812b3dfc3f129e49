// The editor's panels, built every frame with the UI library: the menu bar, the tool
// palette, the tool options, the world and history panels, the status bar, the
// console and the unsaved-changes prompt. Every action runs a command of the command
// language (echoed in the console); nothing here writes world data.
#ifndef OROGEN_APP_EDITOR_UI_H
#define OROGEN_APP_EDITOR_UI_H

#include "app/console.h"
#include "app/file_browser.h"
#include "app/interchange_dialog.h"
#include "app/new_planet_dialog.h"
#include "app/notices.h"
#include "app/recover_offer.h"
#include "app/stamp_browser.h"
#include "app/work_queue.h"
#include "editor/cmd/commands.h"
#include "renderer/viewport.h"
#include "ui/ui.h"

// What the window measured this frame, for the status bar.
typedef struct editor_frame_info {
    int cursor_valid;
    double cursor[3]; // the terrain point under the pointer
    double frame_ms;  // the last terrain frame's time
    float resolution_scale;
    int pending;
    const char *gl_renderer;
    int resizing; // the brush is being resized on screen: its radius and strength so far
    double resize_radius, resize_strength;
    // The window's own state, shown in View (changed by commands or editor_host).
    double ui_scale;
    int camera_mode;          // 0 fly, 1 orbit, 2 walk
    int dynamic_resolution;   // the window lowers the resolution while moving
    const char *glfw_version; // for Help > About
} editor_frame_info;

typedef enum editor_pending {
    PENDING_NONE,
    PENDING_NEW_FLAT,
    PENDING_NEW_PLANET, // planet_command
    PENDING_OPEN,       // open_path
    PENDING_NEW_FROM,   // a new flat world from the heightmap at open_path
    PENDING_QUIT,
} editor_pending;

// What the panels may ask of the window holding them beyond running commands: a
// narrow typed interface the window fills in (a NULL member is not offered).
typedef struct editor_host {
    void *user;
    void (*set_camera_mode)(void *user, int mode); // View > Camera: 0 fly, 1 orbit, 2 walk
    void (*close)(void *user);                     // Quit, once nothing unsaved is left
    int (*submit)(void *user, const char *text);   // a line typed in the console
} editor_host;

// The panels' state: only app/editor_*.c and materials_panel.c see inside it
// (editor_ui_internal.h); the window holds it through the functions below.
typedef struct editor_ui editor_ui;

// Whether the current tool would be refused by the active layer (hidden or locked),
// and why in a few words ("layer Hill is hidden: raise refused").
int editor_ui_tool_refused(const cmd_context *ctx, char *why, size_t len);

// The panels, empty (NULL: out of memory), and their end: with the textures they made,
// so the window's GL context must be current.
editor_ui *editor_ui_create(void);
void editor_ui_destroy(editor_ui *e);

// The window's side: where actions are queued (NULL: they run at once), where
// failures show until dismissed, and what the panels may ask of the window.
void editor_ui_attach(editor_ui *e, work_queue *work, notices *n, editor_host host);

// The console the panels show: the window echoes its own actions there and keeps its
// history between sessions (console.h).
console *editor_ui_console(editor_ui *e);

// The recent worlds, newest first: one added in front (once), and the i-th (NULL past
// the last).
void editor_ui_add_recent(editor_ui *e, const char *path);
const char *editor_ui_recent(const editor_ui *e, int i);

// A new session's offer to recover the edits a never-saved world left in a journal.
void editor_ui_offer_startup_recovery(editor_ui *e);
// Swatches of the paint materials from the renderer's procedural textures (GL current).
void editor_ui_make_material_swatches(editor_ui *e);

// Help > Keyboard shortcuts (F1).
void editor_ui_show_help(editor_ui *e);
// Opens a world file (one dropped on the window), asking first about unsaved changes.
void editor_ui_open_file(editor_ui *e, cmd_context *ctx, const char *path);

// The height of a picked terrain point as the tools' height= takes it: metres up on a
// flat world, above the radius on a planet.
double editor_ui_picked_height(const cmd_context *ctx, const double hit[3]);

// What a left click in the viewport is for: the tool's drag, or a panel waiting for
// a click on the terrain (the Pick button of a height, a 3D shape being placed, the
// stamp tool).
typedef enum editor_click {
    EDITOR_CLICK_DRAG,
    EDITOR_CLICK_PICK_HEIGHT,
    EDITOR_CLICK_SHAPE,
    EDITOR_CLICK_STAMP,
} editor_click;
editor_click editor_ui_click_wanted(const editor_ui *e);
// That click at the terrain point hit (NULL: no terrain under it): 1 with the command
// that carries it out in cmd and what it came from in *label, 0 when nothing runs
// (yet: a shape may want another click).
int editor_ui_viewport_click(editor_ui *e, const cmd_context *ctx, const double *hit, char *cmd,
                             size_t len, const char **label);

// The stamp tool: whether it is the viewport's tool, the half size of its footprint
// (metres, for samples `spacing` apart), the wheel over the viewport with Ctrl (its
// size) or Shift (its turn), and an image dropped to become a stamp: listed now so it
// shows as new, the folder looked at again at once.
int editor_ui_stamp_active(const editor_ui *e);
double editor_ui_stamp_half_size(const editor_ui *e, double spacing);
void editor_ui_stamp_wheel(editor_ui *e, int ctrl, int shift, double dy);
void editor_ui_stamp_dropped(editor_ui *e, const cmd_context *ctx);
// Before a frame: the stamps listed again when the user's folder changed (1 when they
// were). After it: thumbnails rendered since made textures (1 when some were).
int editor_ui_refresh_stamps(editor_ui *e, const cmd_context *ctx, double now);
int editor_ui_upload_thumbnails(editor_ui *e);

// Builds the whole editor for a width x height window; returns the rectangle left for
// the 3D viewport.
ui_rect editor_ui_build(editor_ui *e, ui_context *ui, cmd_context *ctx, viewport *v,
                        const editor_frame_info *info, float width, float height);

// Saves the world to its file (File > Save, Ctrl+S), first asking in a dialog that
// lists the lines that would change when the file loaded with errors.
void editor_ui_save(editor_ui *e, cmd_context *ctx);

// Runs a command as a UI action: echoed in the console, output and errors there too.
// With a work queue the command is queued (and may run off the UI thread): 0 means queued.
int editor_ui_run(editor_ui *e, cmd_context *ctx, const char *text);

// While long work runs (work_queue.h) the editor shows only this over its last frame:
// a bar over the status bar with what runs, its progress and a Cancel button. Reads
// nothing of the world. Returns 1 when Cancel was clicked.
int editor_ui_build_busy(ui_context *ui, const char *what, double fraction, double elapsed_ms,
                         float width, float height);

// The palette's tools by index (the stamp tool last), and the index of the tool named
// as `tool` takes it ("stamp" for the stamp tool; -1 for a name that is none).
void editor_ui_pick_tool(editor_ui *e, cmd_context *ctx, int index);
int editor_ui_tool_index(const char *name);

// Opens the file browser to save the world somewhere (File > Save as, Ctrl+Shift+S) or
// to open one (File > Open, Ctrl+O).
void editor_ui_save_as(editor_ui *e, cmd_context *ctx);
void editor_ui_open(editor_ui *e, cmd_context *ctx);

// Asks before an action that would lose unsaved changes (New, Quit, the window's
// close button); runs it at once when there are none.
void editor_ui_request(editor_ui *e, cmd_context *ctx, editor_pending action);

#endif
