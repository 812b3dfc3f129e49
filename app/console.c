#include "app/console.h"

#include "editor/tools/brush.h"
#include "editor/tools/stamp.h"
#include "io/param_file.h"

#include <dirent.h>
#include <sys/stat.h>

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
        if (c->notices && strcmp(label, "console") != 0)
            notices_add_failure(c->notices, text, err.msg, notices_now());
    } else if (c->notices && notices_user_action(label)) {
        notices_clear_passing(c->notices);
    }
    return rc;
}

void console_toggle(console *c, int key_typed) {
    c->open = !c->open;
    c->focus_input = c->open;
    size_t n = strlen(c->input);
    if (key_typed && n && (c->input[n - 1] == '`' || c->input[n - 1] == '~')) c->input[n - 1] = 0;
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

// Candidates for completion, gathered into one buffer.
typedef struct candidates {
    char text[8192];
    size_t used;
    const char *items[512];
    size_t count;
} candidates;

static void add_candidate(candidates *c, const char *word, size_t len) {
    if (c->count == 512 || c->used + len + 1 > sizeof c->text) return;
    memcpy(c->text + c->used, word, len);
    c->text[c->used + len] = 0;
    c->items[c->count++] = c->text + c->used;
    c->used += len + 1;
}

// Adds each blank-separated word of list.
static void add_words(candidates *c, const char *list, const char *suffix) {
    for (const char *p = list; *p;) {
        while (*p == ' ')
            p++;
        size_t n = strcspn(p, " \n");
        if (n) {
            char word[256];
            snprintf(word, sizeof word, "%.*s%s", (int)n, p, suffix);
            add_candidate(c, word, strlen(word));
        }
        p += n;
        while (*p == '\n')
            p++;
    }
}

// Files and folders whose path starts with prefix (folders end in '/').
static void add_paths(candidates *c, const char *prefix) {
    char dir[4096];
    const char *slash = strrchr(prefix, '/');
    if (slash)
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - prefix + 1), prefix);
    else
        dir[0] = 0;
    DIR *d = opendir(dir[0] ? dir : ".");
    if (!d) return;
    struct dirent *de;
    while ((de = readdir(d))) {
        if (de->d_name[0] == '.') continue;
        char path[4400], full[4400];
        snprintf(path, sizeof path, "%s%s", dir, de->d_name);
        snprintf(full, sizeof full, "%s", path);
        struct stat st;
        if (stat(full, &st) == 0 && S_ISDIR(st.st_mode))
            strncat(path, "/", sizeof path - strlen(path) - 1);
        add_candidate(c, path, strlen(path));
    }
    closedir(d);
}

// Tab completes the word before the caret: a command name first; then tool names after
// `tool`, key= names after a tool, stamp names after `stamp`, paths after load, save and
// the file arguments of stamp and screenshot. Several matches are listed in the
// scrollback and the input gets their common prefix.
static void complete(console *c, const cmd_context *ctx) {
    size_t n = strlen(c->input);
    size_t start = n;
    while (start > 0 && c->input[start - 1] != ' ' && c->input[start - 1] != ';')
        start--;
    const char *word = c->input + start;
    size_t wlen = n - start;
    // The command this word belongs to, and which argument it is.
    size_t cmd_start = start;
    while (cmd_start > 0 && c->input[cmd_start - 1] != ';')
        cmd_start--;
    while (c->input[cmd_start] == ' ')
        cmd_start++;
    char cmd[64] = "";
    int arg = 0;
    if (cmd_start < start) {
        sscanf(c->input + cmd_start, "%63s", cmd);
        for (size_t k = cmd_start; k < start; k++)
            if (c->input[k] == ' ' && (k + 1 < start && c->input[k + 1] != ' ')) arg++;
        arg++;
    }
    static candidates cand;
    cand.used = cand.count = 0;
    if (!cmd[0]) {
        for (size_t i = 0; i < cmd_count(); i++)
            add_words(&cand, cmd_name(i), "");
    } else if (strcmp(cmd, "tool") == 0 && arg == 1) {
        for (int t = 0; t < BRUSH_TOOL_COUNT; t++)
            add_words(&cand, brush_tool_name((brush_tool)t), "");
        add_words(&cand, "lower", "");
    } else if (strcmp(cmd, "tool") == 0) {
        add_words(&cand, brush_keys(), "=");
    } else if (strcmp(cmd, "stamp") == 0 && arg == 1) {
        char *list = NULL;
        size_t len = 0;
        FILE *mem = open_memstream(&list, &len);
        if (mem) {
            stamp_list(ctx->resource_dir, ctx->stamp_dir, mem);
            fclose(mem);
            for (char *line = list; line && *line;) { // "NAME KIND ..." lines
                size_t k = strcspn(line, " \n");
                add_candidate(&cand, line, k);
                char *nl = strchr(line, '\n');
                line = nl ? nl + 1 : NULL;
            }
            free(list);
        }
        add_paths(&cand, word);
    } else if (strcmp(cmd, "stamp") == 0) {
        add_words(&cand, "scale rot mirror intensity mode layer face", "=");
    } else if (strcmp(cmd, "load") == 0 || strcmp(cmd, "save") == 0 ||
               strcmp(cmd, "screenshot") == 0) {
        add_paths(&cand, word);
    } else if (strcmp(cmd, "help") == 0) {
        for (size_t i = 0; i < cmd_count(); i++)
            add_words(&cand, cmd_name(i), "");
    }
    const char *first = NULL;
    size_t common = 0, matches = 0;
    char list[2048] = "";
    for (size_t i = 0; i < cand.count; i++) {
        const char *name = cand.items[i];
        if (strncmp(name, word, wlen) != 0) continue;
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
    // A single match that is a word (not a key= or a folder) gets a blank after it.
    char done = first[common ? common - 1 : 0];
    const char *space = matches == 1 && done != '=' && done != '/' ? " " : "";
    char out[CONSOLE_INPUT];
    snprintf(out, sizeof out, "%.*s%.*s%s", (int)start, c->input, (int)common, first, space);
    snprintf(c->input, sizeof c->input, "%s", out);
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
    if (in->key_pressed[UI_KEY_TAB]) complete(c, ctx);
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
        if (c->submit)
            c->submit(c->submit_user, line);
        else
            console_run(c, ctx, line, "console");
    }
}
