// The state of the window's UI (app/window_panels.c): the editor's panels (editor_ui.h),
// the UI contexts they and the progress of long work are built in, their font and
// renderer, the notices over the viewport, and the viewport's rectangle the last UI
// frame left. Only window_panels.c touches it; the window's other parts ask through its
// functions (window_internal.h).
#ifndef OROGEN_APP_WINDOW_PANELS_STATE_H
#define OROGEN_APP_WINDOW_PANELS_STATE_H

#include "app/editor_ui.h"
#include "app/notices.h"
#include "renderer/ui_renderer.h"
#include "ui/ui.h"

typedef struct window_panels_state {
    editor_ui *ed;       // the panels, asked only through editor_ui.h's functions
    ui_font *font;       // at the user's UI scale
    ui_context *ui;      // the editor's UI over the viewport
    ui_context *busy_ui; // the progress bar and Cancel button of long work
    ui_renderer *uir;    // draws both
    notices notices;     // what failed for the UI, over the viewport until dismissed
    ui_rect view_rect;   // the viewport's part of the window (window coordinates)
    const char *gl_renderer;
    int edited;              // an edit made an undo step this session: the hint goes
    char history_path[4096]; // the console's history between sessions
} window_panels_state;

#endif
