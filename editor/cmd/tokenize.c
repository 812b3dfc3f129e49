#include "editor/cmd/tokenize.h"

#include <stdlib.h>
#include <string.h>

void cmd_tokenizer_init(cmd_tokenizer *t, const char *text, size_t len, const char *label) {
    memset(t, 0, sizeof *t);
    t->text = text;
    t->len = len;
    t->label = label;
    t->line = 1;
}

void cmd_tokenizer_free(cmd_tokenizer *t) {
    free(t->buf);
    free(t->starts);
    free(t->argv);
    memset(t, 0, sizeof *t);
}

static int fail(cmd_tokenizer *t, og_error *err, const char *what) {
    t->pos = t->len; // stop here
    return og_error_set(err, "%s:%d: error: %s", t->label, t->line, what);
}

static int push_byte(cmd_tokenizer *t, size_t *used, char c) {
    if (*used == t->buf_cap) {
        size_t cap = t->buf_cap ? t->buf_cap * 2 : 256;
        char *b = realloc(t->buf, cap);
        if (!b) return -1;
        t->buf = b;
        t->buf_cap = cap;
    }
    t->buf[(*used)++] = c;
    return 0;
}

static int push_start(cmd_tokenizer *t, size_t argc, size_t start) {
    if (argc + 1 >= t->argv_cap) {
        size_t cap = t->argv_cap ? t->argv_cap * 2 : 16;
        size_t *s = realloc(t->starts, cap * sizeof *s);
        if (!s) return -1;
        t->starts = s;
        char **a = realloc(t->argv, cap * sizeof *a);
        if (!a) return -1;
        t->argv = a;
        t->argv_cap = cap;
    }
    t->starts[argc] = start;
    return 0;
}

static int is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r';
}

int cmd_tokenizer_next(cmd_tokenizer *t, int *argc_out, char ***argv_out, int *line_out,
                       og_error *err) {
    const char *text = t->text;
    size_t argc = 0, used = 0;
    int cmd_line = t->line;
    for (;;) {
        while (t->pos < t->len && is_blank(text[t->pos]))
            t->pos++;
        int end =
            t->pos >= t->len || text[t->pos] == '\n' || text[t->pos] == ';' || text[t->pos] == '#';
        if (end) {
            if (t->pos < t->len && text[t->pos] == '#')
                while (t->pos < t->len && text[t->pos] != '\n') {
                    if (text[t->pos] == '\0') return fail(t, err, "NUL byte in command text");
                    t->pos++;
                }
            if (t->pos < t->len) { // the newline or ';' closes the command
                if (text[t->pos] == '\n') t->line++;
                t->pos++;
            }
            if (argc > 0) {
                for (size_t k = 0; k < argc; k++)
                    t->argv[k] = t->buf + t->starts[k];
                t->argv[argc] = NULL;
                *argc_out = (int)argc;
                *argv_out = t->argv;
                *line_out = cmd_line;
                return 1;
            }
            if (t->pos >= t->len) return 0;
            continue;
        }
        if (argc + 1 >= CMD_MAX_ARGS) return fail(t, err, "too many arguments (at most 65535)");
        if (argc == 0) cmd_line = t->line;
        if (push_start(t, argc, used) != 0) return fail(t, err, "out of memory");
        size_t start = used;
        int quoted = 0;
        while (t->pos < t->len) {
            char ch = text[t->pos];
            if (!quoted && (is_blank(ch) || ch == '\n' || ch == ';')) break;
            if (ch == '"') {
                quoted = !quoted;
                t->pos++;
                continue;
            }
            if (ch == '\0') return fail(t, err, "NUL byte in command text");
            if (quoted && ch == '\\' && t->pos + 1 < t->len &&
                (text[t->pos + 1] == '"' || text[t->pos + 1] == '\\'))
                ch = text[++t->pos];
            if (ch == '\n') t->line++;
            if (used - start + 1 >= CMD_MAX_TOKEN) {
                og_error_set(err, "%s:%d: error: argument longer than %d bytes", t->label, t->line,
                             CMD_MAX_TOKEN - 1);
                t->pos = t->len;
                return -1;
            }
            if (push_byte(t, &used, ch) != 0) return fail(t, err, "out of memory");
            t->pos++;
        }
        if (quoted) return fail(t, err, "unterminated \"quote\"");
        if (push_byte(t, &used, 0) != 0) return fail(t, err, "out of memory");
        argc++;
    }
}

void cmd_quote_arg(char *out, size_t size, const char *text) {
    size_t n = 0;
    if (size < 3) {
        if (size) out[0] = 0;
        return;
    }
    out[n++] = '"';
    for (const char *p = text; *p && n + 3 < size; p++) {
        if (*p == '"' || *p == '\\') out[n++] = '\\';
        out[n++] = *p;
    }
    out[n++] = '"';
    out[n] = 0;
}
