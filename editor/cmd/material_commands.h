// The material rule commands: `material_rules` lists the stack, `material_rule add|set|
// move|delete|reset` changes it, one undo step each (README.md, "Material rules").
// Registered in commands.c.
#ifndef OROGEN_EDITOR_MATERIAL_COMMANDS_H
#define OROGEN_EDITOR_MATERIAL_COMMANDS_H

#include "editor/cmd/context.h"

int cmd_material_rules(cmd_context *ctx, int argc, char **argv, og_error *err);
int cmd_material_rule(cmd_context *ctx, int argc, char **argv, og_error *err);

#endif
