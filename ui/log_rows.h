// A log's long lines folded into rows of at most a given number of characters (the log
// draws a monospace face): a console line longer than the panel (an import's summary, an
// error naming a path) was cut at the panel's edge, its end unreadable.
#ifndef OROGEN_UI_LOG_ROWS_H
#define OROGEN_UI_LOG_ROWS_H

#include <stddef.h>

// The bytes of text's first row of at most cols characters (UTF-8 code points, cols >= 1):
// the whole text when it fits, else up to and including the row's last space when that
// lies in the row's second half, else cols characters. 0 only for an empty text.
size_t log_row_bytes(const char *text, size_t cols);

// How many rows text takes at cols characters a row (an empty line takes one).
size_t log_rows(const char *text, size_t cols);

#endif
