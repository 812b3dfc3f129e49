// The viewport's commands in the command language: camera, view, render, screenshot,
// pick. They work with no display: the first render makes a headless EGL context.
// Registered in editor/commands.c.
#ifndef OROGEN_RENDERER_VIEW_COMMANDS_H
#define OROGEN_RENDERER_VIEW_COMMANDS_H

#include "editor/commands.h"

int cmd_camera(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_view(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_render(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_screenshot(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_pick(cmd_context *ctx, int argc, char **argv, og_error *err);

#endif
