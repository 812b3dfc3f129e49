// Shader loading: #include expansion with #line bookkeeping, compilation and
// linking, and mapping the driver's error log back to the original files.
#include "renderer/shader.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { INCLUDE_DEPTH_MAX = 8 };

// Mesa (22.3) reports most errors at source string 0 whatever `#line N S` said (its
// parser's default location drops S; only the line survives), so the file is also
// encoded in the line: file S's line N is compiled as S * LINE_STRIDE + N.
enum { LINE_STRIDE = 100000 };

// A growing string: the expanded source of one shader stage.
typedef struct text {
    char *data;
    size_t len, cap;
} text;

// The files that went into one stage; a file's index is its GLSL source-string
// number in `#line N S` (and its line block, see LINE_STRIDE).
typedef struct source_files {
    char **paths;
    int count, cap;
} source_files;

// One open #include on the way down, for cycle messages.
typedef struct include_frame {
    const char *path;
    int line;
} include_frame;

static int text_append(text *t, const char *s, size_t n, og_error *err) {
    if (t->len + n + 1 > t->cap) {
        size_t cap = t->cap ? t->cap : 4096;
        while (cap < t->len + n + 1)
            cap *= 2;
        char *data = realloc(t->data, cap);
        if (!data) return og_error_set(err, "shader: out of memory");
        t->data = data;
        t->cap = cap;
    }
    memcpy(t->data + t->len, s, n);
    t->len += n;
    t->data[t->len] = '\0';
    return 0;
}

static int text_line_directive(text *t, int line, int source, og_error *err) {
    char directive[64];
    int n =
        snprintf(directive, sizeof directive, "#line %d %d\n", source * LINE_STRIDE + line, source);
    return text_append(t, directive, (size_t)n, err);
}

static char *join_path(const char *dir, const char *name) {
    size_t dn = dir ? strlen(dir) : 0, nn = strlen(name);
    bool slash = dn > 0 && dir[dn - 1] != '/';
    char *path = malloc(dn + slash + nn + 1);
    if (!path) return NULL;
    if (dn) memcpy(path, dir, dn);
    if (slash) path[dn] = '/';
    memcpy(path + dn + slash, name, nn + 1);
    return path;
}

// The source-string number of path, adding it if new.
static int source_number(source_files *files, const char *path, og_error *err) {
    for (int i = 0; i < files->count; i++)
        if (strcmp(files->paths[i], path) == 0) return i;
    if (files->count == files->cap) {
        int cap = files->cap ? files->cap * 2 : 8;
        char **paths = realloc(files->paths, (size_t)cap * sizeof *paths);
        if (!paths) return og_error_set(err, "shader: out of memory");
        files->paths = paths;
        files->cap = cap;
    }
    if (!(files->paths[files->count] = strdup(path)))
        return og_error_set(err, "shader: out of memory");
    return files->count++;
}

static void source_files_free(source_files *files) {
    for (int i = 0; i < files->count; i++)
        free(files->paths[i]);
    free(files->paths);
}

// Reads a whole file, NUL-terminated. NULL with err "PATH: cannot open: reason".
static char *read_whole_file(const char *path, og_error *err) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        og_error_set(err, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    size_t len = 0, cap = 4096;
    char *data = malloc(cap);
    while (data) {
        len += fread(data + len, 1, cap - 1 - len, f);
        if (len < cap - 1) break;
        char *bigger = realloc(data, cap * 2);
        if (!bigger) free(data);
        data = bigger;
        cap *= 2;
    }
    if (!data) {
        fclose(f);
        og_error_set(err, "%s: cannot read: out of memory", path);
        return NULL;
    }
    if (ferror(f)) {
        og_error_set(err, "%s: cannot read: %s", path, strerror(errno));
        fclose(f);
        free(data);
        return NULL;
    }
    fclose(f);
    data[len] = '\0';
    return data;
}

static const char *skip_blanks(const char *p, const char *end) {
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    return p;
}

// If the line is the preprocessor directive `word` (`#include`, `#version`),
// returns where its argument starts, else NULL.
static const char *directive_argument(const char *line, const char *end, const char *word) {
    const char *p = skip_blanks(line, end);
    if (p == end || *p != '#') return NULL;
    p = skip_blanks(p + 1, end);
    size_t n = strlen(word);
    if ((size_t)(end - p) < n || memcmp(p, word, n) != 0) return NULL;
    p += n;
    if (p < end && *p != ' ' && *p != '\t' && *p != '"' && *p != '\r') return NULL;
    return skip_blanks(p, end);
}

static int expand_file(const char *dir, const char *path, int depth, include_frame *stack,
                       source_files *files, text *out, og_error *err);

// Replaces an `#include "name"` at path:line by the named file's expansion.
static int expand_include(const char *dir, const char *arg, const char *end, int depth,
                          include_frame *stack, source_files *files, text *out, og_error *err) {
    const include_frame *at = &stack[depth];
    const char *close =
        arg < end && *arg == '"' ? memchr(arg + 1, '"', (size_t)(end - arg - 1)) : NULL;
    if (!close || close == arg + 1)
        return og_error_set(err, "%s:%d: error: malformed #include (expected #include \"file\")",
                            at->path, at->line);
    char name[512];
    size_t n = (size_t)(close - arg - 1);
    if (n >= sizeof name)
        return og_error_set(err, "%s:%d: error: #include name too long", at->path, at->line);
    memcpy(name, arg + 1, n);
    name[n] = '\0';
    if (depth + 1 > INCLUDE_DEPTH_MAX)
        return og_error_set(err, "%s:%d: error: #include \"%s\" nests deeper than %d files",
                            at->path, at->line, name, INCLUDE_DEPTH_MAX);
    char *child = join_path(dir, name);
    if (!child) return og_error_set(err, "shader: out of memory");
    for (int i = 0; i <= depth; i++) {
        if (strcmp(stack[i].path, child) != 0) continue;
        // Name the chain from the file that closes the loop: a.glsl -> b.glsl -> a.glsl.
        char chain[768] = "";
        for (int j = i, len = 0; j <= depth && len < (int)sizeof chain; j++)
            len += snprintf(chain + len, sizeof chain - (size_t)len, "%s -> ", stack[j].path);
        og_error_set(err, "%s:%d: error: #include cycle: %s%s", at->path, at->line, chain, child);
        free(child);
        return -1;
    }
    int rc = expand_file(dir, child, depth + 1, stack, files, out, err);
    if (rc < 0 && err && strstr(err->msg, ": cannot open: ") &&
        !strstr(err->msg, "(included from")) {
        size_t used = strlen(err->msg);
        snprintf(err->msg + used, sizeof err->msg - used, " (included from %s:%d)", at->path,
                 at->line);
    }
    free(child);
    return rc;
}

// Appends path's lines to out with its #include lines expanded; stack[depth] is
// this file's frame. A #line directive after every include (and after #version)
// keeps the compiler's line numbers those of the original file.
static int expand_file(const char *dir, const char *path, int depth, include_frame *stack,
                       source_files *files, text *out, og_error *err) {
    int source = source_number(files, path, err);
    if (source < 0) return -1;
    char *data = read_whole_file(path, err);
    if (!data) return -1;
    stack[depth] = (include_frame){path, 0};
    int rc = depth > 0 ? text_line_directive(out, 1, source, err) : 0;
    const char *line = data, *data_end = data + strlen(data);
    for (int number = 1; rc == 0 && line < data_end; number++) {
        const char *end = memchr(line, '\n', (size_t)(data_end - line));
        if (!end) end = data_end;
        stack[depth].line = number;
        if (number >= LINE_STRIDE) {
            rc = og_error_set(err, "%s: longer than %d lines", path, LINE_STRIDE - 1);
            break;
        }
        const char *arg;
        if ((arg = directive_argument(line, end, "include"))) {
            rc = expand_include(dir, arg, end, depth, stack, files, out, err);
            if (rc == 0) rc = text_line_directive(out, number + 1, source, err);
        } else if (directive_argument(line, end, "version")) {
            if (depth > 0)
                rc = og_error_set(err, "%s:%d: error: #version belongs in the top-level file only",
                                  path, number);
            else if ((rc = text_append(out, line, (size_t)(end - line), err)) == 0 &&
                     (rc = text_append(out, "\n", 1, err)) == 0)
                rc = text_line_directive(out, number + 1, source, err);
        } else if ((rc = text_append(out, line, (size_t)(end - line), err)) == 0) {
            rc = text_append(out, "\n", 1, err);
        }
        line = end + 1;
    }
    free(data);
    return rc;
}

// Parses one driver log line into source string, line and the message after the
// location. Formats: Mesa "0:12(5): error: ...", NVIDIA "0(12) : error C0000: ...",
// and the "ERROR: 0:12: ..." of AMD and Intel's Windows drivers.
static bool parse_log_location(const char *s, int *source, int *line, const char **message,
                               bool *add_error_prefix) {
    int column, n = 0;
    *add_error_prefix = false;
    if (sscanf(s, "%d:%d(%d): %n", source, line, &column, &n) == 3 && n > 0) {
    } else if (n = 0, sscanf(s, "%d(%d) : %n", source, line, &n) == 2 && n > 0) {
    } else if (n = 0, sscanf(s, "ERROR: %d:%d: %n", source, line, &n) == 2 && n > 0) {
        *add_error_prefix = true;
    } else {
        return false;
    }
    *message = s + n;
    // Warnings come first in some logs; "preprocessor error" is Mesa's glcpp.
    return *add_error_prefix || strncmp(*message, "error", 5) == 0 ||
           strncmp(*message, "preprocessor error", 18) == 0;
}

static char *info_log(GLuint object, bool is_program) {
    GLint len = 0;
    if (is_program)
        glGetProgramiv(object, GL_INFO_LOG_LENGTH, &len);
    else
        glGetShaderiv(object, GL_INFO_LOG_LENGTH, &len);
    char *log = calloc((size_t)(len > 0 ? len : 0) + 1, 1);
    if (log && len > 0) {
        if (is_program)
            glGetProgramInfoLog(object, len, NULL, log);
        else
            glGetShaderInfoLog(object, len, NULL, log);
    }
    return log;
}

static int line_length(const char *s) {
    return (int)strcspn(s, "\r\n");
}

// Reports the first error of a compile log at its original file and line.
static int report_compile_error(const char *log, const source_files *files, og_error *err) {
    for (const char *s = log; *s; s += strcspn(s, "\n"), s += *s == '\n') {
        int source, line;
        const char *message;
        bool add_error_prefix;
        if (!parse_log_location(s, &source, &line, &message, &add_error_prefix)) continue;
        const char *prefix = add_error_prefix ? "error: " : "";
        source = line / LINE_STRIDE; // not the logged source (see LINE_STRIDE)
        line %= LINE_STRIDE;
        if (source >= 0 && source < files->count)
            return og_error_set(err, "%s:%d: %s%.*s", files->paths[source], line, prefix,
                                line_length(message), message);
        return og_error_set(err, "%s (source string %d):%d: %s%.*s", files->paths[0], source, line,
                            prefix, line_length(message), message);
    }
    const char *first = log + strspn(log, " \t\r\n");
    return og_error_set(err, "%s: compile error: %.*s", files->paths[0], line_length(first),
                        *first ? first : "(no log)");
}

// Puts the defines right after the #version line (the first), before the #line that
// keeps the file's own numbering.
static int insert_defines(text *source, const char *defines, og_error *err) {
    if (!defines || !*defines) return 0;
    const char *nl = strchr(source->data, '\n');
    size_t head = nl ? (size_t)(nl - source->data) + 1 : source->len;
    size_t extra = strlen(defines), total = source->len + extra + 2;
    char *data = malloc(total);
    if (!data) return og_error_set(err, "shader: out of memory");
    int n = snprintf(data, total, "%.*s%s%s%s", (int)head, source->data, defines,
                     defines[extra - 1] == '\n' ? "" : "\n", source->data + head);
    free(source->data);
    source->data = data;
    source->len = (size_t)n;
    source->cap = total;
    return 0;
}

static GLuint compile_stage(const char *dir, const char *name, GLenum stage, const char *defines,
                            og_error *err) {
    char *path = join_path(dir, name);
    if (!path) return og_error_set(err, "shader: out of memory"), 0;
    include_frame stack[INCLUDE_DEPTH_MAX + 1];
    source_files files = {0};
    text source = {0};
    GLuint shader = 0;
    if (expand_file(dir, path, 0, stack, &files, &source, err) == 0 &&
        insert_defines(&source, defines, err) == 0) {
        shader = glCreateShader(stage);
        if (!shader) og_error_set(err, "%s: glCreateShader failed (no current GL context?)", path);
    }
    if (shader) {
        const GLchar *string = source.data;
        glShaderSource(shader, 1, &string, NULL);
        glCompileShader(shader);
        GLint ok = GL_FALSE;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char *log = info_log(shader, false);
            if (log)
                report_compile_error(log, &files, err);
            else
                og_error_set(err, "%s: compile error (out of memory for the log)", path);
            free(log);
            glDeleteShader(shader);
            shader = 0;
        }
    }
    free(source.data);
    source_files_free(&files);
    free(path);
    return shader;
}

static GLuint link_program(const char *dir, const char *names[3], const GLuint shaders[3],
                           og_error *err) {
    GLuint program = glCreateProgram();
    if (!program) return og_error_set(err, "glCreateProgram failed (no current GL context?)"), 0;
    for (int i = 0; i < 3; i++)
        if (shaders[i]) glAttachShader(program, shaders[i]);
    glLinkProgram(program);
    for (int i = 0; i < 3; i++)
        if (shaders[i]) glDetachShader(program, shaders[i]);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok) return program;

    char files[1024] = "";
    for (int i = 0, len = 0; i < 3; i++) {
        if (!names[i]) continue;
        char *path = join_path(dir, names[i]);
        if (len < (int)sizeof files)
            len += snprintf(files + len, sizeof files - (size_t)len, "%s%s", len ? ", " : "",
                            path ? path : names[i]);
        free(path);
    }
    char *log = info_log(program, true);
    const char *first = log ? log + strspn(log, " \t\r\n") : "";
    if (strncmp(first, "error: ", 7) == 0) first += 7; // we say "link error:" already
    og_error_set(err, "%s: link error: %.*s", files, line_length(first),
                 *first ? first : "(no log)");
    free(log);
    glDeleteProgram(program);
    return 0;
}

static GLuint load_program(const char *dir, const char *vs_name, const char *gs_name,
                           const char *fs_name, const char *defines, og_error *err) {
    const char *names[3] = {vs_name, gs_name, fs_name};
    const GLenum stages[3] = {GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER};
    GLuint shaders[3] = {0, 0, 0};
    GLuint program = 0;
    bool compiled = true;
    for (int i = 0; i < 3 && compiled; i++)
        if (names[i])
            compiled = (shaders[i] = compile_stage(dir, names[i], stages[i], defines, err)) != 0;
    if (compiled) program = link_program(dir, names, shaders, err);
    for (int i = 0; i < 3; i++)
        if (shaders[i]) glDeleteShader(shaders[i]);
    return program;
}

GLuint shader_program_load_gs(const char *dir, const char *vs_name, const char *gs_name,
                              const char *fs_name, og_error *err) {
    return load_program(dir, vs_name, gs_name, fs_name, NULL, err);
}

GLuint shader_program_load(const char *dir, const char *vs_name, const char *fs_name,
                           og_error *err) {
    return load_program(dir, vs_name, NULL, fs_name, NULL, err);
}

GLuint shader_program_load_variant(const char *dir, const char *vs_name, const char *fs_name,
                                   const char *defines, og_error *err) {
    return load_program(dir, vs_name, NULL, fs_name, defines, err);
}

GLuint shader_program_load_flags(const char *dir, const char *vs_name, const char *fs_name,
                                 const char *const *names, int count, unsigned flags,
                                 og_error *err) {
    char defines[1024] = "";
    size_t used = 0;
    for (int b = 0; b < count && used < sizeof defines; b++)
        if (flags & (1u << b))
            used +=
                (size_t)snprintf(defines + used, sizeof defines - used, "#define %s\n", names[b]);
    if (used >= sizeof defines) return og_error_set(err, "%s: too many defines", fs_name), 0;
    return load_program(dir, vs_name, NULL, fs_name, defines, err);
}
