// The material rule stack: its text, its file lines and its resolution for the shaders
// (material_rules.h says what a rule means).
#include "editor/layers/material_rules.h"

#include "io/parse.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const NAMES[MATERIAL_COUNT] = {"sand", "grass",  "rock", "snow",
                                                  "dirt", "gravel", "moss", "cliff"};

const char *material_name(int material) {
    return material >= 0 && material < MATERIAL_COUNT ? NAMES[material] : NULL;
}

int material_parse(const char *text) {
    for (int m = 0; m < MATERIAL_COUNT; m++)
        if (!strcmp(text, NAMES[m])) return m;
    if (text[0] >= '0' && text[0] < '0' + MATERIAL_COUNT && !text[1]) return text[0] - '0';
    return -1;
}

// Slope bounds as degrees of the rise over run the shaders used to compare: rock from
// 0.55 to 0.85, cliff from 1.1 to 1.5, snow off from 0.55 to 0.8.
void material_rules_default(material_rules *r) {
    static const char *const stack[] = {
        "sand",
        "grass height=1%+6,inf,6", // the beach: 1% of the relief (16 m by default) + 6
        "rock slope=40.3645,90,11.5537",
        "cliff slope=56.3099,90,8.5836",
        "snow height=62%+40,inf,80 slope=0,28.8108,9.849",
    };
    memset(r, 0, sizeof *r);
    for (size_t i = 0; i < sizeof stack / sizeof stack[0]; i++)
        material_rule_parse(&r->rule[r->count++], stack[i], NULL);
    r->implicit = 1;
}

void material_rules_planet_default(material_rules *r) {
    memset(r, 0, sizeof *r);
    r->implicit = 1;
}

void material_rules_planet_adopt(material_rules *r) {
    material_rules flat;
    material_rules_default(&flat);
    if (r->implicit || material_rules_equal(r, &flat)) material_rules_planet_default(r);
}

static int same_height(const material_height *a, const material_height *b) {
    return a->relative == b->relative && a->percent == b->percent && a->metres == b->metres;
}

static int same_range(const layer_mask_range *a, const layer_mask_range *b) {
    return a->on == b->on && (!a->on || (a->lo == b->lo && a->hi == b->hi && a->edge == b->edge));
}

int material_rules_equal(const material_rules *a, const material_rules *b) {
    if (a->count != b->count) return 0;
    for (int i = 0; i < a->count; i++) {
        const material_rule *x = &a->rule[i], *y = &b->rule[i];
        if (x->material != y->material || x->height_on != y->height_on ||
            x->breakup != y->breakup || !same_range(&x->slope, &y->slope) ||
            !same_range(&x->curvature, &y->curvature))
            return 0;
        if (x->height_on &&
            (!same_height(&x->height_lo, &y->height_lo) ||
             !same_height(&x->height_hi, &y->height_hi) || x->height_edge != y->height_edge))
            return 0;
    }
    return 1;
}

// A number filling [s, s + n) exactly (finite unless allow_inf).
static int number(const char *s, size_t n, int allow_inf, double *out) {
    char text[64];
    if (n == 0 || n >= sizeof text) return -1;
    memcpy(text, s, n);
    text[n] = 0;
    const char *end;
    double v;
    if (parse_scan_f64(text, &v, &end) || *end || isnan(v) || (!allow_inf && !isfinite(v)))
        return -1;
    *out = v + 0.0;
    return 0;
}

// "500", "-inf", "62%", "62%+40", "62%-15".
static int parse_bound(const char *s, size_t n, material_height *out) {
    const char *pct = memchr(s, '%', n);
    if (!pct) {
        *out = (material_height){0};
        return number(s, n, 1, &out->metres);
    }
    material_height b = {.relative = 1};
    if (number(s, (size_t)(pct - s), 0, &b.percent)) return -1;
    size_t rest = n - (size_t)(pct + 1 - s);
    if (rest && ((pct[1] != '+' && pct[1] != '-') || number(pct + 1, rest, 0, &b.metres)))
        return -1;
    *out = b;
    return 0;
}

static int format_bound(const material_height *b, char *buf, size_t len) {
    char v[32], m[32];
    parse_format_f64(m, sizeof m, b->metres);
    if (!b->relative) return snprintf(buf, len, "%s", m);
    parse_format_f64(v, sizeof v, b->percent);
    if (b->metres == 0) return snprintf(buf, len, "%s%%", v);
    return snprintf(buf, len, "%s%%%s%s", v, b->metres > 0 ? "+" : "", m);
}

// Whether lo lies above hi whatever the world (both metres, or both relative).
static int bounds_crossed(const material_height *lo, const material_height *hi) {
    if (lo->relative != hi->relative) return 0;
    if (!lo->relative) return lo->metres > hi->metres;
    return lo->percent > hi->percent || (lo->percent == hi->percent && lo->metres > hi->metres);
}

static int set_height(material_rule *r, const char *value, og_error *err) {
    if (!strcmp(value, "off")) {
        r->height_on = 0;
        r->height_lo = r->height_hi = (material_height){0};
        r->height_edge = 0;
        return 0;
    }
    const char *expected = "expected LO,HI or LO,HI,EDGE: metres, or percent of the relief "
                           "above the sea (62%, 62%+40), EDGE metres >= 0; or off";
    const char *c1 = strchr(value, ','), *c2 = c1 ? strchr(c1 + 1, ',') : NULL;
    material_height lo, hi;
    double edge = 0;
    if (!c1 || (c2 && strchr(c2 + 1, ',')) || parse_bound(value, (size_t)(c1 - value), &lo) ||
        parse_bound(c1 + 1, c2 ? (size_t)(c2 - c1 - 1) : strlen(c1 + 1), &hi) ||
        (c2 && number(c2 + 1, strlen(c2 + 1), 0, &edge)))
        return og_error_set(err, "height=%s: %s", value, expected);
    if (edge < 0) return og_error_set(err, "height=%s: the edge %g must be >= 0", value, edge);
    if (bounds_crossed(&lo, &hi))
        return og_error_set(err, "height=%s: the low end is above the high end", value);
    r->height_on = 1, r->height_lo = lo, r->height_hi = hi, r->height_edge = edge;
    return 0;
}

int material_rule_set_option(material_rule *r, const char *key, const char *value, og_error *err) {
    if (!strcmp(key, "material")) {
        int m = material_parse(value);
        if (m < 0)
            return og_error_set(err,
                                "material=%s: expected sand, grass, rock, snow, dirt, gravel, "
                                "moss, cliff or 0-7",
                                value);
        r->material = m;
        return 0;
    }
    if (!strcmp(key, "height")) return set_height(r, value, err);
    if (!strcmp(key, "slope"))
        return layer_mask_range_parse(key, value, 0, 90, "degrees", &r->slope, err);
    if (!strcmp(key, "curvature"))
        return layer_mask_range_parse(key, value, -INFINITY, INFINITY,
                                      "curvature, -100 x Laplacian, positive convex", &r->curvature,
                                      err);
    if (!strcmp(key, "breakup")) {
        double b;
        if (number(value, strlen(value), 0, &b) || b < 0 || b > 1)
            return og_error_set(err, "breakup=%s: expected a number 0..1", value);
        r->breakup = b;
        return 0;
    }
    return og_error_set(
        err, "%s=%s: unknown rule key (material, height, slope, curvature, breakup)", key, value);
}

int material_rule_parse(material_rule *out, const char *text, og_error *err) {
    material_rule r = {0};
    const char *p = text + strspn(text, " \t");
    size_t n = strcspn(p, " \t");
    char word[256];
    if (n == 0) return og_error_set(err, "a rule starts with its material (sand .. cliff)");
    if (n >= sizeof word) return og_error_set(err, "'%.40s...' is too long", p);
    memcpy(word, p, n);
    word[n] = 0;
    if (material_rule_set_option(&r, "material", word, err)) return -1;
    for (p += n;;) {
        p += strspn(p, " \t");
        if (!*p) break;
        n = strcspn(p, " \t");
        if (n >= sizeof word) return og_error_set(err, "'%.40s...' is too long", p);
        memcpy(word, p, n);
        word[n] = 0;
        char *eq = strchr(word, '=');
        if (!eq) return og_error_set(err, "'%s' is not key=value", word);
        *eq = 0;
        if (!strcmp(word, "material"))
            return og_error_set(err, "material=%s: the material is the rule's first word", eq + 1);
        if (material_rule_set_option(&r, word, eq + 1, err)) return -1;
        p += n;
    }
    *out = r;
    return 0;
}

int material_rule_format(const material_rule *r, char *buf, size_t len) {
    char text[512], a[80], b[80], range[200];
    int n = snprintf(text, sizeof text, "%s", material_name(r->material));
    if (r->height_on) {
        format_bound(&r->height_lo, a, sizeof a);
        format_bound(&r->height_hi, b, sizeof b);
        n += snprintf(text + n, sizeof text - (size_t)n, " height=%s,%s", a, b);
        if (r->height_edge != 0) {
            parse_format_f64(a, sizeof a, r->height_edge);
            n += snprintf(text + n, sizeof text - (size_t)n, ",%s", a);
        }
    }
    const layer_mask_range *ranges[2] = {&r->slope, &r->curvature};
    const char *keys[2] = {"slope", "curvature"};
    for (int k = 0; k < 2; k++) {
        if (!ranges[k]->on) continue;
        layer_mask_range_format(ranges[k], range, sizeof range);
        n += snprintf(text + n, sizeof text - (size_t)n, " %s=%s", keys[k], range);
    }
    if (r->breakup != 0) {
        parse_format_f64(a, sizeof a, r->breakup);
        n += snprintf(text + n, sizeof text - (size_t)n, " breakup=%s", a);
    }
    return snprintf(buf, len, "%s", text);
}

int material_rules_insert(material_rules *r, int at, const material_rule *rule, og_error *err) {
    if (r->count >= MATERIAL_RULES_MAX)
        return og_error_set(err, "the stack holds at most %d rules", MATERIAL_RULES_MAX);
    if (at < 0) at = 0;
    if (at > r->count) at = r->count;
    memmove(&r->rule[at + 1], &r->rule[at], sizeof r->rule[0] * (size_t)(r->count - at));
    r->rule[at] = *rule;
    r->count++;
    return 0;
}

void material_rules_remove(material_rules *r, int i) {
    if (i < 0 || i >= r->count) return;
    memmove(&r->rule[i], &r->rule[i + 1], sizeof r->rule[0] * (size_t)(r->count - i - 1));
    r->count--;
    memset(&r->rule[r->count], 0, sizeof r->rule[0]);
}

void material_rules_move(material_rules *r, int from, int to) {
    if (from < 0 || from >= r->count || to < 0 || to >= r->count || from == to) return;
    material_rule moving = r->rule[from];
    material_rules_remove(r, from);
    material_rules_insert(r, to, &moving, NULL);
}

int material_rules_read_entry(material_rules *r, const char *key, const char *value,
                              og_error *err) {
    int empty = !strcmp(key, "material_rules"), slot = 0;
    if (!empty && !strncmp(key, "material_rule_", 14) && key[14] >= '1' && key[14] <= '9') {
        for (const char *d = key + 14; *d >= '0' && *d <= '9' && slot <= MATERIAL_RULES_MAX; d++)
            slot = slot * 10 + (*d - '0');
        if (key[14 + strspn(key + 14, "0123456789")] || slot > MATERIAL_RULES_MAX) slot = 0;
    }
    if (!empty && !slot)
        return strncmp(key, "material_rule", 13) ? 1
                                                 : og_error_set(err,
                                                                "%s: not a rule key "
                                                                "(material_rule_1 .. "
                                                                "material_rule_%d, "
                                                                "material_rules = none)",
                                                                key, MATERIAL_RULES_MAX);
    if (empty && strcmp(value, "none"))
        return og_error_set(err, "material_rules: expected none (an empty stack), got '%s'", value);
    material_rule rule;
    og_error why;
    if (!empty && material_rule_parse(&rule, value, &why))
        return og_error_set(err, "%s: %s", key, why.msg);
    if (r->implicit) r->count = 0, r->implicit = 0, r->reading = 0;
    if (empty) return 0;
    r->rule[slot - 1] = rule;
    r->reading |= 1u << (slot - 1);
    return 0;
}

void material_rules_finish(material_rules *r) {
    if (!r->reading) return;
    int n = 0;
    for (int i = 0; i < MATERIAL_RULES_MAX; i++)
        if (r->reading & (1u << i)) r->rule[n++] = r->rule[i];
    for (int i = n; i < MATERIAL_RULES_MAX; i++)
        memset(&r->rule[i], 0, sizeof r->rule[i]);
    r->count = n;
    r->reading = 0;
}

int material_rules_format_lines(const material_rules *r, char **text, size_t *len, size_t *cap) {
    static const char comment[] =
        "\n# the automatic material rules, bottom first: MATERIAL [height=LO,HI[,EDGE]] "
        "[slope=LO,HI[,EDGE]] [curvature=LO,HI[,EDGE]] [breakup=B] (README, Material rules)\n";
    for (int i = -1; i < (r->count ? r->count : 1); i++) {
        char line[600];
        if (i < 0)
            snprintf(line, sizeof line, "%s", comment);
        else if (!r->count)
            snprintf(line, sizeof line, "material_rules = none;\n");
        else {
            char rule[512];
            material_rule_format(&r->rule[i], rule, sizeof rule);
            snprintf(line, sizeof line, "material_rule_%d = %s;\n", i + 1, rule);
        }
        size_t n = strlen(line);
        if (*len + n + 1 > *cap) {
            size_t grown_cap = (*len + n + 1) * 2;
            char *grown = realloc(*text, grown_cap);
            if (!grown) return -1;
            *text = grown, *cap = grown_cap;
        }
        memcpy(*text + *len, line, n + 1);
        *len += n;
    }
    return 0;
}

double material_height_metres(const material_height *b, double sea, double max_height) {
    if (!b->relative) return b->metres;
    return sea + b->percent / 100.0 * (max_height - sea) + b->metres;
}

// A range for the shaders as its four corners: where the weight starts rising, reaches
// 1, starts falling and reaches 0; open ends and "off" as +-1e30 (uniforms carry finite
// floats). to_tan: slopes go to the shader as rise over run.
static void corners(float out[4], int on, double lo, double hi, double edge, int to_tan) {
    double c[4] = {lo - edge, lo, hi, hi + edge};
    for (int k = 0; k < 4; k++) {
        double v = !on ? (k < 2 ? -1e30 : 1e30) : c[k];
        if (on && to_tan) v = v >= 90 ? 1e30 : v <= -90 ? -1e30 : tan(v * (M_PI / 180));
        out[k] = (float)fmax(fmin(v, 1e30), -1e30);
    }
}

void material_rules_resolve(const material_rules *r, double sea, double max_height,
                            material_rules_resolved *out) {
    memset(out, 0, sizeof *out);
    out->count = r->count;
    for (int i = 0; i < r->count; i++) {
        const material_rule *u = &r->rule[i];
        out->material[i] = u->material;
        corners(out->height[i], u->height_on,
                material_height_metres(&u->height_lo, sea, max_height),
                material_height_metres(&u->height_hi, sea, max_height), u->height_edge, 0);
        corners(out->slope[i], u->slope.on, u->slope.lo, u->slope.hi, u->slope.edge, 1);
        corners(out->curvature[i], u->curvature.on, u->curvature.lo, u->curvature.hi,
                u->curvature.edge, 0);
        out->breakup[i] = (float)u->breakup;
        out->uses_curvature |= u->curvature.on;
    }
}

unsigned material_rules_live(const material_rules_resolved *r, double hmin, double hmax,
                             double slope_max) {
    unsigned live = 0;
    for (int i = 0; i < r->count; i++) {
        const float *h = r->height[i], *s = r->slope[i];
        int dead = r->breakup[i] == 0 && (hmax < h[0] || hmin > h[3] || slope_max < s[0]);
        if (!dead) live |= 1u << i;
    }
    return live;
}
