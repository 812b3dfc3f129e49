// Command text tokenised once: the calls a script, a console line or a UI action holds,
// each with its arguments and the line it starts on. Whoever runs, queues or checks the
// commands works on this, never on the text again.
#ifndef OROGEN_EDITOR_CMD_SCRIPT_H
#define OROGEN_EDITOR_CMD_SCRIPT_H

#include "io/err.h"

#include <stddef.h>

typedef struct cmd_call {
    int argc;
    char **argv; // argc + 1 entries, NULL-terminated; argv[0] the command's name
    int line;    // the line of the text it starts on (1-based)
} cmd_call;

typedef struct cmd_script {
    cmd_call *calls;
    size_t count, cap;
    char label[64]; // names the text in errors ("-c", a script's path, "console")
    // The tokenizer stopped on malformed text after `count` calls: running the script
    // runs those, then fails with this error (as running the text would).
    int malformed;
    og_error parse_error;
} cmd_script;

// Tokenises text (len bytes). 0, or -1 when out of memory (err set; s is empty then).
// Malformed text is not a failure here: see `malformed`.
int cmd_script_parse(cmd_script *s, const char *text, size_t len, const char *label, og_error *err);
// One call made of arguments given as they are (no tokenising). 0, or -1 out of memory.
int cmd_script_add(cmd_script *s, int argc, const char *const *argv, int line);
void cmd_script_free(cmd_script *s);

#endif
