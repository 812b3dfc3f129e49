// libFuzzer target: the command language's tokenizer and parser, with the commands run
// against a tiny bounded world. Only commands that touch no files run (a fuzzer must
// not save, export or load over the machine's files), and the erosion tools, whose
// long runs are by design, are left out; every input is tokenized all the same.
#include "editor/cmd/commands.h"
#include "editor/cmd/context.h"
#include "editor/cmd/edit_commands.h"
#include "editor/cmd/tokenize.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const allowed[] = {
    "tool",    "dab",    "stroke", "stroke_begin", "stroke_to", "stroke_end", "stroke_cancel",
    "sample",  "undo",   "redo",   "seed",         "octaves",   "w_factor",   "exponent",
    "nparams", "params", "info",   "help",         "cmdlist",   "generator",
};

static int is_allowed(const char *name) {
    for (size_t i = 0; i < sizeof allowed / sizeof allowed[0]; i++)
        if (!strcmp(name, allowed[i])) return 1;
    return 0;
}

// Whether every command in text may run here (the tokenizer runs over all of it).
static int runnable(const char *text, size_t len) {
    if (memmem(text, len, "hydraulic", 9) || memmem(text, len, "thermal", 7)) return 0;
    cmd_tokenizer t;
    cmd_tokenizer_init(&t, text, len, "fuzz");
    int ok = 1, argc, line, rc;
    char **argv;
    og_error err;
    while (ok && (rc = cmd_tokenizer_next(&t, &argc, &argv, &line, &err)) > 0)
        ok = argc > 0 && is_allowed(argv[0]);
    cmd_tokenizer_free(&t);
    return ok;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size > 4096) return 0;
    const char *text = (const char *)data;
    if (!runnable(text, size)) return 0;
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.generator = GEN_FLAT;
    p.size = 257;
    world_settings s = {.workers = 1, .cache_budget_bytes = 64 << 20};
    og_error err;
    world *w = world_create(&p, &s, &err);
    if (!w) abort();
    FILE *out = fopen("/dev/null", "w");
    cmd_context ctx;
    cmd_context_init(&ctx, w, &s, out, NULL);
    cmd_run(&ctx, text, size, "fuzz", &err);
    cmd_end_stroke(&ctx, &err);
    world_close(ctx.world);
    fclose(out);
    return 0;
}
