// Numbers and key=value settings as users type them, read one way everywhere: the
// command language, brush, render and stamp settings, and parameter files.
// Locale-independent (a decimal point whatever LC_NUMERIC says, so a file written
// in one locale reads back in another); a value is the whole text, with no blanks.
// Errors read `what: expected ..., got '...'` (long values cut short).
#ifndef OROGEN_IO_PARSE_H
#define OROGEN_IO_PARSE_H

#include "io/err.h"

#include <stddef.h>
#include <stdint.h>

// Reads a number at the start of s (optional sign, digits, point, exponent; also
// "inf" and "nan"); *end gets the first character after it. -1 when s does not start
// with a number. Thread-safe.
int parse_scan_f64(const char *s, double *out, const char **end);

// The whole text as a finite double / a base-10 int64; -1 otherwise (no message).
int parse_f64(const char *text, double *out);
int parse_i64(const char *text, int64_t *out);

// The same with the shared wording: "what: expected a finite number, got 'text'",
// "what: expected an integer, got 'text'".
int parse_number(const char *text, const char *what, double *out, og_error *err);
int parse_integer(const char *text, const char *what, int64_t *out, og_error *err);
// A finite number in [lo, hi]: "what: expected a number in [lo, hi], got 'text'".
int parse_number_in(const char *text, const char *what, double lo, double hi, double *out,
                    og_error *err);
// A whole number in [lo, hi] (also written like 3.0): "what: expected an integer in
// [lo, hi], got 'text'".
int parse_integer_in(const char *text, const char *what, double lo, double hi, double *out,
                     og_error *err);
// on/off/1/0: "what: expected on or off, got 'text'".
int parse_switch(const char *text, const char *what, int *out, og_error *err);

// Splits "key=value" into key and value, pointers into a copy held in buf:
// "expected key=value, got 'arg'" when there is no '=' or no key, and an error when
// arg does not fit in buf.
int parse_setting(const char *arg, char *buf, size_t size, char **key, char **value, og_error *err);

// The value as it appears in messages: quoted, cut short when long.
void parse_quote(char *buf, size_t size, const char *value);

// The shortest %g form of v that reads back to exactly v (C locale).
void parse_format_f64(char *buf, size_t size, double v);

#endif
