// The window's frame: the terrain image (dynamic resolution, smoothing when still),
// the UI built over it and composed, the progress of long work, the title.
#include "app/brush_size.h"
#include "app/window_internal.h"

#include "editor/params/world_grid.h"

#include <time.h>

void update_title(window_state *st) {
    char title[sizeof st->frame.title], name[256];
    const char *path = world_path(st->ctx->world);
    const char *slash = strrchr(path, '/');
    snprintf(name, sizeof name, "%s%s", path[0] ? (slash ? slash + 1 : path) : "unsaved world",
             world_read_only(st->ctx->world)[0] ? " (read-only)" : "");
    const camera *c = &st->v->cam;
    render_stats rs = {0};
    if (st->v->renderer) terrain_renderer_stats(st->v->renderer, &rs);
    int used = st->v->settings.levels - rs.finest_level;
    if (st->frame.render_failed)
        snprintf(title, sizeof title, "Orogen - %s%s - the viewport failed (see the console)", name,
                 world_is_modified(st->ctx->world) ? " *" : "");
    else
        snprintf(title, sizeof title,
                 "Orogen - %s%s - cam (%.1f, %.1f, %.1f) yaw %.1f pitch %.1f - %s %.3g m/s - "
                 "levels %d/%d - tool %s r%g - pending %d",
                 name, world_is_modified(st->ctx->world) ? " *" : "", c->pos[0], c->pos[1],
                 c->pos[2], c->yaw, c->pitch,
                 st->cc.walk            ? "walk"
                 : camera_mode(st) == 1 ? "orbit"
                                        : "fly",
                 camera_controls_speed(&st->cc), rs.levels_ready, used,
                 editor_ui_stamp_active(panels_editor(st)) ? "stamp" : tool_name(&st->ctx->brush),
                 st->ctx->brush.radius, st->frame.pending);
    if (strcmp(title, st->frame.title) != 0) {
        snprintf(st->frame.title, sizeof st->frame.title, "%s", title);
        glfwSetWindowTitle(st->win, title);
    }
}

// The brush cursor's colour for a tool: warm raises, cool lowers, green smooths, yellow
// levels, violet adds noise, cyan erodes, pink paints; the volume tools as their 2D
// counterparts, carving cool.
static void cursor_colour(brush_tool tool, int invert, float rgb[3]) {
    static const float colours[BRUSH_TOOL_COUNT][3] = {
        [BRUSH_RAISE] = {1.0f, 0.55f, 0.1f},     [BRUSH_SMOOTH] = {0.3f, 0.9f, 0.4f},
        [BRUSH_FLATTEN] = {1.0f, 0.85f, 0.2f},   [BRUSH_SET] = {1.0f, 0.85f, 0.2f},
        [BRUSH_RAMP] = {1.0f, 0.85f, 0.2f},      [BRUSH_NOISE] = {0.75f, 0.4f, 1.0f},
        [BRUSH_TERRACE] = {1.0f, 0.85f, 0.2f},   [BRUSH_THERMAL] = {0.2f, 0.85f, 0.9f},
        [BRUSH_HYDRAULIC] = {0.2f, 0.85f, 0.9f}, [BRUSH_PAINT] = {1.0f, 0.35f, 0.75f},
        [BRUSH_FILL] = {1.0f, 0.55f, 0.1f},      [BRUSH_CARVE] = {0.25f, 0.5f, 1.0f},
        [BRUSH_VSMOOTH] = {0.3f, 0.9f, 0.4f},    [BRUSH_VFLATTEN] = {1.0f, 0.85f, 0.2f},
    };
    static const float lowering[3] = {0.25f, 0.5f, 1.0f};
    memcpy(rgb, invert && (tool == BRUSH_RAISE || tool == BRUSH_NOISE) ? lowering : colours[tool],
           3 * sizeof(float));
}

// The pointer is over the viewport's terrain, not a panel, menu or dialog over it (nor
// over what they hide): the brush cursor and the status bar follow only what is seen.
static int pointer_on_terrain(const window_state *st) {
    drag_kind drag = viewport_drag_kind(st);
    double x, y;
    pointer_pos(st, &x, &y);
    return (drag != DRAG_NONE || in_view(st, x, y)) &&
           (drag == DRAG_SCULPT || drag == DRAG_RESIZE || !pointer_over_ui(st));
}

// Until the user gives a radius, the brush follows the distance to the ground under the
// cursor (a fixed size in the picture, about a twelfth of the view's height at the
// default field of view): shown at any distance, from the first view on. Set through
// `tool NAME auto_radius=R`, so a recording replays the same strokes.
static void follow_ground(window_state *st, const double hit[3]) {
    const cmd_context *ctx = st->ctx;
    if (ctx->radius_chosen || viewport_drag_kind(st) != DRAG_NONE || !work_queue_idle(&st->work))
        return;
    const double *c = st->v->cam.pos;
    double d = sqrt((hit[0] - c[0]) * (hit[0] - c[0]) + (hit[1] - c[1]) * (hit[1] - c[1]) +
                    (hit[2] - c[2]) * (hit[2] - c[2]));
    double want =
        brush_radius_auto(0.08 * d, world_grid_sample_metres(world_get_params(ctx->world)));
    if (fabs(want / ctx->brush.radius - 1.0) < 0.25) return; // near enough: no command
    char cmd[96];
    snprintf(cmd, sizeof cmd, "tool %s auto_radius=%g", tool_name(&ctx->brush), want);
    work_queue_add(&st->work, cmd, "radius", 0);
    st->ui_dirty = 1;
}

static void update_cursor(window_state *st) {
    brush_cursor *bc = &st->v->cursor;
    double hit[3], resize_radius, resize_strength, x, y;
    pointer_pos(st, &x, &y);
    int resizing = viewport_drag_resizing(st, hit, &resize_radius, &resize_strength);
    bc->visible = pointer_in_window(st) && !viewport_looking(st) &&
                  viewport_drag_kind(st) != DRAG_ORBIT && pointer_on_terrain(st) &&
                  (resizing || pick_at(st, x, y, hit) == 0);
    if (!bc->visible) return;
    bc->x = hit[0], bc->y = hit[1], bc->z = hit[2]; // y: planets drape it in 3D
    if (viewport_drag_kind(st) != DRAG_RESIZE && !editor_ui_stamp_active(panels_editor(st)))
        follow_ground(st, hit);
    if (editor_ui_stamp_active(panels_editor(st))) { // the stamp's footprint: its half size, no
        bc->radius = editor_ui_stamp_half_size(      // falloff, in face-local metres on a planet
            panels_editor(st), world_grid_sample_metres(world_get_params(st->ctx->world)));
        for (int i = 0; i < BRUSH_FALLOFF_SAMPLES; i++)
            bc->falloff[i] = 1.0f;
        bc->color[0] = bc->color[1] = bc->color[2] = 0.9f;
        bc->opacity = 0.25f;
        return;
    }
    const brush *b = &st->ctx->brush;
    bc->radius = resizing ? resize_radius : b->radius;
    for (int i = 0; i < BRUSH_FALLOFF_SAMPLES; i++)
        bc->falloff[i] = brush_falloff_weight(b, (float)i / (BRUSH_FALLOFF_SAMPLES - 1));
    // Coloured by what a stroke would do now (Ctrl inverts, Shift smooths), as strong
    // as the strength.
    int ctrl =
        glfwGetKey(st->win, GLFW_KEY_LEFT_CONTROL) || glfwGetKey(st->win, GLFW_KEY_RIGHT_CONTROL);
    int shift =
        glfwGetKey(st->win, GLFW_KEY_LEFT_SHIFT) || glfwGetKey(st->win, GLFW_KEY_RIGHT_SHIFT);
    brush_tool tool = shift ? BRUSH_SMOOTH : b->tool;
    int invert = !shift && (b->invert != ctrl);
    double strength = resizing ? resize_strength : b->strength;
    bc->sphere = brush_tool_is_volume(b->tool) && !resizing;
    if (bc->sphere) { // where the next point would go, as big as the ball it would lay
        double p[3];
        bc->visible =
            sculpt_volume_point(viewport_drag_stroke(st), b, sculpt_view_of(st), x, y, hit, p) == 0;
        bc->x = p[0], bc->y = p[1], bc->z = p[2];
        if (b->tool == BRUSH_FILL || b->tool == BRUSH_CARVE) {
            bc->radius *= strength;
            if (ctrl) tool = b->tool == BRUSH_FILL ? BRUSH_CARVE : BRUSH_FILL;
        }
        if (shift) tool = BRUSH_VSMOOTH;
        invert = 0;
    }
    cursor_colour(tool, invert, bc->color);
    bc->opacity = (float)(0.12 + 0.5 * strength);
    char why[160];
    if (editor_ui_tool_refused(st->ctx, why, sizeof why)) { // hidden or locked: a grey ring
        bc->color[0] = bc->color[1] = bc->color[2] = 0.5f;
        bc->opacity = 0.05f;
    }
}

// Brings the clipmaps up to date without waiting for tiles. Returns 1 when the picture
// changed (texels arrived), 0 when not, -1 when this world cannot be drawn.
int update_view(window_state *st) {
    og_error err = {{0}};
    viewport *v = st->v;
    if (st->frame.render_failed) return -1;
    int rc = terrain_renderer_update(v->renderer, st->ctx->world, &v->cam, &v->settings, &err);
    if (rc < 0) {
        report("viewport", &err);
        st->frame.render_failed = 1;
        st->frame.pending = 0;
        st->frame.settled = 2; // nothing to wait for
        return -1;
    }
    render_stats rs;
    terrain_renderer_stats(v->renderer, &rs);
    if (rc == 1) {
        st->frame.settled++;
        st->frame.pending = 0;
    } else {
        int missing = v->settings.levels - rs.finest_level - rs.levels_ready;
        st->frame.settled = 0;
        st->frame.pending = missing > 0 ? missing : 1; // else the material or detail layers
    }
    return rs.texels_uploaded > 0;
}

void frame_status(window_state *st, editor_frame_info *info) {
    info->frame_ms = st->frame.terrain_ms;
    info->resolution_scale = st->frame.drawn_scale;
    info->pending = st->frame.pending;
    info->dynamic_resolution = st->frame.dynamic_res;
    double hit[3], x, y;
    pointer_pos(st, &x, &y);
    if (pointer_in_window(st) && pointer_on_terrain(st) && pick_at(st, x, y, hit) == 0) {
        info->cursor_valid = 1;
        memcpy(info->cursor, hit, sizeof hit);
    }
}

int frame_dynamic_resolution(const window_state *st) {
    return st->frame.dynamic_res;
}

void frame_set_dynamic_resolution(window_state *st, int on) {
    st->frame.dynamic_res = on;
}

static double now_ms(void) {
    return glfwGetTime() * 1e3;
}

// The still, full-size terrain image with its edges smoothed into terrain_smooth: one
// pass over the image, never a new render (and never while moving, where it would
// cost every frame). Returns 1 when compose shows the smoothed image.
int smooth_terrain(window_state *st) {
    og_error err = {{0}};
    const gl_target *t = &st->frame.terrain;
    if (st->frame.terrain_smooth.width != t->width ||
        st->frame.terrain_smooth.height != t->height) {
        gl_target_destroy(&st->frame.terrain_smooth);
        if (gl_target_create(&st->frame.terrain_smooth, t->width, t->height, &err) != 0)
            goto failed;
    }
    if (viewport_antialias(st->v, t, &st->frame.terrain_smooth, &err) != 0) goto failed;
    st->frame.smooth_shown = 1;
    st->frame.smooth_owed = 0;
    return 1;
failed:
    report("viewport", &err);
    st->frame.smooth_failed = 1;
    st->frame.smooth_owed = 0;
    return 0;
}

// Renders the terrain into its own image when something it shows changed: the camera,
// the world, the view settings, the brush cursor, the viewport's size, or newly
// arrived tiles. While the camera moves or a stroke is drawn the image is rendered
// smaller, sized to keep the frame near target_ms. Returns 1 when it rendered.
int render_terrain(window_state *st, int vw, int vh, int arrived) {
    viewport *v = st->v;
    if (vw <= 0 || vh <= 0) return 0;
    v->aspect = (double)vw / vh; // a new planet's first view fits its disc in this view
    update_cursor(st);
    // The cursor is drawn with the terrain: while it moves the frame is made at the
    // moving scale too, so it follows the pointer at the frame-time goal.
    int moving = memcmp(&v->cam, &st->frame.drawn_cam, sizeof v->cam) != 0 ||
                 viewport_drag_kind(st) == DRAG_SCULPT || v->settings.sun_rotation != 0 ||
                 memcmp(&v->cursor, &st->frame.drawn_cursor, sizeof v->cursor) != 0 ||
                 viewport_drag_kind(st) == DRAG_ORBIT || keys_held(st);
    float scale = moving && st->frame.dynamic_res ? st->frame.res_scale : 1.0f;
    int w = (int)fmaxf(1.0f, roundf(vw * scale)), h = (int)fmaxf(1.0f, roundf(vh * scale));
    int changed = !st->frame.terrain_valid || arrived || st->frame.world_changed ||
                  memcmp(&v->cam, &st->frame.drawn_cam, sizeof v->cam) != 0 ||
                  memcmp(&v->settings, &st->frame.drawn_settings, sizeof v->settings) != 0 ||
                  memcmp(&v->cursor, &st->frame.drawn_cursor, sizeof v->cursor) != 0 ||
                  w != st->frame.drawn_w || h != st->frame.drawn_h;
    int wants_smooth = render_settings_smooth_edges(&v->settings) && !st->frame.render_failed &&
                       !st->frame.smooth_failed && scale == 1.0f;
    if (!changed) { // the view came to rest on a full-size image: smooth it now
        if (wants_smooth && !moving && !st->frame.smooth_shown && st->frame.terrain_valid)
            return smooth_terrain(st);
        return 0;
    }
    og_error err = {{0}};
    if (st->frame.terrain.width != w || st->frame.terrain.height != h) {
        gl_target_destroy(&st->frame.terrain);
        if (gl_target_create(&st->frame.terrain, w, h, &err) != 0) {
            report("viewport", &err);
            return 0;
        }
    }
    double t0 = now_ms();
    glBindFramebuffer(GL_FRAMEBUFFER, st->frame.terrain.fbo);
    if (st->frame.render_failed) {
        glViewport(0, 0, w, h);
        glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    } else if (terrain_renderer_draw(v->renderer, st->ctx->world, &v->cam, &v->settings, &v->cursor,
                                     w, h, &err) != 0) {
        report("viewport", &err);
    }
    st->frame.smooth_shown = 0;
    st->frame.smooth_owed = wants_smooth;
    if (wants_smooth && !moving) smooth_terrain(st);
    glFinish(); // the frame's real cost, for the resolution controller
    st->frame.terrain_ms = now_ms() - t0;
    if (moving)
        st->frame.res_scale =
            dynamic_resolution_next(st->frame.res_scale, st->frame.terrain_ms, st->frame.target_ms);
    st->frame.drawn_cam = v->cam;
    st->frame.drawn_settings = v->settings;
    st->frame.drawn_cursor = v->cursor;
    st->frame.drawn_scale = scale;
    st->frame.drawn_w = w, st->frame.drawn_h = h;
    st->frame.world_changed = 0;
    st->frame.terrain_valid = 1;
    return 1;
}

// The window's picture: the terrain image in the viewport's rectangle, the UI over it.
void compose(window_state *st, const ui_draw_list *dl, int fw, int fh) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fw, fh);
    ui_color bg = panels_background(st);
    glClearColor((bg & 255) / 255.0f, ((bg >> 8) & 255) / 255.0f, ((bg >> 16) & 255) / 255.0f, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    float k = ui_px(st, 1.0);
    ui_rect vr = view_rect(st);
    int vx = (int)roundf(vr.x * k), vy = (int)roundf(vr.y * k);
    int vw = (int)roundf(vr.w * k), vh = (int)roundf(vr.h * k);
    const gl_target *image =
        st->frame.smooth_shown ? &st->frame.terrain_smooth : &st->frame.terrain;
    if (st->frame.terrain_valid && vw > 0 && vh > 0)
        glBlitNamedFramebuffer(image->fbo, 0, 0, 0, image->width, image->height, vx, fh - (vy + vh),
                               vx + vw, fh - vy, GL_COLOR_BUFFER_BIT, GL_LINEAR);
    panels_draw(st, dl, fw, fh);
}

// While long work runs: the last frame with a progress bar and a Cancel button over
// its status bar, drawn at most ten times a second (none for work under 150 ms).
void draw_busy(window_state *st, const ui_draw_list *dl, int fw, int fh) {
    cmd_job *job = st->work.job;
    double elapsed = cmd_job_elapsed_ms(job), t = now_ms();
    if (elapsed < 150 || (t - st->frame.busy_drawn_ms < 100 && !st->ui_dirty)) return;
    st->frame.busy_drawn_ms = t;
    st->ui_dirty = 0;
    const char *what = (st->work.running.flags & WORK_STROKE) ? "the stroke's dabs along the drag"
                                                              : cmd_job_text(job);
    const ui_draw_list *busy = build_busy_ui(st, what, cmd_job_progress(job), elapsed, fw, fh);
    compose(st, dl, fw, fh);
    panels_draw(st, busy, fw, fh);
    glfwSwapBuffers(st->win);
    char title[sizeof st->frame.title];
    snprintf(title, sizeof title, "Orogen - working %.0f%% - Esc cancels",
             cmd_job_progress(job) * 100);
    if (strcmp(title, st->frame.title) != 0) {
        snprintf(st->frame.title, sizeof st->frame.title, "%s", title);
        glfwSetWindowTitle(st->win, title);
    }
}

void frame_open(window_state *st, double target_ms) {
    st->frame.res_scale = 1.0f;
    st->frame.drawn_scale = 1.0f;
    st->frame.target_ms = target_ms;
}

void frame_close(window_state *st) {
    gl_target_destroy(&st->frame.terrain);
    gl_target_destroy(&st->frame.terrain_smooth);
}

void frame_world_changed(window_state *st) {
    st->frame.world_changed = 1;
}

void frame_retry_render(window_state *st) {
    st->frame.render_failed = 0;
}

int frame_unsettled(const window_state *st) {
    return st->frame.pending || st->frame.settled < 2;
}

int frame_owes_still(const window_state *st) {
    return st->frame.drawn_scale < 1.0f || st->frame.smooth_owed;
}

double frame_target_ms(const window_state *st) {
    return st->frame.target_ms;
}

const ui_draw_list *render_still(window_state *st, int fw, int fh) {
    for (int i = 0; i < 60000 && !st->frame.render_failed; i++) { // tiles: at most ~60 s
        update_view(st);
        if (st->frame.settled >= 2) break;
        struct timespec pause = {0, 1000000};
        nanosleep(&pause, NULL);
    }
    build_ui(st, fw, fh);
    float k = ui_px(st, 1.0);
    st->frame.terrain_valid = 0; // full resolution, whatever was drawn while moving
    float keep = st->frame.res_scale;
    st->frame.res_scale = 1.0f;
    ui_rect vr = view_rect(st);
    render_terrain(st, (int)roundf(vr.w * k), (int)roundf(vr.h * k), 1);
    if (st->frame.smooth_owed) smooth_terrain(st); // as the view shows once it is still
    st->frame.res_scale = keep;
    return build_ui(st, fw, fh); // the status bar with this frame's figures
}
