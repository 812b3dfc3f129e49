// The editor's menu bar: File, Edit, View, Help.
#include "app/editor_ui_internal.h"
#include "app/shortcuts.h"

// A name for an export, from the world's: beside its file with ext ("dir/alps.exr"), or
// fallback + ext for a world never saved (never the last imported file's name).
static const char *export_name(const cmd_context *ctx, const char *fallback, const char *ext,
                               char *out, size_t size) {
    const char *path = world_path(ctx->world);
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    size_t stem = dot && (!slash || dot > slash) ? (size_t)(dot - path) : strlen(path);
    if (path[0])
        snprintf(out, size, "%.*s%s", (int)stem, path, ext);
    else
        snprintf(out, size, "%s%s", fallback, ext);
    return out;
}

static void file_menu(editor_ui *e, ui_context *ui, cmd_context *ctx) {
    if (ui_menu_item(ui, "New flat world", shortcut_label(SHORTCUT_NEW_FLAT, NULL), 1))
        editor_ui_request(e, ctx, PENDING_NEW_FLAT);
    if (ui_menu_item(ui, "New planet...", NULL, 1)) new_planet_dialog_show(&e->new_planet);
    if (ui_menu_item(ui, "New world from heightmap...", NULL, 1)) // as Gaea, World Machine
        file_browser_show(&e->files, FILE_BROWSER_NEW_FROM, e->interchange.path);
    if (ui_menu_item(ui, "Open...", shortcut_label(SHORTCUT_OPEN, NULL), 1)) editor_ui_open(e, ctx);
    // The window puts the open world in front of the recent ones whenever it is opened or
    // saved (panels_world_opened): the first entry is the open world when it has a file.
    const int first_is_open = world_path(ctx->world)[0] != 0;
    for (int i = 0; i < e->recent_count; i++) {
        char label[1100];
        snprintf(label, sizeof label, "Open %s##recent%d", file_name(e->recent[i]), i);
        if (ui_menu_item(ui, label, NULL, i > 0 || !first_is_open)) {
            snprintf(e->open_path, sizeof e->open_path, "%s", e->recent[i]);
            editor_ui_request(e, ctx, PENDING_OPEN);
        }
    }
    if (e->recent_count) ui_menu_separator(ui);
    if (ui_menu_item(ui, "Save", shortcut_label(SHORTCUT_SAVE, NULL),
                     world_path(ctx->world)[0] != 0))
        editor_ui_save(e, ctx);
    if (ui_menu_item(ui, "Save as...", shortcut_label(SHORTCUT_SAVE_AS, NULL), 1))
        editor_ui_save_as(e, ctx);
    if (ui_menu_item(ui, "Save session as script...", NULL, ctx->session != NULL))
        file_browser_show(&e->files, FILE_BROWSER_SCRIPT, "session.og");
    // Every crash journal, those put off with "Not now" and those set aside included.
    if (ui_menu_item(ui, "Recover unsaved edits...", NULL, 1)) recover_offer_show_all(&e->recovery);
    ui_menu_separator(ui);
    int flat = world_get_params(ctx->world)->kind == WORLD_FLAT;
    if (ui_menu_item(ui, "Import heightmap...", NULL, flat))
        file_browser_show(&e->files, FILE_BROWSER_IMPORT, e->interchange.path);
    char proposed[4200];
    if (flat && ui_menu_item(ui, "Export heightmap...", NULL, 1))
        file_browser_show(&e->files, FILE_BROWSER_EXPORT,
                          export_name(ctx, "heightmap", ".exr", proposed, sizeof proposed));
    if (flat && ui_menu_item(ui, "Export mesh...", NULL, 1))
        file_browser_show(&e->files, FILE_BROWSER_EXPORT_MESH,
                          export_name(ctx, "terrain", ".glb", proposed, sizeof proposed));
    if (!flat && ui_menu_item(ui, "Export planet...", NULL, 1)) // seed 004's export N FILE
        file_browser_show(&e->files, FILE_BROWSER_EXPORT_PLANET,
                          export_name(ctx, "planet", ".obj", proposed, sizeof proposed));
    ui_menu_separator(ui);
    if (ui_menu_item(ui, "Quit", shortcut_label(SHORTCUT_QUIT, NULL), 1))
        editor_ui_request(e, ctx, PENDING_QUIT);
    ui_menu_end(ui);
}

static void edit_menu(editor_ui *e, ui_context *ui, cmd_context *ctx) {
    history *h = world_history(ctx->world);
    size_t pos = history_position(h), n = history_count(h);
    char undo[160] = "Undo", redo[160] = "Redo";
    if (pos > 0) snprintf(undo, sizeof undo, "Undo %s", history_at(h, pos - 1)->label);
    if (pos < n) snprintf(redo, sizeof redo, "Redo %s", history_at(h, pos)->label);
    // Ids by the fixed part of the label, so tests find "Edit/Undo" whatever it says.
    char undo_id[200], redo_id[200];
    snprintf(undo_id, sizeof undo_id, "%s##Undo", undo);
    snprintf(redo_id, sizeof redo_id, "%s##Redo", redo);
    if (ui_menu_item(ui, undo_id, shortcut_label(SHORTCUT_RUN, "undo"), pos > 0))
        editor_ui_run(e, ctx, "undo");
    if (ui_menu_item(ui, redo_id, shortcut_label(SHORTCUT_RUN, "redo"), pos < n))
        editor_ui_run(e, ctx, "redo");
    ui_menu_separator(ui);
    if (ui_menu_item(ui, "History", NULL, 1)) e->history_request = 1; // the dock's section
    ui_menu_end(ui);
}

static void view_menu(editor_ui *e, ui_context *ui, cmd_context *ctx, viewport *v,
                      const editor_frame_info *info) {
    static const char *const modes[] = {"shaded", "wireframe", "levels", "height", "slope"};
    static const char *const labels[] = {"Shaded", "Wireframe", "Clipmap levels", "Height colours",
                                         "Slope colours"};
    for (int i = 0; i < 5; i++) {
        char cmd[64];
        snprintf(cmd, sizeof cmd, "view %s", modes[i]);
        if (ui_menu_item(ui, labels[i], shortcut_label(SHORTCUT_RUN, cmd),
                         (int)v->settings.view != i))
            editor_ui_run(e, ctx, cmd);
    }
    ui_menu_separator(ui);
    if (ui_menu_item(ui,
                     v->settings.parallax ? "Parallax detail: on##Parallax"
                                          : "Parallax detail: off##Parallax",
                     NULL, 1))
        runf(e, ctx, "render parallax=%s", v->settings.parallax ? "off" : "on");
    if (ui_menu_item(ui,
                     v->settings.antialias ? "Smooth edges: on##Antialias"
                                           : "Smooth edges: off##Antialias",
                     NULL, 1))
        runf(e, ctx, "render antialias=%s", v->settings.antialias ? "off" : "on");
    static const double contours[] = {0, 10, 50, 100};
    for (int i = 0; i < 4; i++) {
        char label[64];
        if (contours[i] == 0)
            snprintf(label, sizeof label, "Contour lines: off");
        else
            snprintf(label, sizeof label, "Contour lines every %.0f m", contours[i]);
        if (ui_menu_item(ui, label, NULL, v->settings.contours != contours[i]))
            runf(e, ctx, "render contours=%g", contours[i]);
    }
    static const char *const quality[] = {"Parallax quality: low", "Parallax quality: high"};
    static const int steps[] = {4, 16};
    for (int i = 0; i < 2; i++)
        if (ui_menu_item(ui, quality[i], NULL, v->settings.parallax_steps != steps[i]))
            runf(e, ctx, "render quality=%d", steps[i]);
    static const char *const fogs[] = {"Fog: automatic", "Fog: light", "Fog: thick"};
    static const double densities[] = {0, 0.0002, 0.002};
    for (int i = 0; i < 3; i++)
        if (ui_menu_item(ui, fogs[i], NULL, v->settings.fog_density != densities[i]))
            runf(e, ctx, "render fog=%g", densities[i]);
    static const char *const suns[] = {"Sun: morning", "Sun: noon", "Sun: evening"};
    static const double sun_at[3][2] = {{90, 15}, {135, 60}, {270, 12}};
    for (int i = 0; i < 3; i++)
        if (ui_menu_item(ui, suns[i], NULL, 1))
            runf(e, ctx, "render sun=%g,%g", sun_at[i][0], sun_at[i][1]);
    if (ui_menu_item(ui, v->settings.tile_grid ? "Tile grid: on##Tiles" : "Tile grid: off##Tiles",
                     NULL, 1))
        runf(e, ctx, "render tile_grid=%s", v->settings.tile_grid ? "off" : "on");
    if (ui_menu_item(ui,
                     v->settings.level_grid ? "Clipmap level grid: on##Levels"
                                            : "Clipmap level grid: off##Levels",
                     NULL, 1))
        runf(e, ctx, "render level_grid=%s", v->settings.level_grid ? "off" : "on");
    if (ui_menu_item(ui,
                     v->settings.sun_rotation != 0 ? "Light rotation: on##Light"
                                                   : "Light rotation: off##Light",
                     shortcut_label(SHORTCUT_LIGHT, NULL), 1))
        runf(e, ctx, "render sun_rotation=%g", v->settings.sun_rotation != 0 ? 0.0 : 20.0);
    if (ui_menu_item(ui, "More levels of detail", shortcut_label(SHORTCUT_MORE_LEVELS, NULL),
                     v->settings.levels < RENDER_MAX_LEVELS))
        runf(e, ctx, "render levels=%d", v->settings.levels + 1);
    if (ui_menu_item(ui, "Fewer levels of detail", shortcut_label(SHORTCUT_FEWER_LEVELS, NULL),
                     v->settings.levels > RENDER_MIN_LEVELS))
        runf(e, ctx, "render levels=%d", v->settings.levels - 1);
    if (ui_menu_item(ui,
                     info->dynamic_resolution ? "Dynamic resolution: on##Dynamic"
                                              : "Dynamic resolution: off##Dynamic",
                     shortcut_label(SHORTCUT_DYNAMIC_RES, NULL), 1))
        runf(e, ctx, "dynamic_resolution %s", info->dynamic_resolution ? "off" : "on");
    ui_menu_separator(ui);
    static const char *const cameras[] = {"Camera: fly", "Camera: orbit", "Camera: walk"};
    for (int i = 0; i < 3; i++)
        if (ui_menu_item(ui, cameras[i], shortcut_label(SHORTCUT_NEXT_CAMERA, NULL),
                         info->camera_mode != i)) {
            if (e->host.set_camera_mode) e->host.set_camera_mode(e->host.user, i);
        }
    if (ui_menu_item(ui, "Reset view", shortcut_label(SHORTCUT_RESET_VIEW, NULL), 1))
        editor_ui_run(e, ctx, "camera default");
    ui_menu_separator(ui);
    static const double scales[] = {1.0, 1.25, 1.5, 2.0};
    for (int i = 0; i < 4; i++) {
        char label[64];
        snprintf(label, sizeof label, "UI scale %.0f%%", scales[i] * 100);
        if (ui_menu_item(ui, label, NULL, fabs(info->ui_scale - scales[i]) > 1e-6))
            runf(e, ctx, "ui_scale %g", scales[i]); // a new font, between frames
    }
    if (ui_menu_item(ui, "Console", shortcut_label(SHORTCUT_CONSOLE, NULL), 1))
        console_toggle(&e->console, 0);
    ui_menu_end(ui);
}

void menus(editor_ui *e, ui_context *ui, cmd_context *ctx, viewport *v,
           const editor_frame_info *info, ui_rect bar) {
    ui_menubar_begin(ui, bar);
    if (ui_menu_begin(ui, "File")) file_menu(e, ui, ctx);
    if (ui_menu_begin(ui, "Edit")) edit_menu(e, ui, ctx);
    if (ui_menu_begin(ui, "View")) view_menu(e, ui, ctx, v, info);
    if (ui_menu_begin(ui, "Help")) {
        if (ui_menu_item(ui, "Keyboard shortcuts", shortcut_label(SHORTCUT_HELP, NULL), 1))
            e->show_help = 1;
        if (ui_menu_item(ui, "About Orogen", NULL, 1)) e->show_about = 1;
        ui_menu_end(ui);
    }
    ui_menubar_end(ui);
}
