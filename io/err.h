// A fixed-size error message that library code fills instead of printing or exiting.
// Messages name the file, line or field and what was expected (the habit of SQLite's errors).
#ifndef OROGEN_IO_ERR_H
#define OROGEN_IO_ERR_H

#include <stddef.h>

typedef struct og_error {
    char msg[1024];
} og_error;

// Formats into err->msg (err may be NULL). Always returns -1 so callers can
// write `return og_error_set(err, "...");`.
int og_error_set(og_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
