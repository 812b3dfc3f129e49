// The volume shape commands: arch, tunnel, spire, overhang (editor/tools/volume_shapes.h).
// Registered in commands.c.
#ifndef OROGEN_EDITOR_VOLUME_COMMANDS_H
#define OROGEN_EDITOR_VOLUME_COMMANDS_H

#include "editor/cmd/context.h"

int cmd_arch(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_tunnel(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_spire(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_overhang(cmd_context *ctx, int argc, char **argv, og_error *err);

#endif
