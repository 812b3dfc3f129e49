#include "editor/interchange/sidecar.h"

#include "io/param_file.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int sidecar_write(const char *image_path, const sidecar *s, const char *extra, og_error *err) {
    char path[4200];
    if (snprintf(path, sizeof path, "%s.json", image_path) >= (int)sizeof path)
        return og_error_set(err, "%s: path too long", image_path);
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f) return og_error_set(err, "%s: out of memory", path);
    // Rows apart by another distance than columns (a preset's resampling) say so.
    char rows[64] = "";
    if (s->spacing_z > 0 && s->spacing_z != s->spacing)
        snprintf(rows, sizeof rows, "  \"spacing_z\": %.17g,\n", s->spacing_z);
    // %.17g: every double reads back bit-exactly.
    fprintf(f,
            "{\n  \"generator\": \"orogen\",\n  \"format\": \"%s\",\n  \"layer\": \"%s\",\n"
            "  \"width\": %d,\n  \"height\": %d,\n  \"spacing\": %.17g,\n%s"
            "  \"origin_x\": %.17g,\n  \"origin_z\": %.17g,\n"
            "  \"axes\": \"columns run toward +X, rows toward +Z; origin is row 0, column 0\",\n"
            "  \"height_scale\": %.17g,\n  \"height_offset\": %.17g,\n"
            "  \"min_height\": %.17g,\n  \"max_height\": %.17g%s%s\n}\n",
            s->format, s->layer, s->width, s->height, s->spacing, rows, s->origin_x, s->origin_z,
            s->scale, s->offset, s->min, s->max, extra && *extra ? ",\n" : "", extra ? extra : "");
    fclose(f);
    int rc = param_file_write_atomic(path, text, len, err);
    free(text);
    return rc;
}

void sidecar_georef(char *out, size_t len, int comma, const char *crs, const double gt[6]) {
    size_t n = (size_t)snprintf(out, len, "%s  \"crs\": \"", comma ? ",\n" : "");
    for (const char *c = crs; *c && n + 8 < len; c++) {
        if (*c == '"' || *c == '\\') out[n++] = '\\';
        out[n++] = *c;
    }
    if (n < len) out[n] = 0;
    if (n < len)
        snprintf(out + n, len - n,
                 "\",\n  \"geotransform\": [%.17g, %.17g, %.17g, %.17g, %.17g, %.17g]", gt[0],
                 gt[1], gt[2], gt[3], gt[4], gt[5]);
}

static int parse_text(const char *path, const char *text, sidecar *s, og_error *err);

// Where the value of "key" starts in a flat JSON object (our own files): just after
// its colon; NULL if the key is missing.
static const char *field_value(const char *text, const char *key) {
    char quoted[64];
    snprintf(quoted, sizeof quoted, "\"%s\"", key);
    const char *p = strstr(text, quoted);
    if (!p) return NULL;
    p = strchr(p + strlen(quoted), ':');
    return p ? p + 1 : NULL;
}

// The number after "key":.
static int number_field(const char *text, const char *key, double *out) {
    const char *p = field_value(text, key);
    if (!p) return -1;
    char *end;
    errno = 0;
    double v = strtod(p, &end);
    if (end == p || errno || !isfinite(v)) return -1;
    *out = v;
    return 0;
}

int sidecar_read(const char *image_path, sidecar *s, og_error *err) {
    char path[4200];
    if (snprintf(path, sizeof path, "%s.json", image_path) >= (int)sizeof path) return 0;
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    enum { TEXT_MAX = 1 << 16 };
    char *text = malloc(TEXT_MAX);
    if (!text) {
        fclose(f);
        return og_error_set(err, "%s: out of memory", path);
    }
    size_t n = fread(text, 1, TEXT_MAX - 1, f);
    fclose(f);
    text[n] = 0;
    int rc = parse_text(path, text, s, err);
    free(text);
    return rc;
}

// The string after "key": (JSON escapes \" and \\ undone) into out; -1 if none.
static int string_field(const char *text, const char *key, char *out, size_t len) {
    const char *p = field_value(text, key);
    if (!p) return -1;
    p += strspn(p, " \t\n");
    if (*p++ != '"') return -1;
    size_t n = 0;
    for (; *p && *p != '"'; p++) {
        if (*p == '\\' && p[1]) p++;
        if (n + 1 >= len) return -1;
        out[n++] = *p;
    }
    out[n] = 0;
    return *p == '"' ? 0 : -1;
}

// The six numbers of "geotransform": [...]; -1 if not there.
static int geotransform_field(const char *text, double gt[6]) {
    const char *p = strstr(text, "\"geotransform\"");
    if (!p || !(p = strchr(p, '['))) return -1;
    p++;
    for (int k = 0; k < 6; k++) {
        char *end;
        errno = 0;
        gt[k] = strtod(p, &end);
        if (end == p || errno || !isfinite(gt[k])) return -1;
        p = end + strspn(end, " \t\n");
        if (*p != (k < 5 ? ',' : ']')) return -1;
        p++;
    }
    return gt[1] * gt[5] - gt[2] * gt[4] != 0 ? 0 : -1;
}

static int parse_text(const char *path, const char *text, sidecar *s, og_error *err) {
    memset(s, 0, sizeof *s);
    static const char *const keys[] = {"width",    "height",       "spacing",      "origin_x",
                                       "origin_z", "height_scale", "height_offset"};
    double v[7];
    for (int i = 0; i < 7; i++)
        if (number_field(text, keys[i], &v[i]) != 0)
            return og_error_set(err, "%s: no number for \"%s\"", path, keys[i]);
    if (v[2] <= 0) return og_error_set(err, "%s: \"spacing\" must be positive", path);
    s->width = (int)v[0];
    s->height = (int)v[1];
    s->spacing = v[2];
    s->spacing_z = v[2];
    if (number_field(text, "spacing_z", &s->spacing_z) == 0 && !(s->spacing_z > 0))
        return og_error_set(err, "%s: \"spacing_z\" must be positive", path);
    s->origin_x = v[3];
    s->origin_z = v[4];
    s->scale = v[5];
    s->offset = v[6];
    number_field(text, "min_height", &s->min);
    number_field(text, "max_height", &s->max);
    s->has_georef = geotransform_field(text, s->geotransform) == 0;
    if (s->has_georef && string_field(text, "crs", s->crs, sizeof s->crs) != 0) s->crs[0] = 0;
    return 1;
}
