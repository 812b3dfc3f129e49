#include "editor/tools/stroke.h"

#include "editor/tools/brush_dab.h"
#include "editor/tools/planet_dab.h"
#include "editor/tools/volume_brush.h"
#include "editor/edit/edit.h"
#include "editor/edit/edit_commit.h"
#include "editor/edit/edit_mips.h"
#include "editor/world/layer_grid.h"
#include "io/progress.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

// More dabs than this in one segment is a mistake (a typo'd coordinate), not a stroke.
#define STROKE_MAX_DABS_PER_SEGMENT 1000000

struct stroke {
    world *world;
    brush brush;
    layer_grid grid;
    edit *edit;
    int started;
    double last_x, last_z, last_p; // metres
    double first_x, first_z;
    double carry;      // distance walked since the last dab
    double hold_carry; // dabs owed to the brush held still, less those laid
    float target;      // flatten / set height
    long dabs;
    volume_stroke *volume; // the volume tools' stroke (3D points) instead of the above
};

// Height of the edited layer at (x, z) metres, bilinear.
static int layer_height(stroke *s, double x, double z, float *out, og_error *err) {
    double fx = x / s->grid.spacing, fz = z / s->grid.spacing;
    int64_t ix = (int64_t)floor(fx), iz = (int64_t)floor(fz);
    float q[4];
    if (layer_grid_read(s->world, &s->grid, (grid_rect){ix, iz, ix + 2, iz + 2}, q, err) != 0)
        return -1;
    double ax = fx - ix, az = fz - iz;
    *out = (float)((q[0] * (1 - ax) + q[1] * ax) * (1 - az) + (q[2] * (1 - ax) + q[3] * ax) * az);
    return 0;
}

// target=mask: the stroke paints the active layer's painted mask coverage (its own tile
// slot, io/tile.h); the layer's composite follows at the end of the stroke.
static int aim_at_mask(world *w, layer_grid *g, og_error *err) {
    const layer_table *t = &world_get_params(w)->layers;
    const layer_info *l = &t->layers[t->active];
    if (!l->mask.painted)
        return og_error_set(err,
                            "target=mask: layer '%s' has no painted mask (turn it on with "
                            "'layer mask %s painted=1')",
                            l->name, l->name);
    if (l->locked)
        return og_error_set(err,
                            "layer '%s' is locked against edits (unlock it with 'layer set %s "
                            "locked=0', or select another layer)",
                            l->name, l->name);
    if (!l->visible)
        return og_error_set(err,
                            "layer '%s' is hidden: edits to its mask would not show (show it "
                            "with 'layer set %s visible=1')",
                            l->name, l->name);
    g->layer = (tile_layer)tile_layer_in_slot(TILE_LAYER_COARSE, layer_coverage_slot(l->id));
    return 0;
}

stroke *stroke_begin(world *w, const brush *b, og_error *err) {
    stroke *s = calloc(1, sizeof *s);
    if (!s) {
        og_error_set(err, "out of memory");
        return NULL;
    }
    s->world = w;
    s->brush = *b;
    if (brush_tool_is_volume(b->tool)) {
        if (!(s->volume = volume_stroke_begin(w, b, err))) goto fail;
        return s;
    }
    tile_layer layer = b->tool == BRUSH_PAINT ? TILE_LAYER_MATERIAL : b->target;
    if (layer_grid_init(&s->grid, world_get_params(w), layer, b->face, err) != 0) goto fail;
    if (b->mask && aim_at_mask(w, &s->grid, err) != 0) goto fail;
    if (b->radius / s->grid.spacing > BRUSH_MAX_RADIUS_SAMPLES) {
        og_error_set(err, "radius: %g m is %g samples of the %s layer; the limit is %g samples",
                     b->radius, b->radius / s->grid.spacing, tile_layer_name(layer),
                     BRUSH_MAX_RADIUS_SAMPLES);
        goto fail;
    }
    if (b->tool == BRUSH_SET && !b->has_height) {
        og_error_set(err, "set: give the height first (tool set height=METRES)");
        goto fail;
    }
    if (b->invert && b->tool != BRUSH_RAISE && b->tool != BRUSH_SMOOTH && b->tool != BRUSH_NOISE &&
        b->tool != BRUSH_PAINT) {
        og_error_set(err,
                     "invert: has no meaning for %s (it works with raise, smooth, noise and paint)",
                     brush_tool_name(b->tool));
        goto fail;
    }
    char label[128];
    snprintf(label, sizeof label, "%s stroke", brush_tool_name(b->tool));
    if (!(s->edit = edit_begin(w, label, err))) goto fail;
    // Raise and noise add to the active layer (its opacity scales them); the other tools'
    // results are what the layer shows (editor/edit/edit.h).
    if (b->tool == BRUSH_RAISE || b->tool == BRUSH_NOISE)
        edit_set_layer_mode(s->edit, EDIT_LAYER_DELTA);
    s->target = (float)b->height;
    return s;
fail:
    free(s);
    return NULL;
}

static int dab_at(stroke *s, double x, double z, double pressure, og_error *err) {
    brush_dab d = {
        .brush = &s->brush,
        .cx = x / s->grid.spacing,
        .cz = z / s->grid.spacing,
        .radius = s->brush.radius / s->grid.spacing,
        .strength = (float)(s->brush.strength * pressure),
        .spacing = s->grid.spacing,
        .target = s->target,
        // Each dab's droplets differ, reproducibly.
        .seed = s->brush.hydraulic.seed + 0x9E3779B97F4A7C15ULL * (uint64_t)(s->dabs + 1),
    };
    s->dabs++;
    const world_params *p = world_get_params(s->world);
    if (p->kind == WORLD_PLANET) // on the sphere, over the face's edges
        return planet_dab_apply(s->edit, p, s->grid.layer, s->grid.face, &d, err);
    return brush_dab_apply(s->edit, &s->grid, &d, err);
}

static int check_point(stroke *s, double x, double z, double pressure, og_error *err) {
    if (world_get_params(s->world)->kind == WORLD_PLANET) { // strokes may cross face edges
        if (planet_dab_check_position(&s->grid, x, z, err) != 0) return -1;
    } else if (layer_grid_check_position(&s->grid, x, z, err) != 0) {
        return -1;
    }
    if (!(pressure >= 0.0 && pressure <= 1.0))
        return og_error_set(err, "pressure: expected a number in [0, 1], got '%g'", pressure);
    return 0;
}

// Brings the coarser levels up to date with the dabs laid so far, so the viewport (which
// draws them away from the camera) shows the stroke while it goes on.
static int show_live(stroke *s, og_error *err) {
    const dirty_rect *rects;
    if (edit_dirty_rects(s->edit, &rects) == 0) return 0;
    return edit_mips_update(s->edit, err); // only the areas changed since the last call
}

static int lay_to(stroke *s, double x, double z, double pressure, og_error *err);

int stroke_to(stroke *s, double x, double z, double pressure, og_error *err) {
    if (s->volume)
        return og_error_set(err, "%s is a volume tool: it takes X Y Z points",
                            brush_tool_name(s->brush.tool));
    if (lay_to(s, x, z, pressure, err) != 0) return -1;
    return show_live(s, err);
}

int stroke_hold(stroke *s, double seconds, og_error *err) {
    if (!(seconds >= 0.0 && seconds <= 60.0))
        return og_error_set(err, "stroke_hold: expected seconds in [0, 60], got '%g'", seconds);
    if (s->volume || !s->started || !s->brush.hold || s->brush.tool == BRUSH_RAMP) return 0;
    s->hold_carry += seconds * 2.0 / s->brush.spacing;
    for (; s->hold_carry >= 1.0; s->hold_carry -= 1.0)
        if (dab_at(s, s->last_x, s->last_z, s->last_p, err) != 0) return -1;
    return show_live(s, err);
}

static int lay_to(stroke *s, double x, double z, double pressure, og_error *err) {
    if (check_point(s, x, z, pressure, err) != 0) return -1;
    if (!s->started) {
        s->started = 1;
        s->first_x = s->last_x = x;
        s->first_z = s->last_z = z;
        s->last_p = pressure;
        if (s->brush.tool == BRUSH_FLATTEN && !s->brush.has_height &&
            layer_height(s, x, z, &s->target, err) != 0)
            return -1;
        if (s->brush.tool == BRUSH_RAMP) return 0;
        return dab_at(s, x, z, pressure, err);
    }
    double dx = x - s->last_x, dz = z - s->last_z, len = sqrt(dx * dx + dz * dz);
    double step = fmax(s->brush.spacing * s->brush.radius, 0.25 * s->grid.spacing);
    if (s->brush.tool != BRUSH_RAMP) {
        if ((len + s->carry) / step > STROKE_MAX_DABS_PER_SEGMENT)
            return og_error_set(err, "stroke: a segment of %g m would need more than %d dabs", len,
                                STROKE_MAX_DABS_PER_SEGMENT);
        // Dabs every `step` along the path, continuing the spacing across segments.
        double at = step - s->carry;
        og_progress *progress = og_progress_current();
        int64_t dabs = at <= len ? (int64_t)((len - at) / step) + 1 : 0, dab = 0;
        for (; at <= len; at += step, dab++) {
            double a = at / len;
            if (og_progress_report(progress, dab, dabs) != 0) return og_error_set(err, "cancelled");
            og_progress_part outer = og_progress_enter(progress, dab, dabs);
            int rc = dab_at(s, s->last_x + a * dx, s->last_z + a * dz,
                            s->last_p + a * (pressure - s->last_p), err);
            og_progress_leave(progress, outer);
            if (rc != 0) return -1;
        }
        s->carry = len - (at - step);
    }
    s->last_x = x;
    s->last_z = z;
    s->last_p = pressure;
    return 0;
}

static int apply_ramp(stroke *s, og_error *err) {
    const world_params *p = world_get_params(s->world);
    double k = 1.0 / s->grid.spacing;
    brush_dab d = {.brush = &s->brush,
                   .radius = s->brush.radius * k,
                   .strength = (float)s->brush.strength,
                   .spacing = s->grid.spacing,
                   .ax = s->first_x * k,
                   .az = s->first_z * k,
                   .bx = s->last_x * k,
                   .bz = s->last_z * k};
    s->dabs++;
    if (p->kind == WORLD_PLANET) { // the great-circle segment, over face edges
        planet_dab_prepare(&d, p, s->grid.layer, s->grid.face);
        if (brush_dab_read_sphere(s->world, &s->grid, &d, d.ax, d.az, &d.ha, err) != 0 ||
            brush_dab_read_sphere(s->world, &s->grid, &d, d.bx, d.bz, &d.hb, err) != 0)
            return -1;
        return planet_dab_apply(s->edit, p, s->grid.layer, s->grid.face, &d, err);
    }
    if (layer_height(s, s->first_x, s->first_z, &d.ha, err) != 0 ||
        layer_height(s, s->last_x, s->last_z, &d.hb, err) != 0)
        return -1;
    return brush_dab_apply(s->edit, &s->grid, &d, err);
}

int stroke_to_3d(stroke *s, const double p[3], double pressure, og_error *err) {
    if (!s->volume)
        return og_error_set(err, "%s takes X Z points (the volume tools take X Y Z)",
                            brush_tool_name(s->brush.tool));
    return volume_stroke_to(s->volume, p, pressure, err);
}

int stroke_is_volume(const stroke *s) {
    return s->volume != NULL;
}

int stroke_end(stroke *s, og_error *err) {
    if (s->volume) {
        int rc = volume_stroke_end(s->volume, err);
        free(s);
        return rc;
    }
    int rc = 0;
    if (s->started && s->brush.tool == BRUSH_RAMP) rc = apply_ramp(s, err);
    if (rc != 0) {
        edit_abort(s->edit);
    } else {
        rc = edit_commit(s->edit, err);
    }
    free(s);
    return rc;
}

void stroke_cancel(stroke *s) {
    if (!s) return;
    if (s->volume)
        volume_stroke_cancel(s->volume);
    else
        edit_abort(s->edit);
    free(s);
}

long stroke_dab_count(const stroke *s) {
    if (s->volume) return volume_stroke_dabs(s->volume);
    // A ramp lays its one dab at the end, from the first point to the last: a drag
    // (the window's stroke_begin, stroke_to..., stroke_end) counts it before then.
    int ramp_due = s->started && s->brush.tool == BRUSH_RAMP && s->dabs == 0 &&
                   (s->first_x != s->last_x || s->first_z != s->last_z);
    return s->dabs + ramp_due;
}
