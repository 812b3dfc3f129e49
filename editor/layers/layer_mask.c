// Layer masks: parsing, formatting and the per-sample weights (layer_mask.h says what
// each term means).
#include "editor/layers/layer_mask.h"

#include "io/parse.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void layer_mask_init(layer_mask *m) {
    memset(m, 0, sizeof *m);
}

int layer_mask_active(const layer_mask *m) {
    return m->height.on || m->slope.on || m->curvature.on || m->flow.on || m->invert || m->painted;
}

int layer_mask_border(const layer_mask *m, double spacing) {
    (void)spacing; // the flow border is in samples: what it cuts scales with spacing^2
    if (m->flow.on) return LAYER_MASK_FLOW_BORDER;
    if (m->slope.on || m->curvature.on) return 1;
    return 0;
}

// One number of a value, the whole of [s, end).
static int read_number(const char *s, size_t n, double *out) {
    char text[64];
    if (n == 0 || n >= sizeof text) return -1;
    memcpy(text, s, n);
    text[n] = 0;
    const char *end;
    double v;
    if (parse_scan_f64(text, &v, &end) || *end || isnan(v)) return -1;
    *out = v;
    return 0;
}

// "LO,HI" or, when allow_edge, "LO,HI,EDGE"; "off" clears the term.
static int parse_range(const char *key, const char *value, int allow_edge, double min, double max,
                       const char *unit, layer_mask_range *out, og_error *err) {
    if (!strcmp(value, "off")) {
        *out = (layer_mask_range){0};
        return 0;
    }
    double v[3] = {0, 0, 0};
    int count = 0;
    const char *p = value;
    for (;;) {
        const char *comma = strchr(p, ',');
        size_t n = comma ? (size_t)(comma - p) : strlen(p);
        if (count == 3 || read_number(p, n, &v[count]))
            return og_error_set(err, "%s=%s: expected %s (%s), two numbers%s, or off", key, value,
                                allow_edge ? "LO,HI or LO,HI,EDGE" : "LO,HI", unit,
                                allow_edge ? " and an optional edge width" : "");
        count++;
        if (!comma) break;
        p = comma + 1;
    }
    if (count < 2 || (count == 3 && !allow_edge))
        return og_error_set(err, "%s=%s: expected %s (%s)%s", key, value,
                            allow_edge ? "LO,HI or LO,HI,EDGE" : "LO,HI", unit,
                            allow_edge ? "" : "; its edge width is falloff=M");
    if (v[0] > v[1])
        return og_error_set(err, "%s=%s: the low end %g is above the high end %g", key, value, v[0],
                            v[1]);
    if (v[0] < min || v[1] > max)
        return og_error_set(err, "%s=%s: %s must lie within %g..%g", key, value, unit, min, max);
    if (count == 3 && (!isfinite(v[2]) || v[2] < 0))
        return og_error_set(err, "%s=%s: the edge width %g must be a number >= 0", key, value,
                            v[2]);
    *out = (layer_mask_range){.on = 1, .lo = v[0], .hi = v[1], .edge = v[2] + 0.0};
    return 0;
}

int layer_mask_range_parse(const char *key, const char *value, double min, double max,
                           const char *unit, layer_mask_range *out, og_error *err) {
    return parse_range(key, value, 1, min, max, unit, out, err);
}

int layer_mask_range_format(const layer_mask_range *r, char *buf, size_t len) {
    if (!r->on) return snprintf(buf, len, "off");
    char lo[32], hi[32], edge[32];
    parse_format_f64(lo, sizeof lo, r->lo);
    parse_format_f64(hi, sizeof hi, r->hi);
    parse_format_f64(edge, sizeof edge, r->edge);
    if (r->edge != 0) return snprintf(buf, len, "%s,%s,%s", lo, hi, edge);
    return snprintf(buf, len, "%s,%s", lo, hi);
}

static int parse_flag(const char *key, const char *value, int *out, og_error *err) {
    if (!strcmp(value, "0") || !strcmp(value, "1")) {
        *out = value[0] == '1';
        return 0;
    }
    return og_error_set(err, "%s=%s: expected 0 or 1", key, value);
}

int layer_mask_set_option(layer_mask *m, const char *key, const char *value, og_error *err) {
    layer_mask_range r;
    if (!strcmp(key, "height")) {
        if (parse_range(key, value, 0, -INFINITY, INFINITY, "metres", &r, err)) return -1;
        r.edge = m->height.edge; // falloff is kept apart from the range
        m->height = r;
        return 0;
    }
    layer_mask_range *term = !strcmp(key, "slope")       ? &m->slope
                             : !strcmp(key, "curvature") ? &m->curvature
                             : !strcmp(key, "flow")      ? &m->flow
                                                         : NULL;
    if (term) {
        int slope = term == &m->slope, flow = term == &m->flow;
        if (parse_range(key, value, 1, slope || flow ? 0 : -INFINITY, slope ? 90 : INFINITY,
                        slope  ? "degrees"
                        : flow ? "m^2 of upstream area"
                               : "curvature, -100 x Laplacian, positive convex",
                        &r, err))
            return -1;
        *term = r;
        return 0;
    }
    if (!strcmp(key, "falloff")) {
        double v;
        if (read_number(value, strlen(value), &v) || !isfinite(v) || v < 0)
            return og_error_set(err, "falloff=%s: expected metres >= 0 (the height edge width)",
                                value);
        m->height.edge = v + 0.0;
        return 0;
    }
    if (!strcmp(key, "invert")) return parse_flag(key, value, &m->invert, err);
    if (!strcmp(key, "painted")) return parse_flag(key, value, &m->painted, err);
    return og_error_set(err,
                        "%s=%s: unknown mask key (height, slope, curvature, flow, falloff, "
                        "invert, painted)",
                        key, value);
}

int layer_mask_parse(layer_mask *m, const char *text, og_error *err) {
    layer_mask next = *m;
    const char *p = text;
    while (*p) {
        while (*p == ' ' || *p == '\t')
            p++;
        if (!*p) break;
        const char *end = p + strcspn(p, " \t");
        char word[256], *eq;
        if ((size_t)(end - p) >= sizeof word)
            return og_error_set(err, "mask: '%.40s...' is too long", p);
        memcpy(word, p, (size_t)(end - p));
        word[end - p] = 0;
        if (!(eq = strchr(word, '=')))
            return og_error_set(err, "mask: '%s' is not key=value", word);
        *eq = 0;
        if (layer_mask_set_option(&next, word, eq + 1, err)) return -1;
        p = end;
    }
    *m = next;
    return 0;
}

// Appends text to buf as snprintf would at offset *at, counting what did not fit.
static void append(char *buf, size_t len, int *at, const char *text) {
    size_t room = (size_t)*at < len ? len - (size_t)*at : 0;
    int n = snprintf(room ? buf + *at : NULL, room, "%s%s", *at ? " " : "", text);
    if (n > 0) *at += n;
}

int layer_mask_format(const layer_mask *m, char *buf, size_t len) {
    int at = 0;
    if (len) buf[0] = 0;
    const layer_mask_range *ranges[4] = {&m->height, &m->slope, &m->curvature, &m->flow};
    const char *keys[4] = {"height", "slope", "curvature", "flow"};
    char text[160], range[128];
    for (int k = 0; k < 4; k++) {
        if (!ranges[k]->on) continue;
        layer_mask_range r = *ranges[k];
        if (k == 0) r.edge = 0; // the height's edge is falloff's
        layer_mask_range_format(&r, range, sizeof range);
        snprintf(text, sizeof text, "%s=%s", keys[k], range);
        append(buf, len, &at, text);
    }
    if (m->height.edge != 0) {
        parse_format_f64(range, sizeof range, m->height.edge);
        snprintf(text, sizeof text, "falloff=%s", range);
        append(buf, len, &at, text);
    }
    if (m->invert) append(buf, len, &at, "invert=1");
    if (m->painted) append(buf, len, &at, "painted=1");
    return at;
}

double layer_mask_range_weight(const layer_mask_range *r, double v) {
    if (!r->on) return 1;
    if (isnan(v)) return 0;
    double t;
    if (v < r->lo)
        t = r->edge > 0 ? 1 - (r->lo - v) / r->edge : 0;
    else if (v > r->hi)
        t = r->edge > 0 ? 1 - (v - r->hi) / r->edge : 0;
    else
        return 1;
    if (t <= 0) return 0;
    return t * t * (3 - 2 * t);
}

static int clampi(int v, int lo, int hi) {
    return v < lo ? lo : v > hi ? hi : v;
}

// The window's height at (x, y) of the evaluated area, clamped into the window.
static double at(const float *below, int ww, int wh, int b, int x, int y) {
    return below[(size_t)clampi(y + b, 0, wh - 1) * (size_t)ww + (size_t)clampi(x + b, 0, ww - 1)];
}

// Metres of run between the clamped neighbours of x (2 spacings inside, 1 at the edge).
static double run(int ww, int b, int x, double spacing) {
    int l = clampi(x + b - 1, 0, ww - 1), r = clampi(x + b + 1, 0, ww - 1);
    return (r - l) * spacing;
}

void layer_mask_slope_degrees(const float *below, int w, int h, int b, double spacing, float *out) {
    int ww = w + 2 * b, wh = h + 2 * b;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double gx = (at(below, ww, wh, b, x + 1, y) - at(below, ww, wh, b, x - 1, y)) /
                        run(ww, b, x, spacing);
            double gy = (at(below, ww, wh, b, x, y + 1) - at(below, ww, wh, b, x, y - 1)) /
                        run(wh, b, y, spacing);
            out[(size_t)y * (size_t)w + (size_t)x] =
                (float)(atan(sqrt(gx * gx + gy * gy)) * (180.0 / M_PI));
        }
}

// out *= the slope term's weight. Where the gradient's rise over run lies clearly inside
// [LO, HI] the weight is 1, clearly outside the soft edges 0, both known without the atan
// (most samples: the atan was most of a masked layer's cost); between, the degrees as
// layer_mask_slope_degrees takes them. "Clearly": a ten-thousandth of a degree, far over
// the degrees' float rounding, so the result is the same bit for bit.
static void multiply_slope_weights(const layer_mask_range *r, const float *below, int w, int h,
                                   int b, double spacing, float *out) {
    const double eps = 1e-4, rad = M_PI / 180.0;
    double lo = r->lo, hi = r->hi, edge = r->edge;
#define TAN2(deg) (tan((deg)*rad) * tan((deg)*rad))
    double in_lo2 = lo <= 0 ? -1.0 : lo + eps < 90 ? TAN2(lo + eps) : INFINITY;
    double in_hi2 = hi >= 90 ? INFINITY : hi - eps > 0 ? TAN2(hi - eps) : -1.0;
    double zero_lo2 = lo - edge - eps > 0 ? TAN2(lo - edge - eps) : -1.0;
    double zero_hi2 = hi + edge + eps < 90 ? TAN2(hi + edge + eps) : INFINITY;
#undef TAN2
    int ww = w + 2 * b, wh = h + 2 * b;
    const double across = 2 * spacing; // run() inside the window: a border of 1 or more
    for (int y = 0; y < h; y++) {
        const float *row = below + (size_t)(y + b) * (size_t)ww + (size_t)b;
        for (int x = 0; x < w; x++) {
            double gx, gy;
            if (b > 0) {
                gx = ((double)row[x + 1] - (double)row[x - 1]) / across;
                gy = ((double)row[x + ww] - (double)row[x - ww]) / across;
            } else {
                gx = (at(below, ww, wh, b, x + 1, y) - at(below, ww, wh, b, x - 1, y)) /
                     run(ww, b, x, spacing);
                gy = (at(below, ww, wh, b, x, y + 1) - at(below, ww, wh, b, x, y - 1)) /
                     run(wh, b, y, spacing);
            }
            double g2 = gx * gx + gy * gy;
            float *o = &out[(size_t)y * (size_t)w + (size_t)x];
            if (g2 >= in_lo2 && g2 <= in_hi2) continue; // weight 1
            if (g2 < zero_lo2 || g2 > zero_hi2) {
                *o = 0;
                continue;
            }
            *o *= (float)layer_mask_range_weight(r, (float)(atan(sqrt(g2)) * (180.0 / M_PI)));
        }
    }
}

void layer_mask_curvature(const float *below, int w, int h, int b, double spacing, float *out) {
    int ww = w + 2 * b, wh = h + 2 * b;
    double scale = -100.0 / (spacing * spacing);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double c = at(below, ww, wh, b, x, y);
            double lap = at(below, ww, wh, b, x + 1, y) + at(below, ww, wh, b, x - 1, y) +
                         at(below, ww, wh, b, x, y + 1) + at(below, ww, wh, b, x, y - 1) - 4 * c;
            out[(size_t)y * (size_t)w + (size_t)x] = (float)(scale * lap);
        }
}

// D-infinity's eight facets: a cardinal neighbour and the diagonal beside it.
static const int facet_card[8][2] = {{1, 0},  {0, -1}, {0, -1}, {-1, 0},
                                     {-1, 0}, {0, 1},  {0, 1},  {1, 0}};
static const int facet_diag[8][2] = {{1, -1}, {1, -1}, {-1, -1}, {-1, -1},
                                     {-1, 1}, {-1, 1}, {1, 1},   {1, 1}};

int layer_mask_flow_area(const float *below, int w, int h, int b, double spacing, float *out) {
    int ww = w + 2 * b, wh = h + 2 * b;
    size_t n = (size_t)ww * (size_t)wh;
    int32_t *to = malloc(n * 2 * sizeof *to);    // up to two receivers, -1 for none
    float *share = malloc(n * sizeof *share);    // fraction to the first receiver
    uint8_t *donors = calloc(n, sizeof *donors); // donors not yet passed on
    double *area = malloc(n * sizeof *area);
    int32_t *queue = malloc(n * sizeof *queue);
    if (!to || !share || !donors || !area || !queue) {
        free(to), free(share), free(donors), free(area), free(queue);
        return -1;
    }
    const double diag_angle = M_PI / 4;
    for (int y = 0; y < wh; y++)
        for (int x = 0; x < ww; x++) {
            size_t i = (size_t)y * (size_t)ww + (size_t)x;
            double e0 = below[i], best = 0, best_r = 0;
            int best_f = -1;
            for (int f = 0; f < 8; f++) {
                int x1 = x + facet_card[f][0], y1 = y + facet_card[f][1];
                int x2 = x + facet_diag[f][0], y2 = y + facet_diag[f][1];
                if (x1 < 0 || y1 < 0 || x1 >= ww || y1 >= wh || x2 < 0 || y2 < 0 || x2 >= ww ||
                    y2 >= wh)
                    continue;
                double e1 = below[(size_t)y1 * (size_t)ww + (size_t)x1];
                double e2 = below[(size_t)y2 * (size_t)ww + (size_t)x2];
                double s1 = (e0 - e1) / spacing, s2 = (e1 - e2) / spacing;
                double r = atan2(s2, s1), smax;
                if (r < 0) {
                    r = 0;
                    smax = s1;
                } else if (r > diag_angle) {
                    r = diag_angle;
                    smax = (e0 - e2) / (spacing * M_SQRT2);
                } else {
                    smax = sqrt(s1 * s1 + s2 * s2);
                }
                if (smax > best) best = smax, best_r = r, best_f = f;
            }
            to[2 * i] = to[2 * i + 1] = -1;
            share[i] = 1;
            if (best_f < 0) continue; // a pit or a flat: nothing flows on
            double diag = best_r / diag_angle;
            int32_t c = (int32_t)((y + facet_card[best_f][1]) * ww + x + facet_card[best_f][0]);
            int32_t d = (int32_t)((y + facet_diag[best_f][1]) * ww + x + facet_diag[best_f][0]);
            // Each receiver is strictly lower (D-infinity's facet rules), so flow is acyclic.
            if (diag < 1) to[2 * i] = c, share[i] = (float)(1 - diag), donors[c]++;
            if (diag > 0) to[2 * i + 1] = d, donors[d]++;
        }
    // Kahn's order: a cell passes its area on once every donor has passed it theirs.
    size_t head = 0, tail = 0;
    double cell = spacing * spacing;
    for (size_t i = 0; i < n; i++) {
        area[i] = cell;
        if (!donors[i]) queue[tail++] = (int32_t)i;
    }
    while (head < tail) {
        size_t i = (size_t)queue[head++];
        for (int k = 0; k < 2; k++) {
            int32_t j = to[2 * i + k];
            if (j < 0) continue;
            area[j] += area[i] * (k == 0 ? share[i] : 1.0 - share[i]);
            if (--donors[j] == 0) queue[tail++] = j;
        }
    }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            out[(size_t)y * (size_t)w + (size_t)x] =
                (float)area[(size_t)(y + b) * (size_t)ww + (size_t)(x + b)];
    free(to), free(share), free(donors), free(area), free(queue);
    return 0;
}

void layer_mask_evaluate(const layer_mask *m, const float *below, int w, int h, int b,
                         double spacing, const float *painted, float *out) {
    size_t count = (size_t)w * (size_t)h;
    int ww = w + 2 * b;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            out[(size_t)y * (size_t)w + (size_t)x] = (float)layer_mask_range_weight(
                &m->height, below[(size_t)(y + b) * (size_t)ww + (size_t)(x + b)]);
    const layer_mask_range *terms[3] = {&m->slope, &m->curvature, &m->flow};
    float *values = NULL;
    for (int t = 0; t < 3; t++) {
        if (!terms[t]->on) continue;
        if (!values && !(values = malloc(count * sizeof *values))) {
            memset(out, 0, count * sizeof *out); // no memory: the layer applies nowhere
            return;
        }
        if (t == 0) {
            multiply_slope_weights(terms[t], below, w, h, b, spacing, out);
            continue;
        }
        if (t == 1) layer_mask_curvature(below, w, h, b, spacing, values);
        if (t == 2 && layer_mask_flow_area(below, w, h, b, spacing, values)) {
            memset(out, 0, count * sizeof *out);
            free(values);
            return;
        }
        for (size_t i = 0; i < count; i++)
            out[i] *= (float)layer_mask_range_weight(terms[t], values[i]);
    }
    free(values);
    if (m->painted)
        for (size_t i = 0; i < count; i++) {
            float c = painted ? painted[i] : 0;
            out[i] *= !(c > 0) ? 0 : c > 1 ? 1 : c; // NaN counts as unpainted
        }
    if (m->invert)
        for (size_t i = 0; i < count; i++)
            out[i] = 1 - out[i];
}
