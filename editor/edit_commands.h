// The editing commands of the command language: tool, dab, stroke, undo, redo,
// history, stamp, stamps. Registered in commands.c.
#ifndef OROGEN_EDITOR_EDIT_COMMANDS_H
#define OROGEN_EDITOR_EDIT_COMMANDS_H

#include "editor/commands.h"

int cmd_tool(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_dab(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stroke(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_undo(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_redo(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_history(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stamp(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stamps(cmd_context *ctx, int argc, char **argv, og_error *err);

// Parses "key=value" into key and value (pointers into a copy in buf).
int cmd_split_setting(const char *arg, char *buf, size_t size, char **key, char **value,
                      og_error *err);
int cmd_parse_number(const char *text, const char *what, double *out, og_error *err);

#endif
