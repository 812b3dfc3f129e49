// The viewport's commands in the command language: camera, view, render, screenshot,
// pick. They work with no display: the first render makes a headless EGL context.
// The command language knows no renderer: app/ registers these at start-up.
#ifndef OROGEN_VIEW_VIEW_COMMANDS_H
#define OROGEN_VIEW_VIEW_COMMANDS_H

#include "editor/cmd/commands.h"
#include "renderer/viewport.h"

// Adds camera, view, render, screenshot and pick to the command language (once).
int view_commands_register(og_error *err);

// The viewport the view commands use (ctx->view_state), made on first use; NULL
// when out of memory. The window sets its own with view_commands_set_viewport.
viewport *view_commands_viewport(cmd_context *ctx);
void view_commands_set_viewport(cmd_context *ctx, viewport *v);

#endif
