// The window's UI: the editor's panels (editor_ui.h) over the viewport and the progress
// of long work, their font, contexts and renderer, built each frame and drawn over the
// terrain image. Only this file touches window_state's panels (window_panels_state.h).
#include "app/window_internal.h"

#include <errno.h>
#include <string.h>

// The panels' side of the window (editor_host): what they may ask of it.
static void host_set_camera_mode(void *user, int mode) {
    set_camera_mode(user, mode);
}

static void host_close(void *user) {
    window_state *st = user;
    glfwSetWindowShouldClose(st->win, GLFW_TRUE);
}

static int host_submit(void *user, const char *text) {
    run_commands(user, text, "console");
    return 0;
}

static const char *clipboard_get(void *user) {
    return glfwGetClipboardString(user);
}
static void clipboard_set(void *user, const char *text) {
    glfwSetClipboardString(user, text);
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

int panels_open(window_state *st, og_error *err) {
    window_panels_state *p = &st->panels;
    if (!(p->ed = editor_ui_create())) return og_error_set(err, "out of memory");
    if (!world_path(st->ctx->world)[0]) // a new session: a never-saved world's crash to offer?
        editor_ui_offer_startup_recovery(p->ed);
    app_settings_path(p->history_path, sizeof p->history_path, "console_history");
    console_load_history(editor_ui_console(p->ed), p->history_path);
    for (int i = st->settings.recent_count - 1; i >= 0; i--) // the newest goes in last, in front
        editor_ui_add_recent(p->ed, st->settings.recent[i]);
    panels_world_opened(st); // `orogen W.world`: W goes in front
    p->gl_renderer = (const char *)glGetString(GL_RENDERER);
    og_error ui_err = {{0}};
    if (!(p->font = load_font(st->win, st->settings.ui_scale, &ui_err)) ||
        !(p->ui = ui_create(p->font)) || !(p->busy_ui = ui_create(p->font)) ||
        !(p->uir = ui_renderer_create(st->ctx->resource_dir, &ui_err)))
        return og_error_set(err, "the editor's UI cannot start: %s",
                            ui_err.msg[0] ? ui_err.msg : "out of memory");
    ui_set_clipboard(p->ui, (ui_clipboard){clipboard_get, clipboard_set, st->win});
    editor_ui_attach(p->ed, &st->work, &p->notices,
                     (editor_host){st, host_set_camera_mode, host_close, host_submit});
    ui_messages_attach(p->ui, p->busy_ui);
    editor_ui_make_material_swatches(p->ed);
    return 0;
}

void panels_close(window_state *st) {
    window_panels_state *p = &st->panels;
    ui_messages_attach(NULL, NULL);
    editor_ui_destroy(p->ed); // its textures too: the GL context is still current
    ui_renderer_destroy(p->uir);
    ui_destroy(p->ui);
    ui_destroy(p->busy_ui);
    ui_font_destroy(p->font);
    *p = (window_panels_state){0};
}

void panels_keep(window_state *st) {
    int recent = 0;
    while (editor_ui_recent(st->panels.ed, recent))
        recent++;
    while (recent-- > 0)
        app_settings_add_recent(&st->settings, editor_ui_recent(st->panels.ed, recent));
    og_error err = {{0}};
    const char *path = st->panels.history_path;
    // The settings are written after this: on a first run their folder is not there yet.
    if (path[0] && app_settings_make_folders(path) != 0)
        fprintf(stderr, "orogen: console history not saved: %s: cannot create its folder: %s\n",
                path, strerror(errno));
    else if (console_save_history(editor_ui_console(st->panels.ed), path, &err) != 0)
        fprintf(stderr, "orogen: console history not saved: %s\n", err.msg);
}

editor_ui *panels_editor(window_state *st) {
    return st->panels.ed;
}

notices *panels_notices(window_state *st) {
    return &st->panels.notices;
}

ui_rect view_rect(const window_state *st) {
    return st->panels.view_rect;
}

void panels_world_opened(window_state *st) {
    const char *path = world_path(st->ctx->world);
    if (!path[0]) return;
    char full[1024];
    app_absolute_path(path, full, sizeof full);
    editor_ui_add_recent(st->panels.ed, full);
}

void panels_world_edited(window_state *st) {
    st->panels.edited = 1;
}

int panels_need_frame(const window_state *st) {
    return ui_needs_frame(st->panels.ui) || notices_due(&st->panels.notices, notices_now());
}

int panels_took_keys(const window_state *st) {
    return ui_took_keys(st->panels.ui);
}

int panels_capture_point(const window_state *st, float x, float y) {
    return ui_captures_point(st->panels.ui, x, y);
}

int panels_busy_widget_at(const window_state *st, float x, float y) {
    const ui_context *busy = st->panels.busy_ui;
    for (size_t i = 0; i < ui_widget_count(busy); i++)
        if (ui_rect_contains(ui_widget_at(busy, i)->rect, x, y)) return 1;
    return 0;
}

// Changes the UI scale: a new font at the new size (the renderer re-uploads its atlas).
int panels_set_scale(window_state *st, double scale, og_error *err) {
    window_panels_state *p = &st->panels;
    ui_font *f = load_font(st->win, scale, err);
    if (!f) return -1;
    ui_set_font(p->ui, f);
    ui_set_font(p->busy_ui, f);
    ui_font_destroy(p->font);
    p->font = f;
    st->settings.ui_scale = scale;
    st->ui_dirty = 1;
    return 0;
}

void panels_list_widgets(const window_state *st, FILE *out, const char *filter) {
    const window_panels_state *p = &st->panels;
    float k = ui_px(st, 1.0);
    fprintf(out, "Viewport %.0f %.0f %.0f %.0f\n", p->view_rect.x, p->view_rect.y, p->view_rect.w,
            p->view_rect.h);
    // While long work runs, its progress bar and Cancel button are listed after the rest.
    ui_context *uis[2] = {p->ui, work_queue_busy(&st->work) ? p->busy_ui : NULL};
    for (int u = 0; u < 2 && uis[u]; u++)
        for (size_t i = 0; i < ui_widget_count(uis[u]); i++) {
            const ui_widget_info *w = ui_widget_at(uis[u], i);
            if (!w->name[0] || (filter && !strstr(w->name, filter))) continue;
            fprintf(out, "%s %.0f %.0f %.0f %.0f\n", w->name, w->rect.x / k, w->rect.y / k,
                    w->rect.w / k, w->rect.h / k);
        }
}

// One line over the foot of the viewport until the first edit: what to do first (in
// fewer words when the viewport is narrow).
static void first_view_hint(ui_context *ui, ui_rect vr) {
    static const char *const texts[] = {
        "Drag to sculpt, right-drag to look around, F1 for the keys",
        "Drag: sculpt, right-drag: look, F1: keys",
    };
    float pad = ui_em(ui, 0.6f), h = ui_em(ui, 2.4f), w = 0;
    const char *text = NULL;
    for (int i = 0; i < 2 && !text; i++) {
        w = ui_font_text_width(ui_get_font(ui), UI_FACE_SANS, texts[i], strlen(texts[i])) +
            ui_em(ui, 3.0f);
        if (w <= vr.w - 2 * pad) text = texts[i];
    }
    if (!text || vr.h < 4 * h) return; // no room: the view first
    ui_panel_begin(ui, "Hint", (ui_rect){vr.x + 0.5f * (vr.w - w), vr.y + vr.h - h - pad, w, h});
    ui_label(ui, text);
    ui_panel_end(ui);
}

const ui_draw_list *build_ui(window_state *st, int fw, int fh) {
    window_panels_state *p = &st->panels;
    editor_frame_info info = {.gl_renderer = p->gl_renderer,
                              .ui_scale = st->settings.ui_scale,
                              .camera_mode = camera_mode(st),
                              .glfw_version = glfwGetVersionString()};
    frame_status(st, &info);
    info.resizing = viewport_drag_resizing(st, NULL, &info.resize_radius, &info.resize_strength);
    if (editor_ui_refresh_stamps(p->ed, st->ctx, glfwGetTime())) st->ui_dirty = 1;
    size_t waiting;
    ui_begin(p->ui, input_frame(st, ui_wants_keyboard(p->ui), &waiting), (float)fw, (float)fh);
    ui_rect vr = editor_ui_build(p->ed, p->ui, st->ctx, st->v, &info, (float)fw, (float)fh);
    if (!p->edited && !ui_modal_open(p->ui)) first_view_hint(p->ui, vr); // not over a dialog
    notices_expire(&p->notices, notices_now()); // refusals pass after a few seconds
    notices_draw(&p->notices, p->ui, vr);
    const ui_draw_list *dl = ui_end(p->ui);
    input_frame_done(st);
    float k = ui_px(st, 1.0); // framebuffer pixels per window unit
    p->view_rect = (ui_rect){vr.x / k, vr.y / k, vr.w / k, vr.h / k};
    st->ui_dirty = editor_ui_upload_thumbnails(p->ed) || waiting > 0; // more next frame
    return dl;
}

const ui_draw_list *build_busy_ui(window_state *st, const char *what, double fraction,
                                  double elapsed_ms, int fw, int fh) {
    window_panels_state *p = &st->panels;
    ui_begin(p->busy_ui, input_busy_frame(st), (float)fw, (float)fh);
    if (editor_ui_build_busy(p->busy_ui, what, fraction, elapsed_ms, (float)fw, (float)fh))
        work_queue_cancel(&st->work);
    const ui_draw_list *busy = ui_end(p->busy_ui);
    input_busy_done(st);
    return busy;
}

ui_color panels_background(const window_state *st) {
    return ui_get_theme(st->panels.ui)->bg;
}

void panels_draw(window_state *st, const ui_draw_list *dl, int fw, int fh) {
    og_error err = {{0}};
    if (dl && ui_renderer_draw(st->panels.uir, dl, st->panels.font, fw, fh, &err) != 0)
        report("ui", &err);
}
