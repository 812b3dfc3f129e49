#include "editor/cmd/context.h"

#include <stdlib.h>
#include <string.h>

void cmd_context_init(cmd_context *ctx, world *w, const world_settings *settings, FILE *out,
                      const char *resource_dir) {
    memset(ctx, 0, sizeof *ctx);
    snprintf(ctx->resource_dir, sizeof ctx->resource_dir, "%s", resource_dir ? resource_dir : "");
    const char *env = getenv("OROGEN_STAMP_DIR"), *xdg = getenv("XDG_DATA_HOME"),
               *home = getenv("HOME");
    if (env && *env)
        snprintf(ctx->stamp_dir, sizeof ctx->stamp_dir, "%s", env);
    else if (xdg && *xdg)
        snprintf(ctx->stamp_dir, sizeof ctx->stamp_dir, "%s/orogen/stamps", xdg);
    else if (home && *home)
        snprintf(ctx->stamp_dir, sizeof ctx->stamp_dir, "%s/.local/share/orogen/stamps", home);
    ctx->world = w;
    ctx->next = *world_get_params(w);
    if (settings) ctx->settings = *settings;
    ctx->out = out;
    brush_defaults(&ctx->brush, BRUSH_RAISE);
}
