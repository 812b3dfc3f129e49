// The command language's tokenizer: splits text into commands and their arguments.
// Commands end at a newline or `;`; arguments are separated by blanks (space, tab,
// CR); "double quotes" keep blanks, `;` and `#` inside an argument, with a backslash
// before a quote or a backslash as its escape; `#` at the start of an argument starts a comment
// that runs to the end of the line. A NUL byte is an error (text is not a C string).
#ifndef OROGEN_EDITOR_CMD_TOKENIZE_H
#define OROGEN_EDITOR_CMD_TOKENIZE_H

#include "io/err.h"

#include <stddef.h>

#define CMD_MAX_ARGS 65536 // a command has fewer arguments than this, its name included
#define CMD_MAX_TOKEN 4096 // bytes per argument, the terminating NUL included

typedef struct cmd_tokenizer {
    const char *text;
    size_t len, pos;
    const char *label; // names the text in errors ("-c", a script's path, "console")
    int line;          // line of the tokenizer's position (1-based)
    char *buf;         // the current command's arguments, NUL-separated
    size_t buf_cap;
    size_t *starts; // offsets of the arguments in buf
    char **argv;    // argc + 1 entries, NULL-terminated
    size_t argv_cap;
} cmd_tokenizer;

void cmd_tokenizer_init(cmd_tokenizer *t, const char *text, size_t len, const char *label);
void cmd_tokenizer_free(cmd_tokenizer *t);

// The next command: 1 with *argc >= 1 and *argv (valid until the next call) and *line
// the line it starts on; 0 when the text is used up; -1 on a malformed command, with
// err = "label:line: error: ..." (the tokenizer stops there).
int cmd_tokenizer_next(cmd_tokenizer *t, int *argc, char ***argv, int *line, og_error *err);

// Writes text as one argument the tokenizer reads back as text: double quotes, with a
// backslash before quotes and backslashes (cut short, still quoted, if out is small).
void cmd_quote_arg(char *out, size_t size, const char *text);

#endif
