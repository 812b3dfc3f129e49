#include "editor/cmd/cmd_script.h"

#include "editor/cmd/tokenize.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cmd_script_add(cmd_script *s, int argc, const char *const *argv, int line) {
    if (s->count == s->cap) {
        size_t cap = s->cap ? s->cap * 2 : 4;
        cmd_call *c = realloc(s->calls, cap * sizeof *c);
        if (!c) return -1;
        s->calls = c;
        s->cap = cap;
    }
    // One block: the argv array, then the arguments' bytes.
    size_t bytes = (size_t)(argc + 1) * sizeof(char *);
    for (int i = 0; i < argc; i++)
        bytes += strlen(argv[i]) + 1;
    char **copy = malloc(bytes);
    if (!copy) return -1;
    char *text = (char *)(copy + argc + 1);
    for (int i = 0; i < argc; i++) {
        size_t n = strlen(argv[i]) + 1;
        memcpy(text, argv[i], n);
        copy[i] = text;
        text += n;
    }
    copy[argc] = NULL;
    s->calls[s->count++] = (cmd_call){argc, copy, line};
    return 0;
}

int cmd_script_parse(cmd_script *s, const char *text, size_t len, const char *label,
                     og_error *err) {
    memset(s, 0, sizeof *s);
    snprintf(s->label, sizeof s->label, "%s", label);
    cmd_tokenizer t;
    cmd_tokenizer_init(&t, text, len, label);
    int argc, line, rc;
    char **argv;
    while ((rc = cmd_tokenizer_next(&t, &argc, &argv, &line, &s->parse_error)) == 1) {
        if (cmd_script_add(s, argc, (const char *const *)argv, line) != 0) {
            cmd_tokenizer_free(&t);
            cmd_script_free(s);
            return og_error_set(err, "%s: out of memory", label);
        }
    }
    cmd_tokenizer_free(&t);
    s->malformed = rc < 0;
    return 0;
}

void cmd_script_free(cmd_script *s) {
    for (size_t i = 0; i < s->count; i++)
        free(s->calls[i].argv);
    free(s->calls);
    s->calls = NULL;
    s->count = s->cap = 0;
    s->malformed = 0;
}
