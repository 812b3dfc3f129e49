// The interchange commands: import FILE [key=value ...] and export FILE [key=value
// ...] (editor/interchange/), and what `new flat from=FILE` needs. Registered in
// commands.c.
#ifndef OROGEN_EDITOR_CMD_INTERCHANGE_COMMANDS_H
#define OROGEN_EDITOR_CMD_INTERCHANGE_COMMANDS_H

#include "editor/cmd/context.h"

int cmd_import(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_export(cmd_context *ctx, int argc, char **argv, og_error *err);

// A bounded flat world sized and spaced by the raster at path (options as import's,
// argv[first..argc)), with the raster imported at its corner. Returns the new world.
world *cmd_world_from_raster(cmd_context *ctx, const char *path, int argc, char **argv, int first,
                             og_error *err);

#endif
