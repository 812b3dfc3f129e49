// The edit layer commands: `layers` and `layer new|select|set|move|duplicate|merge|clear|
// delete` (README.md, "Layers"). Each change is one undo step holding the layer table
// and every tile it recomposed. Registered in commands.c.
#ifndef OROGEN_EDITOR_LAYER_COMMANDS_H
#define OROGEN_EDITOR_LAYER_COMMANDS_H

#include "editor/cmd/context.h"

int cmd_layers(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_layer(cmd_context *ctx, int argc, char **argv, og_error *err);

#endif
