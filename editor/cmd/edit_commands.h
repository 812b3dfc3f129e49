// The editing commands of the command language: tool, dab, stroke, undo, redo,
// history, stamp, stamps, and the interactive stroke_begin / stroke_to / stroke_end /
// stroke_cancel the viewport's drags run. Registered in commands.c.
#ifndef OROGEN_EDITOR_EDIT_COMMANDS_H
#define OROGEN_EDITOR_EDIT_COMMANDS_H

#include "editor/cmd/context.h"

int cmd_tool(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_dab(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stroke(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stroke_begin(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stroke_to(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stroke_end(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stroke_hold(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stroke_cancel(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_undo(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_redo(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_history(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stamp(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stamp_add(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_stamps(cmd_context *ctx, int argc, char **argv, og_error *err);

// Ends the open stroke, if any, as one undo step (the end of a batch run, a window
// closing). Returns -1 (err set) when committing it fails.
int cmd_end_stroke(cmd_context *ctx, og_error *err);

#endif
