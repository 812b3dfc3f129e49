#include "support/test_view.h"

#include "editor/cmd/commands.h"
#include "editor/params/world_params.h"
#include "editor/world/world.h"
#include "renderer/viewport.h"
#include "view/view_commands.h"

#include <stdio.h>
#include <string.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

void test_view_context_open(cmd_context *ctx) {
    og_error err = {{0}};
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    world *w = world_create(&p, NULL, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    if (view_commands_register(&err) != 0) fail_msg("view commands: %s", err.msg);
    cmd_context_init(ctx, w, NULL, stdout, OROGEN_RESOURCE_DIR);
}

void test_view_run(cmd_context *ctx, const char *text) {
    og_error err = {{0}};
    if (cmd_run(ctx, text, strlen(text), "test", &err) != 0)
        fail_msg("'%s' failed: %s", text, err.msg);
}

void test_view_context_close(cmd_context *ctx) {
    viewport_destroy(ctx->view_state);
    world_close(ctx->world);
}
