#include "io/param_file.h"

#include "io/file_mode.h"
#include "io/file_kind.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

// Files larger than this are not parameter files; refusing them keeps a wrong path
// (a tile store, a disk image) from being slurped into memory.
#define PARAM_FILE_MAX_BYTES (16u << 20)
// A garbage file could otherwise yield one diagnostic per line; past this many the
// rest are summarised in one line.
#define PARAM_DIAG_MAX 100

static int is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

static char *dup_range(const char *s, size_t n) {
    char *d = malloc(n + 1);
    if (!d) return NULL;
    memcpy(d, s, n);
    d[n] = 0;
    return d;
}

// Trims [*s, *s + *n) in place.
static void trim(const char **s, size_t *n) {
    while (*n && is_space(**s))
        ++*s, --*n;
    while (*n && is_space((*s)[*n - 1]))
        --*n;
}

static void add_diag(param_file *pf, param_severity sev, int line, const char *fmt, va_list ap) {
    if (pf->diag_count > PARAM_DIAG_MAX) return;
    param_diag *d = realloc(pf->diags, (pf->diag_count + 1) * sizeof *d);
    if (!d) return; // diagnostics are best effort; the parse result stays valid
    pf->diags = d;
    d += pf->diag_count++;
    d->severity = sev;
    d->line = line;
    if (pf->diag_count > PARAM_DIAG_MAX) {
        d->severity = PARAM_WARNING;
        snprintf(d->message, sizeof d->message, "too many problems; further ones not reported");
    } else {
        vsnprintf(d->message, sizeof d->message, fmt, ap);
    }
}

void param_file_diag(param_file *pf, param_severity sev, int line, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    add_diag(pf, sev, line, fmt, ap);
    va_end(ap);
}

// Index of the entry with this key, or -1.
static long find_key(const param_file *pf, const char *key, size_t key_len) {
    for (size_t i = 0; i < pf->count; i++)
        if (strlen(pf->entries[i].key) == key_len && !memcmp(pf->entries[i].key, key, key_len))
            return (long)i;
    return -1;
}

// Parses one line (without its newline). Returns -1 only when memory runs out.
static int parse_line(param_file *pf, const char *s, size_t n, int line) {
    if (n > PARAM_LINE_MAX) {
        param_file_diag(pf, PARAM_ERROR, line, "line is too long (%zu bytes; at most %d)", n,
                        PARAM_LINE_MAX);
        return 0;
    }
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        if ((c < 0x20 && c != '\t' && c != '\r' && c != '\v' && c != '\f') || c == 0x7f) {
            param_file_diag(pf, PARAM_ERROR, line,
                            "binary data (byte 0x%02x at column %zu); not a parameter file line", c,
                            i + 1);
            return 0;
        }
    }
    // A '#' starts a comment wherever it appears; values cannot contain one.
    const char *hash = memchr(s, '#', n);
    if (hash) n = (size_t)(hash - s);
    trim(&s, &n);
    if (!n) return 0;
    pf->has_lines = 1;

    const char *eq = memchr(s, '=', n);
    if (!eq) {
        param_file_diag(pf, PARAM_ERROR, line, "expected 'key = value;', found no '='");
        return 0;
    }
    const char *key = s;
    size_t key_len = (size_t)(eq - s);
    trim(&key, &key_len);
    if (!key_len) {
        param_file_diag(pf, PARAM_ERROR, line, "expected 'key = value;', found no key before '='");
        return 0;
    }
    for (size_t i = 0; i < key_len; i++) {
        if (is_space(key[i]) || key[i] == ';') {
            param_file_diag(pf, PARAM_ERROR, line, "expected one word before '=', found '%.*s'",
                            (int)(key_len < 60 ? key_len : 60), key);
            return 0;
        }
    }
    const char *rest = eq + 1;
    size_t rest_len = n - (size_t)(rest - s);
    const char *semi = memchr(rest, ';', rest_len);
    if (!semi) {
        param_file_diag(pf, PARAM_ERROR, line, "missing ';' after the value of '%.*s'",
                        (int)(key_len < 60 ? key_len : 60), key);
        return 0;
    }
    const char *after = semi + 1;
    size_t after_len = rest_len - (size_t)(after - rest);
    trim(&after, &after_len);
    if (after_len) {
        param_file_diag(pf, PARAM_ERROR, line, "unexpected text after ';': '%.*s'",
                        (int)(after_len < 60 ? after_len : 60), after);
        return 0;
    }
    const char *value = rest;
    size_t value_len = (size_t)(semi - rest);
    trim(&value, &value_len);

    char *v = dup_range(value, value_len);
    if (!v) return -1;
    long prev = find_key(pf, key, key_len);
    if (prev >= 0) {
        // Last one wins, as when a person appends an override to the end of a file.
        param_entry *e = &pf->entries[prev];
        param_file_diag(pf, PARAM_WARNING, line,
                        "duplicate key '%s' (also set on line %d); the last one wins", e->key,
                        e->line);
        free(e->value);
        e->value = v;
        e->line = line;
        return 0;
    }
    char *k = dup_range(key, key_len);
    param_entry *grown = k ? realloc(pf->entries, (pf->count + 1) * sizeof *grown) : NULL;
    if (!grown) {
        free(k);
        free(v);
        return -1;
    }
    pf->entries = grown;
    pf->entries[pf->count++] = (param_entry){.key = k, .value = v, .line = line};
    return 0;
}

// Length of the valid UTF-8 sequence at s (at most n bytes), or 0 when it is not one
// (overlong forms, surrogates and code points past U+10FFFF are not).
static size_t utf8_sequence(const unsigned char *s, size_t n) {
    unsigned c = s[0];
    size_t len;
    unsigned min;
    if (c < 0x80) return 1;
    if (c >= 0xC2 && c <= 0xDF)
        len = 2, min = 0x80;
    else if (c >= 0xE0 && c <= 0xEF)
        len = 3, min = 0x800;
    else if (c >= 0xF0 && c <= 0xF4)
        len = 4, min = 0x10000;
    else
        return 0;
    if (n < len) return 0;
    unsigned cp = c & (0x7F >> len);
    for (size_t i = 1; i < len; i++) {
        if ((s[i] & 0xC0) != 0x80) return 0;
        cp = (cp << 6) | (s[i] & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
    return len;
}

// Fills pf->not_text when text is not UTF-8 text of printable characters, tabs and
// line ends.
static void check_text(param_file *pf, const unsigned char *s, size_t n) {
    int line = 1;
    size_t line_start = 0;
    for (size_t i = 0; i < n;) {
        unsigned c = s[i];
        if (c == '\n') {
            line++, line_start = ++i;
            continue;
        }
        if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f) {
            snprintf(pf->not_text, sizeof pf->not_text, "byte 0x%02x at line %d, column %zu", c,
                     line, i - line_start + 1);
            return;
        }
        size_t len = utf8_sequence(s + i, n - i);
        if (!len) {
            snprintf(pf->not_text, sizeof pf->not_text,
                     "not UTF-8 text: byte 0x%02x at line %d, column %zu", c, line,
                     i - line_start + 1);
            return;
        }
        i += len;
    }
}

int param_file_parse(const char *text, size_t len, param_file *out) {
    *out = (param_file){0};
    // Editors on Windows may start the file with a UTF-8 byte order mark.
    if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) text += 3, len -= 3;
    size_t blank = 0;
    while (blank < len && (is_space(text[blank]) || text[blank] == '\n'))
        blank++;
    if (blank == len) {
        param_file_diag(out, PARAM_WARNING, 0, "empty parameter file, using defaults");
        return 0;
    }
    check_text(out, (const unsigned char *)text, len);
    int line = 1;
    for (size_t pos = 0; pos < len; line++) {
        const char *nl = memchr(text + pos, '\n', len - pos);
        size_t end = nl ? (size_t)(nl - text) : len;
        if (parse_line(out, text + pos, end - pos, line) < 0) {
            param_file_free(out);
            return -1;
        }
        pos = end + 1;
    }
    return 0;
}

int param_file_read(const char *path, param_file *out, og_error *err) {
    *out = (param_file){0};
    // O_NONBLOCK so that a FIFO given by mistake is refused instead of hanging.
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return og_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0) {
        int e = errno;
        close(fd);
        return og_error_set(err, "%s: cannot stat: %s", path, strerror(e));
    }
    if (S_ISDIR(st.st_mode)) {
        close(fd);
        return og_error_set(err, "%s: is a folder, not a parameter file", path);
    }
    if (!S_ISREG(st.st_mode)) {
        close(fd);
        return og_error_set(err, "%s: not a regular file", path);
    }
    if ((unsigned long long)st.st_size > PARAM_FILE_MAX_BYTES) {
        close(fd);
        return og_error_set(err, "%s: too large for a parameter file (%lld bytes; at most %u)",
                            path, (long long)st.st_size, PARAM_FILE_MAX_BYTES);
    }
    size_t cap = (size_t)st.st_size + 1, len = 0;
    char *buf = malloc(cap);
    if (!buf) {
        close(fd);
        return og_error_set(err, "%s: out of memory", path);
    }
    for (;;) {
        if (len == cap) { // the file grew while we read it
            if (cap > PARAM_FILE_MAX_BYTES) {
                free(buf);
                close(fd);
                return og_error_set(err, "%s: too large for a parameter file", path);
            }
            char *b = realloc(buf, cap * 2);
            if (!b) {
                free(buf);
                close(fd);
                return og_error_set(err, "%s: out of memory", path);
            }
            buf = b, cap *= 2;
        }
        ssize_t got = read(fd, buf + len, cap - len);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            int e = errno;
            free(buf);
            close(fd);
            return og_error_set(err, "%s: read failed: %s", path, strerror(e));
        }
        if (got == 0) break;
        len += (size_t)got;
    }
    close(fd);
    int rc = param_file_parse(buf, len, out);
    if (rc != 0) {
        free(buf);
        return og_error_set(err, "%s: out of memory", path);
    }
    buf[len] = 0; // cap > len: the loop stops on a read of 0 with room left
    out->text = buf, out->text_len = len;
    return 0;
}

void param_file_free(param_file *pf) {
    if (!pf) return;
    for (size_t i = 0; i < pf->count; i++) {
        free(pf->entries[i].key);
        free(pf->entries[i].value);
    }
    free(pf->entries);
    free(pf->diags);
    free(pf->text);
    *pf = (param_file){0};
}

static int write_all(int fd, const char *p, size_t n) {
    while (n) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w < 0) return -1;
        p += w, n -= (size_t)w;
    }
    return 0;
}

int param_file_write_atomic(const char *path, const char *text, size_t len, og_error *err) {
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    if (!*base) return og_error_set(err, "%s: not a file name", path);
    size_t dir_len = slash ? (size_t)(slash - path) : 0;
    char dir[4096], tmp[4096];
    if (!slash) {
        snprintf(dir, sizeof dir, ".");
    } else if (dir_len == 0) {
        snprintf(dir, sizeof dir, "/");
    } else if (dir_len < sizeof dir) {
        memcpy(dir, path, dir_len);
        dir[dir_len] = 0;
    } else {
        return og_error_set(err, "%s: path too long", path);
    }
    // Hidden temp name beside the target so rename() stays within one file system.
    int n = snprintf(tmp, sizeof tmp, "%.*s%s.%s.tmp-XXXXXX", (int)dir_len, path, slash ? "/" : "",
                     base);
    if (n < 0 || (size_t)n >= sizeof tmp) return og_error_set(err, "%s: path too long", path);

    if (file_kind_check_replace(path, err) != 0) return -1;
    // Keep the permissions of the file being replaced; new files get the umask's mode.
    mode_t mode = og_new_file_mode();
    struct stat st;
    if (stat(path, &st) == 0) {
        if (S_ISDIR(st.st_mode)) return og_error_set(err, "%s: is a folder", path);
        mode = st.st_mode & 07777;
    }

    int fd = mkstemp(tmp);
    if (fd < 0)
        return og_error_set(err, "%s: cannot create a temporary file in '%s': %s", path, dir,
                            strerror(errno));
    const char *step = "write";
    if (write_all(fd, text, len) != 0) goto fail;
    step = "set permissions of";
    if (fchmod(fd, mode) != 0) goto fail;
    step = "flush";
    if (fsync(fd) != 0) goto fail;
    step = "close";
    int rc = close(fd);
    fd = -1;
    if (rc != 0) goto fail; // network file systems report write errors here
    step = "replace";
    if (rename(tmp, path) != 0) goto fail;

    // Make the rename itself durable.
    int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd < 0)
        return og_error_set(err, "%s: cannot open folder '%s' to flush it: %s", path, dir,
                            strerror(errno));
    if (fsync(dfd) != 0 && errno != EINVAL) {
        int e = errno;
        close(dfd);
        return og_error_set(err, "%s: cannot flush folder '%s': %s", path, dir, strerror(e));
    }
    close(dfd);
    return 0;

fail:;
    int e = errno;
    if (fd >= 0) close(fd);
    unlink(tmp);
    return og_error_set(err, "%s: cannot %s the file: %s", path, step, strerror(e));
}
