// The viewport's mouse interaction: a small state machine of drags (none, sculpt,
// orbit, resize) started by the buttons and moved by the cursor; mouse look; the camera
// mode. Only this file touches window_state's drag (viewport_drag_state.h).
#include "app/brush_size.h"
#include "editor/params/world_grid.h"
#include "app/window_internal.h"

drag_kind viewport_drag_kind(const window_state *st) {
    return st->drag.kind;
}

int viewport_looking(const window_state *st) {
    return st->drag.looking;
}

int viewport_drag_resizing(const window_state *st, double at[3], double *radius, double *strength) {
    if (st->drag.kind != DRAG_RESIZE) return 0;
    if (at) memcpy(at, st->drag.resize_at, sizeof st->drag.resize_at);
    if (radius) *radius = st->drag.resize_radius;
    if (strength) *strength = st->drag.resize_strength;
    return 1;
}

sculpt_drag *viewport_drag_stroke(window_state *st) {
    return st->drag.kind == DRAG_SCULPT ? &st->drag.sculpt : NULL;
}

void viewport_drag_after_work(window_state *st) {
    if (st->work.stroke_cancelled) { // Esc or Cancel ended the stroke: the drag is over
        st->work.stroke_cancelled = 0;
        if (st->drag.kind == DRAG_SCULPT) st->drag.kind = DRAG_NONE;
        sculpt_drag_cancelled(&st->drag.sculpt);
    }
    // A planet drag's moves during the job, picked now the world is free.
    sculpt_drag_flush(&st->drag.sculpt, &st->work, sculpt_view_of(st));
}

// Fly, orbit or walk (C, View > Camera): seed 004's camera switch.
void set_camera_mode(window_state *st, int mode) {
    bank_keys(st);
    st->drag.orbit_mode = mode == 1;
    if ((mode == 2) != st->cc.walk)
        camera_controls_toggle_walk(&st->cc, &st->v->cam, ground_height, st);
    st->dirty = st->ui_dirty = 1;
}

int camera_mode(const window_state *st) {
    return st->cc.walk ? 2 : st->drag.orbit_mode ? 1 : 0;
}

sculpt_view sculpt_view_of(const window_state *st) {
    return (sculpt_view){st->v, view_rect(st)};
}

// Ctrl held inverts the tool for the stroke, Shift smooths instead (Unreal, Terrain3D);
// for the volume tools Ctrl swaps fill and carve and Shift smooths in 3D.
static void sculpt_begin(window_state *st, int mods) {
    double mx, my;
    pointer_pos(st, &mx, &my);
    st->dirty = st->ui_dirty = 1;
    // Set height with no height given yet sets the ground to the height where the drag
    // begins (as Unreal's flatten), as a command: the dock shows it and a replay has it.
    double hit[3];
    if (st->ctx->brush.tool == BRUSH_SET && !st->ctx->brush.has_height &&
        pick_at(st, mx, my, hit) == 0) {
        char cmd[96];
        snprintf(cmd, sizeof cmd, "tool set height=%.6g", editor_ui_picked_height(st->ctx, hit));
        run_commands(st, cmd, "sculpt");
    }
    sculpt_drag_begin(&st->drag.sculpt, &st->work, st->ctx, sculpt_view_of(st), mx, my,
                      (mods & GLFW_MOD_SHIFT) != 0, (mods & GLFW_MOD_CONTROL) != 0);
}

static void sculpt_to(window_state *st, double x, double y) {
    if (st->drag.kind != DRAG_SCULPT) return;
    st->dirty = st->ui_dirty = 1;
    sculpt_drag_to(&st->drag.sculpt, &st->work, sculpt_view_of(st), x, y);
}

// Commits the drag's stroke (one undo step); a stroke that laid no dab leaves no step.
// The console shows the drag as one line rather than a line per mouse move.
void sculpt_end(window_state *st) {
    if (st->drag.kind != DRAG_SCULPT) return;
    st->drag.kind = DRAG_NONE;
    st->dirty = st->ui_dirty = 1;
    int points = sculpt_drag_end(&st->drag.sculpt, &st->work);
    char echo[128];
    snprintf(echo, sizeof echo, "> stroke_begin; stroke_to ... (%d points); stroke_end", points);
    console_add(editor_ui_console(panels_editor(st)), CONSOLE_ECHO, echo);
}

const char *tool_name(const brush *b) {
    return b->tool == BRUSH_RAISE && b->invert ? "lower" : brush_tool_name(b->tool);
}

static void resize_begin(window_state *st) {
    double mx, my;
    pointer_pos(st, &mx, &my);
    if (pick_at(st, mx, my, st->drag.resize_at) != 0) return; // no terrain there
    st->drag.kind = DRAG_RESIZE;
    st->drag.resize_x0 = mx, st->drag.resize_y0 = my;
    st->drag.resize_radius = st->drag.resize_r0 = st->ctx->brush.radius;
    st->drag.resize_strength = st->drag.resize_s0 = st->ctx->brush.strength;
}

static void resize_to(window_state *st, double x, double y) {
    double r = st->drag.resize_r0 * pow(1.01, x - st->drag.resize_x0); // 1% a pixel
    double top = brush_radius_key_max(world_grid_sample_metres(world_get_params(st->ctx->world)));
    st->drag.resize_radius = fmin(fmax(r, 0.5), top);
    st->drag.resize_strength =
        fmin(fmax(st->drag.resize_s0 - 0.004 * (y - st->drag.resize_y0), 0), 1);
}

static void resize_end(window_state *st) {
    st->drag.kind = DRAG_NONE;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "tool %s radius=%.4g strength=%.3g", tool_name(&st->ctx->brush),
             st->drag.resize_radius, st->drag.resize_strength);
    run_commands(st, cmd, "resize");
}

void viewport_drag_button(GLFWwindow *win, int button, int action, int mods) {
    window_state *st = glfwGetWindowUserPointer(win);
    st->ui_dirty = 1;
    if (input_defer_button(st, button, action, mods)) return;
    input_button(st, button, action, mods);
    // While long work runs only its Cancel button answers (other presses wait, see
    // deferred_input.h); a stroke's release still ends the stroke (queued after its points).
    if (work_queue_busy(&st->work)) {
        if (action == GLFW_RELEASE && button == GLFW_MOUSE_BUTTON_LEFT) sculpt_end(st);
        if (action == GLFW_RELEASE) st->drag.kind = DRAG_NONE, st->drag.looking = 0;
        return;
    }
    // Presses over the UI (or outside the viewport) are the UI's; releases always end
    // the viewport's drags.
    double mx, my;
    pointer_pos(st, &mx, &my);
    int ui_owns = !in_view(st, mx, my) || pointer_over_ui(st);
    if (action == GLFW_PRESS && ui_owns) return;
    st->dirty = 1;
    // Drags start where the last motion event left the cursor (not where the pointer
    // is now: events queue up, and querying would skip the moves between).
    if (button == GLFW_MOUSE_BUTTON_RIGHT && st->drag.kind == DRAG_RESIZE &&
        action == GLFW_RELEASE) {
        resize_end(st);
        return;
    }
    if (button == GLFW_MOUSE_BUTTON_RIGHT && (mods & GLFW_MOD_ALT) && action == GLFW_PRESS &&
        st->drag.kind == DRAG_NONE && !editor_ui_stamp_active(panels_editor(st))) {
        resize_begin(st);
        return;
    }
    if (button == GLFW_MOUSE_BUTTON_RIGHT && st->drag.orbit_mode && !st->cc.walk) {
        if (action == GLFW_RELEASE) {
            if (st->drag.kind == DRAG_ORBIT) st->drag.kind = DRAG_NONE;
        } else if (st->drag.kind == DRAG_NONE) { // the orbit camera turns about the view's centre
            ui_rect r = view_rect(st);
            double cx = r.x + r.w * 0.5, cy = r.y + r.h * 0.5;
            st->drag.kind = DRAG_ORBIT;
            if (pick_at(st, cx, cy, st->drag.pivot) != 0)
                point_along_ray(st, cx, cy, 100.0, st->drag.pivot);
        }
        return;
    }
    if (button == GLFW_MOUSE_BUTTON_RIGHT) {
        bank_keys(st);
        st->drag.looking = action == GLFW_PRESS;
        return;
    }
    if (button != GLFW_MOUSE_BUTTON_LEFT && button != GLFW_MOUSE_BUTTON_MIDDLE) return;
    if (action == GLFW_RELEASE) {
        if (st->drag.kind == DRAG_SCULPT && button == GLFW_MOUSE_BUTTON_LEFT) sculpt_end(st);
        st->drag.kind = DRAG_NONE;
        return;
    }
    if (st->drag.kind != DRAG_NONE) return; // one drag at a time
    if (button == GLFW_MOUSE_BUTTON_MIDDLE || (mods & GLFW_MOD_ALT)) {
        st->drag.kind = DRAG_ORBIT;
        if (pick_at(st, mx, my, st->drag.pivot) != 0) {
            int ww, wh;
            glfwGetWindowSize(win, &ww, &wh);
            if (pick_at(st, ww * 0.5, wh * 0.5, st->drag.pivot) != 0)
                point_along_ray(st, ww * 0.5, wh * 0.5, 100.0, st->drag.pivot);
        }
        st->cc.walk = 0;
    } else if (editor_ui_click_wanted(panels_editor(st)) != EDITOR_CLICK_DRAG &&
               button == GLFW_MOUSE_BUTTON_LEFT) {
        double hit[3]; // a panel waits for this click on the terrain
        char cmd[512];
        const char *label = NULL;
        int on_terrain = pick_at(st, mx, my, hit) == 0;
        if (editor_ui_viewport_click(panels_editor(st), st->ctx, on_terrain ? hit : NULL, cmd,
                                     sizeof cmd, &label))
            run_commands(st, cmd, label);
    } else {
        st->drag.kind = DRAG_SCULPT;
        sculpt_begin(st, mods);
    }
}

void viewport_drag_cursor(GLFWwindow *win, double x, double y) {
    window_state *st = glfwGetWindowUserPointer(win);
    if (input_defer_cursor(st, x, y)) return;
    double dx, dy;
    input_cursor(st, x, y, &dx, &dy);
    st->ui_dirty = 1;
    // The brush cursor moves with the pointer over the viewport, and goes when it leaves.
    if (st->drag.kind != DRAG_NONE || st->drag.looking || in_view(st, x, y) ||
        st->v->cursor.visible)
        st->dirty = 1;
    if (work_queue_busy(&st->work)) { // the camera waits; a stroke's points queue up
        sculpt_to(st, x, y);
        return;
    }
    if (st->drag.kind == DRAG_RESIZE)
        resize_to(st, x, y);
    else if (st->drag.kind == DRAG_ORBIT)
        camera_controls_orbit(&st->cc, &st->v->cam, st->drag.pivot, dx, dy);
    else if (st->drag.kind == DRAG_SCULPT)
        sculpt_to(st, x, y);
    if (st->drag.looking) camera_controls_look(&st->cc, &st->v->cam, dx, dy);
}
