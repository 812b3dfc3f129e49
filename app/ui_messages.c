#include "app/ui_messages.h"

#include "editor/cmd/commands.h"

#include <stdio.h>

static const ui_context *shown[2]; // one window per process

void ui_messages_attach(const ui_context *editor, const ui_context *busy) {
    shown[0] = editor;
    shown[1] = busy;
}

// "messages N", then each as WHERE: TEXT.
static int cmd_ui_messages(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv;
    if (!shown[0]) return og_error_set(err, "ui_messages: no editor window is open");
    size_t n = 0;
    for (int u = 0; u < 2; u++)
        if (shown[u]) n += ui_message_count(shown[u]);
    fprintf(ctx->out, "messages %zu\n", n);
    for (int u = 0; u < 2; u++)
        for (size_t i = 0; shown[u] && i < ui_message_count(shown[u]); i++) {
            const ui_message_info *m = ui_message_at(shown[u], i);
            fprintf(ctx->out, "%s: %s\n", m->where, m->text);
        }
    return 0;
}

static const cmd_def commands[] = {
    {"ui_messages", "ui_messages",
     "Lists the messages the editor window shows now (notices over the viewport, errors in "
     "dialogs, a slider's refusal of typed text) as WHERE: TEXT after a line 'messages N'.",
     0, 0, cmd_ui_messages, CMD_NOT_RECORDED | CMD_WHILE_BUSY},
};

int ui_messages_register(og_error *err) {
    return cmd_register(commands, sizeof commands / sizeof commands[0], err);
}
