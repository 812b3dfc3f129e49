// The editor's panels (app/editor_*.c) and what they share: each part builds its
// widgets with the UI library and acts by running commands (editor_ui_run).
#ifndef OROGEN_APP_EDITOR_UI_INTERNAL_H
#define OROGEN_APP_EDITOR_UI_INTERNAL_H

#include "app/editor_ui.h"
#include "app/layers_panel_state.h"
#include "app/notices.h"
#include "editor/cmd/tokenize.h"
#include "editor/gen/gen.h"
#include "editor/params/world_params.h"
#include "editor/world/history.h"
#include "io/tile_store.h"
#include "renderer/planet_camera.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#define EDITOR_RECENT 8

struct editor_ui {
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
    row_drag rule_drag;            // a rule's row dragged to another place in the stack
    char rule_fields[4][3][32];    // the picked rule's ranges (height, slope, curvature) and
                                   // breakup as typed
    layers_panel_state layers;     // the Layers panel's rows and mask editor
    editor_host host;              // the window's side
    work_queue *work;              // where actions are queued (NULL: run at once)
    int history_request;           // Edit > History: open the History section
    size_t history_seen[2];        // its steps and position when last drawn
    int picking_height;            // the next click in the viewport picks the tool's height
    int shape_placing;             // a 3D shape waits for clicks in the viewport (0: none)
    int shape_clicks;              // clicks it has had
    double shape_at[3];            // where the first one picked
    long long tiles_stored;        // the World panel's count of stored tiles, and when
    double tiles_counted_at;       // it was taken (seconds)
};

// --- editor_build.c: running actions, building the frame

int editor_ui_run(editor_ui *e, cmd_context *ctx, const char *text);
// Runs text now, on this thread, for actions that go on only when it succeeded (load,
// save): quick file work, not long edits.
int run_now(editor_ui *e, cmd_context *ctx, const char *text);
int problem_lines(const char *problems);
int runf(editor_ui *e, cmd_context *ctx, const char *fmt, ...);
void remember_recent(editor_ui *e, const char *path);
void do_action(editor_ui *e, cmd_context *ctx, editor_pending action);
void editor_ui_request(editor_ui *e, cmd_context *ctx, editor_pending action);
const char *file_name(const char *path);

// --- editor_menus.c: the menu bar

void menus(editor_ui *e, ui_context *ui, cmd_context *ctx, viewport *v,
           const editor_frame_info *info, ui_rect bar);

// --- editor_tools.c: tools

void palette(editor_ui *e, ui_context *ui, cmd_context *ctx, ui_rect r);
// The current tool's name as `tool` takes it.
const char *current_tool(const brush *b);
void tool_options(editor_ui *e, ui_context *ui, cmd_context *ctx);
// A click in the viewport on the surface point hit while a shape is being placed:
// 1 and the command that makes it (cmd) once it has its clicks, 0 while it waits for
// another.
int editor_ui_shape_click(editor_ui *e, const cmd_context *ctx, const double hit[3], char *cmd,
                          size_t len);

// --- editor_panels.c: the dock's panels

void world_panel(editor_ui *e, ui_context *ui, cmd_context *ctx);
// The layers: the coarse and detail heights (the current tool's target), the material
// layer's eight materials (the paint material) and whether the automatic material rules
// colour unpainted ground.
void layers_panel(editor_ui *e, ui_context *ui, cmd_context *ctx, const viewport *v);
void history_panel(editor_ui *e, ui_context *ui, cmd_context *ctx);

// --- layers_panel.c, mask_editor.c: the edit layers, edited by commands

// The stack's rows, New layer and, when a row's Mask is on, the mask editor.
void layer_stack_panel(editor_ui *e, ui_context *ui, cmd_context *ctx, viewport *v);
void mask_editor(editor_ui *e, ui_context *ui, cmd_context *ctx, viewport *v, const layer_info *l);

// --- materials_panel.c: the automatic material rules, edited by commands

void materials_panel(editor_ui *e, ui_context *ui, cmd_context *ctx);

// --- editor_dialogs.c: status bar and dialogs

void status_bar(ui_context *ui, cmd_context *ctx, viewport *v, const editor_frame_info *info,
                const stamp_browser *stamps, ui_rect r);
ui_rect centred(float width, float height, float w, float h);
void unsaved_prompt(editor_ui *e, ui_context *ui, cmd_context *ctx, float width, float height);
// Whether the world has unsaved edits of a session that ended without saving, and the
// user has not put the question off for this world.
// The journal whose edits the Recover dialog offers: the world's own, or one a
// never-saved world left (found when the editor started); "" when none is offered.
// Like Blender's Recover Last Session: the edits a crash or a kill left in a journal,
// offered when the world opens (or, for a world never saved, when the editor starts).
void editor_ui_save(editor_ui *e, cmd_context *ctx);
// Saving over a file that loaded with errors writes defaults where its bad lines were,
// and over a world opened read-only replaces its tile store: say so (which lines, which
// store), and let the user replace it, save elsewhere or keep working.
void replace_dialog(editor_ui *e, ui_context *ui, cmd_context *ctx, ui_rect r);
void editor_ui_save_as(editor_ui *e, cmd_context *ctx);
void editor_ui_open(editor_ui *e, cmd_context *ctx);
// The file browser for Open and Save as; what it chose runs as load or save.
void files_dialog(editor_ui *e, ui_context *ui, cmd_context *ctx, ui_rect r);
// A text dialog's rectangle: as wide as its longest line (within the window).
ui_rect text_dialog_rect(const ui_context *ui, const char *const *lines, int n, float width,
                         float height);
void text_dialog(ui_context *ui, const char *name, const char *const *lines, int n, int *show,
                 float width, float height);

#endif
