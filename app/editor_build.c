// The editor's UI each frame (app/editor_ui.h): its actions run as commands; the
// menus, dock, status bar and dialogs come from the parts in editor_ui_internal.h.
#include "app/editor_ui_internal.h"
#include "app/export_check.h"
#include "app/shortcuts.h"
#include "renderer/ui_renderer.h"

#include <stdlib.h>

editor_ui *editor_ui_create(void) {
    editor_ui *e = calloc(1, sizeof *e);
    if (!e) return NULL;
    console_init(&e->console);
    stamp_browser_init(&e->stamps);
    return e;
}

void editor_ui_destroy(editor_ui *e) {
    if (!e) return;
    for (int i = 0; i < e->stamps.count; i++)
        ui_renderer_delete_texture(e->stamps.entries[i].texture);
    for (int i = 0; i < 8; i++)
        ui_renderer_delete_texture(e->material_textures[i]);
    console_free(&e->console);
    terrain_flow_field_free(&e->layers.flow);
    free(e);
}

int editor_ui_run(editor_ui *e, cmd_context *ctx, const char *text) {
    if (e->work) return work_queue_add(e->work, text, "ui", WORK_ECHO);
    return console_run(&e->console, ctx, text, "ui");
}

// Runs text now, on this thread, for actions that go on only when it succeeded (load,
// save): quick file work, not long edits.
int run_now(editor_ui *e, cmd_context *ctx, const char *text) {
    return console_run(&e->console, ctx, text, "ui");
}

// The problem lines the replace dialog lists (at most this many).
#define REPLACE_LINES_SHOWN 8

// run_now for a dialog that runs commands through a callback.
typedef struct dialog_runner {
    editor_ui *e;
    cmd_context *ctx;
} dialog_runner;

static int run_for_dialog(void *user, const char *text) {
    dialog_runner *r = user;
    return run_now(r->e, r->ctx, text);
}

int problem_lines(const char *problems) {
    int n = problems[0] != 0;
    for (const char *c = problems; *c; c++)
        n += *c == '\n';
    return n < REPLACE_LINES_SHOWN ? n : REPLACE_LINES_SHOWN;
}

int runf(editor_ui *e, cmd_context *ctx, const char *fmt, ...) {
    char text[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    return editor_ui_run(e, ctx, text);
}

void remember_recent(editor_ui *e, const char *path) {
    if (!path[0]) return;
    int n = 0;
    char list[EDITOR_RECENT][1024];
    snprintf(list[n++], sizeof list[0], "%s", path);
    for (int i = 0; i < e->recent_count && n < EDITOR_RECENT; i++)
        if (strcmp(e->recent[i], path) != 0)
            snprintf(list[n++], sizeof list[0], "%s", e->recent[i]);
    memcpy(e->recent, list, sizeof list);
    e->recent_count = n;
}

void do_action(editor_ui *e, cmd_context *ctx, editor_pending action) {
    if (action == PENDING_NEW_FLAT) editor_ui_run(e, ctx, "new flat");
    if (action == PENDING_NEW_PLANET) editor_ui_run(e, ctx, e->planet_command);
    if (action == PENDING_OPEN) {
        char arg[1100], cmd[1200];
        cmd_quote_arg(arg, sizeof arg, e->open_path);
        snprintf(cmd, sizeof cmd, "load %s", arg);
        run_now(e, ctx, cmd); // the window puts the world in front of the recent ones
    }
    if (action == PENDING_NEW_FROM) {
        char arg[1100];
        cmd_quote_arg(arg, sizeof arg, e->open_path);
        runf(e, ctx, "new flat from=%s", arg);
    }
    if (action == PENDING_QUIT && e->host.close) e->host.close(e->host.user);
}

void editor_ui_request(editor_ui *e, cmd_context *ctx, editor_pending action) {
    if (world_is_modified(ctx->world))
        e->pending = action;
    else
        do_action(e, ctx, action);
}

const char *file_name(const char *path) {
    const char *slash = strrchr(path, '/');
    return path[0] ? (slash ? slash + 1 : path) : "unsaved world";
}

// The keyboard shortcuts (Help > Keyboard shortcuts, F1): the shortcut table's rows.
enum { HELP_MAX_LINES = 32 };
static int help_lines(const char *lines[HELP_MAX_LINES]) {
    static char text[HELP_MAX_LINES][200];
    int n = 0;
    for (; n < shortcut_row_count() && n < HELP_MAX_LINES; n++)
        lines[n] = shortcut_help_line(n, text[n], sizeof text[n]);
    return n;
}

// The open dialog's rectangle (they are centred and sized from the font).
static ui_rect dialog_rect(const editor_ui *e, const ui_context *ui, float width, float height) {
    if (e->files.open)
        return centred(width, height, fminf(width * 0.9f, ui_em(ui, 34)),
                       fminf(height * 0.85f, ui_em(ui, 24)));
    if (e->interchange.open && e->interchange.planet) // rows of 1.4 em, 0.2 em gaps, padding
        return centred(width, height, fminf(width * 0.9f, ui_em(ui, 24)),
                       ui_em(ui, 1.6f * (float)interchange_dialog_rows(&e->interchange) + 0.8f));
    if (e->interchange.open)
        return centred(
            width, height, fminf(width * 0.9f, ui_em(ui, 24)),
            fminf(height * 0.9f,
                  ui_em(ui, 1.7f * (float)interchange_dialog_rows(&e->interchange) + 1.5f)));
    if (e->new_planet.open)
        return centred(
            width, height, fminf(width * 0.9f, ui_em(ui, 24)),
            fminf(height * 0.9f,
                  // rows of 1.4 em and their 0.2 em gaps, the panel's padding
                  ui_em(ui, 1.6f * (float)new_planet_dialog_rows(&e->new_planet) + 0.8f)));
    if (e->offer_recovery) // wide enough for its first lines in full
        return centred(width, height, fminf(width * 0.9f, ui_em(ui, 32)),
                       fminf(height * 0.9f, ui_em(ui, recover_offer_lines(&e->recovery))));
    if (e->confirm_replace)
        return centred(width, height, fminf(width * 0.9f, ui_em(ui, 30)),
                       fminf(height * 0.9f, ui_em(ui, 1.45f * (float)(e->replace_lines + 2) + 1)));
    if (e->pending != PENDING_NONE) return centred(width, height, ui_em(ui, 22), ui_em(ui, 6));
    if (e->show_help) {
        const char *lines[HELP_MAX_LINES];
        return text_dialog_rect(ui, lines, help_lines(lines), width, height);
    }
    if (e->show_about) return centred(width, height, ui_em(ui, 34), ui_em(ui, 1.45f * (3 + 3)));
    return (ui_rect){0, 0, 0, 0};
}

ui_rect editor_ui_build(editor_ui *e, ui_context *ui, cmd_context *ctx, viewport *v,
                        const editor_frame_info *info, float width, float height) {
    e->offer_recovery = recover_offer_update(&e->recovery, ctx->world);
    if (ctx->tool_serial != e->tool_serial_seen) { // a tool picked from anywhere ends stamping
        e->tool_serial_seen = ctx->tool_serial;
        stamp_browser_deactivate(&e->stamps);
    }
    e->replace_lines = problem_lines(world_file_problems(ctx->world)) +
                       (world_file_errors(ctx->world) ? 2 : 0) +
                       (world_read_only(ctx->world)[0] ? 3 : 0);
    ui_rect modal = dialog_rect(e, ui, width, height);
    if (modal.w > 0) ui_modal(ui, modal);
    float bar = ui_em(ui, 1.5f), status = ui_em(ui, 1.6f);
    // Side panels follow the font, but leave the viewport at least half the window.
    float left = fminf(ui_em(ui, 7.5f), roundf(width * 0.15f));
    float right = fminf(ui_em(ui, 17), roundf(width * 0.32f));
    ui_rect top = {0, 0, width, bar};
    ui_rect body = {0, bar, width, height - bar - status};
    ui_rect cols[3];
    float sizes[3] = {left, 0, right};
    ui_split(ui, body, 1, 3, sizes, cols);

    palette(e, ui, ctx, cols[0]);
    ui_panel_begin(ui, "Dock", cols[2]);
    ui_row(ui, 1, NULL, 0);
    char tool_title[192];
    if (e->stamps.active)
        snprintf(tool_title, sizeof tool_title, "Tool: stamp %s##Tool",
                 e->stamps.entries[e->stamps.selected].name);
    else
        snprintf(tool_title, sizeof tool_title, "Tool: %s##Tool", current_tool(&ctx->brush));
    if (ui_section(ui, tool_title, 1) && !e->stamps.active) tool_options(e, ui, ctx);
    int picked = 0;
    if (stamp_browser_take_open_request(&e->stamps)) // the palette's Stamp button
        ui_section_set(ui, "Stamps", 1);             // shows the browser
    if (ui_section(ui, "Stamps", 0)) stamp_browser_draw(&e->stamps, ui, ctx, &picked);
    if (ui_section(ui, "Layers", 0)) {
        layer_stack_panel(e, ui, ctx, v);
        layers_panel(e, ui, ctx, v);
    } else {
        v->settings.mask_terms = 0; // the mask editor's overlay closes with the panel
    }
    if (ui_section(ui, "Materials", 0)) materials_panel(e, ui, ctx);
    if (ui_section(ui, "World", 1)) world_panel(e, ui, ctx);
    int show_history = e->history_request;
    if (e->history_request) { // Edit > History: the section opens
        ui_section_set(ui, "History", 1);
        e->history_request = 0;
    }
    if (ui_section(ui, "History", 1)) history_panel(e, ui, ctx);
    if (show_history) ui_reveal_last(ui); // and the dock scrolls to its steps
    ui_panel_end(ui);
    status_bar(ui, ctx, v, info, &e->stamps, (ui_rect){0, height - status, width, status});

    ui_rect view = cols[1];
    if (e->console.open) {
        ui_rect c = {view.x, view.y, view.w, roundf(view.h * 0.45f)};
        console_draw(&e->console, ui, ctx, c);
    }
    if (modal.w > 0) ui_dim(ui); // the dialog stands out; the rest waits
    if (e->show_help) {
        const char *lines[HELP_MAX_LINES];
        text_dialog(ui, "Keyboard shortcuts", lines, help_lines(lines), &e->show_help, width,
                    height);
    }
    if (e->show_about) {
        char gl[256];
        snprintf(gl, sizeof gl, "Renderer: %s", info->gl_renderer ? info->gl_renderer : "?");
        char libs[256];
        snprintf(libs, sizeof libs, "GLFW %s; %s; OpenImageIO, stb_truetype, DejaVu fonts",
                 info->glfw_version ? info->glfw_version : "?", tile_store_library_versions());
        const char *about[] = {"Orogen 0.1: a terrain editor", gl, libs};
        text_dialog(ui, "About", about, 3, &e->show_about, width, height);
    }
    e->view_x = v->cam.pos[0];
    e->view_z = v->cam.pos[2];
    if (e->files.open) {
        files_dialog(e, ui, ctx, modal);
    } else if (e->interchange.open) {
        char cmd[4600];
        if (interchange_dialog_draw(&e->interchange, ui, modal, cmd, sizeof cmd) &&
            export_check_accept(&e->interchange, ctx->world))
            editor_ui_run(e, ctx, cmd);
    } else if (e->new_planet.open) {
        if (new_planet_dialog_draw(&e->new_planet, ui, modal, e->planet_command,
                                   sizeof e->planet_command))
            editor_ui_request(e, ctx, PENDING_NEW_PLANET);
    } else if (e->offer_recovery) {
        recover_offer_draw(&e->recovery, ui, ctx->world, modal, run_for_dialog,
                           &(dialog_runner){e, ctx});
    } else if (e->confirm_replace) {
        replace_dialog(e, ui, ctx, modal);
    } else if (e->pending != PENDING_NONE) {
        unsaved_prompt(e, ui, ctx, width, height);
    }
    // The menu bar last: its menus open over everything.
    menus(e, ui, ctx, v, info, top);
    if (ui_get_input(ui)->key_pressed[UI_KEY_ESCAPE] && !ui_wants_keyboard(ui)) {
        e->show_help = e->show_about = e->picking_height = e->shape_placing = 0;
        if (e->files.open)
            e->files.open = 0;
        else if (e->interchange.open)
            e->interchange.open = 0;
        else if (e->new_planet.open)
            e->new_planet.open = 0;
        else if (e->offer_recovery)
            recover_offer_dismiss(&e->recovery);
        else if (e->confirm_replace)
            e->confirm_replace = 0;
        else if (e->pending != PENDING_NONE)
            e->pending = PENDING_NONE;
    }
    return view;
}

int editor_ui_build_busy(ui_context *ui, const char *what, double fraction, double elapsed_ms,
                         float width, float height) {
    float status = ui_em(ui, 1.6f);
    ui_rect r = {0, height - status, width, status};
    ui_modal(ui, r); // only Cancel answers while the work runs
    ui_panel_begin(ui, "Busy", r);
    char label[160], bar[64];
    snprintf(label, sizeof label, "Working: %.120s", what);
    for (char *c = label; *c; c++) // one line: a script's new lines become separators
        if (*c == '\n') *c = ';';
    snprintf(bar, sizeof bar, "%.0f%%  %.1f s##Progress", fraction * 100, elapsed_ms / 1000);
    float cols[3] = {-0.45f, 0, ui_em(ui, 7)};
    ui_row(ui, 3, cols, r.h - 2 * ui_em(ui, 0.3f));
    ui_label(ui, label);
    ui_tooltip(ui, "Long work runs in the background; the world is back in your hands when it "
                   "ends");
    ui_progress(ui, fraction, bar);
    int cancel = ui_button(ui, "Cancel");
    ui_tooltip(ui, "Stop the work (Esc): it leaves no trace (no undo step, the terrain as it was)");
    ui_panel_end(ui);
    return cancel;
}
