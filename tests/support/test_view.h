// Tests that drive the viewport through the command language (camera, screenshot), as
// batch mode does: a command context on a new default flat world with the view commands.
#ifndef OROGEN_TEST_VIEW_H
#define OROGEN_TEST_VIEW_H

#include "editor/cmd/context.h"

// Opens the world and the context in *ctx (fails the test if it cannot).
void test_view_context_open(cmd_context *ctx);
// Runs text through the command language; fails the test with its error if it fails.
void test_view_run(cmd_context *ctx, const char *text);
// Closes its viewport (made by the first view command) and its world.
void test_view_context_close(cmd_context *ctx);

#endif
