// The editor window: a GLFW window with an EGL OpenGL 4.5 core context whose 3D
// viewport (renderer/viewport.h) fills it. Mouse and keys navigate (app/camera_controls)
// and sculpt with the current tool; the console runs the command language from
// standard input while the window runs. One direction per frame: input -> commands ->
// world -> cache -> renderer.
#ifndef OROGEN_APP_WINDOW_H
#define OROGEN_APP_WINDOW_H

#include "editor/cmd/commands.h"
#include "io/err.h"

// Runs until the window is closed or `exit` is typed. The window's viewport is
// ctx->view_state while it runs (so `camera`, `view`, `render`, `screenshot` and `pick`
// use it) and is freed before returning (ctx->view_state = NULL). Returns 0, or -1 with
// err set when no window or no suitable GL context can be had.
int window_run(cmd_context *ctx, og_error *err);

// Adds the window's own commands (ui_widgets) to the command language.
int window_commands_register(og_error *err);

#endif
