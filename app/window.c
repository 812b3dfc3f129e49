#include "app/window.h"

#include "app/camera_controls.h"
#include "renderer/gl_context.h"
#include "renderer/pick.h"
#include "renderer/view_commands.h"
#include "renderer/viewport.h"

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <math.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char glfw_message[512];

static void on_glfw_error(int code, const char *description) {
    snprintf(glfw_message, sizeof glfw_message, "%s (GLFW error 0x%x)", description, code);
}

// The movement keys: W S A D E Q.
enum { MOVE_KEY_COUNT = 6 };
static const int move_key_codes[MOVE_KEY_COUNT] = {GLFW_KEY_W, GLFW_KEY_S, GLFW_KEY_A,
                                                   GLFW_KEY_D, GLFW_KEY_E, GLFW_KEY_Q};

typedef enum drag_kind { DRAG_NONE, DRAG_SCULPT, DRAG_ORBIT } drag_kind;

typedef struct window_state {
    cmd_context *ctx;
    viewport *v;
    GLFWwindow *win;
    world_subscription *changes; // the world's change notifications (another world: new camera)
    camera_controls cc;
    double mouse_x, mouse_y; // window coordinates of the last motion event
    int mouse_in;
    drag_kind drag;  // left or middle button
    int looking;     // right button held: mouse look, WASD, wheel sets the speed
    double pivot[3]; // orbit pivot of the current drag
    int key_down[MOVE_KEY_COUNT];
    double key_since[MOVE_KEY_COUNT], key_held[MOVE_KEY_COUNT]; // seconds, see bank_keys
    int dirty;         // something changed: draw a frame
    int settled;       // frames in a row with every level current
    int pending;       // levels (or layers) still waiting for tiles
    int render_failed; // the renderer refused this world (a planet): said once
    char title[512];
    char stdin_buf[8192];
    size_t stdin_len;
    int stdin_open;
} window_state;

static void report(const char *what, const og_error *err) {
    fprintf(stderr, "orogen: %s: %s\n", what, err->msg);
}

// --- picking -----------------------------------------------------------------------

// The terrain point under window position (x, y): the ray through that pixel marched
// against the heights the renderer holds (what is on screen), one coarse sample steps.
static int pick_at(window_state *st, double x, double y, double hit[3]) {
    if (!st->v->renderer) return -1;
    int ww, wh;
    glfwGetWindowSize(st->win, &ww, &wh);
    if (ww <= 0 || wh <= 0) return -1;
    return viewport_pick_loaded(st->v, st->ctx->world, x / ww, y / wh, (double)ww / wh, hit);
}

// A point along the ray under (x, y) when no terrain is there: `dist` metres out.
static void point_along_ray(window_state *st, double x, double y, double dist, double out[3]) {
    int ww, wh;
    glfwGetWindowSize(st->win, &ww, &wh);
    double dir[3];
    camera_ray(&st->v->cam, ww > 0 && wh > 0 ? (double)ww / wh : 1.0, ww > 0 ? x / ww : 0.5,
               wh > 0 ? y / wh : 0.5, dir);
    for (int i = 0; i < 3; i++)
        out[i] = st->v->cam.pos[i] + dir[i] * dist;
}

// --- sculpting ---------------------------------------------------------------------

// A drag sculpts through the command language like any other action (stroke_begin,
// stroke_to per mouse move, stroke_end), so it is echoed to a recording and replays
// to the same terrain. Positions are written with 17 digits: the replay is exact.
static int run_action(window_state *st, const char *text, const char *label) {
    og_error err = {{0}};
    st->dirty = 1;
    if (cmd_run(st->ctx, text, strlen(text), label, &err) == 0) return 0;
    fprintf(stderr, "%s\n", err.msg);
    return -1;
}

static void sculpt_to(window_state *st, double x, double y) {
    double hit[3];
    // No stroke (it failed, or a console command ended it), or off the terrain: skip.
    if (!st->ctx->stroke || pick_at(st, x, y, hit) != 0) return;
    char text[128];
    snprintf(text, sizeof text, "stroke_to %.17g %.17g", hit[0], hit[2]);
    run_action(st, text, "sculpt");
}

static void sculpt_begin(window_state *st) {
    if (run_action(st, "stroke_begin", "sculpt") == 0) sculpt_to(st, st->mouse_x, st->mouse_y);
}

// Commits the drag's stroke (one undo step); a stroke that laid no dab leaves no step.
static void sculpt_end(window_state *st) {
    if (st->ctx->stroke) run_action(st, "stroke_end", "sculpt");
}

// --- the camera --------------------------------------------------------------------

static void reset_camera(window_state *st) {
    og_error err = {{0}};
    st->cc.walk = 0;
    st->render_failed = 0;
    if (viewport_default_camera(st->v, st->ctx->world, &err) != 0) report("camera", &err);
    st->dirty = 1;
}

static int ground_height(void *user, double x, double z, double *h) {
    window_state *st = user;
    return st->v->renderer ? terrain_renderer_height_at(st->v->renderer, x, z, h) : -1;
}

// Movement keys count while the right button is held, or always while walking. Their
// held time is banked at every press, release and mode change, so the camera moves
// for as long as a key was held even when frames are slow.
static int movement_allowed(const window_state *st) {
    return st->looking || st->cc.walk;
}

static void bank_keys(window_state *st) {
    double now = glfwGetTime();
    for (int i = 0; i < MOVE_KEY_COUNT; i++) {
        if (st->key_down[i] && movement_allowed(st)) st->key_held[i] += now - st->key_since[i];
        st->key_since[i] = now;
    }
}

// The banked time as a step for camera_controls_move; clears the bank.
static move_keys take_keys(window_state *st) {
    bank_keys(st);
    GLFWwindow *w = st->win;
    double *h = st->key_held;
    move_keys k = {h[0], h[1], h[2], h[3], h[4], h[5], 0};
    k.fast = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT);
    for (int i = 0; i < MOVE_KEY_COUNT; i++)
        h[i] = 0;
    return k;
}

static int keys_held(const window_state *st) {
    if (!movement_allowed(st)) return 0;
    for (int i = 0; i < MOVE_KEY_COUNT; i++)
        if (st->key_down[i]) return 1;
    return 0;
}

// --- the command language ----------------------------------------------------------

static void run_commands(window_state *st, const char *text, const char *label) {
    camera before = st->v->cam;
    og_error err = {{0}};
    if (cmd_run(st->ctx, text, strlen(text), label, &err) != 0) fprintf(stderr, "%s\n", err.msg);
    fflush(stdout);
    if (memcmp(&before, &st->v->cam, sizeof before) != 0) st->cc.walk = 0; // `camera` placed it
    st->dirty = 1;
}

// Runs every complete line waiting on standard input, without blocking.
static void poll_stdin(window_state *st) {
    while (st->stdin_open) {
        struct pollfd pfd = {STDIN_FILENO, POLLIN, 0};
        if (poll(&pfd, 1, 0) <= 0 || !(pfd.revents & (POLLIN | POLLHUP))) return;
        size_t room = sizeof st->stdin_buf - 1 - st->stdin_len;
        ssize_t got = read(STDIN_FILENO, st->stdin_buf + st->stdin_len, room);
        if (got <= 0) {
            st->stdin_open = 0; // the window stays; only the console is gone
            return;
        }
        st->stdin_len += (size_t)got;
        st->stdin_buf[st->stdin_len] = 0;
        char *nl;
        while ((nl = memchr(st->stdin_buf, '\n', st->stdin_len))) {
            *nl = 0;
            run_commands(st, st->stdin_buf, "console");
            size_t used = (size_t)(nl - st->stdin_buf) + 1;
            memmove(st->stdin_buf, nl + 1, st->stdin_len - used);
            st->stdin_len -= used;
            if (st->ctx->exit_requested) return;
        }
        if (st->stdin_len == sizeof st->stdin_buf - 1) {
            fprintf(stderr, "console: line longer than %zu bytes ignored\n", sizeof st->stdin_buf);
            st->stdin_len = 0;
        }
    }
}

// --- GLFW input --------------------------------------------------------------------

static void on_mouse_button(GLFWwindow *win, int button, int action, int mods) {
    window_state *st = glfwGetWindowUserPointer(win);
    st->dirty = 1;
    // Drags start where the last motion event left the cursor (not where the pointer
    // is now: events queue up, and querying would skip the moves between).
    if (button == GLFW_MOUSE_BUTTON_RIGHT) {
        bank_keys(st);
        st->looking = action == GLFW_PRESS;
        return;
    }
    if (button != GLFW_MOUSE_BUTTON_LEFT && button != GLFW_MOUSE_BUTTON_MIDDLE) return;
    if (action == GLFW_RELEASE) {
        if (st->drag == DRAG_SCULPT && button == GLFW_MOUSE_BUTTON_LEFT) sculpt_end(st);
        st->drag = DRAG_NONE;
        return;
    }
    if (st->drag != DRAG_NONE) return; // one drag at a time
    if (button == GLFW_MOUSE_BUTTON_MIDDLE || (mods & GLFW_MOD_ALT)) {
        st->drag = DRAG_ORBIT;
        if (pick_at(st, st->mouse_x, st->mouse_y, st->pivot) != 0) {
            int ww, wh;
            glfwGetWindowSize(win, &ww, &wh);
            if (pick_at(st, ww * 0.5, wh * 0.5, st->pivot) != 0)
                point_along_ray(st, ww * 0.5, wh * 0.5, 100.0, st->pivot);
        }
        st->cc.walk = 0;
    } else {
        st->drag = DRAG_SCULPT;
        sculpt_begin(st);
    }
}

static void on_cursor(GLFWwindow *win, double x, double y) {
    window_state *st = glfwGetWindowUserPointer(win);
    double dx = x - st->mouse_x, dy = y - st->mouse_y;
    st->mouse_x = x, st->mouse_y = y;
    st->dirty = 1;
    if (st->drag == DRAG_ORBIT)
        camera_controls_orbit(&st->cc, &st->v->cam, st->pivot, dx, dy);
    else if (st->drag == DRAG_SCULPT)
        sculpt_to(st, x, y);
    if (st->looking) camera_controls_look(&st->cc, &st->v->cam, dx, dy);
}

static void on_cursor_enter(GLFWwindow *win, int entered) {
    window_state *st = glfwGetWindowUserPointer(win);
    st->mouse_in = entered;
    st->dirty = 1;
}

static void on_scroll(GLFWwindow *win, double dx, double dy) {
    (void)dx;
    window_state *st = glfwGetWindowUserPointer(win);
    st->dirty = 1;
    if (st->looking) {
        camera_controls_speed_wheel(&st->cc, dy);
        return;
    }
    double pivot[3];
    if (pick_at(st, st->mouse_x, st->mouse_y, pivot) != 0)
        point_along_ray(st, st->mouse_x, st->mouse_y, fmax(100.0, 4.0 * st->cc.fly_speed), pivot);
    st->cc.walk = 0;
    camera_controls_dolly(&st->cc, &st->v->cam, pivot, dy);
}

static void save_shortcut(window_state *st) {
    if (!world_path(st->ctx->world)[0]) {
        fprintf(stderr, "orogen: this world has never been saved: type save FILE in the console "
                        "(after that, Ctrl+S saves it there)\n");
        return;
    }
    run_commands(st, "save", "Ctrl+S");
}

static void on_key(GLFWwindow *win, int key, int scancode, int action, int mods) {
    (void)scancode;
    window_state *st = glfwGetWindowUserPointer(win);
    st->dirty = 1;
    for (int i = 0; i < MOVE_KEY_COUNT; i++) {
        if (key != move_key_codes[i] || action == GLFW_REPEAT) continue;
        bank_keys(st);
        // Ctrl+S is a shortcut, not a step back.
        st->key_down[i] = action == GLFW_PRESS && !(mods & GLFW_MOD_CONTROL);
    }
    if (action != GLFW_PRESS) return;
    if (mods & GLFW_MOD_CONTROL) {
        if (key == GLFW_KEY_S)
            save_shortcut(st);
        else if (key == GLFW_KEY_Z && (mods & GLFW_MOD_SHIFT))
            run_commands(st, "redo", "Ctrl+Shift+Z");
        else if (key == GLFW_KEY_Z)
            run_commands(st, "undo", "Ctrl+Z");
        else if (key == GLFW_KEY_Y)
            run_commands(st, "redo", "Ctrl+Y");
        return;
    }
    double hit[3];
    switch (key) {
    case GLFW_KEY_F:
        if (pick_at(st, st->mouse_x, st->mouse_y, hit) == 0)
            camera_controls_focus(&st->cc, &st->v->cam, hit, st->ctx->brush.radius);
        else
            fprintf(stderr, "orogen: focus: no terrain under the cursor\n");
        break;
    case GLFW_KEY_G:
        bank_keys(st);
        camera_controls_toggle_walk(&st->cc, &st->v->cam, ground_height, st);
        break;
    case GLFW_KEY_HOME:
        reset_camera(st);
        break;
    case GLFW_KEY_1:
    case GLFW_KEY_2:
    case GLFW_KEY_3:
    case GLFW_KEY_4:
    case GLFW_KEY_5:
        st->v->settings.view = (view_mode)(key - GLFW_KEY_1);
        break;
    default:
        break;
    }
}

static void on_refresh(GLFWwindow *win) {
    window_state *st = glfwGetWindowUserPointer(win);
    st->dirty = 1;
}

// --- changes ------------------------------------------------------------------------

// Edits made by another thread's publish (none today) must not wait for input.
static void wake_window(void *user) {
    (void)user;
    glfwPostEmptyEvent();
}

// Any change redraws; another world (new, load) gets its default camera.
static void take_changes(window_state *st) {
    world_event e[32];
    size_t n;
    while ((n = world_subscription_take(st->changes, e, 32)) > 0) {
        st->dirty = 1;
        for (size_t i = 0; i < n; i++)
            if (e[i].kind == WORLD_EVENT_REPLACED) reset_camera(st);
        if (n < 32) break;
    }
}

// --- the frame ---------------------------------------------------------------------

static void update_title(window_state *st) {
    char title[sizeof st->title], name[256];
    const char *path = world_path(st->ctx->world);
    const char *slash = strrchr(path, '/');
    snprintf(name, sizeof name, "%s", path[0] ? (slash ? slash + 1 : path) : "unsaved world");
    const camera *c = &st->v->cam;
    render_stats rs = {0};
    if (st->v->renderer) terrain_renderer_stats(st->v->renderer, &rs);
    int used = st->v->settings.levels - rs.finest_level;
    if (st->render_failed)
        snprintf(title, sizeof title, "Orogen - %s%s - planet worlds are not drawn yet", name,
                 world_is_modified(st->ctx->world) ? " *" : "");
    else
        snprintf(title, sizeof title,
                 "Orogen - %s%s - cam (%.1f, %.1f, %.1f) yaw %.1f pitch %.1f - %s %.3g m/s - "
                 "levels %d/%d - tool %s r%g - pending %d",
                 name, world_is_modified(st->ctx->world) ? " *" : "", c->pos[0], c->pos[1],
                 c->pos[2], c->yaw, c->pitch, st->cc.walk ? "walk" : "fly",
                 camera_controls_speed(&st->cc), rs.levels_ready, used,
                 brush_tool_name(st->ctx->brush.tool), st->ctx->brush.radius, st->pending);
    if (strcmp(title, st->title) != 0) {
        snprintf(st->title, sizeof st->title, "%s", title);
        glfwSetWindowTitle(st->win, title);
    }
}

static void update_cursor(window_state *st) {
    brush_cursor *bc = &st->v->cursor;
    double hit[3];
    bc->visible = st->mouse_in && !st->looking && st->drag != DRAG_ORBIT &&
                  pick_at(st, st->mouse_x, st->mouse_y, hit) == 0;
    if (!bc->visible) return;
    bc->x = hit[0], bc->z = hit[2];
    bc->radius = st->ctx->brush.radius;
    for (int i = 0; i < BRUSH_FALLOFF_SAMPLES; i++)
        bc->falloff[i] =
            brush_falloff_weight(&st->ctx->brush, (float)i / (BRUSH_FALLOFF_SAMPLES - 1));
}

// Brings the clipmaps up to date without waiting for tiles. Returns 1 when the picture
// changed (texels arrived), 0 when not, -1 when this world cannot be drawn.
static int update_view(window_state *st) {
    og_error err = {{0}};
    viewport *v = st->v;
    if (st->render_failed) return -1;
    int rc = terrain_renderer_update(v->renderer, st->ctx->world, &v->cam, &v->settings, &err);
    if (rc < 0) {
        report("viewport", &err);
        st->render_failed = 1;
        st->pending = 0;
        st->settled = 2; // nothing to wait for
        return -1;
    }
    render_stats rs;
    terrain_renderer_stats(v->renderer, &rs);
    if (rc == 1) {
        st->settled++;
        st->pending = 0;
    } else {
        int missing = v->settings.levels - rs.finest_level - rs.levels_ready;
        st->settled = 0;
        st->pending = missing > 0 ? missing : 1; // else the material or detail layers
    }
    return rs.texels_uploaded > 0;
}

static void draw_view(window_state *st, int width, int height) {
    og_error err = {{0}};
    viewport *v = st->v;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (st->render_failed) {
        glViewport(0, 0, width, height);
        glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        return;
    }
    update_cursor(st);
    if (terrain_renderer_draw(v->renderer, st->ctx->world, &v->cam, &v->settings, &v->cursor, width,
                              height, &err) != 0)
        report("viewport", &err);
}

// Makes the viewport the console's view commands use: this window's context, its renderer.
static viewport *attach_viewport(cmd_context *ctx, og_error *err) {
    viewport *v = viewport_create(ctx->resource_dir);
    if (!v) return og_error_set(err, "out of memory"), NULL;
    viewport *batch_view = ctx->view_state;
    if (batch_view) { // made by a batch command: keep its camera and settings
        v->cam = batch_view->cam;
        v->cam_set = batch_view->cam_set;
        v->settings = batch_view->settings;
        viewport_destroy(batch_view);
    }
    v->window_context = 1;
    view_commands_set_viewport(ctx, v);
    return v;
}

int window_run(cmd_context *ctx, og_error *err) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) return og_error_set(err, "cannot start the window system: %s", glfw_message);
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    GLFWwindow *win = glfwCreateWindow(1280, 800, "Orogen", NULL, NULL);
    if (!win) {
        glfwTerminate();
        return og_error_set(err,
                            "cannot open a window with an OpenGL 4.5 core context through "
                            "EGL: %s",
                            glfw_message);
    }
    glfwMakeContextCurrent(win);
    glfwSwapInterval(1);
    og_error gl_err = {{0}};
    viewport *v = NULL;
    if (gl_require_features(&gl_err) != 0 || !(v = attach_viewport(ctx, &gl_err)) ||
        viewport_prepare(v, &gl_err) != 0) {
        og_error_set(err, "the window's OpenGL context cannot run the viewport: %s", gl_err.msg);
        if (v) viewport_destroy(v), view_commands_set_viewport(ctx, NULL);
        glfwDestroyWindow(win);
        glfwTerminate();
        return -1;
    }

    window_state st = {.ctx = ctx, .v = v, .win = win, .stdin_open = 1, .dirty = 1};
    camera_controls_init(&st.cc);
    st.changes = world_events_subscribe(world_event_hub(ctx->world), wake_window, NULL);
    if (!st.changes) {
        og_error_set(err, "out of memory");
        viewport_destroy(v);
        view_commands_set_viewport(ctx, NULL);
        glfwDestroyWindow(win);
        glfwTerminate();
        return -1;
    }
    if (!v->cam_set) reset_camera(&st);
    glfwGetCursorPos(win, &st.mouse_x, &st.mouse_y);
    glfwSetWindowUserPointer(win, &st);
    glfwSetMouseButtonCallback(win, on_mouse_button);
    glfwSetCursorPosCallback(win, on_cursor);
    glfwSetCursorEnterCallback(win, on_cursor_enter);
    glfwSetScrollCallback(win, on_scroll);
    glfwSetKeyCallback(win, on_key);
    glfwSetWindowRefreshCallback(win, on_refresh);
    printf("Orogen viewport:\n"
           "  left-drag sculpts with the current tool (console: tool NAME key=value ...)\n"
           "  Alt+left-drag or middle-drag orbits, wheel dollies to the point under the cursor\n"
           "  right-drag looks; with it held W A S D move, Q E down/up, Shift faster, wheel "
           "sets the speed\n"
           "  G walk mode (WASD walk on the ground), F focus on the point under the cursor, "
           "Home resets the view\n"
           "  1-5 shaded, wireframe, levels, height, slope views\n"
           "  Ctrl+Z undo, Ctrl+Shift+Z or Ctrl+Y redo, Ctrl+S save\n"
           "Console: type commands here ('help' lists them, 'exit' quits).\n");
    fflush(stdout);

    GLenum last_gl_error = GL_NO_ERROR;
    while (!glfwWindowShouldClose(win) && !ctx->exit_requested) {
        // Input first; wake often while tiles arrive or keys fly the camera, rarely when idle.
        int busy = st.pending || st.settled < 2 || keys_held(&st) || ctx->stroke;
        glfwWaitEventsTimeout(busy ? 0.01 : 0.1);
        move_keys keys = take_keys(&st);
        if (camera_controls_move(&st.cc, &v->cam, &keys, ground_height, &st)) st.dirty = 1;
        poll_stdin(&st);
        if (ctx->exit_requested) break;
        take_changes(&st);

        // Tiles are requested every wake-up while some are missing; a frame is drawn
        // when input or commands changed something or new texels arrived.
        int w, h;
        glfwGetFramebufferSize(win, &w, &h);
        if (w > 0 && h > 0 && (st.dirty || st.pending || st.settled < 2)) {
            int arrived = update_view(&st);
            if (st.dirty || arrived) {
                st.dirty = 0;
                draw_view(&st, w, h);
                glfwSwapBuffers(win);
                GLenum e = glGetError();
                if (e != GL_NO_ERROR && e != last_gl_error)
                    fprintf(stderr, "orogen: OpenGL error 0x%x in the viewport\n", e);
                last_gl_error = e;
            }
        }
        update_title(&st);
    }
    sculpt_end(&st);
    world_events_unsubscribe(st.changes);
    // The renderer's GL objects belong to this context: free them while it is current.
    viewport_destroy(v);
    view_commands_set_viewport(ctx, NULL);
    glfwDestroyWindow(win);
    glfwTerminate();
    return 0;
}
