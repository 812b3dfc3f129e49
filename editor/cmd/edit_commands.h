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

// A point of the viewport's drag, typed (the window never writes it as text): a height
// tool's x z (metres; a planet's in the stroke's face), or a volume tool's x y z.
typedef struct cmd_stroke_point {
    double x, y, z;
    int volume; // y is used
} cmd_stroke_point;

// `stroke_to` for a typed point: lays the open stroke's next dab, and writes the
// command it stands for to the recording and the session (17 significant digits).
// Fails like stroke_to (no stroke open, a failed dab abandons the stroke whole).
int cmd_stroke_to_point(cmd_context *ctx, const cmd_stroke_point *pt, og_error *err);
// Whether a stroke is open (stroke_begin ran and no end or cancel yet).
int cmd_stroke_is_open(const cmd_context *ctx);
// The typed stroke_cancel: abandons the open stroke, if any, undoing its dabs, and
// records `stroke_cancel` (a replay then drops it too).
void cmd_cancel_stroke(cmd_context *ctx);

// Ends the open stroke, if any, as one undo step (the end of a batch run, a window
// closing). Returns -1 (err set) when committing it fails.
int cmd_end_stroke(cmd_context *ctx, og_error *err);

#endif
