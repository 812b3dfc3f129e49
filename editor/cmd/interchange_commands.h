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
// The raster is the world's base: its crash journal names the file (and checks it on
// recovery) instead of copying its samples. With ctx->defer_base the raster is not
// imported yet: *pending (base_pending.h) imports its parts; else *pending is NULL.
struct base_pending;
world *cmd_world_from_raster(cmd_context *ctx, const char *path, int argc, char **argv, int first,
                             struct base_pending **pending, og_error *err);
// Recovery's remake of such a world (edit_recover_unsaved's recover_base_fn): the raster
// imported again into w, refused when the file changed since.
int cmd_world_from_raster_again(world *w, const char *source, og_error *err);

#endif
