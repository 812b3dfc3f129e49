#include "app/window.h"

#include "app/shortcuts.h"
#include "app/window_internal.h"
#include "app/world_warnings.h"

#include <poll.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static char glfw_message[512];

static void on_glfw_error(int code, const char *description) {
    snprintf(glfw_message, sizeof glfw_message, "%s (GLFW error 0x%x)", description, code);
}

void report(const char *what, const og_error *err) {
    fprintf(stderr, "orogen: %s: %s\n", what, err->msg);
}

// The terrain point under window position (x, y): the ray through that pixel marched
// against the heights the renderer holds (what is on screen), one coarse sample steps.
int pick_at(window_state *st, double x, double y, double hit[3]) {
    ui_rect r = view_rect(st);
    if (!st->v->renderer || r.w <= 0 || r.h <= 0) return -1;
    return viewport_pick_loaded(st->v, st->ctx->world, (x - r.x) / r.w, (y - r.y) / r.h,
                                (double)r.w / r.h, hit);
}

int in_view(const window_state *st, double x, double y) {
    return ui_rect_contains(view_rect(st), (float)x, (float)y);
}

// A point along the ray under (x, y) when no terrain is there: `dist` metres out.
void point_along_ray(window_state *st, double x, double y, double dist, double out[3]) {
    ui_rect r = view_rect(st);
    double dir[3];
    camera_ray(&st->v->cam, r.w > 0 && r.h > 0 ? (double)r.w / r.h : 1.0,
               r.w > 0 ? (x - r.x) / r.w : 0.5, r.h > 0 ? (y - r.y) / r.h : 0.5, dir);
    for (int i = 0; i < 3; i++)
        out[i] = st->v->cam.pos[i] + dir[i] * dist;
}

static int planet_ground(void *user, const double pos[3], double *h) {
    window_state *st = user;
    og_error err = {{0}};
    return planet_surface_height(st->ctx->world, pos, h, &err); // floats on the sea
}

// The camera of the world being left, kept for when it is opened again.
static void keep_world_camera(window_state *st) {
    const camera *c = &st->v->cam;
    const double pose[5] = {c->pos[0], c->pos[1], c->pos[2], c->yaw, c->pitch};
    app_settings_put_camera(&st->settings, st->run.cam_path, pose);
}

void reset_camera(window_state *st) {
    og_error err = {{0}};
    st->cc.walk = 0;
    const world_params *p = world_get_params(st->ctx->world);
    st->cc.planet_radius = p->kind == WORLD_PLANET ? p->radius : 0;
    st->cc.planet_ground = planet_ground;
    st->cc.planet_user = st;
    frame_retry_render(st);
    if (viewport_camera_on_land(st->v, st->ctx->world, &err) != 0) report("camera", &err);
    // A world opened again comes back as it was left.
    const char *path = world_path(st->ctx->world);
    double pose[5];
    if (app_settings_find_camera(&st->settings, path, pose) == 0) {
        camera *c = &st->v->cam;
        c->pos[0] = pose[0], c->pos[1] = pose[1], c->pos[2] = pose[2];
        c->yaw = pose[3], c->pitch = pose[4];
    }
    snprintf(st->run.cam_path, sizeof st->run.cam_path, "%s", path);
    st->v->cam_world_serial = st->ctx->world_serial;
    st->dirty = 1;
}

int ground_height(void *user, double x, double z, double *h) {
    window_state *st = user;
    return st->v->renderer ? terrain_renderer_height_at(st->v->renderer, x, z, h) : -1;
}

// Queues text as an action that is echoed in the console.
void run_commands(window_state *st, const char *text, const char *label) {
    work_queue_add(&st->work, text, label, WORK_ECHO);
    st->ui_dirty = 1;
    st->dirty = 1;
}

// What the worlds warned about since the last frame: in the console, and as notices; an
// error stays until dismissed (a damaged file opened read-only says why where the user
// looks), a warning passes (a file edited by hand is read as it is).
static void show_world_warnings(window_state *st) {
    char msg[1024];
    while (world_warnings_take(msg, sizeof msg)) {
        console_add(editor_ui_console(panels_editor(st)), CONSOLE_ERROR, msg);
        if (strstr(msg, "error:"))
            notices_add(panels_notices(st), msg);
        else
            notices_add_failure(panels_notices(st), "", msg, notices_now());
        st->ui_dirty = 1;
    }
}

// Runs what is queued (waiting up to a frame for work to end); after it the window
// shows whatever changed.
static void pump_work(window_state *st) {
    camera before = st->v->cam;
    work_queue_pump(&st->work, 30);
    show_world_warnings(st);
    if (work_queue_busy(&st->work)) return;
    if (work_queue_take_ran(&st->work)) {
        fflush(stdout);
        st->dirty = st->ui_dirty = 1;
        if (memcmp(&before, &st->v->cam, sizeof before) != 0) st->cc.walk = 0; // `camera`
    }
    viewport_drag_after_work(st);
    input_replay_deferred(st);
}

// Runs every complete line waiting on standard input, without blocking. While the work
// queue is nearly full it reads no more (the lines wait, in order, in the buffer and the
// pipe, whose writer waits): a script piping hundreds of commands loses none.
static void run_stdin_lines(window_state *st) {
    char *nl;
    while (!work_queue_filling(&st->work) &&
           (nl = memchr(st->run.stdin_buf, '\n', st->run.stdin_len))) {
        *nl = 0;
        if (work_queue_busy(&st->work) &&
            cmd_text_all_flagged(st->run.stdin_buf, strlen(st->run.stdin_buf), CMD_WHILE_BUSY)) {
            // A question about the window itself, answered while work runs.
            cmd_context side = {.out = stdout};
            og_error err = {{0}};
            if (cmd_run(&side, st->run.stdin_buf, strlen(st->run.stdin_buf), "console", &err) != 0)
                fprintf(stderr, "%s\n", err.msg);
            fflush(stdout);
        } else {
            run_commands(st, st->run.stdin_buf, "console");
        }
        size_t used = (size_t)(nl - st->run.stdin_buf) + 1;
        memmove(st->run.stdin_buf, nl + 1, st->run.stdin_len - used);
        st->run.stdin_len -= used;
    }
}

static void poll_stdin(window_state *st) {
    run_stdin_lines(st); // lines kept back while the queue was filling
    while (st->run.stdin_open && !work_queue_filling(&st->work)) {
        struct pollfd pfd = {STDIN_FILENO, POLLIN, 0};
        if (poll(&pfd, 1, 0) <= 0 || !(pfd.revents & (POLLIN | POLLHUP))) return;
        size_t room = sizeof st->run.stdin_buf - 1 - st->run.stdin_len;
        ssize_t got = read(STDIN_FILENO, st->run.stdin_buf + st->run.stdin_len, room);
        if (got <= 0) {
            st->run.stdin_open = 0; // the window stays; only the console is gone
            return;
        }
        st->run.stdin_len += (size_t)got;
        st->run.stdin_buf[st->run.stdin_len] = 0;
        run_stdin_lines(st);
        if (st->run.stdin_len == sizeof st->run.stdin_buf - 1 &&
            !memchr(st->run.stdin_buf, '\n', st->run.stdin_len)) {
            fprintf(stderr, "console: line longer than %zu bytes ignored\n",
                    sizeof st->run.stdin_buf);
            st->run.stdin_len = 0;
        }
    }
}

// Window coordinates to the UI's (framebuffer) pixels.
float ui_px(const window_state *st, double v) {
    return (float)(v * st->run.px_scale);
}

// Framebuffer pixels per window unit, kept from the size callbacks: asking the window
// system on every pointer event would be a round trip to the X server each time.
void close_after_work(window_state *st) {
    st->run.close_after_work = 1;
}

void update_px_scale(window_state *st) {
    int ww, fw, h;
    glfwGetWindowSize(st->win, &ww, &h);
    glfwGetFramebufferSize(st->win, &fw, &h);
    st->run.px_scale = ww > 0 && fw > 0 ? (double)fw / ww : 1.0;
}

// Changes published from another thread (a job's edits, work_queue.c) must not wait
// for input: they wake the event loop.
static void wake_window(void *user) {
    (void)user;
    glfwPostEmptyEvent();
}

// Any change redraws; another world (new, load) gets its default camera unless a
// command placed the camera after it came (`new planet; camera_geo ...`).
void take_changes(window_state *st) {
    world_event e[32];
    size_t n;
    int other_world = 0; // another world, or this one's kind may have changed
    while ((n = world_subscription_take(st->run.changes, e, 32)) > 0) {
        st->dirty = 1;
        st->ui_dirty = 1;              // the panels show the world (history, file, unsaved)
        for (size_t i = 0; i < n; i++) // saves and history steps leave the picture as it is
            if (e[i].kind == WORLD_EVENT_AREA || e[i].kind == WORLD_EVENT_PARAMS ||
                e[i].kind == WORLD_EVENT_REPLACED)
                frame_world_changed(st);
        for (size_t i = 0; i < n; i++)
            if (e[i].kind == WORLD_EVENT_HISTORY) panels_world_edited(st);
        for (size_t i = 0; i < n; i++) {
            if (e[i].kind == WORLD_EVENT_SAVED || e[i].kind == WORLD_EVENT_REPLACED)
                panels_world_opened(st);
            if (e[i].kind == WORLD_EVENT_SAVED) { // Save as: the camera goes with the new file
                keep_world_camera(st);
                snprintf(st->run.cam_path, sizeof st->run.cam_path, "%s",
                         world_path(st->ctx->world));
            }
            other_world |= e[i].kind == WORLD_EVENT_REPLACED || e[i].kind == WORLD_EVENT_PARAMS;
            if (e[i].kind != WORLD_EVENT_REPLACED) continue;
            if (st->v->cam_world_serial != st->ctx->world_serial) { // still the last world's view
                keep_world_camera(st);
                reset_camera(st);
            } else { // a command placed the camera for the new world: nothing to keep
                snprintf(st->run.cam_path, sizeof st->run.cam_path, "%s",
                         world_path(st->ctx->world));
            }
        }
        if (n < 32) break;
    }
    // Planets have no volume tools (nor their palette buttons): raise instead, as a
    // command, so the console, the recording, the palette and the dock agree.
    if (other_world && world_get_params(st->ctx->world)->kind == WORLD_PLANET &&
        brush_tool_is_volume(st->ctx->brush.tool))
        run_commands(st, "tool raise", "planet");
}

// Makes the viewport the console's view commands use: this window's context, its renderer.
static viewport *attach_viewport(cmd_context *ctx, og_error *err) {
    viewport *v = viewport_create(ctx->resource_dir);
    if (!v) return og_error_set(err, "out of memory"), NULL;
    viewport *batch_view = ctx->view_state;
    if (batch_view) { // made by a batch command: keep its camera and settings
        v->cam = batch_view->cam;
        v->cam_set = batch_view->cam_set;
        v->cam_world_serial = batch_view->cam_world_serial;
        v->settings = batch_view->settings;
        viewport_destroy(batch_view);
    }
    v->window_context = 1;
    view_commands_set_viewport(ctx, v);
    return v;
}

// The window's size and place, the UI scale, the recent worlds and the console's
// history, for the next run. A failure is only reported.
static void save_settings(window_state *st) {
    app_settings *s = &st->settings;
    s->maximized = glfwGetWindowAttrib(st->win, GLFW_MAXIMIZED);
    if (!s->maximized && !s->fullscreen) {
        glfwGetWindowSize(st->win, &s->width, &s->height);
        glfwGetWindowPos(st->win, &s->x, &s->y);
        s->has_position = 1;
    }
    panels_keep(st); // the recent worlds, the console's history
    app_settings_add_recent(s, world_path(st->ctx->world));
    tool_settings_capture(st->ctx, s);
    keep_world_camera(st);
    s->fly_speed = st->cc.fly_speed;
    s->dynamic_lod = frame_dynamic_resolution(st);
    s->lod_pixels = st->v->settings.lod_pixels;
    og_error err = {{0}};
    if (app_settings_save(s, st->run.settings_path, &err) != 0)
        fprintf(stderr, "orogen: settings not saved: %s\n", err.msg);
}

// GLFW and a window with an EGL OpenGL 4.5 core context, placed as the settings say,
// fitted to the primary monitor's work area (which the settings then keep).
static GLFWwindow *open_window(app_settings *settings, og_error *err) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        og_error_set(err, "cannot start the window system: %s", glfw_message);
        return NULL;
    }
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    GLFWmonitor *monitor = settings->fullscreen ? glfwGetPrimaryMonitor() : NULL;
    const GLFWvidmode *mode = monitor ? glfwGetVideoMode(monitor) : NULL;
    if (!monitor && glfwGetPrimaryMonitor()) {
        int ax = 0, ay = 0, aw = 0, ah = 0;
        glfwGetMonitorWorkarea(glfwGetPrimaryMonitor(), &ax, &ay, &aw, &ah);
        app_settings_fit_to_screen(settings, ax, ay, aw, ah);
    }
    if (settings->maximized) glfwWindowHint(GLFW_MAXIMIZED, GLFW_TRUE);
    GLFWwindow *win =
        glfwCreateWindow(mode ? mode->width : settings->width,
                         mode ? mode->height : settings->height, "Orogen", monitor, NULL);
    if (!win) {
        glfwTerminate();
        og_error_set(err, "cannot open a window with an OpenGL 4.5 core context through EGL: %s",
                     glfw_message);
        return NULL;
    }
    if (settings->has_position && !monitor) glfwSetWindowPos(win, settings->x, settings->y);
    glfwMakeContextCurrent(win);
    glfwSwapInterval(1);
    return win;
}

// Frees whatever of the window exists (a start that failed half way, or the end):
// each part closes its own.
static void window_teardown(window_state *st) {
    cmd_context *ctx = st->ctx;
    if (ctx->session) fclose(ctx->session);
    ctx->session = NULL;
    free(st->run.session_text);
    if (st->run.changes) world_events_unsubscribe(st->run.changes);
    current_window = NULL;
    frame_close(st);
    panels_close(st);
    input_close(st);
    // The renderer's GL objects belong to this context: free them while it is current.
    viewport_destroy(st->v);
    view_commands_set_viewport(ctx, NULL);
    glfwDestroyWindow(st->win);
    glfwTerminate();
}

// The window's state from the settings: the viewport, the UI, the console, the queue.
static int window_start(window_state *st, const app_settings *settings, const char *settings_path,
                        og_error *err) {
    cmd_context *ctx = st->ctx;
    og_error gl_err = {{0}};
    if (gl_require_features(&gl_err) != 0 || !(st->v = attach_viewport(ctx, &gl_err)) ||
        viewport_prepare(st->v, &gl_err) != 0)
        return og_error_set(err, "the window's OpenGL context cannot run the viewport: %s",
                            gl_err.msg);
    camera_controls_init(&st->cc);
    st->run.changes = world_events_subscribe(world_event_hub(ctx->world), wake_window, NULL);
    if (!st->run.changes) return og_error_set(err, "out of memory");
    update_px_scale(st);
    st->settings = *settings;
    snprintf(st->run.settings_path, sizeof st->run.settings_path, "%s", settings_path);
    frame_open(st, settings->frame_target_ms);
    frame_set_dynamic_resolution(st, settings->dynamic_lod);
    st->cc.fly_speed = settings->fly_speed; // the wheel with the right button held changes it
    if (panels_open(st, err) != 0) return -1;
    if (input_open(st) != 0)
        return og_error_set(err, "the editor's UI cannot start: out of memory");
    // The session's commands, kept for `history script FILE` (File > Save session...).
    ctx->session = open_memstream(&st->run.session_text, &st->run.session_len);
    ctx->session_text = &st->run.session_text;
    ctx->session_len = &st->run.session_len;
    tool_settings_restore(ctx, settings, settings_path); // each tool as it was last used
    work_queue_init(&st->work, ctx, editor_ui_console(panels_editor(st)), wake_window, NULL);
    st->work.notices = panels_notices(st);
    current_window = st;
    return 0;
}

// The first frame lays out the UI, so the viewport's rectangle is known for the camera.
static void first_frame(window_state *st) {
    viewport *v = st->v;
    int w, h;
    glfwGetFramebufferSize(st->win, &w, &h);
    build_ui(st, w > 0 ? w : 1, h > 0 ? h : 1);
    if (!v->cam_set) reset_camera(st);
    if (!v->cam_set) v->cam.fov_y = st->settings.field_of_view;
    v->settings.lod_pixels = st->settings.lod_pixels;
    input_first_pointer(st);
    window_input_attach(st);
    printf("Orogen viewport (F1 lists every shortcut):\n");
    for (int i = 0; i < shortcut_row_count(); i++)
        if (shortcut_row_at(i)->banner)
            printf("  %s: %s\n", shortcut_row_at(i)->input, shortcut_row_at(i)->help);
    printf("Console: type commands here ('help' lists them, 'exit' quits).\n");
    fflush(stdout);
}

// Input, the camera's movement and the turning light; then the queue. 1 when the loop
// should go on to draw, 0 to wait for the next events, -1 to end.
static int frame_input(window_state *st, int w, int h, const ui_draw_list *dl) {
    cmd_context *ctx = st->ctx;
    viewport *v = st->v;
    if (work_queue_busy(&st->work)) { // the world is the job's: only progress is drawn
        poll_stdin(st);
        pump_work(st);
        if (work_queue_busy(&st->work)) {
            if (w > 0 && h > 0 && dl) draw_busy(st, dl, w, h);
            return 0;
        }
    }
    if (ctx->exit_requested) return -1; // `exit` ran (read only when no work runs)
    if (st->run.close_after_work) {     // the close button, pressed while work ran
        st->run.close_after_work = 0;
        on_close(st->win);
        if (!world_is_modified(ctx->world)) return -1;
    }
    move_keys keys = take_keys(st);
    if (camera_controls_move(&st->cc, &v->cam, &keys, ground_height, st)) st->dirty = 1;
    double now_s = glfwGetTime();
    if (v->settings.sun_rotation != 0) { // R: the light turns while time passes
        double dt = fmin(now_s - st->run.sun_turned_at, 0.25);
        v->settings.sun_yaw = fmod(v->settings.sun_yaw + v->settings.sun_rotation * dt, 360.0);
        st->dirty = 1;
    }
    st->run.sun_turned_at = now_s;
    poll_stdin(st);
    pump_work(st);
    if (ctx->exit_requested) return -1;
    if (work_queue_busy(&st->work)) return 0;
    // A brush held still keeps applying (Unreal, Terrain3D), at its spacing's rate.
    sculpt_drag *held = viewport_drag_stroke(st);
    if (held && sculpt_drag_hold(held, &st->work)) st->dirty = 1;
    take_changes(st);
    return w > 0 && h > 0;
}

// The UI, the actions it asked for, the terrain image and the composed picture. 0, or
// -1 when `exit` ran.
static int frame_draw(window_state *st, int w, int h, const ui_draw_list **dl,
                      GLenum *last_gl_error) {
    // The UI is rebuilt after input or changes; the terrain image only when what
    // it shows changed (a hover or a keystroke in a text field never re-renders it).
    int drawn = 0;
    if (st->ui_dirty || st->dirty || panels_need_frame(st) || !*dl) {
        *dl = build_ui(st, w, h);
        drawn = 1;
    }
    // The actions the UI asked for run before the frame is drawn.
    if (!work_queue_idle(&st->work)) {
        pump_work(st);
        if (st->ctx->exit_requested) return -1;
        if (work_queue_busy(&st->work)) return 0;
        take_changes(st);
        *dl = build_ui(st, w, h);
    }
    if (st->dirty || frame_unsettled(st)) {
        int arrived = update_view(st) > 0;
        float k = ui_px(st, 1.0);
        ui_rect vr = view_rect(st);
        if (render_terrain(st, (int)roundf(vr.w * k), (int)roundf(vr.h * k), arrived)) {
            drawn = 1;
            st->ui_dirty = 1; // the status bar shows the new frame's figures
        }
        // A lowered frame: full size once all is still; a full-size one: smoothed then.
        st->dirty = frame_owes_still(st);
    }
    if (drawn) {
        compose(st, *dl, w, h);
        glfwSwapBuffers(st->win);
        GLenum e = glGetError();
        if (e != GL_NO_ERROR && e != *last_gl_error)
            fprintf(stderr, "orogen: OpenGL error 0x%x in the viewport\n", e);
        *last_gl_error = e;
    }
    update_title(st);
    return 0;
}

int window_run(cmd_context *ctx, og_error *err) {
    app_settings settings;
    app_settings_default(&settings);
    char settings_path[4096];
    app_settings_path(settings_path, sizeof settings_path, "settings");
    app_settings_load(&settings, settings_path);
    const char *env_scale = getenv("OROGEN_UI_SCALE"); // overrides the saved scale
    if (env_scale && *env_scale) {
        double u;
        if (parse_number_in(env_scale, "OROGEN_UI_SCALE", 0.5, 4, &u, err) != 0) return -1;
        settings.ui_scale = u;
    }
    GLFWwindow *win = open_window(&settings, err);
    if (!win) return -1;
    window_state st = {.ctx = ctx, .win = win, .run.stdin_open = 1, .dirty = 1};
    if (window_start(&st, &settings, settings_path, err) != 0) {
        window_teardown(&st);
        return -1;
    }
    first_frame(&st);
    GLenum last_gl_error = GL_NO_ERROR;
    const ui_draw_list *dl = NULL;
    while (!glfwWindowShouldClose(win)) {
        // Input first; wake often while tiles arrive, keys fly the camera or work runs.
        int awake = frame_unsettled(&st) || keys_held(&st) ||
                    viewport_drag_kind(&st) == DRAG_SCULPT || st.v->settings.sun_rotation != 0 ||
                    !work_queue_idle(&st.work) || panels_need_frame(&st) ||
                    memchr(st.run.stdin_buf, '\n', st.run.stdin_len); // console lines kept back
        glfwWaitEventsTimeout(awake ? 0.01 : 0.1);
        sculpt_drag *stroke = viewport_drag_stroke(&st);
        if (stroke && st.input.deferred.count == 0) sculpt_drag_input_taken(stroke);
        int w, h;
        glfwGetFramebufferSize(win, &w, &h);
        int go = frame_input(&st, w, h, dl);
        if (go < 0 || (go > 0 && frame_draw(&st, w, h, &dl, &last_gl_error) < 0)) break;
    }
    // A stroke still held is committed, and queued work finishes (or is cancelled by
    // a second close) before the world is saved or closed by the caller.
    sculpt_end(&st);
    while (!work_queue_idle(&st.work)) {
        pump_work(&st);
        if (work_queue_busy(&st.work)) glfwWaitEventsTimeout(0.05);
    }
    work_queue_free(&st.work);
    save_settings(&st);
    window_teardown(&st);
    return 0;
}
