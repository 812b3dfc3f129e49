#include "app/console.h"

#include "io/param_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void console_init(console *c) {
    memset(c, 0, sizeof *c);
    c->history_at = -1;
}

void console_free(console *c) {
    for (size_t i = 0; i < c->count; i++)
        free(c->lines[(c->first + i) % CONSOLE_LINES]);
    for (size_t i = 0; i < c->history_count; i++)
        free(c->history[i]);
    memset(c, 0, sizeof *c);
}

static void add_line(console *c, console_kind kind, const char *text, size_t n) {
    char *line = malloc(n + 1);
    if (!line) return;
    memcpy(line, text, n);
    line[n] = 0;
    size_t at;
    if (c->count == CONSOLE_LINES) { // full: drop the oldest
        at = c->first;
        free(c->lines[at]);
        c->first = (c->first + 1) % CONSOLE_LINES;
    } else {
        at = (c->first + c->count++) % CONSOLE_LINES;
    }
    c->lines[at] = line;
    c->kinds[at] = kind;
}

void console_add(console *c, console_kind kind, const char *text) {
    const char *p = text;
    while (*p) {
        const char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) : strlen(p);
        add_line(c, kind, p, n);
        p += n + (nl ? 1 : 0);
    }
}

static void remember(console *c, const char *text) {
    if (c->history_count && strcmp(c->history[c->history_count - 1], text) == 0) return;
    if (c->history_count == CONSOLE_HISTORY) {
        free(c->history[0]);
        memmove(c->history, c->history + 1, (CONSOLE_HISTORY - 1) * sizeof *c->history);
        c->history_count--;
    }
    char *copy = strdup(text);
    if (copy) c->history[c->history_count++] = copy;
}

int console_run(console *c, cmd_context *ctx, const char *text, const char *label) {
    char echo[CONSOLE_INPUT + 4];
    snprintf(echo, sizeof echo, "> %s", text);
    console_add(c, CONSOLE_ECHO, echo);
    // The command's output is captured for the scrollback and passed on to stdout.
    char *out = NULL;
    size_t out_len = 0;
    FILE *mem = open_memstream(&out, &out_len);
    FILE *keep = ctx->out;
    if (mem) ctx->out = mem;
    og_error err = {{0}};
    int rc = cmd_run(ctx, text, strlen(text), label, &err);
    ctx->out = keep;
    if (mem) {
        fclose(mem);
        if (out_len) {
            fwrite(out, 1, out_len, keep);
            fflush(keep);
            console_add(c, CONSOLE_OUTPUT, out);
        }
        free(out);
    }
    if (rc != 0) {
        fprintf(stderr, "%s\n", err.msg);
        console_add(c, CONSOLE_ERROR, err.msg);
    }
    return rc;
}

void console_load_history(console *c, const char *path) {
    FILE *f = path[0] ? fopen(path, "r") : NULL;
    if (!f) return;
    char line[CONSOLE_INPUT];
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = 0;
        if (line[0]) remember(c, line);
    }
    fclose(f);
}

int console_save_history(const console *c, const char *path, og_error *err) {
    if (!path[0]) return og_error_set(err, "no settings folder (HOME is not set)");
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    if (!mem) return og_error_set(err, "out of memory");
    for (size_t i = 0; i < c->history_count; i++)
        fprintf(mem, "%s\n", c->history[i]);
    fclose(mem);
    int rc = param_file_write_atomic(path, text, len, err);
    free(text);
    return rc;
}

static ui_log_line line_at(void *user, size_t i) {
    console *c = user;
    size_t at = (c->first + i) % CONSOLE_LINES;
    static const ui_color colours[] = {UI_RGBA(150, 190, 255, 255), UI_RGBA(222, 222, 222, 255),
                                       UI_RGBA(255, 110, 100, 255)};
    return (ui_log_line){c->lines[at], colours[c->kinds[at]]};
}

// Tab: completes the command name being typed (the longest common prefix of the
// matches); several matches are listed in the scrollback.
static void complete(console *c) {
    size_t n = strlen(c->input);
    if (strchr(c->input, ' ')) return;
    const char *first = NULL;
    size_t common = 0, matches = 0;
    char list[2048] = "";
    for (size_t i = 0; i < cmd_count(); i++) {
        const char *name = cmd_name(i);
        if (strncmp(name, c->input, n) != 0) continue;
        if (!first) {
            first = name;
            common = strlen(name);
        } else {
            size_t k = 0;
            while (k < common && first[k] == name[k])
                k++;
            common = k;
        }
        matches++;
        size_t l = strlen(list);
        snprintf(list + l, sizeof list - l, "%s%s", l ? "  " : "", name);
    }
    if (!first) return;
    if (matches > 1) console_add(c, CONSOLE_OUTPUT, list);
    snprintf(c->input, sizeof c->input, "%.*s%s", (int)common, first, matches == 1 ? " " : "");
}

void console_draw(console *c, ui_context *ui, cmd_context *ctx, ui_rect r) {
    ui_panel_begin(ui, "Console", r);
    float line = ui_em(ui, 1.4f);
    ui_row(ui, 1, NULL, 0);
    ui_log(ui, "Scrollback", c->count, line_at, c, r.h - line - ui_em(ui, 1.2f));
    ui_row(ui, 1, NULL, line);
    if (c->focus_input) {
        ui_focus(ui, "Input");
        c->focus_input = 0;
    }
    int rc = ui_textbox_flags(ui, "Input", c->input, sizeof c->input, UI_TEXTBOX_OWN_TAB);
    int focused = ui_last_focused(ui);
    ui_tooltip(ui,
               "Type a command (help lists them); Enter runs it, Up/Down recall, Tab completes");
    ui_panel_end(ui);
    const ui_input *in = ui_get_input(ui);
    if (!focused) return;
    if (in->key_pressed[UI_KEY_TAB]) complete(c);
    if (in->key_pressed[UI_KEY_UP] && c->history_count) {
        c->history_at = c->history_at < 0 ? (int)c->history_count - 1
                                          : (c->history_at > 0 ? c->history_at - 1 : 0);
        snprintf(c->input, sizeof c->input, "%s", c->history[c->history_at]);
    }
    if (in->key_pressed[UI_KEY_DOWN] && c->history_at >= 0) {
        c->history_at++;
        if (c->history_at >= (int)c->history_count) {
            c->history_at = -1;
            c->input[0] = 0;
        } else {
            snprintf(c->input, sizeof c->input, "%s", c->history[c->history_at]);
        }
    }
    if ((rc & UI_TEXT_SUBMIT) && c->input[0]) {
        char line[CONSOLE_INPUT];
        snprintf(line, sizeof line, "%s", c->input);
        remember(c, line);
        c->history_at = -1;
        c->input[0] = 0;
        console_run(c, ctx, line, "console");
    }
}
