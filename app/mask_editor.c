// The mask editor of the Layers panel: a layer's mask terms (height, slope, curvature,
// flow), each on or off, with its low, high and soft-edge values typed and a range
// dragged over a histogram of the composite around the view (flow's on a log scale;
// on a planet, of the cube face under the camera); invert and clear. While the editor is open the
// viewport tints where the mask (as dragged so far) lets the layer apply. Each change runs one
// `layer mask` command.
#include "app/editor_ui_internal.h"

#include "app/layers_panel_state.h"
#include "app/value_field.h"

#include <stdlib.h>

enum { TERM_HEIGHT, TERM_SLOPE, TERM_CURVATURE, TERM_FLOW, TERM_COUNT };
static const char *const term_keys[TERM_COUNT] = {"height", "slope", "curvature", "flow"};
static const char *const term_labels[TERM_COUNT] = {"Height (m)", "Slope (degrees)",
                                                    "Curvature (convex +)", "Flow (m2 upstream)"};

static layer_mask_range *term(layer_mask *m, int k) {
    layer_mask_range *r[TERM_COUNT] = {&m->height, &m->slope, &m->curvature, &m->flow};
    return r[k];
}

// The `layer mask` command that sets every term of m on layer name.
static void mask_command(const char *name, const layer_mask *m, char *cmd, size_t len) {
    size_t n = (size_t)snprintf(cmd, len, "layer mask %s", name);
    for (int k = 0; k < TERM_COUNT && n < len; k++) {
        layer_mask_range r = *term((layer_mask *)m, k);
        if (k == TERM_HEIGHT) r.edge = 0; // height's soft edge is the falloff key
        char text[96];
        layer_mask_range_format(&r, text, sizeof text);
        n += (size_t)snprintf(cmd + n, len - n, " %s=%s", term_keys[k], text);
    }
    if (n < len)
        snprintf(cmd + n, len - n, " falloff=%.6g invert=%d painted=%d",
                 m->height.on ? m->height.edge : 0, m->invert, m->painted);
}

static void apply(editor_ui *e, cmd_context *ctx, const layer_info *l, const layer_mask *m) {
    char cmd[1024], now[1024];
    mask_command(l->name, m, cmd, sizeof cmd);
    mask_command(l->name, &l->mask, now, sizeof now);
    if (strcmp(cmd, now) != 0) editor_ui_run(e, ctx, cmd);
}

// The histogram around the camera, read again after an edit or once the camera has
// moved a quarter of the area away (a quick read of at most 256 x 256 samples).
static void refresh_histogram(layers_panel_state *s, cmd_context *ctx, const viewport *v,
                              int force) {
    history *h = world_history(ctx->world);
    size_t step = history_position(h) * 1000003u + history_count(h);
    const world_params *p = world_get_params(ctx->world);
    double sp = world_grid_sample_metres(p), x = v->cam.pos[0], z = v->cam.pos[2], ground = 0;
    int face = 0;
    if (p->kind == WORLD_PLANET) { // the face under the camera, its face-local metres
        double s_, t_, n = (double)world_grid_face_samples(p);
        world_grid_direction_face(v->cam.pos, &face, &s_, &t_);
        x = ((s_ + 1) * 0.5 * n - 0.5) * sp, z = ((t_ + 1) * 0.5 * n - 0.5) * sp;
    }
    double half = s->hist_valid ? (s->hist.x1 - s->hist.x0) * 0.5 : 0;
    int moved = s->hist_valid &&
                (fabs(x - s->hist_at[0]) > half * 0.5 || fabs(z - s->hist_at[1]) > half * 0.5);
    if (!force && s->hist_step == step && (s->hist_valid || s->hist_error[0]) && !moved) return;
    og_error err = {{0}};
    world_sample(ctx->world, face, x, z, &ground, &err);
    double above = v->cam.pos[1] - ground;
    if (p->kind == WORLD_PLANET)
        above = sqrt(v->cam.pos[0] * v->cam.pos[0] + v->cam.pos[1] * v->cam.pos[1] +
                     v->cam.pos[2] * v->cam.pos[2]) -
                p->radius - ground;
    // About what the view takes in from the camera's height, at least 256 samples.
    half = fmin(fmax(fabs(above) * 3, sp * 128), sp * 65536);
    s->hist_step = step;
    s->hist_at[0] = x, s->hist_at[1] = z;
    s->hist_valid =
        terrain_histogram_compute_flow(ctx->world, face, x, z, half, &s->hist, &s->flow, &err) == 0;
    s->flow_serial++;
    snprintf(s->hist_error, sizeof s->hist_error, "%.200s", s->hist_valid ? "" : err.msg);
}

// A number field (value_field.h); Enter gives *out (inf and -inf too), or says what is
// wrong under the fields.
static int number_field(layers_panel_state *s, ui_context *ui, const char *label, char *buf,
                        size_t len, double value, double *out, const char *tip) {
    char shown[32];
    snprintf(shown, sizeof shown, "%.6g", value);
    if (!value_field(ui, label, buf, len, shown, tip)) return 0;
    char *end;
    double d = strtod(buf, &end);
    while (*end == ' ')
        end++;
    if (end == buf || *end || d != d) {
        snprintf(s->field_error, sizeof s->field_error, "%s: '%s' is not a number", label, buf);
        return 0;
    }
    s->field_error[0] = 0;
    *out = d;
    return 1;
}

// v to two significant digits, as a person would type it.
static double two_digits(double v) {
    if (!(v != 0) || !isfinite(v)) return v;
    double q = pow(10, floor(log10(fabs(v))) - 1);
    return round(v / q) * q;
}

// What a term's histogram spans and holds, and the tooltip of its range.
typedef struct term_histogram {
    double min, max; // the range's ends (flow: log10 of m2)
    const float *bars;
    const char *tip;
} term_histogram;

static term_histogram histogram_of(const terrain_histogram *h, int k) {
    switch (k) {
    case TERM_HEIGHT:
        return (term_histogram){h->height_min, h->height_max, h->height,
                                "Drag an end: the heights the layer applies at, over how much of "
                                "the view lies at each height"};
    case TERM_SLOPE:
        return (term_histogram){0, 90, h->slope,
                                "Drag an end: the slopes the layer applies on, over how much of "
                                "the view has each slope"};
    case TERM_CURVATURE:
        return (term_histogram){h->curvature_min, h->curvature_max, h->curvature,
                                "Drag an end: the curvatures the layer applies at (convex right, "
                                "concave left), over how much of the view has each"};
    default:
        return (term_histogram){log10(h->flow_min), log10(h->flow_max), h->flow,
                                "Drag an end: the upstream areas the layer applies at (log scale: "
                                "channels right), over how much of the view drains each"};
    }
}

// A term's range dragged over its histogram (flow on a log10 scale); the command runs
// when the drag is released.
static void histogram_range(editor_ui *e, ui_context *ui, cmd_context *ctx, const layer_info *l,
                            int k, layer_mask_range *r) {
    layers_panel_state *s = &e->layers;
    term_histogram th = histogram_of(&s->hist, k);
    const int log_scale = k == TERM_FLOW;
    double rlo = r->lo, rhi = r->hi;
    if (log_scale) rlo = rlo > 0 ? log10(rlo) : -INFINITY, rhi = rhi > 0 ? log10(rhi) : -INFINITY;
    double min = th.min, max = th.max;
    if (k != TERM_SLOPE) { // the range shows even when set beyond what the view holds
        if (isfinite(rlo)) min = fmin(min, rlo);
        if (isfinite(rhi)) max = fmax(max, rhi);
        double pad = (max - min) * 0.05;
        min -= pad, max += pad;
    }
    double lo = isfinite(rlo) ? rlo : min, hi = isfinite(rhi) ? rhi : max;
    double edge = log_scale
                      ? (r->edge > 0 && rhi > -INFINITY ? log10(pow(10, hi) + r->edge) - hi : 0)
                      : r->edge;
    ui_row(ui, 1, NULL, ui_em(ui, 2.6f));
    int rc = ui_range(ui, "Range", &lo, &hi, edge, min, max, th.bars, TERRAIN_HISTOGRAM_BINS);
    ui_tooltip(ui, th.tip);
    if (!rc) return;
    double lo_seen = lo, hi_seen = hi;
    if (log_scale) {
        r->lo = two_digits(pow(10, lo)), r->hi = two_digits(pow(10, hi));
    } else { // rounded as a person would type them
        double q = k == TERM_SLOPE ? 0.5 : pow(10, floor(log10(fmax(max - min, 1e-3))) - 2);
        r->lo = round(lo / q) * q, r->hi = round(hi / q) * q;
    }
    if (!isfinite(rlo) && lo_seen == min) r->lo = rlo; // an open end left alone stays open
    if (!isfinite(rhi) && hi_seen == max) r->hi = rhi;
    s->draft_live = rc == UI_RANGE_DRAGGING;
    if (rc == UI_RANGE_DONE) apply(e, ctx, l, &s->draft);
}

// One term: its checkbox, its range over the histogram, its fields.
static void term_rows(editor_ui *e, ui_context *ui, cmd_context *ctx, const layer_info *l, int k) {
    layers_panel_state *s = &e->layers;
    layer_mask_range *r = term(&s->draft, k);
    ui_push_scope(ui, term_keys[k]);
    ui_row(ui, 1, NULL, 0);
    int on = r->on;
    if (ui_checkbox(ui, term_labels[k], &on)) {
        layer_mask m = s->draft;
        layer_mask_range *t = term(&m, k);
        t->on = on;
        if (on) { // a first range: the middle of what the view shows, or a usual one
            static const double lo[TERM_COUNT] = {0, 20, 5, 1e4},
                                hi[TERM_COUNT] = {0, 45, 1e9, 1e12};
            t->lo = lo[k], t->hi = hi[k], t->edge = k == TERM_SLOPE ? 5 : 0;
            if (k == TERM_HEIGHT) {
                double a = s->hist_valid ? s->hist.height_min : 0;
                double b = s->hist_valid ? s->hist.height_max : 1000;
                t->lo = round(a + (b - a) / 3), t->hi = round(a + (b - a) * 2 / 3);
            } else if (k == TERM_CURVATURE && s->hist_valid) { // the more convex ground
                t->lo = two_digits(s->hist.curvature_max / 2), t->hi = INFINITY;
            } else if (k == TERM_FLOW && s->hist_valid) { // the channels
                double a = log10(s->hist.flow_min), b = log10(s->hist.flow_max);
                t->lo = two_digits(pow(10, a + (b - a) * 0.6)), t->hi = INFINITY;
            }
        }
        apply(e, ctx, l, &m);
    }
    ui_tooltip(ui, k == TERM_FLOW ? "Where water gathers: the area draining through a sample"
                                  : "Limit the layer to this range of the composite below it");
    if (!r->on) {
        ui_pop_scope(ui);
        return;
    }
    if (s->hist_valid) histogram_range(e, ui, ctx, l, k, r);
    ui_row(ui, 3, NULL, 0);
    double lo = r->lo, hi = r->hi, edge = r->edge;
    int set = number_field(s, ui, "Low", s->fields[k][0], sizeof s->fields[k][0], r->lo, &lo,
                           "Where the range starts (-inf: no lower bound); Enter sets it");
    set |= number_field(s, ui, "High", s->fields[k][1], sizeof s->fields[k][1], r->hi, &hi,
                        "Where the range ends (inf: no upper bound); Enter sets it");
    set |= number_field(s, ui, k == TERM_HEIGHT ? "Falloff" : "Edge", s->fields[k][2],
                        sizeof s->fields[k][2], r->edge, &edge,
                        "The soft edge outside the range, in the term's units (0: hard)");
    if (set) {
        layer_mask m = s->draft;
        layer_mask_range *t = term(&m, k);
        t->lo = lo, t->hi = hi, t->edge = edge;
        apply(e, ctx, l, &m); // the command says what is wrong with a bad range
    }
    ui_pop_scope(ui);
}

// The overlay the terrain renderer draws: the draft's terms, flow over the field read
// with the histograms (drawn on flat worlds).
static void set_overlay(render_settings *rs, const layer_mask *m, const terrain_flow_field *f,
                        unsigned serial) {
    const layer_mask_range *r[4] = {&m->height, &m->slope, &m->curvature, &m->flow};
    float *out[4] = {rs->mask_height, rs->mask_slope, rs->mask_curvature, rs->mask_flow};
    rs->mask_terms = 0;
    rs->mask_flow_area = f->area;
    rs->mask_flow_w = f->w, rs->mask_flow_h = f->h;
    rs->mask_flow_x0 = f->x0, rs->mask_flow_z0 = f->z0, rs->mask_flow_spacing = f->spacing;
    rs->mask_flow_serial = serial;
    for (int k = 0; k < 4; k++) {
        if (!r[k]->on) continue;
        rs->mask_terms |= 1 << k;
        double lo = isfinite(r[k]->lo) ? r[k]->lo : -1e30,
               hi = isfinite(r[k]->hi) ? r[k]->hi : 1e30;
        double e = r[k]->edge;
        out[k][0] = (float)(lo - e), out[k][1] = (float)lo, out[k][2] = (float)hi;
        out[k][3] = (float)(hi + e);
    }
    rs->mask_invert = m->invert;
}

void mask_editor(editor_ui *e, ui_context *ui, cmd_context *ctx, viewport *v, const layer_info *l) {
    layers_panel_state *s = &e->layers;
    const ui_theme *th = ui_get_theme(ui);
    int flat = world_get_params(ctx->world)->kind != WORLD_PLANET;
    if (!s->draft_live) s->draft = l->mask; // an undo or a command shows at once
    ui_push_scope(ui, "Mask editor");
    ui_row(ui, 1, NULL, 0);
    ui_separator(ui);
    char line[400];
    snprintf(line, sizeof line, "Mask of %s: where it applies", l->name);
    ui_label_wrapped(ui, line, th->text); // a long name in a narrow dock: two rows, not "..."
    refresh_histogram(s, ctx, v, 0);
    if (s->hist_valid)
        snprintf(line, sizeof line,
                 "Histograms of %.0f x %.0f m around the view, samples %g m apart%s",
                 s->hist.x1 - s->hist.x0, s->hist.z1 - s->hist.z0, s->hist.spacing,
                 flat ? "" : " (on its cube face; the view does not draw the flow term)");
    else
        snprintf(line, sizeof line, "No histogram: %s", s->hist_error);
    ui_label_wrapped(ui, line, th->text_dim);
    for (int k = 0; k < TERM_COUNT; k++)
        term_rows(e, ui, ctx, l, k);
    if (s->field_error[0]) ui_label_wrapped(ui, s->field_error, th->text_error);
    float two[2] = {0, 0};
    ui_row(ui, 2, two, 0);
    int invert = s->draft.invert;
    if (ui_checkbox(ui, "Invert", &invert)) {
        layer_mask m = s->draft;
        m.invert = invert;
        apply(e, ctx, l, &m);
    }
    ui_tooltip(ui, "Apply the layer where the terms do not hold instead");
    int painted = s->draft.painted;
    if (ui_checkbox(ui, "Painted", &painted)) {
        layer_mask m = s->draft;
        m.painted = painted;
        apply(e, ctx, l, &m);
    }
    ui_tooltip(ui, "A painted coverage multiplies the terms: paint it with a height tool aimed "
                   "at the mask (tool raise target=mask; lower erases)");
    if (ui_button(ui, "Clear paint")) runf(e, ctx, "layer mask %s painted=clear", l->name);
    ui_tooltip(ui, "Empty the painted coverage (undo brings it back)");
    if (ui_button(ui, "Clear mask")) runf(e, ctx, "layer mask %s clear", l->name);
    ui_tooltip(ui, "Remove every term: the layer applies everywhere again (undo brings it back)");
    ui_row(ui, 1, NULL, 0);
    if (ui_button(ui, "Close mask editor")) s->mask_layer = 0;
    ui_pop_scope(ui);
    if (s->mask_layer)
        set_overlay(&v->settings, &s->draft, &s->flow, s->flow_serial);
    else
        v->settings.mask_terms = 0;
}
