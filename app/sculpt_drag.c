#include "app/sculpt_drag.h"

#include "editor/params/world_grid.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

static double now_seconds(const sculpt_drag *d) {
    if (d->clock) return d->clock();
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

int sculpt_face_metres(const world_params *p, int face, const double hit[3], double *x, double *z) {
    double s, t, n = (double)world_grid_face_samples(p);
    if (!world_grid_face_coords_on(face, hit, &s, &t)) return -1;
    *x = ((s + 1.0) * 0.5 * n - 0.5) * world_grid_sample_metres(p);
    *z = ((t + 1.0) * 0.5 * n - 0.5) * world_grid_sample_metres(p);
    return 0;
}

int sculpt_volume_point(sculpt_drag *d, const brush *b, sculpt_view view, double x, double y,
                        const double hit[3], double out[3]) {
    const camera *cam = &view.v->cam;
    ui_rect r = view.rect;
    double dir[3];
    camera_ray(cam, (double)r.w / r.h, (x - r.x) / r.w, (y - r.y) / r.h, dir);
    int dragging = d && d->active;
    if (dragging && b->lock_plane && d->points > 0) {
        double dy = d->plane_y - cam->pos[1];
        if (fabs(dir[1]) < 1e-9 || dy / dir[1] <= 0) return -1; // the ray never meets it
        for (int a = 0; a < 3; a++)
            out[a] = cam->pos[a] + dir[a] * (dy / dir[1]);
        return 0;
    }
    for (int a = 0; a < 3; a++)
        out[a] = hit[a] + dir[a] * b->depth;
    if (dragging && d->points == 0) d->plane_y = out[1];
    return 0;
}

// The terrain under (x, y). w: the world, when it may be read (no job runs); without
// it planets have no answer.
static int pick(const sculpt_drag *d, world *w, sculpt_view view, double x, double y,
                double hit[3]) {
    ui_rect r = view.rect;
    if (!view.v->renderer || r.w <= 0 || r.h <= 0) return -1;
    double sx = (x - r.x) / r.w, sy = (y - r.y) / r.h, aspect = (double)r.w / r.h;
    if (d->params.kind == WORLD_PLANET)
        return w ? viewport_pick_loaded(view.v, w, sx, sy, aspect, hit) : -1;
    return viewport_pick_shown(view.v, &d->params, sx, sy, aspect, hit);
}

static void add(work_queue *q, const char *text, int flags) {
    work_queue_add(q, text, "sculpt", WORK_STROKE | flags);
}

// The point under (x, y), queued. w as for pick.
static void point_at(sculpt_drag *d, work_queue *q, world *w, sculpt_view view, double x,
                     double y) {
    double hit[3];
    if (pick(d, w, view, x, y, hit) != 0) return; // off the terrain
    cmd_stroke_point pt = {hit[0], 0, hit[2], 0};
    if (d->face >= 0) { // a planet: the stroke's face, in its metres
        if (sculpt_face_metres(&d->params, d->face, hit, &pt.x, &pt.z) != 0) return;
    } else if (d->volume) {
        double p[3];
        if (sculpt_volume_point(d, &d->brush, view, x, y, hit, p) != 0) return;
        pt = (cmd_stroke_point){p[0], p[1], p[2], 1};
    }
    work_queue_add_point(q, &pt);
    // Moved a dab's spacing: the path lays the dabs, the hold starts again from here.
    double dx = pt.x - d->hold_anchor[0], dz = pt.z - d->hold_anchor[1];
    if (d->points == 0 || sqrt(dx * dx + dz * dz) >= d->brush.spacing * d->brush.radius) {
        d->hold_anchor[0] = pt.x, d->hold_anchor[1] = pt.z;
        d->hold_from = now_seconds(d);
        if (d->points == 0) d->seen_held_at = d->hold_from;
    }
    d->points++;
}

// Queues the time held since the last hold, up to the last time the window saw the
// button still down; at least a dab's worth unless final (the release: what was seen
// held up to it counts, however slow the frames were). Never the time to the release's
// handling: a release that waited behind a slow frame or a job would count that wait
// (a 0.1 s click laid as much as a 1.2 s hold on a loaded machine).
static int hold(sculpt_drag *d, work_queue *q, int final) {
    const brush *b = &d->brush;
    if (!d->active || !b->hold || d->volume || b->tool == BRUSH_RAMP || d->points == 0 ||
        d->held_count || (!final && work_queue_busy(q)))
        return 0;
    double held = d->seen_held_at - d->hold_from;
    if (held < (final ? 0.001 : 0.5 * b->spacing)) return 0; // 2 / spacing dabs a second
    char cmd[64];
    snprintf(cmd, sizeof cmd, "stroke_hold %.4f", fmin(held, 60.0));
    d->hold_from = d->seen_held_at;
    return work_queue_add(q, cmd, "sculpt", WORK_STROKE) == 0;
}

void sculpt_drag_input_taken(sculpt_drag *d) {
    if (d->active) d->seen_held_at = now_seconds(d);
}

int sculpt_drag_hold(sculpt_drag *d, work_queue *q) {
    return hold(d, q, 0);
}

void sculpt_drag_flush(sculpt_drag *d, work_queue *q, sculpt_view view) {
    if (work_queue_busy(q)) return;
    for (int i = 0; i < d->held_count; i++)
        point_at(d, q, d->world, view, d->held[i][0], d->held[i][1]);
    d->held_count = 0;
    if (d->end_held) add(q, "stroke_end", 0);
    d->end_held = 0;
}

void sculpt_drag_to(sculpt_drag *d, work_queue *q, sculpt_view view, double x, double y) {
    if (!d->active) return;
    if (d->params.kind == WORLD_PLANET && work_queue_busy(q)) { // the world is the job's
        int i = d->held_count < SCULPT_HELD_MAX ? d->held_count++ : SCULPT_HELD_MAX - 1;
        d->held[i][0] = x, d->held[i][1] = y;
        return;
    }
    sculpt_drag_flush(d, q, view); // what was held goes first
    point_at(d, q, work_queue_busy(q) ? NULL : d->world, view, x, y);
}

void sculpt_drag_begin(sculpt_drag *d, work_queue *q, cmd_context *ctx, sculpt_view view, double x,
                       double y, int smooth, int invert) {
    d->active = 1;
    d->points = 0;
    d->held_count = d->end_held = 0;
    d->world = ctx->world;
    d->params = *world_get_params(ctx->world);
    d->brush = ctx->brush;
    const brush *b = &d->brush;
    d->volume = brush_tool_is_volume(b->tool);
    d->face = -1;
    char cmd[96] = "stroke_begin";
    double hit[3];
    if (d->params.kind == WORLD_PLANET && !d->volume && pick(d, ctx->world, view, x, y, hit) == 0) {
        // The stroke's face is where it starts; it may run over the edges from there.
        double s, t;
        world_grid_direction_face(hit, &d->face, &s, &t);
        snprintf(cmd, sizeof cmd, "stroke_begin face=%d%s", d->face,
                 smooth   ? " tool=smooth"
                 : invert ? (b->invert ? " invert=0" : " invert=1")
                          : "");
    } else if (d->volume) {
        if (smooth)
            snprintf(cmd, sizeof cmd, "stroke_begin tool=vsmooth");
        else if (invert && (b->tool == BRUSH_FILL || b->tool == BRUSH_CARVE))
            snprintf(cmd, sizeof cmd, "stroke_begin tool=%s",
                     b->tool == BRUSH_FILL ? "carve" : "fill");
    } else if (smooth) {
        snprintf(cmd, sizeof cmd, "stroke_begin tool=smooth");
    } else if (invert) {
        snprintf(cmd, sizeof cmd, "stroke_begin invert=%d", !b->invert);
    }
    add(q, cmd, WORK_STROKE_BEGIN);
    point_at(d, q, ctx->world, view, x, y);
}

int sculpt_drag_end(sculpt_drag *d, work_queue *q) {
    if (!d->active) return 0;
    hold(d, q, 1);
    d->active = 0;
    if (d->held_count)
        d->end_held = 1; // after the held positions, once the job ends
    else
        add(q, "stroke_end", 0);
    return d->points + d->held_count;
}

void sculpt_drag_cancelled(sculpt_drag *d) {
    d->active = 0;
    d->held_count = d->end_held = 0;
}
