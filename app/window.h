// The editor window: a GLFW window with an EGL OpenGL 4.5 core context showing
// the world's shaded map (renderer/map_image), panned with the mouse, with the
// console on standard input. The 3D clipmap viewport will take its place.
#ifndef OROGEN_APP_WINDOW_H
#define OROGEN_APP_WINDOW_H

#include "editor/commands.h"
#include "io/err.h"

// Runs until the window is closed or `exit` is typed. Returns 0, or -1 with err set
// when no window or no suitable GL context can be had.
int window_run(cmd_context *ctx, og_error *err);

#endif
