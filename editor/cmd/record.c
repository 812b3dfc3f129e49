#include "editor/cmd/record.h"

#include <stdio.h>

// Writes the command to a recording, quoted so that running the file repeats it.
static void record_to(FILE *f, int argc, char **argv) {
    for (int k = 0; k < argc; k++) {
        const char *a = argv[k];
        int plain = *a != 0;
        for (const char *c = a; *c && plain; c++)
            plain = !(*c == ' ' || *c == '\t' || *c == '\r' || *c == '\n' || *c == ';' ||
                      *c == '#' || *c == '"' || *c == '\\');
        fputs(k ? " " : "", f);
        if (plain) {
            fputs(a, f);
            continue;
        }
        fputc('"', f);
        for (const char *c = a; *c; c++) {
            if (*c == '"' || *c == '\\') fputc('\\', f);
            fputc(*c, f);
        }
        fputc('"', f);
    }
    fputc('\n', f);
    fflush(f); // a crash keeps every command that ran
}

void cmd_record(cmd_context *ctx, int argc, char **argv) {
    if (ctx->record) record_to(ctx->record, argc, argv);
    if (ctx->session) record_to(ctx->session, argc, argv);
}
