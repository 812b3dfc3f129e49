#include "io/parse.h"

#include <errno.h>
#include <locale.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// strtod_l / snprintf under uselocale with one "C" locale made once: the
// application's locale (a decimal comma) never changes how numbers read or print.
static pthread_once_t c_locale_once = PTHREAD_ONCE_INIT;
static locale_t c_locale_obj;
static void c_locale_init(void) {
    c_locale_obj = newlocale(LC_ALL_MASK, "C", (locale_t)0);
}
static locale_t c_locale(void) {
    pthread_once(&c_locale_once, c_locale_init);
    return c_locale_obj;
}

int parse_scan_f64(const char *s, double *out, const char **end) {
    // strtod would skip leading blanks and read hex; a number starts here or not at all.
    char c = *s;
    if (!((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'i' || c == 'I' ||
          c == 'n' || c == 'N'))
        return -1;
    if (c == '-' || c == '+') {
        char d = s[1];
        if (!((d >= '0' && d <= '9') || d == '.' || d == 'i' || d == 'I' || d == 'n' || d == 'N'))
            return -1;
    }
    char *e;
    double v = strtod_l(s, &e, c_locale());
    if (e == s) return -1;
    // Hexadecimal floats are not a user's notation: "0x10" is 0 followed by junk.
    for (const char *p = s; p < e; p++)
        if (*p == 'x' || *p == 'X') return -1;
    *out = v;
    *end = e;
    return 0;
}

int parse_f64(const char *text, double *out) {
    const char *end;
    double v;
    // ERANGE on underflow still gives a usable (subnormal or zero) value; overflow is inf.
    if (parse_scan_f64(text, &v, &end) != 0 || *end || !isfinite(v)) return -1;
    *out = v;
    return 0;
}

int parse_i64(const char *text, int64_t *out) {
    const char *s = text;
    if (*s == '-' || *s == '+') s++;
    if (!(*s >= '0' && *s <= '9')) return -1;
    char *end;
    errno = 0;
    long long v = strtoll(text, &end, 10);
    if (errno || *end) return -1;
    *out = (int64_t)v;
    return 0;
}

void parse_quote(char *buf, size_t size, const char *value) {
    size_t n = strlen(value);
    snprintf(buf, size, "'%.*s%s'", (int)(n > 48 ? 40 : n), value, n > 48 ? "..." : "");
}

int parse_number(const char *text, const char *what, double *out, og_error *err) {
    if (parse_f64(text, out) == 0) return 0;
    char q[64];
    parse_quote(q, sizeof q, text);
    return og_error_set(err, "%s: expected a finite number, got %s", what, q);
}

int parse_integer(const char *text, const char *what, int64_t *out, og_error *err) {
    if (parse_i64(text, out) == 0) return 0;
    char q[64];
    parse_quote(q, sizeof q, text);
    return og_error_set(err, "%s: expected an integer, got %s", what, q);
}

int parse_number_in(const char *text, const char *what, double lo, double hi, double *out,
                    og_error *err) {
    double v;
    if (parse_f64(text, &v) != 0 || v < lo || v > hi) {
        char q[64];
        parse_quote(q, sizeof q, text);
        return og_error_set(err, "%s: expected a number in [%g, %g], got %s", what, lo, hi, q);
    }
    *out = v;
    return 0;
}

int parse_integer_in(const char *text, const char *what, double lo, double hi, double *out,
                     og_error *err) {
    double v;
    if (parse_f64(text, &v) != 0 || v < lo || v > hi || v != floor(v)) {
        char q[64];
        parse_quote(q, sizeof q, text);
        return og_error_set(err, "%s: expected an integer in [%g, %g], got %s", what, lo, hi, q);
    }
    *out = v;
    return 0;
}

int parse_switch(const char *text, const char *what, int *out, og_error *err) {
    if (strcmp(text, "on") == 0 || strcmp(text, "1") == 0) return *out = 1, 0;
    if (strcmp(text, "off") == 0 || strcmp(text, "0") == 0) return *out = 0, 0;
    char q[64];
    parse_quote(q, sizeof q, text);
    return og_error_set(err, "%s: expected on or off, got %s", what, q);
}

int parse_setting(const char *arg, char *buf, size_t size, char **key, char **value,
                  og_error *err) {
    const char *eq = strchr(arg, '=');
    char q[64];
    parse_quote(q, sizeof q, arg);
    if (!eq || eq == arg) return og_error_set(err, "expected key=value, got %s", q);
    size_t n = strlen(arg);
    if (n + 1 > size) return og_error_set(err, "setting too long (%zu bytes): %s", n, q);
    memcpy(buf, arg, n + 1);
    buf[eq - arg] = 0;
    *key = buf;
    *value = buf + (eq - arg) + 1;
    return 0;
}

void parse_format_f64(char *buf, size_t size, double v) {
    locale_t old = uselocale(c_locale());
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(buf, size, "%.*g", prec, v);
        double back = strtod_l(buf, NULL, c_locale());
        if (back == v && signbit(back) == signbit(v)) break;
    }
    uselocale(old);
}
