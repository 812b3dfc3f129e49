// Reader and writer for Orogen's parameter files: the syntax of Kahoun 2010's planet
// and configuration files. One `key = value;` per line, `#` starts a comment
// (whole line or after the `;`), blank lines are ignored. The reader is tolerant
// in the way Kahoun 2010 asks: a bad line is reported with its line number and
// reading goes on.
#ifndef OROGEN_IO_PARAM_FILE_H
#define OROGEN_IO_PARAM_FILE_H

#include "io/err.h"

#include <stddef.h>

// Longest line accepted; longer lines are reported and skipped.
#define PARAM_LINE_MAX 4096

typedef struct param_entry {
    char *key;   // as written (trimmed)
    char *value; // trimmed, without the `;`; may be an empty string
    int line;    // 1-based
} param_entry;

typedef enum param_severity { PARAM_WARNING, PARAM_ERROR } param_severity;

typedef struct param_diag {
    param_severity severity;
    int line; // 1-based; 0 when the message is about the whole file
    char message[256];
} param_diag;

typedef struct param_file {
    param_entry *entries;
    size_t count;
    param_diag *diags;
    size_t diag_count;
    // Why the bytes are not text ("" when they are): the first NUL or control byte
    // other than tab, CR and LF, or the first invalid UTF-8 sequence, with its line
    // and column. A caller refuses such a file as not a parameter file at all.
    char not_text[128];
    int has_lines; // some line is neither blank nor only a comment
    char *text;    // param_file_read: the file's bytes, NUL-terminated (NULL from parse)
    size_t text_len;
} param_file;

// Parses text (not necessarily NUL-terminated; len bytes). Never fails on
// content: syntax problems become diagnostics (missing `;`, no `=`, empty key,
// NUL bytes or other binary data, over-long lines, duplicate keys). Returns 0, or -1
// only when memory runs out.
int param_file_parse(const char *text, size_t len, param_file *out);
// Reads and parses a file. Returns -1 with err naming the path when it cannot
// be read (missing, a directory, unreadable, larger than 16 MiB).
int param_file_read(const char *path, param_file *out, og_error *err);
void param_file_free(param_file *pf);
// Adds a diagnostic (used by schema checks that run after parsing).
void param_file_diag(param_file *pf, param_severity sev, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

// Writes text to path atomically: a temporary file in the same folder, fsync,
// rename over the target, fsync of the folder. On any failure (unwritable folder,
// full disk) the old file is left untouched and err names the path.
int param_file_write_atomic(const char *path, const char *text, size_t len, og_error *err);

#endif
