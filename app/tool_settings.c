#include "app/tool_settings.h"

#include "editor/cmd/commands.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// "NAME key=value ..." for brush b: what `tool` prints, less what is not a setting of
// the tool (its name, the planet face, paint's fixed layer, flatten's "no height yet")
// and falloff=curve, which curve= implies.
static void describe(const brush *b, char *out, size_t size) {
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    snprintf(out, size, "%s",
             b->tool == BRUSH_RAISE && b->invert ? "lower" : brush_tool_name(b->tool));
    if (!mem) return;
    brush_print(b, mem);
    fclose(mem);
    size_t n = strlen(out);
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
        if (strncmp(line, "tool=", 5) == 0 || strncmp(line, "face=", 5) == 0 ||
            strcmp(line, "target=material") == 0 || strcmp(line, "falloff=curve") == 0 ||
            strchr(line, '(') || strchr(line, ' ') || strpbrk(line, ";#"))
            continue;
        if (n + strlen(line) + 2 >= size) break;
        n += (size_t)snprintf(out + n, size - n, " %s", line);
    }
    free(text);
}

void tool_settings_capture(const cmd_context *ctx, app_settings *s) {
    s->tool_count = 0;
    for (int t = 0; t < BRUSH_TOOL_COUNT && s->tool_count < SETTINGS_TOOLS; t++) {
        const brush *b = ctx->brush.tool == (brush_tool)t     ? &ctx->brush
                         : (ctx->tool_remembered & (1u << t)) ? &ctx->tool_memory[t]
                                                              : NULL;
        if (!b) continue;
        brush kept = *b;
        if (!ctx->tool_size_per_tool) { // shared: every line restores the size in use
            kept.radius = ctx->brush.radius;
            if (brush_tool_is_volume(kept.tool) == brush_tool_is_volume(ctx->brush.tool))
                kept.strength = ctx->brush.strength;
        }
        char *line = s->tools[s->tool_count++];
        describe(&kept, line, sizeof s->tools[0]);
        size_t n = strlen(line);
        char *radius = strstr(line, " radius=");
        if (radius && !ctx->radius_chosen && n + 6 < sizeof s->tools[0]) { // still the view's
            memmove(radius + 6, radius + 1, n - (size_t)(radius + 1 - line) + 1);
            memcpy(radius + 1, "auto_", 5);
            n += 5;
        }
        if (ctx->tool_size_per_tool && n + 16 < sizeof s->tools[0])
            snprintf(line + n, sizeof s->tools[0] - n, " memory=per_tool");
    }
    const brush *b = &ctx->brush;
    snprintf(s->tool, sizeof s->tool, "%s",
             b->tool == BRUSH_RAISE && b->invert ? "lower" : brush_tool_name(b->tool));
}

void tool_settings_restore(cmd_context *ctx, const app_settings *s, const char *path) {
    char cmd[1024];
    for (int i = 0; i < s->tool_count; i++) {
        snprintf(cmd, sizeof cmd, "tool %s", s->tools[i]);
        og_error err = {{0}};
        if (cmd_run(ctx, cmd, strlen(cmd), path, &err) != 0)
            fprintf(stderr, "%s: warning: %s (that tool keeps its defaults)\n", path, err.msg);
    }
    if (!s->tool[0]) return;
    snprintf(cmd, sizeof cmd, "tool %s", s->tool);
    og_error err = {{0}};
    if (cmd_run(ctx, cmd, strlen(cmd), path, &err) != 0)
        fprintf(stderr, "%s: warning: %s\n", path, err.msg);
}
