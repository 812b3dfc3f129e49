#include "app/window.h"

#include "editor/edit/recover.h"
#include "editor/params/world_grid.h"

#include "app/camera_controls.h"
#include "app/dynamic_resolution.h"
#include "app/editor_ui.h"
#include "app/sculpt_drag.h"
#include "app/settings.h"
#include "app/tool_settings.h"
#include "app/work_queue.h"
#include "editor/tools/stamp.h"
#include "renderer/gl_context.h"
#include "renderer/gl_target.h"
#include "renderer/material_textures.h"
#include "editor/cmd/tokenize.h"
#include "renderer/pick.h"
#include "renderer/planet_camera.h"
#include "renderer/ui_renderer.h"
#include "io/image_read.h"
#include "view/view_commands.h"
#include "renderer/viewport.h"
#include "io/parse.h"
#include "ui/ui.h"

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <math.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

static char glfw_message[512];

static void on_glfw_error(int code, const char *description) {
    snprintf(glfw_message, sizeof glfw_message, "%s (GLFW error 0x%x)", description, code);
}

// The movement keys: W S A D E Q.
enum { MOVE_KEY_COUNT = 6 };
static const int move_key_codes[MOVE_KEY_COUNT] = {GLFW_KEY_W, GLFW_KEY_S, GLFW_KEY_A,
                                                   GLFW_KEY_D, GLFW_KEY_E, GLFW_KEY_Q};

// Left: sculpt; middle or Alt+left: orbit; Alt+right: resize the brush on screen.
typedef enum drag_kind { DRAG_NONE, DRAG_SCULPT, DRAG_ORBIT, DRAG_RESIZE } drag_kind;

typedef struct window_state {
    cmd_context *ctx;
    viewport *v;
    GLFWwindow *win;
    world_subscription *changes; // the world's change notifications (another world: new camera)
    camera_controls cc;
    double mouse_x, mouse_y; // window coordinates of the last motion event
    int mouse_in;
    drag_kind drag;       // left or middle button
    int looking;          // right button held: mouse look, WASD, wheel sets the speed
    int orbit_mode;       // the orbit camera (C): the right button orbits the view's centre
    int dynamic_res;      // lower the resolution while moving (L)
    double sun_turned_at; // when the rotating light last turned (seconds)
    double pivot[3];      // orbit pivot of the current drag
    // Alt+right drag: right/left sizes the brush, up/down its strength; the cursor stays
    // where the drag began and one `tool` command applies the result on release.
    double resize_x0, resize_y0, resize_r0, resize_s0, resize_radius, resize_strength;
    double resize_at[3];
    int key_down[MOVE_KEY_COUNT];
    double key_since[MOVE_KEY_COUNT], key_held[MOVE_KEY_COUNT]; // seconds, see bank_keys
    int dirty;                                                  // something changed: draw a frame
    int settled;       // frames in a row with every level current
    int pending;       // levels (or layers) still waiting for tiles
    int render_failed; // the renderer refused this world (a planet): said once
    char title[512];
    char stdin_buf[8192];
    size_t stdin_len;
    int stdin_open;

    // The editor's UI over the viewport.
    ui_font *font;
    ui_context *ui;
    ui_renderer *uir;
    editor_ui ed;
    ui_input in;       // input gathered since the last UI frame
    int ui_dirty;      // input or state changed: build and draw the UI again
    ui_rect view_rect; // the viewport's part of the window (window coordinates)
    const char *gl_renderer;

    // The terrain image, reused while only the UI changes; rendered at a lower
    // resolution while the camera moves or a stroke is drawn (dynamic resolution).
    gl_target terrain;
    gl_target terrain_smooth; // the terrain image with its edges smoothed (full-size frames)
    int smooth_shown;         // compose shows terrain_smooth
    int smooth_owed;          // the image wants smoothing once the view is still
    int smooth_failed;        // the pass failed once (reported): not tried again
    int terrain_valid;
    float res_scale;
    double terrain_ms; // wall time of the last terrain frame
    double target_ms;  // frame-time goal while moving
    camera drawn_cam;  // what the terrain image shows
    render_settings drawn_settings;
    brush_cursor drawn_cursor;
    float drawn_scale;
    int drawn_w, drawn_h;
    int world_changed;  // change notifications since the terrain image
    sculpt_drag sculpt; // the left button's sculpting drag
    double px_scale;    // framebuffer pixels per window unit (HiDPI)
    app_settings settings;
    char settings_path[4096], history_path[4096];

    // Every action's command text runs through this queue; long work runs off this
    // thread, and while it does the window shows its progress over the last frame.
    work_queue work;
    ui_context *busy_ui;  // the progress bar and Cancel button of long work
    double busy_drawn_ms; // when the progress was last drawn
    int close_after_work; // the close button was pressed while work ran
} window_state;

// The window whose UI the ui_widgets command reports (one window per process).
static window_state *current_window;

static void report(const char *what, const og_error *err) {
    fprintf(stderr, "orogen: %s: %s\n", what, err->msg);
}

// --- picking -----------------------------------------------------------------------

// The terrain point under window position (x, y): the ray through that pixel marched
// against the heights the renderer holds (what is on screen), one coarse sample steps.
static int pick_at(window_state *st, double x, double y, double hit[3]) {
    ui_rect r = st->view_rect;
    if (!st->v->renderer || r.w <= 0 || r.h <= 0) return -1;
    return viewport_pick_loaded(st->v, st->ctx->world, (x - r.x) / r.w, (y - r.y) / r.h,
                                (double)r.w / r.h, hit);
}

static int in_view(const window_state *st, double x, double y) {
    return ui_rect_contains(st->view_rect, (float)x, (float)y);
}

// Whether a cursor position (window coordinates) lies inside the window.
static int in_window(GLFWwindow *win, double x, double y) {
    int w, h;
    glfwGetWindowSize(win, &w, &h);
    return x >= 0 && y >= 0 && x < w && y < h;
}

// A point along the ray under (x, y) when no terrain is there: `dist` metres out.
static void point_along_ray(window_state *st, double x, double y, double dist, double out[3]) {
    ui_rect r = st->view_rect;
    double dir[3];
    camera_ray(&st->v->cam, r.w > 0 && r.h > 0 ? (double)r.w / r.h : 1.0,
               r.w > 0 ? (x - r.x) / r.w : 0.5, r.h > 0 ? (y - r.y) / r.h : 0.5, dir);
    for (int i = 0; i < 3; i++)
        out[i] = st->v->cam.pos[i] + dir[i] * dist;
}

// --- sculpting ---------------------------------------------------------------------

static sculpt_view sculpt_view_of(const window_state *st) {
    return (sculpt_view){st->v, st->view_rect};
}

// Ctrl held inverts the tool for the stroke, Shift smooths instead (Unreal, Terrain3D);
// for the volume tools Ctrl swaps fill and carve and Shift smooths in 3D.
static void sculpt_begin(window_state *st, int mods) {
    st->dirty = st->ui_dirty = 1;
    sculpt_drag_begin(&st->sculpt, &st->work, st->ctx, sculpt_view_of(st), st->mouse_x, st->mouse_y,
                      (mods & GLFW_MOD_SHIFT) != 0, (mods & GLFW_MOD_CONTROL) != 0);
}

static void sculpt_to(window_state *st, double x, double y) {
    if (st->drag != DRAG_SCULPT) return;
    st->dirty = st->ui_dirty = 1;
    sculpt_drag_to(&st->sculpt, &st->work, sculpt_view_of(st), x, y);
}

// Commits the drag's stroke (one undo step); a stroke that laid no dab leaves no step.
// The console shows the drag as one line rather than a line per mouse move.
static void sculpt_end(window_state *st) {
    if (st->drag != DRAG_SCULPT) return;
    st->drag = DRAG_NONE;
    st->dirty = st->ui_dirty = 1;
    int points = sculpt_drag_end(&st->sculpt, &st->work);
    char echo[128];
    snprintf(echo, sizeof echo, "> stroke_begin; stroke_to ... (%d points); stroke_end", points);
    console_add(&st->ed.console, CONSOLE_ECHO, echo);
}

// --- the brush on screen -------------------------------------------------------------

static void run_commands(window_state *st, const char *text, const char *label);

static const char *tool_name(const brush *b) {
    return b->tool == BRUSH_RAISE && b->invert ? "lower" : brush_tool_name(b->tool);
}

static void resize_begin(window_state *st) {
    if (pick_at(st, st->mouse_x, st->mouse_y, st->resize_at) != 0) return; // no terrain there
    st->drag = DRAG_RESIZE;
    st->resize_x0 = st->mouse_x, st->resize_y0 = st->mouse_y;
    st->resize_radius = st->resize_r0 = st->ctx->brush.radius;
    st->resize_strength = st->resize_s0 = st->ctx->brush.strength;
}

static void resize_to(window_state *st, double x, double y) {
    double r = st->resize_r0 * pow(1.01, x - st->resize_x0); // 1% a pixel
    st->resize_radius = fmin(fmax(r, 0.5), 5000);
    st->resize_strength = fmin(fmax(st->resize_s0 - 0.004 * (y - st->resize_y0), 0), 1);
}

static void resize_end(window_state *st) {
    st->drag = DRAG_NONE;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "tool %s radius=%.4g strength=%.3g", tool_name(&st->ctx->brush),
             st->resize_radius, st->resize_strength);
    run_commands(st, cmd, "resize");
}

// --- the camera --------------------------------------------------------------------

static int planet_ground(void *user, const double pos[3], double *h) {
    window_state *st = user;
    og_error err = {{0}};
    return planet_surface_height(st->ctx->world, pos, h, &err); // floats on the sea
}

static void reset_camera(window_state *st) {
    og_error err = {{0}};
    st->cc.walk = 0;
    const world_params *p = world_get_params(st->ctx->world);
    st->cc.planet_radius = p->kind == WORLD_PLANET ? p->radius : 0;
    st->cc.planet_ground = planet_ground;
    st->cc.planet_user = st;
    st->render_failed = 0;
    if (viewport_default_camera(st->v, st->ctx->world, &err) != 0) report("camera", &err);
    st->v->cam_world_serial = st->ctx->world_serial;
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

// Queues text as an action that is echoed in the console.
static void run_commands(window_state *st, const char *text, const char *label) {
    work_queue_add(&st->work, text, label, WORK_ECHO);
    st->ui_dirty = 1;
    st->dirty = 1;
}

static int submit_console_line(void *user, const char *text) {
    window_state *st = user;
    run_commands(st, text, "console");
    return 0;
}

// Runs what is queued (waiting up to a frame for work to end); after it the window
// shows whatever changed.
static void pump_work(window_state *st) {
    camera before = st->v->cam;
    work_queue_pump(&st->work, 30);
    if (work_queue_busy(&st->work)) return;
    if (work_queue_take_ran(&st->work)) {
        fflush(stdout);
        st->dirty = st->ui_dirty = 1;
        if (memcmp(&before, &st->v->cam, sizeof before) != 0) st->cc.walk = 0; // `camera`
    }
    if (st->work.stroke_cancelled) { // Esc or Cancel ended the stroke: the drag is over
        st->work.stroke_cancelled = 0;
        if (st->drag == DRAG_SCULPT) st->drag = DRAG_NONE;
        sculpt_drag_cancelled(&st->sculpt);
    }
    // A planet drag's moves during the job, picked now the world is free.
    sculpt_drag_flush(&st->sculpt, &st->work, sculpt_view_of(st));
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
            if (work_queue_busy(&st->work) &&
                cmd_text_all_flagged(st->stdin_buf, strlen(st->stdin_buf), CMD_WHILE_BUSY)) {
                // A question about the window itself, answered while work runs.
                cmd_context side = {.out = stdout};
                og_error err = {{0}};
                if (cmd_run(&side, st->stdin_buf, strlen(st->stdin_buf), "console", &err) != 0)
                    fprintf(stderr, "%s\n", err.msg);
                fflush(stdout);
            } else {
                run_commands(st, st->stdin_buf, "console");
            }
            size_t used = (size_t)(nl - st->stdin_buf) + 1;
            memmove(st->stdin_buf, nl + 1, st->stdin_len - used);
            st->stdin_len -= used;
        }
        if (st->stdin_len == sizeof st->stdin_buf - 1) {
            fprintf(stderr, "console: line longer than %zu bytes ignored\n", sizeof st->stdin_buf);
            st->stdin_len = 0;
        }
    }
}

// --- GLFW input --------------------------------------------------------------------

// Window coordinates to the UI's (framebuffer) pixels.
static float ui_px(const window_state *st, double v) {
    return (float)(v * st->px_scale);
}

// Framebuffer pixels per window unit, kept from the size callbacks: asking the window
// system on every pointer event would be a round trip to the X server each time.
static void update_px_scale(window_state *st) {
    int ww, fw, h;
    glfwGetWindowSize(st->win, &ww, &h);
    glfwGetFramebufferSize(st->win, &fw, &h);
    st->px_scale = ww > 0 && fw > 0 ? (double)fw / ww : 1.0;
}

static void on_framebuffer_size(GLFWwindow *win, int width, int height) {
    (void)width, (void)height;
    window_state *st = glfwGetWindowUserPointer(win);
    update_px_scale(st);
    st->ui_dirty = st->dirty = 1;
}

static void on_mouse_button(GLFWwindow *win, int button, int action, int mods) {
    window_state *st = glfwGetWindowUserPointer(win);
    st->ui_dirty = 1;
    int b = button == GLFW_MOUSE_BUTTON_LEFT     ? 0
            : button == GLFW_MOUSE_BUTTON_RIGHT  ? 1
            : button == GLFW_MOUSE_BUTTON_MIDDLE ? 2
                                                 : -1;
    if (b >= 0) {
        if (action == GLFW_PRESS) {
            st->in.mouse_pressed[b] = 1;
            double now = glfwGetTime();
            static double last_left;
            if (b == 0) {
                st->in.double_click = now - last_left < 0.35;
                last_left = now;
            }
        } else {
            st->in.mouse_released[b] = 1;
        }
        st->in.mouse_down[b] = action == GLFW_PRESS;
    }
    // While long work runs only its Cancel button answers; a stroke's release still
    // ends the stroke (queued after its points).
    if (work_queue_busy(&st->work)) {
        if (action == GLFW_RELEASE && button == GLFW_MOUSE_BUTTON_LEFT) sculpt_end(st);
        if (action == GLFW_RELEASE) st->drag = DRAG_NONE, st->looking = 0;
        return;
    }
    // Presses over the UI (or outside the viewport) are the UI's; releases always end
    // the viewport's drags.
    int ui_owns = !in_view(st, st->mouse_x, st->mouse_y) ||
                  ui_captures_point(st->ui, st->in.mouse_x, st->in.mouse_y);
    if (action == GLFW_PRESS && ui_owns) return;
    st->dirty = 1;
    // Drags start where the last motion event left the cursor (not where the pointer
    // is now: events queue up, and querying would skip the moves between).
    if (button == GLFW_MOUSE_BUTTON_RIGHT && st->drag == DRAG_RESIZE && action == GLFW_RELEASE) {
        resize_end(st);
        return;
    }
    if (button == GLFW_MOUSE_BUTTON_RIGHT && (mods & GLFW_MOD_ALT) && action == GLFW_PRESS &&
        st->drag == DRAG_NONE && !st->ed.stamps.active) {
        resize_begin(st);
        return;
    }
    if (button == GLFW_MOUSE_BUTTON_RIGHT && st->orbit_mode && !st->cc.walk) {
        if (action == GLFW_RELEASE) {
            if (st->drag == DRAG_ORBIT) st->drag = DRAG_NONE;
        } else if (st->drag == DRAG_NONE) { // the orbit camera turns about the view's centre
            ui_rect r = st->view_rect;
            double cx = r.x + r.w * 0.5, cy = r.y + r.h * 0.5;
            st->drag = DRAG_ORBIT;
            if (pick_at(st, cx, cy, st->pivot) != 0) point_along_ray(st, cx, cy, 100.0, st->pivot);
        }
        return;
    }
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
    } else if (st->ed.picking_height && button == GLFW_MOUSE_BUTTON_LEFT) {
        double hit[3]; // the tool's height from the terrain (the Pick button)
        st->ed.picking_height = 0;
        if (pick_at(st, st->mouse_x, st->mouse_y, hit) == 0) {
            char cmd[128];
            snprintf(cmd, sizeof cmd, "tool %s height=%.6g", tool_name(&st->ctx->brush), hit[1]);
            run_commands(st, cmd, "pick");
        }
    } else if (st->ed.shape_placing && button == GLFW_MOUSE_BUTTON_LEFT) {
        double hit[3]; // a 3D shape: its clicks, then its command
        char cmd[512];
        if (pick_at(st, st->mouse_x, st->mouse_y, hit) == 0 &&
            editor_ui_shape_click(&st->ed, st->ctx, hit, cmd, sizeof cmd) == 1)
            run_commands(st, cmd, "shape");
    } else if (st->ed.stamps.active && button == GLFW_MOUSE_BUTTON_LEFT) {
        double hit[3]; // the stamp tool: one click, one stamp at the picked point
        char cmd[512];
        if (pick_at(st, st->mouse_x, st->mouse_y, hit) == 0) {
            double x = hit[0], z = hit[2], s, t;
            int face = -1;
            if (world_get_params(st->ctx->world)->kind == WORLD_PLANET) { // that face's metres
                world_grid_direction_face(hit, &face, &s, &t);
                sculpt_face_metres(world_get_params(st->ctx->world), face, hit, &x, &z);
            }
            if (stamp_browser_command(&st->ed.stamps, x, z, cmd, sizeof cmd) == 0) {
                if (face >= 0) {
                    size_t used = strlen(cmd);
                    snprintf(cmd + used, sizeof cmd - used, " face=%d", face);
                }
                run_commands(st, cmd, "stamp");
            }
        }
    } else {
        st->drag = DRAG_SCULPT;
        sculpt_begin(st, mods);
    }
}

static void on_cursor(GLFWwindow *win, double x, double y) {
    window_state *st = glfwGetWindowUserPointer(win);
    double dx = x - st->mouse_x, dy = y - st->mouse_y;
    st->mouse_x = x, st->mouse_y = y;
    st->in.mouse_x = ui_px(st, x);
    st->in.mouse_y = ui_px(st, y);
    st->ui_dirty = 1;
    // The brush cursor moves with the pointer over the viewport.
    if (st->drag != DRAG_NONE || st->looking || in_view(st, x, y)) st->dirty = 1;
    if (work_queue_busy(&st->work)) { // the camera waits; a stroke's points queue up
        sculpt_to(st, x, y);
        return;
    }
    if (st->drag == DRAG_RESIZE)
        resize_to(st, x, y);
    else if (st->drag == DRAG_ORBIT)
        camera_controls_orbit(&st->cc, &st->v->cam, st->pivot, dx, dy);
    else if (st->drag == DRAG_SCULPT)
        sculpt_to(st, x, y);
    if (st->looking) camera_controls_look(&st->cc, &st->v->cam, dx, dy);
}

static void on_cursor_enter(GLFWwindow *win, int entered) {
    window_state *st = glfwGetWindowUserPointer(win);
    st->mouse_in = entered;
    st->dirty = 1;
    // A pointer that left (with no button held) hovers nothing: no widget stays lit and no
    // tooltip comes up for a place the pointer no longer is.
    if (!entered && !st->in.mouse_down[0] && !st->in.mouse_down[1] && !st->in.mouse_down[2]) {
        st->in.mouse_x = st->in.mouse_y = -1e6f;
        st->ui_dirty = 1;
    }
}

static void on_scroll(GLFWwindow *win, double dx, double dy) {
    (void)dx;
    window_state *st = glfwGetWindowUserPointer(win);
    st->ui_dirty = 1;
    if (work_queue_busy(&st->work)) return;
    if (!in_view(st, st->mouse_x, st->mouse_y) ||
        ui_captures_point(st->ui, st->in.mouse_x, st->in.mouse_y)) {
        st->in.wheel += (float)dy;
        return;
    }
    st->dirty = 1;
    if (st->looking) {
        camera_controls_speed_wheel(&st->cc, dy);
        return;
    }
    int ctrl = glfwGetKey(win, GLFW_KEY_LEFT_CONTROL) || glfwGetKey(win, GLFW_KEY_RIGHT_CONTROL);
    int shift = glfwGetKey(win, GLFW_KEY_LEFT_SHIFT) || glfwGetKey(win, GLFW_KEY_RIGHT_SHIFT);
    if (st->ed.stamps.active && (ctrl || shift)) { // the stamp preview: size and turn
        stamp_browser *b = &st->ed.stamps;
        if (ctrl) b->scale = fmin(20, fmax(0.1, b->scale * pow(1.1, dy)));
        if (shift) b->rotation = fmod(b->rotation + 5 * dy + 540, 360) - 180;
        st->ui_dirty = 1;
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
                        "or use File > Save as (after that, Ctrl+S saves it there)\n");
        return;
    }
    if (world_file_errors(st->ctx->world) || world_read_only(st->ctx->world)[0]) {
        editor_ui_save(&st->ed, st->ctx); // asks first: saving would lose something
        st->ui_dirty = 1;
        return;
    }
    run_commands(st, "save", "Ctrl+S");
}

// GLFW keys the UI uses.
static int ui_key_of(int key) {
    switch (key) {
    case GLFW_KEY_TAB:
        return UI_KEY_TAB;
    case GLFW_KEY_ENTER:
    case GLFW_KEY_KP_ENTER:
        return UI_KEY_ENTER;
    case GLFW_KEY_ESCAPE:
        return UI_KEY_ESCAPE;
    case GLFW_KEY_BACKSPACE:
        return UI_KEY_BACKSPACE;
    case GLFW_KEY_DELETE:
        return UI_KEY_DELETE;
    case GLFW_KEY_LEFT:
        return UI_KEY_LEFT;
    case GLFW_KEY_RIGHT:
        return UI_KEY_RIGHT;
    case GLFW_KEY_UP:
        return UI_KEY_UP;
    case GLFW_KEY_DOWN:
        return UI_KEY_DOWN;
    case GLFW_KEY_HOME:
        return UI_KEY_HOME;
    case GLFW_KEY_END:
        return UI_KEY_END;
    case GLFW_KEY_A:
        return UI_KEY_A;
    case GLFW_KEY_C:
        return UI_KEY_C;
    case GLFW_KEY_V:
        return UI_KEY_V;
    case GLFW_KEY_X:
        return UI_KEY_X;
    case GLFW_KEY_Z:
        return UI_KEY_Z;
    default:
        return -1;
    }
}

static void on_char(GLFWwindow *win, unsigned int codepoint) {
    window_state *st = glfwGetWindowUserPointer(win);
    st->ui_dirty = 1;
    if (work_queue_busy(&st->work)) return;
    if (!ui_wants_keyboard(st->ui)) return; // typed into the viewport: shortcuts
    char u[5] = {0};
    if (codepoint < 0x80)
        u[0] = (char)codepoint;
    else if (codepoint < 0x800)
        u[0] = (char)(0xC0 | codepoint >> 6), u[1] = (char)(0x80 | (codepoint & 0x3F));
    else if (codepoint < 0x10000)
        u[0] = (char)(0xE0 | codepoint >> 12), u[1] = (char)(0x80 | ((codepoint >> 6) & 0x3F)),
        u[2] = (char)(0x80 | (codepoint & 0x3F));
    else
        u[0] = (char)(0xF0 | codepoint >> 18), u[1] = (char)(0x80 | ((codepoint >> 12) & 0x3F)),
        u[2] = (char)(0x80 | ((codepoint >> 6) & 0x3F)), u[3] = (char)(0x80 | (codepoint & 0x3F));
    size_t n = strlen(st->in.text);
    if (n + strlen(u) < sizeof st->in.text) memcpy(st->in.text + n, u, strlen(u) + 1);
}

// Fly, orbit or walk (C, View > Camera): seed 004's camera switch.
static void set_camera_mode(window_state *st, int mode) {
    bank_keys(st);
    st->orbit_mode = mode == 1;
    if ((mode == 2) != st->cc.walk)
        camera_controls_toggle_walk(&st->cc, &st->v->cam, ground_height, st);
    st->dirty = st->ui_dirty = 1;
}

static int camera_mode(const window_state *st) {
    return st->cc.walk ? 2 : st->orbit_mode ? 1 : 0;
}

static void toggle_console(window_state *st) {
    st->ed.console.open = !st->ed.console.open;
    st->ed.console.focus_input = st->ed.console.open;
}

static void on_key(GLFWwindow *win, int key, int scancode, int action, int mods) {
    (void)scancode;
    window_state *st = glfwGetWindowUserPointer(win);
    st->ui_dirty = 1;
    st->in.mods = ((mods & GLFW_MOD_SHIFT) ? UI_MOD_SHIFT : 0) |
                  ((mods & GLFW_MOD_CONTROL) ? UI_MOD_CTRL : 0) |
                  ((mods & GLFW_MOD_ALT) ? UI_MOD_ALT : 0);
    int k = ui_key_of(key);
    if (k >= 0 && action != GLFW_RELEASE) st->in.key_pressed[k] = 1;
    if (work_queue_busy(&st->work)) { // Esc cancels long work; other keys wait for it
        if (action == GLFW_PRESS && key == GLFW_KEY_ESCAPE) work_queue_cancel(&st->work);
        for (int i = 0; i < MOVE_KEY_COUNT; i++) // a key let go is never left held
            if (key == move_key_codes[i] && action == GLFW_RELEASE) st->key_down[i] = 0;
        return;
    }
    // A focused text field takes every key; ~ still closes the console.
    if (ui_wants_keyboard(st->ui)) {
        if (action == GLFW_PRESS && key == GLFW_KEY_GRAVE_ACCENT && st->ed.console.open) {
            toggle_console(st);
            st->in.text[0] = 0;
        }
        return;
    }
    if (action == GLFW_PRESS && key == GLFW_KEY_ESCAPE) return; // the UI closes menus, dialogs
    st->dirty = 1;
    for (int i = 0; i < MOVE_KEY_COUNT; i++) {
        if (key != move_key_codes[i] || action == GLFW_REPEAT) continue;
        bank_keys(st);
        // Ctrl+S is a shortcut, not a step back.
        st->key_down[i] = action == GLFW_PRESS && !(mods & GLFW_MOD_CONTROL);
    }
    if (action != GLFW_PRESS) return;
    if (mods & GLFW_MOD_CONTROL) {
        if (key == GLFW_KEY_S && (mods & GLFW_MOD_SHIFT))
            editor_ui_save_as(&st->ed, st->ctx);
        else if (key == GLFW_KEY_O)
            editor_ui_open(&st->ed, st->ctx);
        else if (key == GLFW_KEY_S)
            save_shortcut(st);
        else if (key == GLFW_KEY_N)
            editor_ui_request(&st->ed, st->ctx, PENDING_NEW_FLAT);
        else if (key == GLFW_KEY_Q)
            editor_ui_request(&st->ed, st->ctx, PENDING_QUIT);
        else if (key == GLFW_KEY_Z && (mods & GLFW_MOD_SHIFT))
            run_commands(st, "redo", "Ctrl+Shift+Z");
        else if (key == GLFW_KEY_Z)
            run_commands(st, "undo", "Ctrl+Z");
        else if (key == GLFW_KEY_Y)
            run_commands(st, "redo", "Ctrl+Y");
        else if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_MINUS) { // seed 004's = and -
            int levels = st->v->settings.levels + (key == GLFW_KEY_EQUAL ? 1 : -1);
            if (levels >= RENDER_MIN_LEVELS && levels <= RENDER_MAX_LEVELS) {
                char cmd[64];
                snprintf(cmd, sizeof cmd, "render levels=%d", levels);
                run_commands(st, cmd, "key");
            }
        }
        return;
    }
    double hit[3];
    switch (key) {
    case GLFW_KEY_GRAVE_ACCENT:
        toggle_console(st);
        break;
    case GLFW_KEY_F1:
        st->ed.show_help = 1;
        break;
    case GLFW_KEY_LEFT_BRACKET: // brush size and strength, as in Terrain3D
    case GLFW_KEY_RIGHT_BRACKET:
    case GLFW_KEY_MINUS:
    case GLFW_KEY_EQUAL: {
        const brush *b = &st->ctx->brush;
        const char *name = tool_name(b);
        char cmd[128];
        if (key == GLFW_KEY_LEFT_BRACKET || key == GLFW_KEY_RIGHT_BRACKET) {
            double r = b->radius * (key == GLFW_KEY_RIGHT_BRACKET ? 1.15 : 1 / 1.15);
            snprintf(cmd, sizeof cmd, "tool %s radius=%.4g", name, fmin(fmax(r, 0.5), 5000));
        } else {
            double k = b->strength + (key == GLFW_KEY_EQUAL ? 0.05 : -0.05);
            snprintf(cmd, sizeof cmd, "tool %s strength=%.3g", name, fmin(fmax(k, 0), 1));
        }
        run_commands(st, cmd, "key");
        break;
    }
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
    case GLFW_KEY_5: {
        char cmd[64];
        snprintf(cmd, sizeof cmd, "view %s", view_mode_name((view_mode)(key - GLFW_KEY_1)));
        run_commands(st, cmd, "key");
        break;
    }
    case GLFW_KEY_C:
        set_camera_mode(st, (camera_mode(st) + 1) % 3);
        break;
    case GLFW_KEY_R: { // the light turns; on a planet at its omega (seed 004)
        const world_params *p = world_get_params(st->ctx->world);
        double speed = p->kind == WORLD_PLANET && p->omega != 0 ? p->omega * 180.0 / M_PI : 20.0;
        char cmd[64];
        snprintf(cmd, sizeof cmd, "render sun_rotation=%.6g",
                 st->v->settings.sun_rotation != 0 ? 0.0 : fmax(-360, fmin(360, speed)));
        run_commands(st, cmd, "key");
        break;
    }
    case GLFW_KEY_L:
        run_commands(st, st->dynamic_res ? "dynamic_resolution off" : "dynamic_resolution on",
                     "key");
        break;
    default:
        // One letter per tool, while the pointer is over the viewport.
        if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z && !st->looking &&
            in_view(st, st->mouse_x, st->mouse_y)) {
            int tool = editor_ui_tool_for_key('A' + (key - GLFW_KEY_A));
            if (tool >= 0) editor_ui_pick_tool(&st->ed, st->ctx, tool);
        }
        break;
    }
}

// Elevation rasters (not pictures): dropped, they are imported, not made stamps.
static int is_elevation_raster(const char *path) {
    static const char *const ext[] = {".hgt", ".tif", ".tiff", ".asc", ".r16",
                                      ".raw", ".dem", ".bil",  ".exr"};
    const char *dot = strrchr(path, '.');
    for (size_t i = 0; dot && i < sizeof ext / sizeof ext[0]; i++)
        if (strcasecmp(dot, ext[i]) == 0) return 1;
    return 0;
}

// Files dropped on the window: a world opens (asking first about unsaved changes), a
// heightmap (.hgt .tif .exr .r16 ...) is imported centred under the pointer, another
// image becomes a user stamp (stamp_add; the browser then selects it), anything else
// is refused with a message.
static void on_drop(GLFWwindow *win, int count, const char **paths) {
    window_state *st = glfwGetWindowUserPointer(win);
    st->ui_dirty = 1;
    for (int i = 0; i < count; i++) {
        const char *p = paths[i], *dot = strrchr(p, '.');
        char msg[4400];
        if (work_queue_busy(&st->work)) {
            snprintf(msg, sizeof msg, "%.4000s: dropped while work runs; drop it again after", p);
            console_add(&st->ed.console, CONSOLE_ERROR, msg);
            fprintf(stderr, "%s\n", msg);
        } else if (dot && (strcmp(dot, ".world") == 0 || strcmp(dot, ".planet") == 0)) {
            snprintf(st->ed.open_path, sizeof st->ed.open_path, "%.1023s", p);
            editor_ui_request(&st->ed, st->ctx, PENDING_OPEN);
        } else if (is_elevation_raster(p)) {
            // Imported centred on the point under the pointer (else where the file says).
            double hit[3], mx, my;
            char arg[4200], cmd[4400];
            cmd_quote_arg(arg, sizeof arg, p);
            glfwGetCursorPos(win, &mx, &my);
            if (pick_at(st, mx, my, hit) == 0)
                snprintf(cmd, sizeof cmd, "import %s x=%.3f z=%.3f anchor=centre", arg, hit[0],
                         hit[2]);
            else
                snprintf(cmd, sizeof cmd, "import %s", arg);
            run_commands(st, cmd, "drop");
        } else if (stamp_is_image_file(p)) {
            char arg[4200], cmd[4300];
            cmd_quote_arg(arg, sizeof arg, p);
            snprintf(cmd, sizeof cmd, "stamp_add %s", arg);
            stamp_browser_load(&st->ed.stamps,
                               st->ctx); // listed before, so the new one shows as new
            run_commands(st, cmd, "drop");
            st->ed.stamps.checked_at = 0; // look at the folder again at once
        } else {
            snprintf(
                msg, sizeof msg,
                "%.4000s: Orogen opens .world and .planet files, imports heightmaps (.hgt .tif "
                ".exr .r16 ...) and makes other images stamps",
                p);
            console_add(&st->ed.console, CONSOLE_ERROR, msg);
            fprintf(stderr, "%s\n", msg);
        }
    }
}

static void on_refresh(GLFWwindow *win) {
    window_state *st = glfwGetWindowUserPointer(win);
    st->dirty = 1;
    st->ui_dirty = 1;
}

// The close button asks first when there are unsaved changes.
static void on_close(GLFWwindow *win) {
    window_state *st = glfwGetWindowUserPointer(win);
    if (work_queue_busy(&st->work)) { // stop the work first, then ask as usual
        glfwSetWindowShouldClose(win, GLFW_FALSE);
        work_queue_cancel(&st->work);
        st->close_after_work = 1;
        return;
    }
    if (world_is_modified(st->ctx->world)) {
        glfwSetWindowShouldClose(win, GLFW_FALSE);
        editor_ui_request(&st->ed, st->ctx, PENDING_QUIT);
        st->ui_dirty = 1;
    }
}

// --- changes ------------------------------------------------------------------------

// Changes published from another thread (a job's edits, work_queue.c) must not wait
// for input: they wake the event loop.
static void wake_window(void *user) {
    (void)user;
    glfwPostEmptyEvent();
}

// Any change redraws; another world (new, load) gets its default camera unless a
// command placed the camera after it came (`new planet; camera_geo ...`).
static void take_changes(window_state *st) {
    world_event e[32];
    size_t n;
    while ((n = world_subscription_take(st->changes, e, 32)) > 0) {
        st->dirty = 1;
        st->ui_dirty = 1;              // the panels show the world (history, file, unsaved)
        for (size_t i = 0; i < n; i++) // saves and history steps leave the picture as it is
            st->world_changed |= e[i].kind == WORLD_EVENT_AREA || e[i].kind == WORLD_EVENT_PARAMS ||
                                 e[i].kind == WORLD_EVENT_REPLACED;
        for (size_t i = 0; i < n; i++)
            if (e[i].kind == WORLD_EVENT_REPLACED &&
                st->v->cam_world_serial != st->ctx->world_serial)
                reset_camera(st);
        if (n < 32) break;
    }
}

// --- the frame ---------------------------------------------------------------------

static void update_title(window_state *st) {
    char title[sizeof st->title], name[256];
    const char *path = world_path(st->ctx->world);
    const char *slash = strrchr(path, '/');
    snprintf(name, sizeof name, "%s%s", path[0] ? (slash ? slash + 1 : path) : "unsaved world",
             world_read_only(st->ctx->world)[0] ? " (read-only)" : "");
    const camera *c = &st->v->cam;
    render_stats rs = {0};
    if (st->v->renderer) terrain_renderer_stats(st->v->renderer, &rs);
    int used = st->v->settings.levels - rs.finest_level;
    if (st->render_failed)
        snprintf(title, sizeof title, "Orogen - %s%s - the viewport failed (see the console)", name,
                 world_is_modified(st->ctx->world) ? " *" : "");
    else
        snprintf(title, sizeof title,
                 "Orogen - %s%s - cam (%.1f, %.1f, %.1f) yaw %.1f pitch %.1f - %s %.3g m/s - "
                 "levels %d/%d - tool %s r%g - pending %d",
                 name, world_is_modified(st->ctx->world) ? " *" : "", c->pos[0], c->pos[1],
                 c->pos[2], c->yaw, c->pitch,
                 st->cc.walk      ? "walk"
                 : st->orbit_mode ? "orbit"
                                  : "fly",
                 camera_controls_speed(&st->cc), rs.levels_ready, used,
                 brush_tool_name(st->ctx->brush.tool), st->ctx->brush.radius, st->pending);
    if (strcmp(title, st->title) != 0) {
        snprintf(st->title, sizeof st->title, "%s", title);
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

static void update_cursor(window_state *st) {
    brush_cursor *bc = &st->v->cursor;
    double hit[3];
    bc->visible = st->mouse_in && !st->looking && st->drag != DRAG_ORBIT &&
                  (st->drag == DRAG_RESIZE || pick_at(st, st->mouse_x, st->mouse_y, hit) == 0);
    if (!bc->visible) return;
    if (st->drag == DRAG_RESIZE) memcpy(hit, st->resize_at, sizeof hit);
    bc->x = hit[0], bc->y = hit[1], bc->z = hit[2]; // y: planets drape it in 3D
    if (st->ed.stamps.active) { // the stamp's footprint: its half size, no falloff
        bc->radius =
            stamp_browser_half_size(&st->ed.stamps, world_get_params(st->ctx->world)->spacing);
        for (int i = 0; i < BRUSH_FALLOFF_SAMPLES; i++)
            bc->falloff[i] = 1.0f;
        bc->color[0] = bc->color[1] = bc->color[2] = 0.9f;
        bc->opacity = 0.25f;
        return;
    }
    const brush *b = &st->ctx->brush;
    bc->radius = st->drag == DRAG_RESIZE ? st->resize_radius : b->radius;
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
    double strength = st->drag == DRAG_RESIZE ? st->resize_strength : b->strength;
    bc->sphere = brush_tool_is_volume(b->tool) && st->drag != DRAG_RESIZE;
    if (bc->sphere) { // where the next point would go, as big as the ball it would lay
        double p[3];
        bc->visible =
            sculpt_volume_point(st->drag == DRAG_SCULPT ? &st->sculpt : NULL, b, sculpt_view_of(st),
                                st->mouse_x, st->mouse_y, hit, p) == 0;
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

// --- the UI and the terrain image ------------------------------------------------------

static const char *clipboard_get(void *user) {
    return glfwGetClipboardString(user);
}
static void clipboard_set(void *user, const char *text) {
    glfwSetClipboardString(user, text);
}

static void clear_frame_input(ui_input *in) {
    memset(in->mouse_pressed, 0, sizeof in->mouse_pressed);
    memset(in->mouse_released, 0, sizeof in->mouse_released);
    memset(in->key_pressed, 0, sizeof in->key_pressed);
    in->double_click = 0;
    in->wheel = 0;
    in->text[0] = 0;
}

// Builds this frame's UI (running the commands its widgets ask for); sets the
// viewport's rectangle. fw, fh: the framebuffer's size.
// Textures of the stamp thumbnails, once the browser has rendered them.
static int upload_stamp_thumbnails(stamp_browser *b) {
    if (!b->needs_upload) return 0;
    b->needs_upload = 0;
    for (int i = 0; i < b->count; i++)
        if (!b->entries[i].texture)
            b->entries[i].texture =
                ui_renderer_create_texture(STAMP_THUMB, STAMP_THUMB, b->entries[i].rgba);
    return 1;
}

// Lists the stamps again when the user's stamp folder changed (an image dropped on the
// window, stamp_add in the console, a file copied there by hand).
static void refresh_stamps(window_state *st) {
    stamp_browser *b = &st->ed.stamps;
    if (!stamp_browser_stale(b, st->ctx, glfwGetTime())) return;
    for (int i = 0; i < b->count; i++) {
        ui_renderer_delete_texture(b->entries[i].texture);
        b->entries[i].texture = 0;
    }
    stamp_browser_reload(b, st->ctx);
    st->ui_dirty = 1;
}

static const ui_draw_list *build_ui(window_state *st, int fw, int fh) {
    editor_frame_info info = {.frame_ms = st->terrain_ms,
                              .resolution_scale = st->drawn_scale,
                              .pending = st->pending,
                              .gl_renderer = st->gl_renderer,
                              .resizing = st->drag == DRAG_RESIZE,
                              .resize_radius = st->resize_radius,
                              .resize_strength = st->resize_strength};
    double hit[3];
    if (st->mouse_in && pick_at(st, st->mouse_x, st->mouse_y, hit) == 0) {
        info.cursor_valid = 1;
        memcpy(info.cursor, hit, sizeof hit);
    }
    st->in.time = glfwGetTime();
    refresh_stamps(st);
    st->ed.ui_scale = st->settings.ui_scale; // the ui_scale command may have changed it
    st->ed.camera_mode = camera_mode(st);
    st->ed.dynamic_resolution = st->dynamic_res;
    ui_begin(st->ui, &st->in, (float)fw, (float)fh);
    ui_rect vr = editor_ui_build(&st->ed, st->ui, st->ctx, st->v, &info, (float)fw, (float)fh);
    const ui_draw_list *dl = ui_end(st->ui);
    clear_frame_input(&st->in);
    float k = ui_px(st, 1.0); // framebuffer pixels per window unit
    st->view_rect = (ui_rect){vr.x / k, vr.y / k, vr.w / k, vr.h / k};
    if (st->ed.quit_requested) glfwSetWindowShouldClose(st->win, GLFW_TRUE);
    st->ui_dirty = upload_stamp_thumbnails(&st->ed.stamps); // shown from the next frame
    return dl;
}

static double now_ms(void) {
    return glfwGetTime() * 1e3;
}

// The still, full-size terrain image with its edges smoothed into terrain_smooth: one
// pass over the image, never a new render (and never while moving, where it would
// cost every frame). Returns 1 when compose shows the smoothed image.
static int smooth_terrain(window_state *st) {
    og_error err = {{0}};
    const gl_target *t = &st->terrain;
    if (st->terrain_smooth.width != t->width || st->terrain_smooth.height != t->height) {
        gl_target_destroy(&st->terrain_smooth);
        if (gl_target_create(&st->terrain_smooth, t->width, t->height, &err) != 0) goto failed;
    }
    if (viewport_antialias(st->v, t, &st->terrain_smooth, &err) != 0) goto failed;
    st->smooth_shown = 1;
    st->smooth_owed = 0;
    return 1;
failed:
    report("viewport", &err);
    st->smooth_failed = 1;
    st->smooth_owed = 0;
    return 0;
}

// Renders the terrain into its own image when something it shows changed: the camera,
// the world, the view settings, the brush cursor, the viewport's size, or newly
// arrived tiles. While the camera moves or a stroke is drawn the image is rendered
// smaller, sized to keep the frame near target_ms. Returns 1 when it rendered.
static int render_terrain(window_state *st, int vw, int vh, int arrived) {
    viewport *v = st->v;
    if (vw <= 0 || vh <= 0) return 0;
    update_cursor(st);
    // The cursor is drawn with the terrain: while it moves the frame is made at the
    // moving scale too, so it follows the pointer at the frame-time goal.
    int moving = memcmp(&v->cam, &st->drawn_cam, sizeof v->cam) != 0 || st->drag == DRAG_SCULPT ||
                 v->settings.sun_rotation != 0 ||
                 memcmp(&v->cursor, &st->drawn_cursor, sizeof v->cursor) != 0 ||
                 st->drag == DRAG_ORBIT || keys_held(st);
    float scale = moving && st->dynamic_res ? st->res_scale : 1.0f;
    int w = (int)fmaxf(1.0f, roundf(vw * scale)), h = (int)fmaxf(1.0f, roundf(vh * scale));
    int changed = !st->terrain_valid || arrived || st->world_changed ||
                  memcmp(&v->cam, &st->drawn_cam, sizeof v->cam) != 0 ||
                  memcmp(&v->settings, &st->drawn_settings, sizeof v->settings) != 0 ||
                  memcmp(&v->cursor, &st->drawn_cursor, sizeof v->cursor) != 0 ||
                  w != st->drawn_w || h != st->drawn_h;
    int wants_smooth = render_settings_smooth_edges(&v->settings) && !st->render_failed &&
                       !st->smooth_failed && scale == 1.0f;
    if (!changed) { // the view came to rest on a full-size image: smooth it now
        if (wants_smooth && !moving && !st->smooth_shown && st->terrain_valid)
            return smooth_terrain(st);
        return 0;
    }
    og_error err = {{0}};
    if (st->terrain.width != w || st->terrain.height != h) {
        gl_target_destroy(&st->terrain);
        if (gl_target_create(&st->terrain, w, h, &err) != 0) {
            report("viewport", &err);
            return 0;
        }
    }
    double t0 = now_ms();
    glBindFramebuffer(GL_FRAMEBUFFER, st->terrain.fbo);
    if (st->render_failed) {
        glViewport(0, 0, w, h);
        glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    } else if (terrain_renderer_draw(v->renderer, st->ctx->world, &v->cam, &v->settings, &v->cursor,
                                     w, h, &err) != 0) {
        report("viewport", &err);
    }
    st->smooth_shown = 0;
    st->smooth_owed = wants_smooth;
    if (wants_smooth && !moving) smooth_terrain(st);
    glFinish(); // the frame's real cost, for the resolution controller
    st->terrain_ms = now_ms() - t0;
    if (moving)
        st->res_scale = dynamic_resolution_next(st->res_scale, st->terrain_ms, st->target_ms);
    st->drawn_cam = v->cam;
    st->drawn_settings = v->settings;
    st->drawn_cursor = v->cursor;
    st->drawn_scale = scale;
    st->drawn_w = w, st->drawn_h = h;
    st->world_changed = 0;
    st->terrain_valid = 1;
    return 1;
}

// The window's picture: the terrain image in the viewport's rectangle, the UI over it.
static void compose(window_state *st, const ui_draw_list *dl, int fw, int fh) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fw, fh);
    const ui_theme *t = ui_get_theme(st->ui);
    glClearColor((t->bg & 255) / 255.0f, ((t->bg >> 8) & 255) / 255.0f,
                 ((t->bg >> 16) & 255) / 255.0f, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    float k = ui_px(st, 1.0);
    int vx = (int)roundf(st->view_rect.x * k), vy = (int)roundf(st->view_rect.y * k);
    int vw = (int)roundf(st->view_rect.w * k), vh = (int)roundf(st->view_rect.h * k);
    const gl_target *image = st->smooth_shown ? &st->terrain_smooth : &st->terrain;
    if (st->terrain_valid && vw > 0 && vh > 0)
        glBlitNamedFramebuffer(image->fbo, 0, 0, 0, image->width, image->height, vx, fh - (vy + vh),
                               vx + vw, fh - vy, GL_COLOR_BUFFER_BIT, GL_LINEAR);
    og_error err = {{0}};
    if (dl && ui_renderer_draw(st->uir, dl, st->font, fw, fh, &err) != 0) report("ui", &err);
}

// While long work runs: the last frame with a progress bar and a Cancel button over
// its status bar, drawn at most ten times a second (none for work under 150 ms).
static void draw_busy(window_state *st, const ui_draw_list *dl, int fw, int fh) {
    cmd_job *job = st->work.job;
    double elapsed = cmd_job_elapsed_ms(job), t = now_ms();
    if (elapsed < 150 || (t - st->busy_drawn_ms < 100 && !st->ui_dirty)) return;
    st->busy_drawn_ms = t;
    st->ui_dirty = 0;
    st->in.time = glfwGetTime();
    ui_begin(st->busy_ui, &st->in, (float)fw, (float)fh);
    const char *what = (st->work.running.flags & WORK_STROKE) ? "the stroke's dabs along the drag"
                                                              : cmd_job_text(job);
    if (editor_ui_build_busy(st->busy_ui, what, cmd_job_progress(job), elapsed, (float)fw,
                             (float)fh))
        work_queue_cancel(&st->work);
    const ui_draw_list *busy = ui_end(st->busy_ui);
    clear_frame_input(&st->in);
    compose(st, dl, fw, fh);
    og_error err = {{0}};
    if (ui_renderer_draw(st->uir, busy, st->font, fw, fh, &err) != 0) report("ui", &err);
    glfwSwapBuffers(st->win);
    char title[sizeof st->title];
    snprintf(title, sizeof title, "Orogen - working %.0f%% - Esc cancels",
             cmd_job_progress(job) * 100);
    if (strcmp(title, st->title) != 0) {
        snprintf(st->title, sizeof st->title, "%s", title);
        glfwSetWindowTitle(st->win, title);
    }
}

// The UI's fonts: DejaVu from fonts-dejavu-core ($OROGEN_FONT_DIR overrides the folder),
// at 15 px times the monitor's content scale times the user's UI scale.
static ui_font *load_font(GLFWwindow *win, double user, og_error *err) {
    const char *dir = getenv("OROGEN_FONT_DIR");
    if (!dir || !*dir) dir = "/usr/share/fonts/truetype/dejavu";
    char sans[4200], mono[4200], why[512];
    snprintf(sans, sizeof sans, "%s/DejaVuSans.ttf", dir);
    snprintf(mono, sizeof mono, "%s/DejaVuSansMono.ttf", dir);
    float xs = 1, ys = 1;
    glfwGetWindowContentScale(win, &xs, &ys);
    ui_font *f =
        ui_font_create(sans, mono, roundf(15.0f * fmaxf(xs, 1.0f) * (float)user), why, sizeof why);
    if (!f) og_error_set(err, "the UI's font: %s (install fonts-dejavu-core)", why);
    return f;
}

// Changes the UI scale: a new font at the new size (the renderer re-uploads its atlas).
static int set_ui_scale(window_state *st, double scale, og_error *err) {
    ui_font *f = load_font(st->win, scale, err);
    if (!f) return -1;
    ui_set_font(st->ui, f);
    ui_set_font(st->busy_ui, f);
    ui_font_destroy(st->font);
    st->font = f;
    st->settings.ui_scale = scale;
    st->ui_dirty = 1;
    return 0;
}

// ui_scale [FACTOR]: the editor's UI scale (times the monitor's content scale).
static int cmd_ui_scale(cmd_context *ctx, int argc, char **argv, og_error *err) {
    window_state *st = current_window;
    if (!st) return og_error_set(err, "ui_scale: no editor window is open");
    if (argc == 1) {
        fprintf(ctx->out, "ui_scale %g\n", st->settings.ui_scale);
        return 0;
    }
    double v;
    if (parse_number_in(argv[1], "FACTOR", 0.5, 4, &v, err) != 0) return -1;
    return set_ui_scale(st, v, err);
}

// dynamic_resolution [on|off]: lower the viewport's resolution while moving (L).
static int cmd_dynamic_resolution(cmd_context *ctx, int argc, char **argv, og_error *err) {
    window_state *st = current_window;
    if (!st) return og_error_set(err, "dynamic_resolution: no editor window is open");
    if (argc > 1 && parse_switch(argv[1], "dynamic_resolution", &st->dynamic_res, err) != 0)
        return -1;
    st->dirty = st->ui_dirty = 1;
    fprintf(ctx->out, "dynamic_resolution %s (target %g ms)\n", st->dynamic_res ? "on" : "off",
            st->target_ms);
    return 0;
}

// ui_widgets: the named widgets of the last UI frame, for tests that click by name.
static int cmd_ui_widgets(cmd_context *ctx, int argc, char **argv, og_error *err) {
    window_state *st = current_window;
    if (!st) return og_error_set(err, "ui_widgets: no editor window is open");
    float k = ui_px(st, 1.0);
    const char *filter = argc > 1 ? argv[1] : NULL;
    fprintf(ctx->out, "Viewport %.0f %.0f %.0f %.0f\n", st->view_rect.x, st->view_rect.y,
            st->view_rect.w, st->view_rect.h);
    // While long work runs, its progress bar and Cancel button are listed after the rest.
    ui_context *uis[2] = {st->ui, work_queue_busy(&st->work) ? st->busy_ui : NULL};
    for (int u = 0; u < 2 && uis[u]; u++)
        for (size_t i = 0; i < ui_widget_count(uis[u]); i++) {
            const ui_widget_info *w = ui_widget_at(uis[u], i);
            if (!w->name[0] || (filter && !strstr(w->name, filter))) continue;
            fprintf(ctx->out, "%s %.0f %.0f %.0f %.0f\n", w->name, w->rect.x / k, w->rect.y / k,
                    w->rect.w / k, w->rect.h / k);
        }
    return 0;
}

// window_screenshot FILE: the whole window (UI and viewport) as an RGB PNG, once every
// tile in view has arrived, with the terrain at full resolution.
static int cmd_window_screenshot(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc;
    window_state *st = current_window;
    if (!st) return og_error_set(err, "window_screenshot: no editor window is open");
    int w, h;
    glfwGetFramebufferSize(st->win, &w, &h);
    if (w <= 0 || h <= 0) return og_error_set(err, "window_screenshot: the window has no area");
    float k = ui_px(st, 1.0);
    take_changes(st); // a world made earlier in the same batch of commands gets its camera
    for (int i = 0; i < 60000 && !st->render_failed; i++) { // tiles: at most ~60 s
        update_view(st);
        if (st->settled >= 2) break;
        struct timespec pause = {0, 1000000};
        nanosleep(&pause, NULL);
    }
    const ui_draw_list *dl = build_ui(st, w, h);
    st->terrain_valid = 0; // full resolution, whatever was drawn while moving
    float keep = st->res_scale;
    st->res_scale = 1.0f;
    render_terrain(st, (int)roundf(st->view_rect.w * k), (int)roundf(st->view_rect.h * k), 1);
    if (st->smooth_owed) smooth_terrain(st); // as the view shows once it is still
    st->res_scale = keep;
    dl = build_ui(st, w, h); // the status bar with this frame's figures
    compose(st, dl, w, h);
    unsigned char *rgba = malloc((size_t)w * h * 4), *rgb = malloc((size_t)w * h * 3);
    if (!rgba || !rgb) {
        free(rgba), free(rgb);
        return og_error_set(err, "out of memory");
    }
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    for (int y = 0; y < h; y++) // GL's rows are bottom first
        for (int x = 0; x < w; x++)
            memcpy(rgb + ((size_t)y * w + x) * 3, rgba + ((size_t)(h - 1 - y) * w + x) * 4, 3);
    int rc = image_write_rgb8(argv[1], rgb, w, h, err);
    free(rgba), free(rgb);
    if (rc != 0) return -1;
    st->dirty = st->ui_dirty = 1; // the next frame is drawn normally again
    fprintf(ctx->out, "window_screenshot %s %dx%d\n", argv[1], w, h);
    return 0;
}

static const cmd_def window_commands[] = {
    {"window_screenshot", "window_screenshot FILE",
     "Writes the whole editor window (UI and viewport) to an RGB PNG once every tile in view has "
     "arrived.",
     1, 1, cmd_window_screenshot, CMD_NOT_RECORDED},
    {"ui_scale", "ui_scale [FACTOR]",
     "Sets the editor's UI scale (0.5-4, times the monitor's content scale; View > UI scale); "
     "without a value, prints it.",
     0, 1, cmd_ui_scale, CMD_NOT_RECORDED},
    {"dynamic_resolution", "dynamic_resolution [on|off]",
     "While the camera moves or a stroke is drawn, render the viewport at a lower resolution "
     "chosen to keep frames near the frame-time goal (L toggles it); without a value, prints it.",
     0, 1, cmd_dynamic_resolution, CMD_NOT_RECORDED},
    {"ui_widgets", "ui_widgets [FILTER]",
     "Lists the editor window's named widgets of the last frame as NAME X Y W H (window pixels; "
     "names containing FILTER), and the Viewport's rectangle first.",
     0, 1, cmd_ui_widgets, CMD_NOT_RECORDED | CMD_WHILE_BUSY},
};

int window_commands_register(og_error *err) {
    return cmd_register(window_commands, sizeof window_commands / sizeof window_commands[0], err);
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

// Swatches of the paint materials from the renderer's own procedural textures (a
// 64-pixel crop of each); "automatic" shows its rules' grass, rock and snow side by side.
static void make_material_swatches(uint32_t out[8], ui_color mean[8]) {
    enum { SWATCH = 64 };
    static unsigned char full[MATERIAL_TEXTURE_COUNT]
                             [MATERIAL_TEXTURE_SIZE * MATERIAL_TEXTURE_SIZE * 4];
    static unsigned char swatch[SWATCH * SWATCH * 4];
    for (int t = 0; t < MATERIAL_TEXTURE_COUNT; t++)
        material_texture_generate(t, full[t]);
    for (int m = 0; m < 8; m++) {
        for (int y = 0; y < SWATCH; y++)
            for (int x = 0; x < SWATCH; x++) {
                // Paint material m is texture m - 1 (sand .. moss); automatic shows three.
                int t = m > 0 ? m - 1 : (x < SWATCH / 3 ? 1 : x < 2 * SWATCH / 3 ? 2 : 3);
                const unsigned char *src =
                    full[t] + ((size_t)(y * 2) * MATERIAL_TEXTURE_SIZE + x * 2) * 4;
                unsigned char *dst = swatch + ((size_t)y * SWATCH + x) * 4;
                dst[0] = src[0], dst[1] = src[1], dst[2] = src[2], dst[3] = 255;
            }
        double sum[3] = {0, 0, 0};
        for (int i = 0; i < SWATCH * SWATCH; i++)
            for (int c = 0; c < 3; c++)
                sum[c] += swatch[i * 4 + c];
        mean[m] = UI_RGBA((int)(sum[0] / (SWATCH * SWATCH)), (int)(sum[1] / (SWATCH * SWATCH)),
                          (int)(sum[2] / (SWATCH * SWATCH)), 255);
        out[m] = ui_renderer_create_texture(SWATCH, SWATCH, swatch);
    }
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
    for (int i = st->ed.recent_count - 1; i >= 0; i--)
        app_settings_add_recent(s, st->ed.recent[i]);
    app_settings_add_recent(s, world_path(st->ctx->world));
    tool_settings_capture(st->ctx, s);
    s->fly_speed = st->cc.fly_speed;
    s->dynamic_lod = st->dynamic_res;
    s->lod_pixels = st->v->settings.lod_pixels;
    og_error err = {{0}};
    if (app_settings_save(s, st->settings_path, &err) != 0)
        fprintf(stderr, "orogen: settings not saved: %s\n", err.msg);
    if (console_save_history(&st->ed.console, st->history_path, &err) != 0)
        fprintf(stderr, "orogen: console history not saved: %s\n", err.msg);
}

int window_run(cmd_context *ctx, og_error *err) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) return og_error_set(err, "cannot start the window system: %s", glfw_message);
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
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
    GLFWmonitor *monitor = settings.fullscreen ? glfwGetPrimaryMonitor() : NULL;
    const GLFWvidmode *mode = monitor ? glfwGetVideoMode(monitor) : NULL;
    if (settings.maximized) glfwWindowHint(GLFW_MAXIMIZED, GLFW_TRUE);
    GLFWwindow *win =
        glfwCreateWindow(mode ? mode->width : settings.width, mode ? mode->height : settings.height,
                         "Orogen", monitor, NULL);
    if (win && settings.has_position && !monitor) glfwSetWindowPos(win, settings.x, settings.y);
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
    editor_ui_init(&st.ed);
    if (!world_path(ctx->world)[0]) { // a new session: a never-saved world's crash to offer?
        recovery_scan scan;
        if (edit_find_unsaved_journal(st.ed.unsaved_journal, sizeof st.ed.unsaved_journal, &scan)) {
            st.ed.unsaved_journal_steps = scan.records;
            st.ed.unsaved_journal_when = scan.last;
        }
    }
    st.res_scale = 1.0f;
    st.dynamic_res = 1;
    update_px_scale(&st);
    st.settings = settings;
    snprintf(st.settings_path, sizeof st.settings_path, "%s", settings_path);
    app_settings_path(st.history_path, sizeof st.history_path, "console_history");
    console_load_history(&st.ed.console, st.history_path);
    for (int i = 0; i < settings.recent_count; i++)
        snprintf(st.ed.recent[i], sizeof st.ed.recent[0], "%s", settings.recent[i]);
    st.ed.recent_count = settings.recent_count;
    st.target_ms = settings.frame_target_ms;
    st.cc.fly_speed = settings.fly_speed; // the wheel with the right button held changes it
    st.dynamic_res = settings.dynamic_lod;
    st.ed.glfw_version = glfwGetVersionString();
    st.ed.ui_scale = settings.ui_scale;
    st.drawn_scale = 1.0f;
    st.gl_renderer = (const char *)glGetString(GL_RENDERER);
    og_error ui_err = {{0}};
    if (!(st.font = load_font(win, settings.ui_scale, &ui_err)) || !(st.ui = ui_create(st.font)) ||
        !(st.busy_ui = ui_create(st.font)) ||
        !(st.uir = ui_renderer_create(ctx->resource_dir, &ui_err))) {
        og_error_set(err, "the editor's UI cannot start: %s",
                     ui_err.msg[0] ? ui_err.msg : "out of memory");
        ui_destroy(st.ui);
        ui_destroy(st.busy_ui);
        ui_font_destroy(st.font);
        editor_ui_free(&st.ed);
        world_events_unsubscribe(st.changes);
        viewport_destroy(v);
        view_commands_set_viewport(ctx, NULL);
        glfwDestroyWindow(win);
        glfwTerminate();
        return -1;
    }
    ui_set_clipboard(st.ui, (ui_clipboard){clipboard_get, clipboard_set, win});
    // The session's commands, kept for `history script FILE` (File > Save session...).
    char *session_text = NULL;
    size_t session_len = 0;
    ctx->session = open_memstream(&session_text, &session_len);
    ctx->session_text = &session_text;
    ctx->session_len = &session_len;
    tool_settings_restore(ctx, &settings, settings_path); // each tool as it was last used
    work_queue_init(&st.work, ctx, &st.ed.console, wake_window, NULL);
    st.ed.work = &st.work;
    st.ed.console.submit = submit_console_line;
    st.ed.console.submit_user = &st;
    current_window = &st;
    make_material_swatches(st.ed.material_textures, st.ed.material_colors);

    // The first frame lays out the UI, so the viewport's rectangle is known for the camera.
    {
        int w, h;
        glfwGetFramebufferSize(win, &w, &h);
        build_ui(&st, w > 0 ? w : 1, h > 0 ? h : 1);
    }
    if (!v->cam_set) reset_camera(&st);
    if (!v->cam_set) v->cam.fov_y = settings.field_of_view;
    v->settings.lod_pixels = settings.lod_pixels;
    glfwGetCursorPos(win, &st.mouse_x, &st.mouse_y);
    st.mouse_in = in_window(win, st.mouse_x, st.mouse_y);
    st.in.mouse_x = st.mouse_in ? ui_px(&st, st.mouse_x) : -1e6f; // not (0, 0): File's place
    st.in.mouse_y = st.mouse_in ? ui_px(&st, st.mouse_y) : -1e6f;
    glfwSetWindowUserPointer(win, &st);
    glfwSetMouseButtonCallback(win, on_mouse_button);
    glfwSetCursorPosCallback(win, on_cursor);
    glfwSetCursorEnterCallback(win, on_cursor_enter);
    glfwSetScrollCallback(win, on_scroll);
    glfwSetKeyCallback(win, on_key);
    glfwSetWindowRefreshCallback(win, on_refresh);
    glfwSetCharCallback(win, on_char);
    glfwSetFramebufferSizeCallback(win, on_framebuffer_size);
    glfwSetWindowCloseCallback(win, on_close);
    glfwSetDropCallback(win, on_drop);
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
    const ui_draw_list *dl = NULL;
    while (!glfwWindowShouldClose(win)) {
        // Input first; wake often while tiles arrive, keys fly the camera or work runs.
        int awake = st.pending || st.settled < 2 || keys_held(&st) || st.drag == DRAG_SCULPT ||
                    v->settings.sun_rotation != 0 || !work_queue_idle(&st.work) ||
                    ui_needs_frame(st.ui);
        glfwWaitEventsTimeout(awake ? 0.01 : 0.1);
        int w, h;
        glfwGetFramebufferSize(win, &w, &h);
        if (work_queue_busy(&st.work)) { // the world is the job's: only progress is drawn
            poll_stdin(&st);
            pump_work(&st);
            if (work_queue_busy(&st.work)) {
                if (w > 0 && h > 0 && dl) draw_busy(&st, dl, w, h);
                continue;
            }
        }
        if (ctx->exit_requested) break; // `exit` ran (read only when no work runs)
        if (st.close_after_work) {      // the close button, pressed while work ran
            st.close_after_work = 0;
            on_close(win);
            if (!world_is_modified(ctx->world)) break;
        }
        move_keys keys = take_keys(&st);
        if (camera_controls_move(&st.cc, &v->cam, &keys, ground_height, &st)) st.dirty = 1;
        if (st.ed.camera_mode_request >= 0) { // View > Camera
            set_camera_mode(&st, st.ed.camera_mode_request);
            st.ed.camera_mode_request = -1;
        }
        double now_s = glfwGetTime();
        if (v->settings.sun_rotation != 0) { // R: the light turns while time passes
            double dt = fmin(now_s - st.sun_turned_at, 0.25);
            v->settings.sun_yaw = fmod(v->settings.sun_yaw + v->settings.sun_rotation * dt, 360.0);
            st.dirty = 1;
        }
        st.sun_turned_at = now_s;
        poll_stdin(&st);
        pump_work(&st);
        if (ctx->exit_requested) break;
        if (work_queue_busy(&st.work)) continue;
        take_changes(&st);

        if (w <= 0 || h <= 0) continue;
        // The UI is rebuilt after input or changes; the terrain image only when what
        // it shows changed (a hover or a keystroke in a text field never re-renders it).
        int drawn = 0;
        if (st.ui_dirty || st.dirty || ui_needs_frame(st.ui) || !dl) {
            dl = build_ui(&st, w, h);
            drawn = 1;
        }
        if (st.ed.ui_scale_request > 0) { // View > UI scale: a new font between frames
            char cmd[64];
            snprintf(cmd, sizeof cmd, "ui_scale %g", st.ed.ui_scale_request);
            st.ed.ui_scale_request = 0;
            run_commands(&st, cmd, "ui");
        }
        // The actions the UI asked for run before the frame is drawn.
        if (!work_queue_idle(&st.work)) {
            pump_work(&st);
            if (ctx->exit_requested) break;
            if (work_queue_busy(&st.work)) continue;
            take_changes(&st);
            st.ed.ui_scale = st.settings.ui_scale;
            dl = build_ui(&st, w, h);
        }
        if (st.dirty || st.pending || st.settled < 2) {
            int arrived = update_view(&st) > 0;
            float k = ui_px(&st, 1.0);
            if (render_terrain(&st, (int)roundf(st.view_rect.w * k),
                               (int)roundf(st.view_rect.h * k), arrived)) {
                drawn = 1;
                st.ui_dirty = 1; // the status bar shows the new frame's figures
            }
            // A lowered frame: full size once all is still; a full-size one: smoothed then.
            st.dirty = st.drawn_scale < 1.0f || st.smooth_owed;
        }
        if (drawn) {
            compose(&st, dl, w, h);
            glfwSwapBuffers(win);
            GLenum e = glGetError();
            if (e != GL_NO_ERROR && e != last_gl_error)
                fprintf(stderr, "orogen: OpenGL error 0x%x in the viewport\n", e);
            last_gl_error = e;
        }
        update_title(&st);
    }
    // A stroke still held is committed, and queued work finishes (or is cancelled by
    // a second close) before the world is saved or closed by the caller.
    sculpt_end(&st);
    while (!work_queue_idle(&st.work)) {
        pump_work(&st);
        if (work_queue_busy(&st.work)) glfwWaitEventsTimeout(0.05);
    }
    work_queue_free(&st.work);
    if (ctx->session) fclose(ctx->session);
    ctx->session = NULL;
    free(session_text);
    save_settings(&st);
    world_events_unsubscribe(st.changes);
    current_window = NULL;
    gl_target_destroy(&st.terrain);
    gl_target_destroy(&st.terrain_smooth);
    for (int i = 0; i < st.ed.stamps.count; i++)
        ui_renderer_delete_texture(st.ed.stamps.entries[i].texture);
    for (int i = 0; i < 8; i++)
        ui_renderer_delete_texture(st.ed.material_textures[i]);
    ui_renderer_destroy(st.uir);
    ui_destroy(st.ui);
    ui_destroy(st.busy_ui);
    ui_font_destroy(st.font);
    editor_ui_free(&st.ed);
    // The renderer's GL objects belong to this context: free them while it is current.
    viewport_destroy(v);
    view_commands_set_viewport(ctx, NULL);
    glfwDestroyWindow(win);
    glfwTerminate();
    return 0;
}
