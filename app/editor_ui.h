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
    int camera_mode;        // 0 fly, 1 orbit, 2 walk
    int dynamic_resolution; // the window lowers the resolution while moving
} editor_frame_info;

typedef enum editor_pending {
    PENDING_NONE,
    PENDING_NEW_FLAT,
    PENDING_NEW_PLANET, // planet_command
    PENDING_OPEN,       // open_path
    PENDING_NEW_FROM,   // a new flat world from the heightmap at open_path
    PENDING_QUIT,
} editor_pending;

#define EDITOR_RECENT 8

// What the panels may ask of the window holding them beyond running commands: a
// narrow typed interface the window fills in (a NULL member is not offered).
typedef struct editor_host {
    void *user;
    void (*set_camera_mode)(void *user, int mode); // View > Camera: 0 fly, 1 orbit, 2 walk
    void (*close)(void *user);                     // Quit, once nothing unsaved is left
} editor_host;

typedef struct editor_ui {
    console console;
    int show_help, show_about;
    unsigned tool_serial_seen;      // ctx->tool_serial when last drawn: a tool command ends
                                    // the stamp tool (the palette, dock and title agree)
    file_browser files;             // Open and Save as
    interchange_dialog interchange; // Import / Export heightmap options
    double view_x, view_z;          // where the camera is (metres): default placements
    editor_pending pending;         // an action waiting on the unsaved-changes prompt
    int confirm_replace;            // asking before saving over a file that loaded with errors
    int replace_lines;              // how many of its bad lines the dialog lists
    int offer_recovery;             // the Recover unsaved edits dialog is up
    recover_offer recovery;         // what it offers
    char open_path[1024];
    new_planet_dialog new_planet;     // File > New planet...
    char planet_command[1024];        // PENDING_NEW_PLANET: the dialog's new planet command
    char recent[EDITOR_RECENT][1024]; // worlds opened or saved lately, newest first
    int recent_count;
    stamp_browser stamps;          // the stamp tool (stamps.active) and its options
    uint32_t material_textures[8]; // swatches of the paint materials (0: automatic)
    ui_color material_colors[8];   // and their mean colours (the Layers panel)
    int new_rule_material;         // the Materials panel: the material Add rule uses,
    int selected_rule;             // and the rule its buttons act on (-1: none)
    editor_host host;              // the window's side
    work_queue *work;              // where actions are queued (NULL: run at once)
    int history_request;           // Edit > History: open the History section
    const char *glfw_version;      // for Help > About
    int picking_height;            // the next click in the viewport picks the tool's height
    int shape_placing;             // a 3D shape waits for clicks in the viewport (0: none)
    int shape_clicks;              // clicks it has had
    double shape_at[3];            // where the first one picked
    long long tiles_stored;        // the World panel's count of stored tiles, and when
    double tiles_counted_at;       // it was taken (seconds)
} editor_ui;

// A click in the viewport on the surface point hit while a shape is being placed:
// 1 and the command that makes it (cmd) once it has its clicks, 0 while it waits for
// another.
int editor_ui_shape_click(editor_ui *e, const cmd_context *ctx, const double hit[3], char *cmd,
                          size_t len);

void editor_ui_init(editor_ui *e);
void editor_ui_free(editor_ui *e);

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
