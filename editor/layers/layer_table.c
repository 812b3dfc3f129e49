#include "editor/layers/layer_table.h"

#include "io/tile.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const BLEND_NAMES[LAYER_BLEND_COUNT] = {"add", "replace", "max", "min"};

const char *layer_blend_name(layer_blend b) {
    return (unsigned)b < LAYER_BLEND_COUNT ? BLEND_NAMES[b] : "unknown";
}

static const char *const KIND_NAMES[LAYER_KIND_COUNT] = {"height", "paint"};

const char *layer_kind_name(layer_kind k) {
    return (unsigned)k < LAYER_KIND_COUNT ? KIND_NAMES[k] : "unknown";
}

int layer_kind_parse(const char *text) {
    for (int i = 0; i < LAYER_KIND_COUNT; i++)
        if (!strcmp(text, KIND_NAMES[i])) return i;
    return -1;
}

int layer_tile_kind(const layer_info *l) {
    return l->kind == LAYER_KIND_PAINT ? TILE_LAYER_MATERIAL : TILE_LAYER_COARSE;
}

int layer_table_top_visible(const layer_table *t, layer_kind kind) {
    int top = -1;
    for (int i = 0; i < t->count; i++)
        if (t->layers[i].visible && t->layers[i].kind == kind) top = i;
    return top;
}

int layer_blend_parse(const char *text) {
    for (int i = 0; i < LAYER_BLEND_COUNT; i++)
        if (!strcmp(text, BLEND_NAMES[i])) return i;
    return -1;
}

void layer_table_default(layer_table *t) {
    memset(t, 0, sizeof *t);
    t->next_id = LAYER_FIRST_ID;
    layer_table_insert(t, 0, "Sculpt", LAYER_BLEND_ADD, 1.0, NULL);
}

int layer_table_find(const layer_table *t, const char *name) {
    for (int i = 0; i < t->count; i++)
        if (!strcmp(t->layers[i].name, name)) return i;
    return -1;
}

int layer_table_find_id(const layer_table *t, int32_t id) {
    for (int i = 0; i < t->count; i++)
        if (t->layers[i].id == id) return i;
    return -1;
}

int layer_table_equal(const layer_table *a, const layer_table *b) {
    if (a->count != b->count || a->active != b->active || a->next_id != b->next_id) return 0;
    for (int i = 0; i < a->count; i++) {
        const layer_info *x = &a->layers[i], *y = &b->layers[i];
        if (x->id != y->id || x->kind != y->kind || strcmp(x->name, y->name) ||
            x->blend != y->blend || x->opacity != y->opacity || x->visible != y->visible ||
            x->locked != y->locked)
            return 0;
        char mx[512], my[512];
        layer_mask_format(&x->mask, mx, sizeof mx);
        layer_mask_format(&y->mask, my, sizeof my);
        if (strcmp(mx, my)) return 0;
    }
    return 1;
}

int layer_name_check(const char *name, og_error *err) {
    size_t n = strlen(name);
    if (n == 0 || n >= LAYER_NAME_MAX)
        return og_error_set(err, "layer name '%s': expected 1 to %d characters", name,
                            LAYER_NAME_MAX - 1);
    for (size_t i = 0; i < n; i++) {
        char c = name[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '_' || c == '-' || c == '.'))
            return og_error_set(err,
                                "layer name '%s': '%c' is not allowed (letters, digits, '_', "
                                "'-' and '.' only)",
                                name, c);
    }
    return 0;
}

static int opacity_parse(const char *text, double *out, og_error *err) {
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end || !(v >= 0.0 && v <= 1.0))
        return og_error_set(err, "opacity: expected a number from 0 to 1, got '%s'", text);
    *out = v;
    return 0;
}

static int flag_parse(const char *key, const char *text, int *out, og_error *err) {
    if (strcmp(text, "0") && strcmp(text, "1"))
        return og_error_set(err, "%s: expected 0 or 1, got '%s'", key, text);
    *out = text[0] == '1';
    return 0;
}

int layer_table_insert(layer_table *t, int at, const char *name, layer_blend blend, double opacity,
                       og_error *err) {
    if (t->count >= LAYER_MAX)
        return og_error_set(err, "layer '%s': a world holds at most %d layers", name, LAYER_MAX);
    if (layer_name_check(name, err) != 0) return -1;
    if (layer_table_find(t, name) >= 0)
        return og_error_set(err, "layer '%s' exists already; choose another name", name);
    if (t->next_id < LAYER_FIRST_ID) t->next_id = LAYER_FIRST_ID;
    if (t->next_id > LAYER_ID_MAX)
        return og_error_set(err, "layer '%s': this world has used up its layer ids", name);
    if (at < 0) at = 0;
    if (at > t->count) at = t->count;
    memmove(&t->layers[at + 1], &t->layers[at], (size_t)(t->count - at) * sizeof t->layers[0]);
    layer_info *l = &t->layers[at];
    memset(l, 0, sizeof *l);
    l->id = t->next_id++;
    snprintf(l->name, sizeof l->name, "%s", name);
    l->blend = blend;
    l->opacity = opacity;
    l->visible = 1;
    layer_mask_init(&l->mask);
    if (t->count > 0 && t->active >= at) t->active++;
    t->count++;
    return at;
}

void layer_table_remove(layer_table *t, int i) {
    if (i < 0 || i >= t->count) return;
    memmove(&t->layers[i], &t->layers[i + 1], (size_t)(t->count - i - 1) * sizeof t->layers[0]);
    t->count--;
    if (t->active > i || t->active >= t->count) t->active = t->active > 0 ? t->active - 1 : 0;
}

void layer_table_move(layer_table *t, int from, int to) {
    if (from < 0 || from >= t->count || to < 0 || to >= t->count || from == to) return;
    int32_t active_id = t->layers[t->active].id;
    layer_info moved = t->layers[from];
    if (from < to)
        memmove(&t->layers[from], &t->layers[from + 1], (size_t)(to - from) * sizeof moved);
    else
        memmove(&t->layers[to + 1], &t->layers[to], (size_t)(from - to) * sizeof moved);
    t->layers[to] = moved;
    t->active = layer_table_find_id(t, active_id);
}

int layer_info_set(layer_table *t, int i, const char *key, const char *value, og_error *err) {
    layer_info *l = &t->layers[i];
    if (!strcmp(key, "name")) {
        if (layer_name_check(value, err) != 0) return -1;
        int other = layer_table_find(t, value);
        if (other >= 0 && other != i)
            return og_error_set(err, "name: a layer named '%s' exists already", value);
        snprintf(l->name, sizeof l->name, "%s", value);
        return 0;
    }
    if (!strcmp(key, "blend")) {
        if (l->kind == LAYER_KIND_PAINT)
            return og_error_set(err,
                                "blend: '%s' is a paint layer: it covers what is below by its "
                                "painted coverage (blend is for height layers)",
                                l->name);
        int b = layer_blend_parse(value);
        if (b < 0)
            return og_error_set(err, "blend: expected add, replace, max or min, got '%s'", value);
        l->blend = (layer_blend)b;
        return 0;
    }
    if (!strcmp(key, "opacity")) return opacity_parse(value, &l->opacity, err);
    if (!strcmp(key, "visible")) return flag_parse(key, value, &l->visible, err);
    if (!strcmp(key, "locked")) return flag_parse(key, value, &l->locked, err);
    return 1;
}

int layer_mask_key(const char *key) {
    static const char *const keys[] = {"height",  "slope",  "curvature", "flow",
                                       "falloff", "invert", "painted"};
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        if (!strcmp(keys[i], key)) return 1;
    return 0;
}

// "NAME id=N blend=B ..." into the table's top.
static int read_layer(layer_table *t, const char *value, og_error *err) {
    char copy[1024];
    if (strlen(value) >= sizeof copy) return og_error_set(err, "layer: the line is too long");
    snprintf(copy, sizeof copy, "%s", value);
    char *save = NULL, *word = strtok_r(copy, " \t", &save);
    if (!word) return og_error_set(err, "layer: expected 'NAME id=N blend=B opacity=O ...'");
    if (t->count >= LAYER_MAX)
        return og_error_set(err, "layer '%s': a world holds at most %d layers", word, LAYER_MAX);
    if (layer_name_check(word, err) != 0) return -1;
    if (layer_table_find(t, word) >= 0) return og_error_set(err, "layer '%s' is named twice", word);
    layer_table next = *t;
    layer_info *l = &next.layers[next.count];
    memset(l, 0, sizeof *l);
    snprintf(l->name, sizeof l->name, "%s", word);
    l->opacity = 1.0;
    l->visible = 1;
    l->id = -1;
    layer_mask_init(&l->mask);
    next.count++;
    while ((word = strtok_r(NULL, " \t", &save))) {
        char *eq = strchr(word, '=');
        if (!eq)
            return og_error_set(err, "layer '%s': expected KEY=VALUE, got '%s'", l->name, word);
        *eq = 0;
        if (!strcmp(word, "id")) {
            char *end;
            long id = strtol(eq + 1, &end, 10);
            if (*end || end == eq + 1 || id < LAYER_FIRST_ID || id > LAYER_ID_MAX)
                return og_error_set(err,
                                    "layer '%s': id: expected an integer from %d to %d, got '%s'",
                                    l->name, LAYER_FIRST_ID, LAYER_ID_MAX, eq + 1);
            l->id = (int32_t)id;
            continue;
        }
        if (!strcmp(word, "kind")) {
            int k = layer_kind_parse(eq + 1);
            if (k < 0)
                return og_error_set(err, "layer '%s': kind: expected height or paint, got '%s'",
                                    l->name, eq + 1);
            l->kind = (layer_kind)k;
            continue;
        }
        og_error why;
        int rc = layer_info_set(&next, next.count - 1, word, eq + 1, &why);
        if (rc > 0 && layer_mask_key(word))
            rc = layer_mask_set_option(&l->mask, word, eq + 1, &why);
        if (rc > 0 || !strcmp(word, "name"))
            return og_error_set(err, "layer '%s': unknown field '%s'", l->name, word);
        if (rc < 0) return og_error_set(err, "layer '%s': %s", l->name, why.msg);
    }
    if (l->id < 0) return og_error_set(err, "layer '%s': missing id=N", l->name);
    if (layer_table_find_id(t, l->id) >= 0)
        return og_error_set(err, "layer '%s': id %d is another layer's", l->name, (int)l->id);
    *t = next;
    return 0;
}

int layer_table_read_entry(layer_table *t, const char *key, const char *value, og_error *err) {
    if (!strncmp(key, "layer.", 6)) {
        // One key per layer (a parameter file keeps the last of a repeated key), bottom first.
        char *end;
        long i = strtol(key + 6, &end, 10);
        if (*end || end == key + 6 || i < 0) return 1;
        if (i != t->count)
            return og_error_set(err,
                                "%s: expected layer.%d here (one line per layer, bottom first)",
                                key, t->count);
        return read_layer(t, value, err);
    }
    if (!strcmp(key, "layer_active")) {
        int i = layer_table_find(t, value);
        if (i < 0)
            return og_error_set(err, "layer_active: no layer named '%s' above this line", value);
        t->active = i;
        return 0;
    }
    if (!strcmp(key, "layer_next_id")) {
        char *end;
        long id = strtol(value, &end, 10);
        if (*end || end == value || id < LAYER_FIRST_ID || id > LAYER_ID_MAX)
            return og_error_set(err, "layer_next_id: expected an integer from %d to %d, got '%s'",
                                LAYER_FIRST_ID, LAYER_ID_MAX, value);
        t->next_id = (int32_t)id;
        return 0;
    }
    return 1;
}

int layer_table_finish(layer_table *t, og_error *err) {
    (void)err;
    for (int i = 0; i < t->count; i++)
        if (t->layers[i].id >= t->next_id) t->next_id = t->layers[i].id + 1;
    if (t->next_id < LAYER_FIRST_ID) t->next_id = LAYER_FIRST_ID;
    if (t->active < 0 || t->active >= t->count) t->active = t->count ? t->count - 1 : 0;
    return 0;
}

void layer_info_format(const layer_info *l, char *buf, size_t len) {
    int n =
        l->kind == LAYER_KIND_PAINT
            ? snprintf(buf, len, "%s id=%d kind=paint opacity=%.17g visible=%d locked=%d", l->name,
                       (int)l->id, l->opacity, l->visible, l->locked)
            : snprintf(buf, len, "%s id=%d blend=%s opacity=%.17g visible=%d locked=%d", l->name,
                       (int)l->id, layer_blend_name(l->blend), l->opacity, l->visible, l->locked);
    if (n > 0 && (size_t)n + 1 < len && layer_mask_active(&l->mask)) {
        buf[n] = ' ';
        layer_mask_format(&l->mask, buf + n + 1, len - (size_t)n - 1);
    }
}

static int append(char **text, size_t *len, size_t *cap, const char *s) {
    size_t n = strlen(s);
    if (*len + n + 1 > *cap) {
        size_t c = (*len + n + 1) * 2;
        char *grown = realloc(*text, c);
        if (!grown) return -1;
        *text = grown;
        *cap = c;
    }
    memcpy(*text + *len, s, n + 1);
    *len += n;
    return 0;
}

int layer_table_format(const layer_table *t, char **text, size_t *len, size_t *cap) {
    char line[LAYER_NAME_MAX + 800];
    if (append(
            text, len, cap,
            "\n# Edit layers over the generated terrain, bottom first: NAME id=N (its tiles in "
            "the tile store) [kind=paint] blend=add|replace|max|min (height layers) opacity=0..1 "
            "visible=0|1 locked=0|1\n"))
        return -1;
    for (int i = 0; i < t->count; i++) {
        char value[LAYER_NAME_MAX + 700];
        layer_info_format(&t->layers[i], value, sizeof value);
        snprintf(line, sizeof line, "layer.%d = %s;\n", i, value);
        if (append(text, len, cap, line)) return -1;
    }
    if (t->count) {
        snprintf(line, sizeof line, "layer_active = %s;\n", t->layers[t->active].name);
        if (append(text, len, cap, line)) return -1;
    }
    snprintf(line, sizeof line, "layer_next_id = %d;\n", (int)t->next_id);
    return append(text, len, cap, line);
}
