// The window's own commands: ui_scale, dynamic_resolution, ui_widgets, window_screenshot.
#include "app/window.h"

#include "app/window_internal.h"

// The window whose UI the ui_widgets command reports (one window per process).
window_state *current_window;

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
    return panels_set_scale(st, v, err);
}

// dynamic_resolution [on|off]: lower the viewport's resolution while moving (L).
static int cmd_dynamic_resolution(cmd_context *ctx, int argc, char **argv, og_error *err) {
    window_state *st = current_window;
    if (!st) return og_error_set(err, "dynamic_resolution: no editor window is open");
    int on = frame_dynamic_resolution(st);
    if (argc > 1 && parse_switch(argv[1], "dynamic_resolution", &on, err) != 0) return -1;
    frame_set_dynamic_resolution(st, on);
    st->dirty = st->ui_dirty = 1;
    fprintf(ctx->out, "dynamic_resolution %s (target %g ms)\n", on ? "on" : "off",
            frame_target_ms(st));
    return 0;
}

// ui_widgets: the named widgets of the last UI frame, for tests that click by name.
static int cmd_ui_widgets(cmd_context *ctx, int argc, char **argv, og_error *err) {
    window_state *st = current_window;
    if (!st) return og_error_set(err, "ui_widgets: no editor window is open");
    panels_list_widgets(st, ctx->out, argc > 1 ? argv[1] : NULL);
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
    take_changes(st); // a world made earlier in the same batch of commands gets its camera
    compose(st, render_still(st, w, h), w, h);
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

// ui_input_waiting: 0 once the window has acted on every input event it was given and
// run what they asked for (tests wait on it instead of sleeping).
static int cmd_ui_input_waiting(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv;
    if (!current_window) return og_error_set(err, "ui_input_waiting: no editor window is open");
    fprintf(ctx->out, "ui_input_waiting %zu\n", input_waiting(current_window));
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
    {"ui_input_waiting", "ui_input_waiting",
     "Prints how many of the mouse and key events the editor window was given it has not yet "
     "acted on (queued for its UI, or held while work runs), plus the commands queued behind "
     "the work running: 0 once the window has caught up (long work may still run).",
     0, 0, cmd_ui_input_waiting, CMD_NOT_RECORDED | CMD_WHILE_BUSY},
};

int window_commands_register(og_error *err) {
    return cmd_register(window_commands, sizeof window_commands / sizeof window_commands[0], err);
}
