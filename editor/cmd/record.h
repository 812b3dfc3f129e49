// Writing the commands that succeeded to the recording (--record) and the session's
// history (`history script`), quoted so that running the file repeats them.
#ifndef OROGEN_EDITOR_CMD_RECORD_H
#define OROGEN_EDITOR_CMD_RECORD_H

#include "editor/cmd/context.h"

// What the driver does after every command; typed calls such as cmd_stroke_to_point
// record the command they stand for.
void cmd_record(cmd_context *ctx, int argc, char **argv);

#endif
