// GLFW's events turned into the UI's input (ui_input), the camera's movement keys and
// the keyboard shortcuts; dropped files; the close button.
#include "app/brush_size.h"
#include "editor/params/world_grid.h"
#include "app/shortcuts.h"
#include "app/window_internal.h"

#include <strings.h>

static const int move_key_codes[MOVE_KEY_COUNT] = {GLFW_KEY_W, GLFW_KEY_S, GLFW_KEY_A,
                                                   GLFW_KEY_D, GLFW_KEY_E, GLFW_KEY_Q};

// Movement keys count while the right button is held, or always while walking. Their
// held time is banked at every press, release and mode change, so the camera moves
// for as long as a key was held even when frames are slow.
static int movement_allowed(const window_state *st) {
    return viewport_looking(st) || st->cc.walk;
}

void bank_keys(window_state *st) {
    double now = glfwGetTime();
    for (int i = 0; i < MOVE_KEY_COUNT; i++) {
        if (st->input.key_down[i] && movement_allowed(st))
            st->input.key_held[i] += now - st->input.key_since[i];
        st->input.key_since[i] = now;
    }
}

// The banked time as a step for camera_controls_move; clears the bank.
move_keys take_keys(window_state *st) {
    bank_keys(st);
    GLFWwindow *w = st->win;
    double *h = st->input.key_held;
    move_keys k = {h[0], h[1], h[2], h[3], h[4], h[5], 0};
    k.fast = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT);
    for (int i = 0; i < MOVE_KEY_COUNT; i++)
        h[i] = 0;
    return k;
}

int keys_held(const window_state *st) {
    if (!movement_allowed(st)) return 0;
    for (int i = 0; i < MOVE_KEY_COUNT; i++)
        if (st->input.key_down[i]) return 1;
    return 0;
}

static void on_framebuffer_size(GLFWwindow *win, int width, int height) {
    (void)width, (void)height;
    window_state *st = glfwGetWindowUserPointer(win);
    update_px_scale(st);
    st->ui_dirty = st->dirty = 1;
}

static void on_cursor_enter(GLFWwindow *win, int entered) {
    window_state *st = glfwGetWindowUserPointer(win);
    st->input.mouse_in = entered;
    st->dirty = 1;
    // A pointer that left (with no button held) hovers nothing: no widget stays lit and no
    // tooltip comes up for a place the pointer no longer is.
    if (!entered && !st->input.in.mouse_down[0] && !st->input.in.mouse_down[1] &&
        !st->input.in.mouse_down[2]) {
        st->input.in.mouse_x = st->input.in.mouse_y = -1e6f;
        queue_ui_event(st, (ui_event){.kind = UI_EVENT_MOVE, .x = -1e6f, .y = -1e6f});
        st->ui_dirty = 1;
    }
}

static void on_scroll(GLFWwindow *win, double dx, double dy) {
    (void)dx;
    window_state *st = glfwGetWindowUserPointer(win);
    st->ui_dirty = 1;
    if (input_defer_scroll(st, dx, dy)) return;
    if (!in_view(st, st->input.mouse_x, st->input.mouse_y) ||
        panels_capture_point(st, st->input.in.mouse_x, st->input.in.mouse_y)) {
        st->input.in.wheel += (float)dy;
        queue_ui_event(st, (ui_event){.kind = UI_EVENT_WHEEL, .wheel = (float)dy});
        return;
    }
    st->dirty = 1;
    if (viewport_looking(st)) {
        camera_controls_speed_wheel(&st->cc, dy);
        return;
    }
    int ctrl = glfwGetKey(win, GLFW_KEY_LEFT_CONTROL) || glfwGetKey(win, GLFW_KEY_RIGHT_CONTROL);
    int shift = glfwGetKey(win, GLFW_KEY_LEFT_SHIFT) || glfwGetKey(win, GLFW_KEY_RIGHT_SHIFT);
    if (editor_ui_stamp_active(panels_editor(st)) &&
        (ctrl || shift)) { // the stamp preview: size, turn
        editor_ui_stamp_wheel(panels_editor(st), ctrl, shift, dy);
        st->ui_dirty = 1;
        return;
    }
    double pivot[3];
    if (pick_at(st, st->input.mouse_x, st->input.mouse_y, pivot) != 0)
        point_along_ray(st, st->input.mouse_x, st->input.mouse_y,
                        fmax(100.0, 4.0 * st->cc.fly_speed), pivot);
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
        editor_ui_save(panels_editor(st), st->ctx); // asks first: saving would lose something
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
    if (input_defer_char(st, codepoint)) return;
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
    // Queued whether or not a field has the keyboard now: a click just before it may
    // open one (the UI ignores text with no field focused).
    ui_event e = {.kind = UI_EVENT_TEXT};
    memcpy(e.text, u, sizeof u);
    queue_ui_event(st, e);
}

int ui_mods_of(int glfw_mods) {
    return ((glfw_mods & GLFW_MOD_SHIFT) ? UI_MOD_SHIFT : 0) |
           ((glfw_mods & GLFW_MOD_CONTROL) ? UI_MOD_CTRL : 0) |
           ((glfw_mods & GLFW_MOD_ALT) ? UI_MOD_ALT : 0);
}

void queue_ui_event(window_state *st, ui_event e) {
    e.time = glfwGetTime();
    ui_input_queue_push(st->input.queue, &e);
}

static void brush_step(window_state *st, shortcut_action action) {
    const brush *b = &st->ctx->brush;
    const char *name = tool_name(b);
    char cmd[128];
    if (action == SHORTCUT_RADIUS_DOWN || action == SHORTCUT_RADIUS_UP) {
        double r = b->radius * (action == SHORTCUT_RADIUS_UP ? 1.15 : 1 / 1.15);
        double top =
            brush_radius_key_max(world_grid_sample_metres(world_get_params(st->ctx->world)));
        snprintf(cmd, sizeof cmd, "tool %s radius=%.4g", name, fmin(fmax(r, 0.5), top));
    } else {
        double k = b->strength + (action == SHORTCUT_STRENGTH_UP ? 0.05 : -0.05);
        snprintf(cmd, sizeof cmd, "tool %s strength=%.3g", name, fmin(fmax(k, 0), 1));
    }
    run_commands(st, cmd, "key");
}

static void levels_step(window_state *st, int step) { // seed 004's = and -, with Ctrl here
    int levels = st->v->settings.levels + step;
    if (levels >= RENDER_MIN_LEVELS && levels <= RENDER_MAX_LEVELS) {
        char cmd[64];
        snprintf(cmd, sizeof cmd, "render levels=%d", levels);
        run_commands(st, cmd, "key");
    }
}

static void turn_light(window_state *st) { // the light turns; on a planet at its omega (seed 004)
    const world_params *p = world_get_params(st->ctx->world);
    double speed = p->kind == WORLD_PLANET && p->omega != 0 ? p->omega * 180.0 / M_PI : 20.0;
    char cmd[64];
    snprintf(cmd, sizeof cmd, "render sun_rotation=%.6g",
             st->v->settings.sun_rotation != 0 ? 0.0 : fmax(-360, fmin(360, speed)));
    run_commands(st, cmd, "key");
}

// A key of the shortcut table (app/shortcuts.c) does what its row says.
static void run_shortcut(window_state *st, const shortcut_key *k) {
    double hit[3];
    switch (k->action) {
    case SHORTCUT_RUN:
        run_commands(st, k->arg, strchr(k->label, '+') ? k->label : "key");
        break;
    case SHORTCUT_TOOL: // one letter per tool, while the pointer is over the viewport
        if (!viewport_looking(st) && in_view(st, st->input.mouse_x, st->input.mouse_y)) {
            int tool = editor_ui_tool_index(k->arg);
            if (tool >= 0) editor_ui_pick_tool(panels_editor(st), st->ctx, tool);
        }
        break;
    case SHORTCUT_CONSOLE:
        console_toggle(editor_ui_console(panels_editor(st)), 0);
        break;
    case SHORTCUT_HELP:
        editor_ui_show_help(panels_editor(st));
        break;
    case SHORTCUT_RADIUS_DOWN:
    case SHORTCUT_RADIUS_UP:
    case SHORTCUT_STRENGTH_DOWN:
    case SHORTCUT_STRENGTH_UP:
        brush_step(st, k->action);
        break;
    case SHORTCUT_FOCUS:
        if (pick_at(st, st->input.mouse_x, st->input.mouse_y, hit) == 0)
            camera_controls_focus(&st->cc, &st->v->cam, hit, st->ctx->brush.radius);
        else
            fprintf(stderr, "orogen: focus: no terrain under the cursor\n");
        break;
    case SHORTCUT_WALK:
        bank_keys(st);
        camera_controls_toggle_walk(&st->cc, &st->v->cam, ground_height, st);
        break;
    case SHORTCUT_RESET_VIEW:
        reset_camera(st);
        break;
    case SHORTCUT_NEXT_CAMERA:
        set_camera_mode(st, (camera_mode(st) + 1) % 3);
        break;
    case SHORTCUT_LIGHT:
        turn_light(st);
        break;
    case SHORTCUT_DYNAMIC_RES:
        run_commands(
            st, frame_dynamic_resolution(st) ? "dynamic_resolution off" : "dynamic_resolution on",
            "key");
        break;
    case SHORTCUT_MORE_LEVELS:
    case SHORTCUT_FEWER_LEVELS:
        levels_step(st, k->action == SHORTCUT_MORE_LEVELS ? 1 : -1);
        break;
    case SHORTCUT_SAVE:
        save_shortcut(st);
        break;
    case SHORTCUT_SAVE_AS:
        editor_ui_save_as(panels_editor(st), st->ctx);
        break;
    case SHORTCUT_OPEN:
        editor_ui_open(panels_editor(st), st->ctx);
        break;
    case SHORTCUT_NEW_FLAT:
        editor_ui_request(panels_editor(st), st->ctx, PENDING_NEW_FLAT);
        break;
    case SHORTCUT_QUIT:
        editor_ui_request(panels_editor(st), st->ctx, PENDING_QUIT);
        break;
    case SHORTCUT_ACTION_COUNT:
        break;
    }
}

static int shortcut_mods_of(int glfw_mods) {
    return ((glfw_mods & GLFW_MOD_CONTROL) ? SHORTCUT_CTRL : 0) |
           ((glfw_mods & GLFW_MOD_SHIFT) ? SHORTCUT_SHIFT : 0);
}

// A key goes to the UI's queue first; what the UI's frame does not take comes back to
// key_after_ui as a shortcut, in order (a Ctrl+click that opens a field and the digits
// typed after it, however quickly, are the field's).
static void on_key(GLFWwindow *win, int key, int scancode, int action, int mods) {
    (void)scancode;
    window_state *st = glfwGetWindowUserPointer(win);
    st->ui_dirty = 1;
    if (input_defer_key(st, key, action, mods)) return; // typed during a job: after it
    st->input.in.mods = ui_mods_of(mods);
    int k = ui_key_of(key);
    if (k >= 0 && action != GLFW_RELEASE) st->input.in.key_pressed[k] = 1;
    if (work_queue_busy(&st->work)) { // Esc cancels long work
        if (action == GLFW_PRESS && key == GLFW_KEY_ESCAPE) work_queue_cancel(&st->work);
        for (int i = 0; i < MOVE_KEY_COUNT; i++) // a key let go is never left held
            if (key == move_key_codes[i] && action == GLFW_RELEASE) st->input.key_down[i] = 0;
        return; // the rest waits for the work's end (input_defer_key)
    }
    // Shift, Ctrl, Alt alone are no event of their own: they travel as the mods of the rest
    // (queued, each would take a frame before the key they go with).
    if (key >= GLFW_KEY_LEFT_SHIFT && key <= GLFW_KEY_RIGHT_SUPER) return;
    queue_ui_event(st, (ui_event){.kind = UI_EVENT_KEY,
                                  .key = k,
                                  .code = key,
                                  .down = action != GLFW_RELEASE,
                                  .repeat = action == GLFW_REPEAT,
                                  .mods = ui_mods_of(mods)});
}

static void key_after_ui(window_state *st, int key, int action, int mods, int taken) {
    for (int i = 0; i < MOVE_KEY_COUNT; i++) // a key let go is never left held
        if (taken && key == move_key_codes[i] && action == GLFW_RELEASE && st->input.key_down[i]) {
            bank_keys(st);
            st->input.key_down[i] = 0;
        }
    // A focused text field took it; ~ still closes the console.
    if (taken) {
        if (action == GLFW_PRESS && key == GLFW_KEY_GRAVE_ACCENT &&
            editor_ui_console(panels_editor(st))->open)
            console_toggle(editor_ui_console(panels_editor(st)), 1);
        return;
    }
    if (action == GLFW_PRESS && key == GLFW_KEY_ESCAPE) return; // the UI closes menus, dialogs
    st->dirty = 1;
    for (int i = 0; i < MOVE_KEY_COUNT; i++) {
        if (key != move_key_codes[i] || action == GLFW_REPEAT) continue;
        bank_keys(st);
        // Ctrl+S is a shortcut, not a step back.
        st->input.key_down[i] = action == GLFW_PRESS && !(mods & GLFW_MOD_CONTROL);
    }
    if (action != GLFW_PRESS) return;
    const shortcut_key *k = shortcut_find(key, shortcut_mods_of(mods));
    if (k) run_shortcut(st, k);
}

static void keys_after_ui(window_state *st, const ui_input *in) {
    int taken = panels_took_keys(st);
    for (int i = 0; i < in->event_count; i++) {
        const ui_event *e = &in->events[i];
        if (e->kind != UI_EVENT_KEY) continue;
        int mods = ((e->mods & UI_MOD_SHIFT) ? GLFW_MOD_SHIFT : 0) |
                   ((e->mods & UI_MOD_CTRL) ? GLFW_MOD_CONTROL : 0) |
                   ((e->mods & UI_MOD_ALT) ? GLFW_MOD_ALT : 0);
        int action = !e->down ? GLFW_RELEASE : e->repeat ? GLFW_REPEAT : GLFW_PRESS;
        key_after_ui(st, e->code, action, mods, taken);
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
            console_add(editor_ui_console(panels_editor(st)), CONSOLE_ERROR, msg);
            fprintf(stderr, "%s\n", msg);
        } else if (dot && (strcmp(dot, ".world") == 0 || strcmp(dot, ".planet") == 0)) {
            editor_ui_open_file(panels_editor(st), st->ctx, p);
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
            editor_ui_stamp_dropped(panels_editor(st), st->ctx);
            run_commands(st, cmd, "drop");
        } else {
            snprintf(
                msg, sizeof msg,
                "%.4000s: Orogen opens .world and .planet files, imports heightmaps (.hgt .tif "
                ".exr .r16 ...) and makes other images stamps",
                p);
            console_add(editor_ui_console(panels_editor(st)), CONSOLE_ERROR, msg);
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
void on_close(GLFWwindow *win) {
    window_state *st = glfwGetWindowUserPointer(win);
    if (work_queue_busy(&st->work)) { // stop the work first, then ask as usual
        glfwSetWindowShouldClose(win, GLFW_FALSE);
        work_queue_cancel(&st->work);
        close_after_work(st);
        return;
    }
    if (world_is_modified(st->ctx->world)) {
        glfwSetWindowShouldClose(win, GLFW_FALSE);
        editor_ui_request(panels_editor(st), st->ctx, PENDING_QUIT);
        st->ui_dirty = 1;
    }
}

static void clear_frame_input(ui_input *in) {
    memset(in->mouse_pressed, 0, sizeof in->mouse_pressed);
    memset(in->mouse_released, 0, sizeof in->mouse_released);
    memset(in->key_pressed, 0, sizeof in->key_pressed);
    in->double_click = 0;
    in->wheel = 0;
    in->text[0] = 0;
}

void window_input_attach(window_state *st) {
    GLFWwindow *win = st->win;
    glfwSetWindowUserPointer(win, st);
    st->input.deferred.handlers =
        (deferred_handlers){viewport_drag_button, viewport_drag_cursor, on_key, on_char, on_scroll};
    glfwSetMouseButtonCallback(win, viewport_drag_button);
    glfwSetCursorPosCallback(win, viewport_drag_cursor);
    glfwSetCursorEnterCallback(win, on_cursor_enter);
    glfwSetScrollCallback(win, on_scroll);
    glfwSetKeyCallback(win, on_key);
    glfwSetWindowRefreshCallback(win, on_refresh);
    glfwSetCharCallback(win, on_char);
    glfwSetFramebufferSizeCallback(win, on_framebuffer_size);
    glfwSetWindowCloseCallback(win, on_close);
    glfwSetDropCallback(win, on_drop);
}

int input_open(window_state *st) {
    if (!(st->input.queue = malloc(sizeof *st->input.queue))) return -1;
    ui_input_queue_init(st->input.queue);
    return 0;
}

void input_close(window_state *st) {
    free(st->input.queue);
    st->input.queue = NULL;
}

// Where the pointer is before any motion event: the UI hovers what is under it, or
// nothing when it is outside the window (not (0, 0): File's place).
void input_first_pointer(window_state *st) {
    window_input_state *in = &st->input;
    glfwGetCursorPos(st->win, &in->mouse_x, &in->mouse_y);
    int w, h;
    glfwGetWindowSize(st->win, &w, &h);
    in->mouse_in = in->mouse_x >= 0 && in->mouse_y >= 0 && in->mouse_x < w && in->mouse_y < h;
    in->in.mouse_x = in->mouse_in ? ui_px(st, in->mouse_x) : -1e6f;
    in->in.mouse_y = in->mouse_in ? ui_px(st, in->mouse_y) : -1e6f;
    queue_ui_event(st, (ui_event){.kind = UI_EVENT_MOVE, .x = in->in.mouse_x, .y = in->in.mouse_y});
}

void pointer_pos(const window_state *st, double *x, double *y) {
    *x = st->input.mouse_x, *y = st->input.mouse_y;
}

int pointer_in_window(const window_state *st) {
    return st->input.mouse_in;
}

int pointer_over_ui(const window_state *st) {
    return panels_capture_point(st, st->input.in.mouse_x, st->input.in.mouse_y);
}

void input_button(window_state *st, int button, int action, int mods) {
    ui_input *in = &st->input.in;
    int b = button == GLFW_MOUSE_BUTTON_LEFT     ? 0
            : button == GLFW_MOUSE_BUTTON_RIGHT  ? 1
            : button == GLFW_MOUSE_BUTTON_MIDDLE ? 2
                                                 : -1;
    if (b < 0) return;
    if (action == GLFW_PRESS) {
        in->mouse_pressed[b] = 1;
        double now = glfwGetTime();
        static double last_left;
        if (b == 0) {
            in->double_click = now - last_left < 0.35;
            last_left = now;
        }
    } else {
        in->mouse_released[b] = 1;
    }
    in->mouse_down[b] = action == GLFW_PRESS;
    // The UI's copy (a release even during long work: no widget stays held).
    if (!work_queue_busy(&st->work) || action == GLFW_RELEASE)
        queue_ui_event(st, (ui_event){.kind = UI_EVENT_BUTTON,
                                      .button = b,
                                      .down = action == GLFW_PRESS,
                                      .x = in->mouse_x,
                                      .y = in->mouse_y,
                                      .mods = ui_mods_of(mods)});
}

void input_cursor(window_state *st, double x, double y, double *dx, double *dy) {
    window_input_state *in = &st->input;
    *dx = x - in->mouse_x, *dy = y - in->mouse_y;
    in->mouse_x = x, in->mouse_y = y;
    in->in.mouse_x = ui_px(st, x);
    in->in.mouse_y = ui_px(st, y);
    queue_ui_event(st, (ui_event){.kind = UI_EVENT_MOVE, .x = in->in.mouse_x, .y = in->in.mouse_y});
}

const ui_input *input_frame(window_state *st, int wants_keyboard, size_t *waiting) {
    st->input.in.time = glfwGetTime();
    *waiting = ui_input_queue_frame(st->input.queue, wants_keyboard, &st->input.frame_in);
    st->input.frame_in.time = glfwGetTime();
    return &st->input.frame_in;
}

void input_frame_done(window_state *st) {
    clear_frame_input(&st->input.in);
    keys_after_ui(st, &st->input.frame_in);
}

ui_input *input_busy_frame(window_state *st) {
    st->input.in.time = glfwGetTime();
    return &st->input.in;
}

void input_busy_done(window_state *st) {
    clear_frame_input(&st->input.in);
}
