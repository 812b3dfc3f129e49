#include "app/editor_ui.h"

#include "editor/cmd/tokenize.h"

#include "editor/gen/gen.h"
#include "editor/params/world_params.h"
#include "editor/world/history.h"
#include "io/tile_store.h"
#include "renderer/planet_camera.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

void editor_ui_init(editor_ui *e) {
    memset(e, 0, sizeof *e);
    e->camera_mode_request = -1;
    e->dynamic_resolution = 1;
    console_init(&e->console);
    stamp_browser_init(&e->stamps);
}

void editor_ui_free(editor_ui *e) {
    console_free(&e->console);
}

int editor_ui_run(editor_ui *e, cmd_context *ctx, const char *text) {
    if (e->work) return work_queue_add(e->work, text, "ui", WORK_ECHO);
    return console_run(&e->console, ctx, text, "ui");
}

// Runs text now, on this thread, for actions that go on only when it succeeded (load,
// save): quick file work, not long edits.
static int run_now(editor_ui *e, cmd_context *ctx, const char *text) {
    return console_run(&e->console, ctx, text, "ui");
}

// The problem lines the replace dialog lists (at most this many).
#define REPLACE_LINES_SHOWN 8

static int problem_lines(const char *problems) {
    int n = problems[0] != 0;
    for (const char *c = problems; *c; c++)
        n += *c == '\n';
    return n < REPLACE_LINES_SHOWN ? n : REPLACE_LINES_SHOWN;
}

static int runf(editor_ui *e, cmd_context *ctx, const char *fmt, ...) {
    char text[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    return editor_ui_run(e, ctx, text);
}

static void remember_recent(editor_ui *e, const char *path) {
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

static void do_action(editor_ui *e, cmd_context *ctx, editor_pending action) {
    if (action == PENDING_NEW_FLAT) editor_ui_run(e, ctx, "new flat");
    if (action == PENDING_NEW_PLANET) editor_ui_run(e, ctx, e->planet_command);
    if (action == PENDING_OPEN) {
        char arg[1100], cmd[1200];
        cmd_quote_arg(arg, sizeof arg, e->open_path);
        snprintf(cmd, sizeof cmd, "load %s", arg);
        if (run_now(e, ctx, cmd) == 0) remember_recent(e, e->open_path);
    }
    if (action == PENDING_QUIT) e->quit_requested = 1;
}

void editor_ui_request(editor_ui *e, cmd_context *ctx, editor_pending action) {
    if (world_is_modified(ctx->world))
        e->pending = action;
    else
        do_action(e, ctx, action);
}

static const char *file_name(const char *path) {
    const char *slash = strrchr(path, '/');
    return path[0] ? (slash ? slash + 1 : path) : "unsaved world";
}

// ---- menus --------------------------------------------------------------------------

static void menus(editor_ui *e, ui_context *ui, cmd_context *ctx, viewport *v, ui_rect bar) {
    ui_menubar_begin(ui, bar);
    int saved_before = world_path(ctx->world)[0] != 0;
    if (ui_menu_begin(ui, "File")) {
        if (ui_menu_item(ui, "New flat world", "Ctrl+N", 1))
            editor_ui_request(e, ctx, PENDING_NEW_FLAT);
        if (ui_menu_item(ui, "New planet...", NULL, 1)) new_planet_dialog_show(&e->new_planet);
        if (ui_menu_item(ui, "Open...", "Ctrl+O", 1)) editor_ui_open(e, ctx);
        for (int i = 0; i < e->recent_count; i++) {
            char label[1100];
            snprintf(label, sizeof label, "Open %s##recent%d", file_name(e->recent[i]), i);
            if (ui_menu_item(ui, label, NULL, strcmp(e->recent[i], world_path(ctx->world)) != 0)) {
                snprintf(e->open_path, sizeof e->open_path, "%s", e->recent[i]);
                editor_ui_request(e, ctx, PENDING_OPEN);
            }
        }
        if (e->recent_count) ui_menu_separator(ui);
        if (ui_menu_item(ui, "Save", "Ctrl+S", saved_before)) editor_ui_save(e, ctx);
        if (ui_menu_item(ui, "Save as...", "Ctrl+Shift+S", 1)) editor_ui_save_as(e, ctx);
        if (ui_menu_item(ui, "Save session as script...", NULL, ctx->session != NULL))
            file_browser_show(&e->files, FILE_BROWSER_SCRIPT, "session.og");
        ui_menu_separator(ui);
        int flat = world_get_params(ctx->world)->kind == WORLD_FLAT;
        if (ui_menu_item(ui, "Import heightmap...", NULL, flat))
            file_browser_show(&e->files, FILE_BROWSER_IMPORT, e->interchange.path);
        if (flat && ui_menu_item(ui, "Export heightmap...", NULL, 1))
            file_browser_show(&e->files, FILE_BROWSER_EXPORT,
                              e->interchange.path[0] ? e->interchange.path : "heightmap.exr");
        if (!flat && ui_menu_item(ui, "Export planet...", NULL, 1)) // seed 004's export N FILE
            file_browser_show(&e->files, FILE_BROWSER_EXPORT_PLANET, "planet.obj");
        ui_menu_separator(ui);
        if (ui_menu_item(ui, "Quit", "Ctrl+Q", 1)) editor_ui_request(e, ctx, PENDING_QUIT);
        ui_menu_end(ui);
    }
    if (ui_menu_begin(ui, "Edit")) {
        history *h = world_history(ctx->world);
        size_t pos = history_position(h), n = history_count(h);
        char undo[160] = "Undo", redo[160] = "Redo";
        if (pos > 0) snprintf(undo, sizeof undo, "Undo %s", history_at(h, pos - 1)->label);
        if (pos < n) snprintf(redo, sizeof redo, "Redo %s", history_at(h, pos)->label);
        // Ids by the fixed part of the label, so tests find "Edit/Undo" whatever it says.
        char undo_id[200], redo_id[200];
        snprintf(undo_id, sizeof undo_id, "%s##Undo", undo);
        snprintf(redo_id, sizeof redo_id, "%s##Redo", redo);
        if (ui_menu_item(ui, undo_id, "Ctrl+Z", pos > 0)) editor_ui_run(e, ctx, "undo");
        if (ui_menu_item(ui, redo_id, "Ctrl+Shift+Z", pos < n)) editor_ui_run(e, ctx, "redo");
        ui_menu_separator(ui);
        if (ui_menu_item(ui, "History", NULL, 1)) e->history_request = 1; // the dock's section
        ui_menu_end(ui);
    }
    if (ui_menu_begin(ui, "View")) {
        static const char *const modes[] = {"shaded", "wireframe", "levels", "height", "slope"};
        static const char *const labels[] = {"Shaded", "Wireframe", "Clipmap levels",
                                             "Height colours", "Slope colours"};
        static const char *const keys[] = {"1", "2", "3", "4", "5"};
        for (int i = 0; i < 5; i++)
            if (ui_menu_item(ui, labels[i], keys[i], (int)v->settings.view != i))
                runf(e, ctx, "view %s", modes[i]);
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
        if (ui_menu_item(ui,
                         v->settings.tile_grid ? "Tile grid: on##Tiles" : "Tile grid: off##Tiles",
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
                         "R", 1))
            runf(e, ctx, "render sun_rotation=%g", v->settings.sun_rotation != 0 ? 0.0 : 20.0);
        if (ui_menu_item(ui, "More levels of detail",
                         "Ctrl+=", v->settings.levels < RENDER_MAX_LEVELS))
            runf(e, ctx, "render levels=%d", v->settings.levels + 1);
        if (ui_menu_item(ui, "Fewer levels of detail", "Ctrl+-",
                         v->settings.levels > RENDER_MIN_LEVELS))
            runf(e, ctx, "render levels=%d", v->settings.levels - 1);
        if (ui_menu_item(ui,
                         e->dynamic_resolution ? "Dynamic resolution: on##Dynamic"
                                               : "Dynamic resolution: off##Dynamic",
                         "L", 1))
            runf(e, ctx, "dynamic_resolution %s", e->dynamic_resolution ? "off" : "on");
        ui_menu_separator(ui);
        static const char *const cameras[] = {"Camera: fly", "Camera: orbit", "Camera: walk"};
        for (int i = 0; i < 3; i++)
            if (ui_menu_item(ui, cameras[i], "C", e->camera_mode != i)) e->camera_mode_request = i;
        if (ui_menu_item(ui, "Reset view", "Home", 1)) editor_ui_run(e, ctx, "camera default");
        ui_menu_separator(ui);
        static const double scales[] = {1.0, 1.25, 1.5, 2.0};
        for (int i = 0; i < 4; i++) {
            char label[64];
            snprintf(label, sizeof label, "UI scale %.0f%%", scales[i] * 100);
            if (ui_menu_item(ui, label, NULL, fabs(e->ui_scale - scales[i]) > 1e-6))
                e->ui_scale_request = scales[i]; // applied between frames (a new font)
        }
        if (ui_menu_item(ui, "Console", "~", 1)) {
            e->console.open = !e->console.open;
            e->console.focus_input = e->console.open;
        }
        ui_menu_end(ui);
    }
    if (ui_menu_begin(ui, "Help")) {
        if (ui_menu_item(ui, "Keyboard shortcuts", "F1", 1)) e->show_help = 1;
        if (ui_menu_item(ui, "About Orogen", NULL, 1)) e->show_about = 1;
        ui_menu_end(ui);
    }
    ui_menubar_end(ui);
}

// ---- tools ---------------------------------------------------------------------------

typedef struct tool_entry {
    const char *name;  // as `tool` takes it
    const char *label; // on the button
    const char *tip;
    char key; // its shortcut over the viewport (none collides with the camera's keys)
} tool_entry;

static const tool_entry tools[] = {
    {"raise", "Raise", "Raise the terrain by amount metres per dab (key U)", 'U'},
    {"lower", "Lower", "Lower the terrain by amount metres per dab (key J)", 'J'},
    {"smooth", "Smooth",
     "Blend toward a blur that widens with the radius; invert sharpens (key M; Shift while "
     "dragging smooths with any tool)",
     'M'},
    {"flatten", "Flatten", "Blend toward a height, or the height under the stroke's start (key T)",
     'T'},
    {"set", "Set height", "Blend toward the height you give (key H)", 'H'},
    {"ramp", "Ramp", "A ramp from the stroke's first point to its last (key P)", 'P'},
    {"noise", "Noise", "Add fractal noise (key N)", 'N'},
    {"terrace", "Terrace", "Blend toward terraces of a step height (key K)", 'K'},
    {"thermal", "Thermal", "Thermal erosion down to the talus angle (key Y)", 'Y'},
    {"hydraulic", "Hydraulic", "Droplet erosion: water carves and deposits (key O)", 'O'},
    {"paint", "Paint", "Paint a material; invert removes it (key I)", 'I'},
    {"fill", "Fill",
     "Add rock in 3D: a ball per dab, a tube along a drag (overhangs, arches; "
     "Ctrl carves instead)",
     0},
    {"carve", "Carve",
     "Cut rock away in 3D: a ball per dab, a tube along a drag (caves, "
     "undercuts; Ctrl fills instead)",
     0},
    {"vsmooth", "Smooth 3D", "Smooth the surface in 3D, overhangs included", 0},
    {"vflatten", "Flatten 3D",
     "Flatten the surface in 3D to a level plane (height, or the "
     "first point's)",
     0},
};
#define STAMP_KEY 'B' // the stamp tool's shortcut
#define TOOL_COUNT (sizeof tools / sizeof tools[0])

static int tool_is_current(const brush *b, const char *name) {
    if (strcmp(name, "lower") == 0) return b->tool == BRUSH_RAISE && b->invert;
    if (strcmp(name, "raise") == 0) return b->tool == BRUSH_RAISE && !b->invert;
    return strcmp(brush_tool_name(b->tool), name) == 0;
}

// A small icon for each palette entry, drawn with lines and triangles in box r.
static void tool_icon(ui_context *ui, int tool, ui_rect r, ui_color c) {
    ui_draw_list *dl = ui_draw_target(ui);
    float x0 = r.x, y0 = r.y, w = r.w, h = r.h, t = fmaxf(1.5f, w * 0.09f);
#define P(fx, fy) x0 + (fx)*w, y0 + (fy)*h
    switch (tool) {
    case 0: // raise: a mound and an arrow up
        ui_draw_triangle(dl, P(0.5f, 0.05f), P(0.8f, 0.4f), P(0.2f, 0.4f), c);
        ui_draw_rect(dl, (ui_rect){P(0.42f, 0.4f), w * 0.16f, h * 0.5f}, c);
        break;
    case 1: // lower
        ui_draw_triangle(dl, P(0.5f, 0.95f), P(0.2f, 0.6f), P(0.8f, 0.6f), c);
        ui_draw_rect(dl, (ui_rect){P(0.42f, 0.1f), w * 0.16f, h * 0.5f}, c);
        break;
    case 2: // smooth: a gentle wave
        for (int i = 0; i < 8; i++) {
            float a = i / 8.0f, b = (i + 1) / 8.0f;
            ui_draw_line(dl, P(a, 0.5f - 0.15f * sinf(a * 6.283f)),
                         P(b, 0.5f - 0.15f * sinf(b * 6.283f)), c, t);
        }
        break;
    case 3: // flatten: a bar over a bump
        ui_draw_rect(dl, (ui_rect){P(0.05f, 0.45f), w * 0.9f, t}, c);
        ui_draw_triangle(dl, P(0.3f, 0.85f), P(0.5f, 0.55f), P(0.7f, 0.85f), c);
        break;
    case 4: // set height: a level mark and an arrow to it
        ui_draw_rect(dl, (ui_rect){P(0.05f, 0.3f), w * 0.9f, t}, c);
        ui_draw_triangle(dl, P(0.5f, 0.38f), P(0.7f, 0.65f), P(0.3f, 0.65f), c);
        break;
    case 5: // ramp
        ui_draw_triangle(dl, P(0.05f, 0.9f), P(0.95f, 0.15f), P(0.95f, 0.9f), c);
        break;
    case 6: // noise: a zigzag
        for (int i = 0; i < 6; i++)
            ui_draw_line(dl, P(0.05f + i * 0.15f, i % 2 ? 0.25f : 0.75f),
                         P(0.2f + i * 0.15f, i % 2 ? 0.75f : 0.25f), c, t);
        break;
    case 7: // terrace: steps
        for (int i = 0; i < 3; i++)
            ui_draw_rect(dl,
                         (ui_rect){P(0.1f + i * 0.27f, 0.65f - i * 0.25f), w * 0.27f,
                                   h * (0.25f + i * 0.25f)},
                         c);
        break;
    case 8: // thermal: a slope and falling grains
        ui_draw_triangle(dl, P(0.05f, 0.9f), P(0.5f, 0.2f), P(0.5f, 0.9f), c);
        ui_draw_rect(dl, (ui_rect){P(0.65f, 0.55f), t * 1.5f, t * 1.5f}, c);
        ui_draw_rect(dl, (ui_rect){P(0.82f, 0.78f), t * 1.5f, t * 1.5f}, c);
        break;
    case 9: // hydraulic: a droplet
        ui_draw_triangle(dl, P(0.5f, 0.05f), P(0.75f, 0.55f), P(0.25f, 0.55f), c);
        ui_draw_rect(dl, (ui_rect){P(0.27f, 0.5f), w * 0.46f, h * 0.3f}, c);
        ui_draw_triangle(dl, P(0.27f, 0.8f), P(0.73f, 0.8f), P(0.5f, 0.95f), c);
        break;
    case 10: // paint: a brush
        ui_draw_rect(dl, (ui_rect){P(0.42f, 0.05f), w * 0.16f, h * 0.5f}, c);
        ui_draw_triangle(dl, P(0.25f, 0.55f), P(0.75f, 0.55f), P(0.5f, 0.95f), c);
        break;
    case 11: // fill: a ball on the ground
    case 12: // carve: a ring cut into a block
        if (tool == 12) ui_draw_rect(dl, (ui_rect){P(0.05f, 0.55f), w * 0.9f, h * 0.4f}, c);
        for (int i = 0; i < 12; i++) {
            float a = i * 0.5236f, b = (i + 1) * 0.5236f;
            if (tool == 11)
                ui_draw_triangle(dl, P(0.5f, 0.45f),
                                 P(0.5f + 0.3f * cosf(a), 0.45f + 0.3f * sinf(a)),
                                 P(0.5f + 0.3f * cosf(b), 0.45f + 0.3f * sinf(b)), c);
            else
                ui_draw_line(dl, P(0.5f + 0.28f * cosf(a), 0.55f + 0.28f * sinf(a)),
                             P(0.5f + 0.28f * cosf(b), 0.55f + 0.28f * sinf(b)), c, t);
        }
        if (tool == 11) ui_draw_rect(dl, (ui_rect){P(0.05f, 0.8f), w * 0.9f, t}, c);
        break;
    case 13: // smooth 3D: a wave under an arch
        for (int i = 0; i < 8; i++) {
            float a = i / 8.0f, b = (i + 1) / 8.0f;
            ui_draw_line(dl, P(a, 0.75f - 0.12f * sinf(a * 6.283f)),
                         P(b, 0.75f - 0.12f * sinf(b * 6.283f)), c, t);
            ui_draw_line(dl, P(0.15f + 0.7f * a, 0.45f - 0.3f * sinf(a * 3.1416f)),
                         P(0.15f + 0.7f * b, 0.45f - 0.3f * sinf(b * 3.1416f)), c, t);
        }
        break;
    case 14: // flatten 3D: a bar across a ball
        ui_draw_rect(dl, (ui_rect){P(0.05f, 0.45f), w * 0.9f, t}, c);
        for (int i = 0; i < 6; i++) {
            float a = 3.1416f + i * 0.5236f, b = 3.1416f + (i + 1) * 0.5236f;
            ui_draw_triangle(dl, P(0.5f, 0.48f), P(0.5f + 0.3f * cosf(a), 0.48f - 0.3f * sinf(a)),
                             P(0.5f + 0.3f * cosf(b), 0.48f - 0.3f * sinf(b)), c);
        }
        break;
    default: // stamp: a block and its print
        ui_draw_rect(dl, (ui_rect){P(0.25f, 0.1f), w * 0.5f, h * 0.45f}, c);
        ui_draw_rect(dl, (ui_rect){P(0.1f, 0.75f), w * 0.8f, t * 1.5f}, c);
        break;
    }
#undef P
}

int editor_ui_tool_for_key(int letter) {
    for (size_t i = 0; i < TOOL_COUNT; i++)
        if (tools[i].key == letter) return (int)i;
    return letter == STAMP_KEY ? (int)TOOL_COUNT : -1;
}

// The volume tools (caves, overhangs) work on flat worlds only: on a planet they are
// not in the palette and their keys do nothing.
static int tool_available(const cmd_context *ctx, size_t index) {
    if (index >= TOOL_COUNT || world_get_params(ctx->world)->kind != WORLD_PLANET) return 1;
    int tool = brush_tool_parse(tools[index].name);
    return tool < 0 || !brush_tool_is_volume((brush_tool)tool);
}

void editor_ui_pick_tool(editor_ui *e, cmd_context *ctx, int index) {
    if (index >= 0 && !tool_available(ctx, (size_t)index)) return;
    if (index >= 0 && index < (int)TOOL_COUNT) {
        runf(e, ctx, "tool %s", tools[index].name);
        e->stamps.active = 0;
    } else if (index == (int)TOOL_COUNT) { // the stamp tool: the browser shows its stamps
        stamp_browser_load(&e->stamps, ctx);
        if (e->stamps.selected < 0 && e->stamps.count > 0) e->stamps.selected = 0;
        e->stamps.active = e->stamps.selected >= 0;
        e->stamps.open_request = 1;
    }
}

static void palette(editor_ui *e, ui_context *ui, cmd_context *ctx, ui_rect r) {
    ui_panel_begin(ui, "Tools", r);
    // Names beside the icons when they fit; icons alone (names in the tooltips) when the
    // window is narrow, as Blender's toolbar does.
    float indent = ui_em(ui, 1.3f), widest = 0;
    for (size_t i = 0; i < TOOL_COUNT; i++)
        widest = fmaxf(widest, ui_font_text_width(ui_get_font(ui), UI_FACE_SANS, tools[i].label,
                                                  strlen(tools[i].label)));
    int names = r.w >= indent + widest + ui_em(ui, 1.3f);
    if (!names) indent = r.w;
    // Icons two to a row when one column of them would not fit the height (a small
    // window, a large UI scale), so every tool stays in view without scrolling.
    int columns = !names && (TOOL_COUNT + 1) * ui_em(ui, 1.9f) > r.h ? 2 : 1;
    float halves[2] = {0, 0};
    if (columns == 2) indent = r.w / 2;
    ui_row(ui, columns, columns == 2 ? halves : NULL, ui_em(ui, 1.6f));
    char tip[300];
    for (size_t i = 0; i <= TOOL_COUNT; i++) {
        if (!tool_available(ctx, i)) continue;
        int stamp = i == TOOL_COUNT;
        const char *label = stamp ? "Stamp" : tools[i].label;
        int on = stamp ? e->stamps.active
                       : !e->stamps.active && tool_is_current(&ctx->brush, tools[i].name);
        int clicked = ui_toggle_button_indented(ui, label, on, indent);
        ui_rect b = ui_last_rect(ui);
        float side = b.h * 0.6f, x = names ? b.x + b.h * 0.2f : b.x + (b.w - side) * 0.5f;
        tool_icon(ui, (int)i, (ui_rect){x, b.y + b.h * 0.2f, side, side}, ui_get_theme(ui)->text);
        snprintf(tip, sizeof tip, "%s%s%s", names ? "" : label, names ? "" : ": ",
                 stamp ? "Place a stamp (a shape or heightmap) with a click in the viewport "
                         "(key B)"
                       : tools[i].tip);
        ui_tooltip(ui, tip);
        if (clicked) editor_ui_pick_tool(e, ctx, (int)i);
    }
    ui_panel_end(ui);
}

// The current tool's name as `tool` takes it.
static const char *current_tool(const brush *b) {
    return b->tool == BRUSH_RAISE && b->invert ? "lower" : brush_tool_name(b->tool);
}

static void slider_key(editor_ui *e, ui_context *ui, cmd_context *ctx, const char *label,
                       const char *key, double value, double lo, double hi, const char *fmt,
                       const char *tip) {
    double v = value;
    if (ui_slider(ui, label, &v, lo, hi, fmt)) {
        // Whole numbers for integer keys, else enough digits to keep the value.
        if (strcmp(fmt, "%.0f") == 0)
            runf(e, ctx, "tool %s %s=%.0f", current_tool(&ctx->brush), key, v);
        else
            runf(e, ctx, "tool %s %s=%.6g", current_tool(&ctx->brush), key, v);
    }
    ui_tooltip(ui, tip);
}

// Runs `tool T curve=...` for the points (which makes the falloff the curve).
static void set_curve(editor_ui *e, cmd_context *ctx, const char *tool, const float *ct,
                      const float *cv, int n) {
    char pts[BRUSH_CURVE_MAX * 24] = "";
    for (int i = 0; i < n; i++) {
        size_t at = strlen(pts);
        snprintf(pts + at, sizeof pts - at, "%s%.3g:%.3g", i ? "," : "", ct[i], cv[i]);
    }
    runf(e, ctx, "tool %s curve=%s", tool, pts);
}

// The falloff: Unreal's four presets, constant and the user's curve, and a curve
// editor showing the profile (editing it turns a preset into a curve).
static void falloff_options(editor_ui *e, ui_context *ui, cmd_context *ctx, const char *tool) {
    const brush *b = &ctx->brush;
    static const char *const names[] = {"smooth", "linear",   "spherical",
                                        "tip",    "constant", "curve"};
    static const brush_falloff kinds[] = {FALLOFF_SMOOTH, FALLOFF_LINEAR,   FALLOFF_SPHERICAL,
                                          FALLOFF_TIP,    FALLOFF_CONSTANT, FALLOFF_CURVE};
    int f = 0;
    for (int i = 0; i < 6; i++)
        if (kinds[i] == b->falloff) f = i;
    // The profile as points: the curve's own, or five samples of the preset.
    float ct[BRUSH_CURVE_MAX], cv[BRUSH_CURVE_MAX];
    int n = 5;
    if (b->falloff == FALLOFF_CURVE) {
        n = b->curve_count;
        memcpy(ct, b->curve_t, sizeof ct);
        memcpy(cv, b->curve_v, sizeof cv);
    } else {
        for (int i = 0; i < n; i++) {
            ct[i] = i / (float)(n - 1);
            cv[i] = brush_falloff_weight(b, fminf(ct[i], 0.999f)); // the edge's own value
        }
    }
    if (ui_combo(ui, "Falloff", &f, names, 6)) {
        if (kinds[f] == FALLOFF_CURVE && b->curve_count < 2)
            set_curve(e, ctx, tool, ct, cv, n); // a curve starts as the preset it replaces
        else
            runf(e, ctx, "tool %s falloff=%s", tool, names[f]);
    }
    ui_tooltip(ui, "How the effect fades from the centre to the edge: Unreal's smooth, linear, "
                   "spherical and tip, constant, or your own curve");
    ui_row(ui, 1, NULL, ui_em(ui, 4.5f));
    if (ui_curve(ui, "Falloff curve", ct, cv, &n, BRUSH_CURVE_MAX))
        set_curve(e, ctx, tool, ct, cv, n);
    ui_tooltip(ui, "The falloff from the centre (left) to the edge (right). Drag a point, "
                   "double-click to add one, right-click to remove one: the brush then uses "
                   "this curve");
    ui_row(ui, 1, NULL, 0);
}

// The tool's seed with a button for another one.
static void seed_row(editor_ui *e, ui_context *ui, cmd_context *ctx, const char *tip) {
    const brush *b = &ctx->brush;
    float cols[2] = {0, ui_em(ui, 4.5f)};
    ui_row(ui, 2, cols, 0);
    char line[64];
    snprintf(line, sizeof line, "Seed: %u##tool_seed", b->seed);
    ui_label(ui, line);
    ui_tooltip(ui, tip);
    if (ui_button(ui, "Random##tool_seed"))
        runf(e, ctx, "tool %s seed=%u", current_tool(b),
             (b->seed * 2654435761u + 12345u) % 1000000u);
    ui_tooltip(ui, "Pick another seed");
    ui_row(ui, 1, NULL, 0);
}

// The Height slider and its Pick button (the next click in the viewport takes the
// height there).
static void height_row(editor_ui *e, ui_context *ui, cmd_context *ctx, const char *tip) {
    float cols[2] = {0, ui_em(ui, 3.5f)};
    ui_row(ui, 2, cols, 0);
    slider_key(e, ui, ctx, "Height", "height", ctx->brush.height, -1000, 5000, "%.1f m", tip);
    if (ui_toggle_button(ui, "Pick##height", e->picking_height))
        e->picking_height = !e->picking_height;
    ui_tooltip(ui, "Pick the height from the terrain: the next click in the viewport takes "
                   "the height there (Esc: no)");
    ui_row(ui, 1, NULL, 0);
}

// The 3D shapes placed with clicks in the viewport, sized by the brush radius R.
enum { SHAPE_NONE, SHAPE_ARCH, SHAPE_SPIRE, SHAPE_HOODOO, SHAPE_OVERHANG, SHAPE_COUNT };
static const struct {
    const char *label;
    int clicks;
    const char *tip;
} shapes[SHAPE_COUNT] = {
    {NULL, 0, NULL},
    {"Arch", 2, "An arch: click its two feet (R thick, rising half its span)"},
    {"Spire", 1, "A rock spire: click its foot (R/2 wide at the foot, 3R tall)"},
    {"Hoodoo", 1, "A spire with a capstone: click its foot"},
    {"Overhang", 2,
     "A shelf out over a cliff: click two points along the cliff's top edge (R "
     "out, R/2 thick)"},
};

int editor_ui_shape_click(editor_ui *e, const cmd_context *ctx, const double hit[3], char *cmd,
                          size_t len) {
    int kind = e->shape_placing;
    if (kind <= SHAPE_NONE || kind >= SHAPE_COUNT) return 0;
    if (++e->shape_clicks < shapes[kind].clicks) {
        memcpy(e->shape_at, hit, sizeof e->shape_at);
        return 0;
    }
    double r = ctx->brush.radius;
    const double *a = e->shape_at;
    switch (kind) {
    case SHAPE_ARCH:
        snprintf(cmd, len, "arch %.17g %.17g %.17g %.17g %.17g %.17g thickness=%.6g", a[0], a[1],
                 a[2], hit[0], hit[1], hit[2], r);
        break;
    case SHAPE_SPIRE:
    case SHAPE_HOODOO:
        snprintf(cmd, len, "spire %.17g %.17g %.17g height=%.6g radius=%.6g%s", hit[0], hit[1],
                 hit[2], 3 * r, r / 2, kind == SHAPE_HOODOO ? " taper=0.4" : "");
        if (kind == SHAPE_HOODOO) {
            size_t at = strlen(cmd);
            snprintf(cmd + at, len - at, " cap=%.6g", r * 0.6);
        }
        break;
    default:
        snprintf(cmd, len, "overhang %.17g %.17g %.17g %.17g distance=%.6g thickness=%.6g", a[0],
                 a[2], hit[0], hit[2], r, r / 2);
        break;
    }
    e->shape_placing = 0;
    e->shape_clicks = 0;
    return 1;
}

// The shape buttons: one arms its placement (a second click on it, or Esc, disarms).
static void shape_buttons(editor_ui *e, ui_context *ui) {
    float halves[2] = {0, 0};
    for (int k = SHAPE_ARCH; k < SHAPE_COUNT; k++) {
        if ((k - SHAPE_ARCH) % 2 == 0) ui_row(ui, 2, halves, 0);
        if (ui_toggle_button(ui, shapes[k].label, e->shape_placing == k)) {
            e->shape_placing = e->shape_placing == k ? SHAPE_NONE : k;
            e->shape_clicks = 0;
        }
        ui_tooltip(ui, shapes[k].tip);
    }
    ui_row(ui, 1, NULL, 0);
    if (e->shape_placing) {
        char line[96];
        snprintf(line, sizeof line, "%s: click %s in the view (Esc: no)",
                 shapes[e->shape_placing].label,
                 shapes[e->shape_placing].clicks - e->shape_clicks > 1 ? "twice" : "once");
        ui_label(ui, line);
    }
}

// The volume tools: where the brush sits in 3D, and vflatten's plane.
static void volume_options(editor_ui *e, ui_context *ui, cmd_context *ctx, const char *t) {
    const brush *b = &ctx->brush;
    slider_key(e, ui, ctx, "Depth", "depth", b->depth, -50, 50, "%.1f m",
               "How far past the surface under the mouse the brush centre sits, along the view "
               "(negative: in front of it)");
    static const char *const locks[] = {"surface", "plane"};
    int lock = b->lock_plane;
    if (ui_combo(ui, "Follow", &lock, locks, 2)) runf(e, ctx, "tool %s lock=%s", t, locks[lock]);
    ui_tooltip(ui, "surface: the brush follows the surface under the mouse; plane: it stays on "
                   "the level plane where the drag began (a tunnel at one height)");
    if (b->tool == BRUSH_VFLATTEN)
        height_row(e, ui, ctx, "The plane's height in metres (unset: the first point's height)");
    shape_buttons(e, ui);
}

static void tool_options(editor_ui *e, ui_context *ui, cmd_context *ctx) {
    const brush *b = &ctx->brush;
    if (!brush_tool_is_volume(b->tool)) e->shape_placing = 0; // its buttons are gone
    const char *t = current_tool(b);
    ui_row(ui, 1, NULL, 0);
    slider_key(e, ui, ctx, "Radius", "radius", b->radius, 0.5, 500, "%.1f m",
               "Brush radius in metres ([ and ] change it)");
    slider_key(e, ui, ctx, "Strength", "strength", b->strength, 0, 1, "%.2f",
               "How much of the tool's effect one dab applies");
    slider_key(e, ui, ctx, "Spacing", "spacing", b->spacing, 0.05, 2, "%.2f x radius",
               "Distance between dabs along a stroke, as a fraction of the radius");
    falloff_options(e, ui, ctx, t);
    if (brush_tool_is_volume(b->tool)) {
        volume_options(e, ui, ctx, t);
        return;
    }
    if (b->tool != BRUSH_RAISE) { // raise/lower is the invert pair
        int inv = b->invert;
        if (ui_checkbox(ui, "Invert", &inv)) runf(e, ctx, "tool %s invert=%d", t, inv);
        ui_tooltip(ui, "The opposite effect (lower, sharpen, subtract, remove the material)");
    }
    if (b->tool != BRUSH_PAINT) {
        static const char *const targets[] = {"coarse", "detail"};
        int target = b->target == TILE_LAYER_DETAIL;
        if (ui_combo(ui, "Layer", &target, targets, 2))
            runf(e, ctx, "tool %s target=%s", t, targets[target]);
        ui_tooltip(ui, "coarse: the terrain's shape; detail: fine relief drawn with parallax");
    }
    switch (b->tool) {
    case BRUSH_RAISE:
    case BRUSH_NOISE:
        slider_key(e, ui, ctx, "Amount", "amount", b->amount, 0, 50, "%.2f m",
                   "Metres per dab at full strength");
        if (b->tool == BRUSH_NOISE) {
            slider_key(e, ui, ctx, "Noise scale", "scale", b->noise_scale, 1, 2000, "%.0f m",
                       "Metres per noise feature");
            slider_key(e, ui, ctx, "Octaves", "octaves", b->noise_octaves, 1, 12, "%.1f",
                       "Layers of finer noise");
            seed_row(e, ui, ctx, "The noise pattern's seed");
        }
        break;
    case BRUSH_FLATTEN:
    case BRUSH_SET: {
        height_row(e, ui, ctx, "The height to blend toward, in metres");
        if (b->tool == BRUSH_FLATTEN) {
            static const char *const modes[] = {"both", "raise", "lower"};
            int m = (int)b->flatten;
            if (ui_combo(ui, "Mode", &m, modes, 3)) runf(e, ctx, "tool flatten mode=%s", modes[m]);
            ui_tooltip(ui, "both: raise and lower toward the height; raise: only fill up to it; "
                           "lower: only cut down to it");
        }
        break;
    }
    case BRUSH_TERRACE:
        slider_key(e, ui, ctx, "Step", "step", b->terrace_step, 0.5, 200, "%.1f m",
                   "Height of one terrace");
        slider_key(e, ui, ctx, "Sharpness", "sharpness", b->terrace_sharpness, 0, 1, "%.2f",
                   "0: ramps, 1: flat treads and vertical risers");
        break;
    case BRUSH_THERMAL:
        slider_key(e, ui, ctx, "Talus", "talus", b->thermal.talus_deg, 0.1, 89, "%.1f deg",
                   "Slopes steeper than this angle crumble");
        slider_key(e, ui, ctx, "Iterations", "iterations", b->thermal.iterations, 1, 200, "%.0f",
                   "Passes per dab");
        break;
    case BRUSH_HYDRAULIC:
        slider_key(e, ui, ctx, "Droplets", "droplets", b->hydraulic.droplets, 1, 20000, "%.0f",
                   "Water droplets per dab");
        slider_key(e, ui, ctx, "Erosion", "erosion", b->hydraulic.erosion, 0, 1, "%.2f",
                   "How fast the water takes material away where it carries less than it can");
        slider_key(e, ui, ctx, "Deposition", "deposition", b->hydraulic.deposition, 0, 1, "%.2f",
                   "How fast it lays material down where it carries more than it can");
        slider_key(e, ui, ctx, "Evaporation", "evaporation", b->hydraulic.evaporation, 0, 0.2,
                   "%.3f", "The water lost at each step (shorter, more local channels)");
        slider_key(e, ui, ctx, "Capacity", "capacity", b->hydraulic.capacity, 0, 20, "%.1f",
                   "How much sediment fast water can carry");
        slider_key(e, ui, ctx, "Inertia", "inertia", b->hydraulic.inertia, 0, 1, "%.2f",
                   "How much of its direction a droplet keeps (0: straight downhill)");
        seed_row(e, ui, ctx, "The droplets' seed");
        break;
    case BRUSH_PAINT: {
        static const char *const materials[] = {"automatic", "sand", "grass",  "rock",
                                                "snow",      "dirt", "gravel", "moss"};
        float quarters[4] = {0, 0, 0, 0};
        ui_push_scope(ui, "Materials");
        for (int m = 0; m < 8; m++) {
            if (m % 4 == 0) ui_row(ui, 4, quarters, ui_em(ui, 3.4f));
            if (ui_image_button(ui, materials[m], e->material_textures[m], b->material == m))
                runf(e, ctx, "tool paint material=%d", m);
            ui_tooltip(ui, m == 0 ? "automatic: back to the rules (sand by the water, grass, rock "
                                    "on slopes, snow up high)"
                                  : "Paint this material (invert removes it)");
        }
        ui_pop_scope(ui);
        ui_row(ui, 1, NULL, 0);
        break;
    }
    default:
        break;
    }
}

// ---- world and history ------------------------------------------------------------------

// A slider for one parameter of the next generate (`set KEY VALUE`), with the
// parameter's own description as its tooltip.
static void param_slider(editor_ui *e, ui_context *ui, cmd_context *ctx, const char *label,
                         const char *key, double value, double lo, double hi, const char *fmt) {
    double v = value;
    if (ui_slider(ui, label, &v, lo, hi, fmt)) runf(e, ctx, "set %s %.6g", key, v);
    ui_tooltip(ui, world_params_key_help(key));
}

// The tile store's count is a query: asked again at most once a second.
static long long tiles_stored(editor_ui *e, cmd_context *ctx, double now) {
    if (now - e->tiles_counted_at >= 1.0 || now < e->tiles_counted_at) {
        tile_store *store = world_store(ctx->world);
        e->tiles_stored = store ? (long long)tile_store_count(store, -1) : 0;
        e->tiles_counted_at = now;
    }
    return e->tiles_stored;
}

// The World panel's less used parameters: fBm shape, the generator's own keys, the
// grid (collapsed by default, so the dock keeps room for the history).
static void world_more(editor_ui *e, ui_context *ui, cmd_context *ctx, const world_params *next) {
    char line[128];
    if (next->generator != GEN_FLAT) {
        param_slider(e, ui, ctx, "Gain (w_factor)", "w_factor", next->w_factor, 0.05, 1.45, "%.2f");
        param_slider(e, ui, ctx, "Lacunarity (exponent)", "exponent", next->exponent, 1.1, 4,
                     "%.2f");
        param_slider(e, ui, ctx, "Feature size", "feature_size", next->feature_size, 0, 50000,
                     next->feature_size > 0 ? "%.0f m" : "automatic");
    }
    param_slider(e, ui, ctx, "Base height", "base_height", next->base_height, -2000, 2000,
                 "%.0f m");
    if (next->generator == GEN_DIAMOND_SQUARE) {
        param_slider(e, ui, ctx, "Roughness", "roughness", next->roughness, 0, 2, "%.2f");
        param_slider(e, ui, ctx, "Smoothing", "smoothing", next->smoothing, 0, 1, "%.2f");
    } else if (next->generator == GEN_RIDGED) {
        param_slider(e, ui, ctx, "Ridge offset", "ridge_offset", next->ridge_offset, 0, 2, "%.2f");
    } else if (next->generator == GEN_FAULTS) {
        param_slider(e, ui, ctx, "Faults", "fault_count", next->fault_count, 0, 1000,
                     "%.0f per 64 km");
    }
    param_slider(e, ui, ctx, "Spacing", "spacing", next->spacing, 0.25, 100, "%.2f m");
    if (next->kind == WORLD_PLANET) return; // a planet's faces follow its radius and spacing
    static const char *const sizes[] = {"unbounded", "512",  "1024", "2048",
                                        "4096",      "8192", "16384"};
    static const long long size_values[] = {0, 512, 1024, 2048, 4096, 8192, 16384};
    int sz = -1;
    for (int i = 0; i < 7; i++)
        if (size_values[i] == next->size) sz = i;
    if (sz < 0) { // another size, set by a command: shown, not offered
        snprintf(line, sizeof line, "Size: %lld samples", (long long)next->size);
        ui_label(ui, line);
    } else if (ui_combo(ui, "Size", &sz, sizes, 7)) {
        runf(e, ctx, "set size %lld", size_values[sz]);
    }
    ui_tooltip(ui, world_params_key_help("size"));
}

static void world_panel(editor_ui *e, ui_context *ui, cmd_context *ctx) {
    const world_params *next = &ctx->next;
    char line[1200];
    ui_row(ui, 1, NULL, 0);
    snprintf(line, sizeof line, "%s%s", file_name(world_path(ctx->world)),
             world_is_modified(ctx->world) ? " (unsaved changes)" : "");
    ui_label(ui, line);
    ui_tooltip(ui, "The world's parameter file; its edits are kept in NAME.tiles beside it");
    tile_store *store = world_store(ctx->world);
    snprintf(line, sizeof line, "%lld tiles stored%s%s",
             tiles_stored(e, ctx, ui_get_input(ui)->time), store ? " in " : "",
             store ? file_name(tile_store_path(store)) : "");
    ui_label_colored(ui, line, ui_get_theme(ui)->text_dim);
    ui_tooltip(ui, "The tile store: the sculpted and painted tiles kept on disk");
    const char *names[GEN_COUNT];
    for (int g = 0; g < GEN_COUNT; g++)
        names[g] = gen_kind_name((gen_kind)g);
    int g = (int)next->generator;
    if (ui_combo(ui, "Generator", &g, names, GEN_COUNT)) runf(e, ctx, "generator %s", names[g]);
    ui_tooltip(ui, "The generator of the next Generate (the parameters below apply when you "
                   "press Generate: one undo step)");
    float half[2] = {0, ui_em(ui, 4.5f)};
    ui_row(ui, 2, half, 0);
    snprintf(line, sizeof line, "Seed: %lld", (long long)next->seed);
    ui_label(ui, line);
    ui_tooltip(ui, world_params_key_help("seed"));
    if (ui_button(ui, "Random##seed"))
        runf(e, ctx, "seed %u", (unsigned)(next->seed * 2654435761u + 12345u) % 1000000u);
    ui_tooltip(ui, "Pick another seed (applied by Generate)");
    ui_row(ui, 1, NULL, 0);
    if (next->generator != GEN_FLAT) {
        // Up to Mars-like relief (10 km) and octaves down to 1 m samples on an Earth-sized
        // planet (the presets use 18).
        param_slider(e, ui, ctx, "Max height", "max_height", next->max_height, 10, 12000, "%.0f m");
        param_slider(e, ui, ctx, "Octaves", "octaves", next->octaves, 1, 24, "%.1f");
    }
    if (next->kind == WORLD_PLANET) { // a radius there (seed 004)
        // The sea keeps its height above the datum when the radius changes (ocean_level
        // is a radius on planets): both commands run, both are echoed.
        // Both shown as a person thinks of them: the radius in km, the sea by its height
        // above the datum (the command still sets ocean_level, the sea's radius).
        double km = next->radius / 1000.0;
        if (ui_slider(ui, "Radius", &km, 1, 10000, "%.1f km"))
            runf(e, ctx, "set radius %.9g; set ocean_level %.9g", km * 1000.0,
                 next->ocean_level + (km * 1000.0 - next->radius));
        ui_tooltip(ui, world_params_key_help("radius"));
        double sea = next->ocean_level - next->radius;
        const char *sea_fmt = sea < -next->max_height ? "no sea" : "%.0f m"; // all under ground
        if (ui_slider(ui, "Sea level", &sea, -next->max_height, next->max_height, sea_fmt))
            runf(e, ctx, "set ocean_level %.9g", next->radius + sea);
        ui_tooltip(ui, "The sea's surface, metres above the datum (set ocean_level: the sea's "
                       "radius, seed 004's way; under all the ground: no sea)");
        param_slider(e, ui, ctx, "Atmosphere", "atmosphere", next->atmosphere, 0, 3, "%.2f");
        // The light's rotation as a day's length (omega = 2 pi / day); 0: it does not turn.
        double day = next->omega > 0 ? 2.0 * M_PI / next->omega / 3600.0 : 1000.0;
        if (ui_slider(ui, "Day", &day, 1, 1000, next->omega > 0 ? "%.1f h" : "not turning"))
            runf(e, ctx, "set omega %.9g", 2.0 * M_PI / (day * 3600.0));
        ui_tooltip(ui, "Hours per turn of the light (R in the view toggles the turning; set "
                       "omega 0: it does not turn)");
    } else
        param_slider(e, ui, ctx, "Ocean level", "ocean_level", next->ocean_level, -1000, 3000,
                     "%.0f m");
    if (ui_section(ui, "More parameters", 0)) world_more(e, ui, ctx, next);
    ui_row(ui, 1, NULL, 0);
    if (ui_button(ui, "Generate")) editor_ui_run(e, ctx, "generate");
    ui_tooltip(ui, "Regenerate the terrain from these parameters (one undo step; edits stay)");
}

// The layers: the coarse and detail heights (the current tool's target), the material
// layer's eight materials (the paint material) and whether the automatic material rules
// colour unpainted ground.
static void layers_panel(editor_ui *e, ui_context *ui, cmd_context *ctx, const viewport *v) {
    static const char *const names[8] = {"automatic", "sand", "grass",  "rock",
                                         "snow",      "dirt", "gravel", "moss"};
    const brush *b = &ctx->brush;
    int painting = b->tool == BRUSH_PAINT && !e->stamps.active;
    ui_row(ui, 1, NULL, 0);
    if (ui_tree_push(ui, "Height layers", 1)) {
        static const char *const targets[2] = {"coarse", "detail"};
        static const char *const labels[2] = {"Coarse: the terrain's shape",
                                              "Detail: fine relief (parallax)"};
        for (int i = 0; i < 2; i++) {
            int on = !painting && (b->target == TILE_LAYER_DETAIL) == i;
            if (ui_selectable(ui, labels[i], on))
                runf(e, ctx, "tool %s target=%s", painting ? "raise" : current_tool(b), targets[i]);
            ui_tooltip(ui, "Sculpt this layer (the current tool's target)");
        }
        ui_tree_pop(ui);
    }
    if (ui_tree_push(ui, "Material layer", 1)) {
        for (int m = 0; m < 8; m++) {
            if (ui_color_swatch(ui, names[m], e->material_colors[m], painting && b->material == m))
                runf(e, ctx, "tool paint material=%d", m);
            ui_tooltip(ui, m == 0 ? "Paint back to the automatic rules (grass, rock, snow by "
                                    "height and slope)"
                                  : "Paint this material (picks the paint tool)");
        }
        int rules = v->settings.auto_materials;
        if (ui_checkbox(ui, "Automatic material rules", &rules))
            runf(e, ctx, "render auto_materials=%s", rules ? "on" : "off");
        ui_tooltip(ui, "Show the automatic materials on unpainted ground; off shows it as plain "
                       "clay, so painted areas stand out");
        ui_tree_pop(ui);
    }
}

static void history_panel(editor_ui *e, ui_context *ui, cmd_context *ctx) {
    history *h = world_history(ctx->world);
    size_t n = history_count(h), pos = history_position(h);
    char line[256];
    ui_row(ui, 1, NULL, 0);
    snprintf(line, sizeof line, "%zu steps, %.1f of %.0f MiB", n, history_bytes(h) / 1048576.0,
             history_budget(h) / 1048576.0);
    ui_label_colored(ui, line, ui_get_theme(ui)->text_dim);
    // Where the file on disk stands in the history (a world never saved has none).
    long saved = world_path(ctx->world)[0] ? history_saved_position(h) : -1;
    if (saved == 0)
        ui_label_colored(ui, "(saved before the first step)", ui_get_theme(ui)->text_dim);
    ui_push_scope(ui, "Steps");
    float cols[2] = {0, ui_em(ui, 5.5f)};
    ui_row(ui, 2, cols, 0);
    for (size_t i = 0; i < n; i++) {
        const history_step *s = history_at(h, i);
        snprintf(line, sizeof line, "%zu %s##%zu", i + 1, s->label, i + 1);
        if (ui_toggle_button(ui, line, i < pos)) {
            // Clicking a step makes it the last one applied.
            char cmds[1024] = "";
            size_t target = i + 1;
            for (size_t k = pos; k > target && strlen(cmds) + 8 < sizeof cmds; k--)
                strcat(cmds, "undo;");
            for (size_t k = pos; k < target && strlen(cmds) + 8 < sizeof cmds; k++)
                strcat(cmds, "redo;");
            if (cmds[0]) editor_ui_run(e, ctx, cmds);
        }
        ui_tooltip(ui, i < pos ? "Applied: click to undo the steps after it"
                               : "Undone: click to redo up to here");
        // The step's memory, and the saved state marked.
        snprintf(line, sizeof line, "%.0f KiB%s##size%zu", s->bytes / 1024.0,
                 saved == (long)i + 1 ? ", saved" : "", i + 1);
        ui_label_colored(ui, line, ui_get_theme(ui)->text_dim);
        ui_tooltip(ui, saved == (long)i + 1 ? "Undo memory of the step; the world was saved here"
                                            : "Undo memory of the step");
    }
    ui_pop_scope(ui);
}

// ---- status bar and dialogs -------------------------------------------------------------

static void status_bar(ui_context *ui, cmd_context *ctx, viewport *v, const editor_frame_info *info,
                       const stamp_browser *stamps, ui_rect r) {
    ui_panel_begin(ui, "Status", r);
    char cursor[128] = "", cam[128], tool[96], frame[128], cache[160];
    const world_params *wp = world_get_params(ctx->world);
    if (info->cursor_valid && wp->kind == WORLD_PLANET) { // where on the globe, how high
        const double *c = info->cursor;
        double lat, lon, r = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        planet_lat_lon(c, &lat, &lon);
        snprintf(cursor, sizeof cursor, "%.5f%c %.5f%c  height %.2f m", fabs(lat),
                 lat < 0 ? 'S' : 'N', fabs(lon), lon < 0 ? 'W' : 'E', r - wp->radius);
    } else if (info->cursor_valid)
        snprintf(cursor, sizeof cursor, "x %.1f  z %.1f  height %.2f m", info->cursor[0],
                 info->cursor[2], info->cursor[1]);
    else
        snprintf(cursor, sizeof cursor, "no terrain under the pointer");
    snprintf(cam, sizeof cam, "camera %.0f, %.0f, %.0f", v->cam.pos[0], v->cam.pos[1],
             v->cam.pos[2]);
    if (wp->kind == WORLD_PLANET) { // latitude, longitude, altitude above the datum
        double lat, lon,
            r = sqrt(v->cam.pos[0] * v->cam.pos[0] + v->cam.pos[1] * v->cam.pos[1] +
                     v->cam.pos[2] * v->cam.pos[2]);
        planet_lat_lon(v->cam.pos, &lat, &lon);
        double alt = r - wp->radius;
        // As many digits as tell places apart from this high (0.001 degrees: ~100 m),
        // so the whole line fits its column.
        int far = fabs(alt) >= 10000, digits = far ? 3 : 5;
        char height[48];
        if (fabs(alt) >= 1e6)
            snprintf(height, sizeof height, "%.0f km", alt / 1000.0);
        else if (far)
            snprintf(height, sizeof height, "%.1f km", alt / 1000.0);
        else
            snprintf(height, sizeof height, "%.1f m", alt);
        snprintf(cam, sizeof cam, "%.*f%c %.*f%c  alt %s", digits, fabs(lat), lat < 0 ? 'S' : 'N',
                 digits, fabs(lon), lon < 0 ? 'W' : 'E', height);
    }
    snprintf(tool, sizeof tool, "%s r %.1f m", current_tool(&ctx->brush), ctx->brush.radius);
    if (info->resizing)
        snprintf(tool, sizeof tool, "%s r %.1f m, strength %.2f", current_tool(&ctx->brush),
                 info->resize_radius, info->resize_strength);
    if (stamps->active)
        snprintf(tool, sizeof tool, "stamp %s x%.2f", stamps->entries[stamps->selected].name,
                 stamps->scale);
    render_stats rs = {0};
    if (v->renderer) terrain_renderer_stats(v->renderer, &rs);
    snprintf(frame, sizeof frame, "%.0f ms (%.0f%%) %.0fk tris%s", info->frame_ms,
             info->resolution_scale * 100, rs.triangles / 1000.0, info->pending ? "  loading" : "");
    tile_cache_stats s;
    tile_cache_stats_get(world_cache(ctx->world), &s);
    snprintf(cache, sizeof cache, "cache %.0f / %.0f MiB, undo %.1f MiB",
             s.resident_bytes / 1048576.0, s.budget_bytes / 1048576.0,
             history_bytes(world_history(ctx->world)) / 1048576.0);
    // Each item as wide as its text, the rest shared out; in a narrow window (or at a
    // large UI scale) the least important go first: the cache, the frame time, the tool.
    const char *texts[5] = {cursor, cam, tool, frame, cache};
    const char *tips[5] = {
        "The terrain point under the pointer",
        wp->kind == WORLD_PLANET ? "The camera's latitude, longitude and altitude above the datum"
                                 : "The camera's position in metres",
        "The current tool and its radius",
        "The last terrain frame's time, its resolution (lowered while moving) and its "
        "triangles",
        "Tile cache memory in use against its budget, and the undo history's"};
    float need[5], sum = 0, room = r.w - ui_em(ui, 0.6f);
    for (int i = 0; i < 5; i++)
        need[i] = ui_font_text_width(ui_get_font(ui), UI_FACE_SANS, texts[i], strlen(texts[i])) +
                  ui_em(ui, 1.2f);
    int shown = 5;
    for (int i = 0; i < 5; i++)
        sum += need[i];
    while (shown > 2 && sum > room)
        sum -= need[--shown];
    float cols[5] = {0};
    for (int i = 0; i + 1 < shown; i++)
        cols[i] = need[i] + fmaxf(room - sum, 0) / (float)shown;
    ui_row(ui, shown, cols, r.h - 2 * ui_em(ui, 0.3f)); // the panel's padding above and below
    for (int i = 0; i < shown; i++) {
        ui_label(ui, texts[i]);
        ui_tooltip(ui, tips[i]);
    }
    ui_panel_end(ui);
}

static ui_rect centred(float width, float height, float w, float h) {
    return (ui_rect){roundf((width - w) * 0.5f), roundf((height - h) * 0.4f), w, h};
}

static void unsaved_prompt(editor_ui *e, ui_context *ui, cmd_context *ctx, float width,
                           float height) {
    ui_rect r = centred(width, height, ui_em(ui, 22), ui_em(ui, 6));
    ui_panel_begin(ui, "Unsaved changes", r);
    char text[512];
    snprintf(text, sizeof text, "%s has unsaved changes.", file_name(world_path(ctx->world)));
    ui_row(ui, 1, NULL, 0);
    ui_label(ui, text);
    ui_label_colored(ui,
                     e->pending == PENDING_QUIT ? "Save them before quitting?"
                                                : "Save them before the new world?",
                     ui_get_theme(ui)->text_dim);
    float thirds[3] = {-0.333f, -0.333f, 0};
    ui_row(ui, 3, thirds, ui_em(ui, 1.5f));
    int can_save = world_path(ctx->world)[0] != 0;
    if (can_save ? ui_button(ui, "Save") : ui_button(ui, "Save as...##Save")) {
        if (can_save && (world_file_errors(ctx->world) || world_read_only(ctx->world)[0])) {
            e->confirm_replace = 1; // asks first; goes on from there once saved
        } else if (can_save) {
            if (run_now(e, ctx, "save") == 0) {
                editor_pending a = e->pending;
                e->pending = PENDING_NONE;
                do_action(e, ctx, a);
            }
        } else {
            editor_ui_save_as(e, ctx);
        }
    }
    ui_tooltip(ui, "Save the world, then go on");
    if (ui_button(ui, "Discard")) {
        editor_pending a = e->pending;
        e->pending = PENDING_NONE;
        do_action(e, ctx, a);
    }
    ui_tooltip(ui, "Go on without saving: the changes are lost");
    if (ui_button(ui, "Cancel")) e->pending = PENDING_NONE;
    ui_tooltip(ui, "Keep working");
    ui_panel_end(ui);
}

// Whether the world has unsaved edits of a session that ended without saving, and the
// user has not put the question off for this world.
// The journal whose edits the Recover dialog offers: the world's own, or one a
// never-saved world left (found when the editor started); "" when none is offered.
static const char *offered_journal(const editor_ui *e, cmd_context *ctx, size_t *steps,
                                   int64_t *when) {
    const char *own = world_recovery_path(ctx->world);
    *steps = world_recoverable(ctx->world, when);
    if (*steps && strcmp(e->recover_dismissed, own) != 0) return own;
    if (e->unsaved_journal[0] && strcmp(e->recover_dismissed, e->unsaved_journal) != 0 &&
        !world_path(ctx->world)[0] && !world_is_modified(ctx->world)) {
        *steps = e->unsaved_journal_steps;
        *when = e->unsaved_journal_when;
        return e->unsaved_journal;
    }
    return "";
}

// Like Blender's Recover Last Session: the edits a crash or a kill left in a journal,
// offered when the world opens (or, for a world never saved, when the editor starts).
static void recover_dialog(editor_ui *e, ui_context *ui, cmd_context *ctx, ui_rect r) {
    ui_panel_begin(ui, "Recover unsaved edits", r);
    ui_row(ui, 1, NULL, 0);
    int64_t when = 0;
    size_t steps = 0;
    const char *journal = offered_journal(e, ctx, &steps, &when);
    int own = !strcmp(journal, world_recovery_path(ctx->world));
    char text[1200], stamp[64], cmd[4600], arg[4400];
    if (own)
        snprintf(text, sizeof text, "%s was not saved when Orogen last stopped.",
                 file_name(world_path(ctx->world)));
    else
        snprintf(text, sizeof text, "A world that was never saved was open when Orogen stopped.");
    ui_label(ui, text);
    time_t t = (time_t)when;
    struct tm tm;
    if (!localtime_r(&t, &tm) || !strftime(stamp, sizeof stamp, "%Y-%m-%d %H:%M", &tm))
        snprintf(stamp, sizeof stamp, "?");
    snprintf(text, sizeof text, "Its edits of %s (%zu step%s) can be recovered.", stamp, steps,
             steps == 1 ? "" : "s");
    ui_label(ui, text);
    ui_tooltip(ui, journal);
    cmd_quote_arg(arg, sizeof arg, journal);
    float thirds[3] = {-0.333f, -0.333f, 0};
    ui_row(ui, 3, thirds, ui_em(ui, 1.5f));
    if (ui_button(ui, "Recover")) {
        snprintf(cmd, sizeof cmd, own ? "recover" : "recover %s", arg);
        if (run_now(e, ctx, cmd) == 0 && !own) e->unsaved_journal[0] = 0;
    }
    ui_tooltip(ui, "Restore those edits: undoable, and unsaved until you save (recover)");
    if (ui_button(ui, "Discard")) {
        snprintf(cmd, sizeof cmd, own ? "recover discard" : "recover discard %s", arg);
        if (run_now(e, ctx, cmd) == 0 && !own) e->unsaved_journal[0] = 0;
    }
    ui_tooltip(ui, "Drop those edits for good (recover discard)");
    if (ui_button(ui, "Not now"))
        snprintf(e->recover_dismissed, sizeof e->recover_dismissed, "%s", journal);
    ui_tooltip(ui, "Keep them for later: the console's 'recover' restores them until the world "
                   "is edited or saved");
    ui_panel_end(ui);
}

void editor_ui_save(editor_ui *e, cmd_context *ctx) {
    if (world_file_errors(ctx->world) || world_read_only(ctx->world)[0])
        e->confirm_replace = 1;
    else
        editor_ui_run(e, ctx, "save");
}

// Saving over a file that loaded with errors writes defaults where its bad lines were,
// and over a world opened read-only replaces its tile store: say so (which lines, which
// store), and let the user replace it, save elsewhere or keep working.
static void replace_dialog(editor_ui *e, ui_context *ui, cmd_context *ctx, ui_rect r) {
    ui_panel_begin(ui, "Replace file", r);
    ui_row(ui, 1, NULL, 0);
    int errors = world_file_errors(ctx->world);
    const char *read_only = world_read_only(ctx->world);
    char text[1200];
    if (read_only[0]) {
        // "its tile store X is empty (0 bytes); showing ...": the part before the ';'.
        snprintf(text, sizeof text, "%s was opened read-only:", file_name(world_path(ctx->world)));
        ui_label(ui, text);
        const char *semi = strchr(read_only, ';');
        int n = semi ? (int)(semi - read_only) : (int)strlen(read_only);
        snprintf(text, sizeof text, "%.*s.", n < 1000 ? n : 1000, read_only);
        ui_label_colored(ui, text, ui_get_theme(ui)->text_error);
        ui_tooltip(ui, read_only);
        ui_label(ui, "Saving replaces its tile store with the terrain you see.");
    }
    if (errors) {
        snprintf(text, sizeof text, "%s had %d error%s when it was loaded.",
                 file_name(world_path(ctx->world)), errors, errors == 1 ? "" : "s");
        ui_label(ui, text);
        ui_label(ui, errors == 1 ? "Saving writes the default over this line:"
                                 : "Saving writes the defaults over these lines:");
    }
    const char *line = world_file_problems(ctx->world);
    for (int i = 0; i < problem_lines(world_file_problems(ctx->world)); i++) {
        const char *end = strchr(line, '\n');
        size_t n = end ? (size_t)(end - line) : strlen(line);
        snprintf(text, sizeof text, "line %.*s", (int)(n < 1000 ? n : 1000), line);
        ui_label_colored(ui, text, ui_get_theme(ui)->text_error);
        ui_tooltip(ui, text);
        line = end ? end + 1 : line + n;
    }
    float thirds[3] = {-0.333f, -0.333f, 0};
    ui_row(ui, 3, thirds, ui_em(ui, 1.5f));
    if (ui_button(ui, "Replace")) {
        e->confirm_replace = 0;
        if (run_now(e, ctx, "save force=1") == 0 && e->pending != PENDING_NONE) {
            editor_pending a = e->pending; // saved from the unsaved-changes prompt: go on
            e->pending = PENDING_NONE;
            do_action(e, ctx, a);
        }
    }
    ui_tooltip(ui, read_only[0] ? "Save over the file and its tile store (save force=1)"
                                : "Save over the file: those lines become their defaults "
                                  "(save force=1)");
    if (ui_button(ui, "Save as...")) {
        e->confirm_replace = 0;
        editor_ui_save_as(e, ctx);
    }
    ui_tooltip(ui, "Save to another file and leave this one as it is");
    if (ui_button(ui, "Cancel")) e->confirm_replace = 0;
    ui_tooltip(ui, "Keep working; nothing is written");
    ui_panel_end(ui);
}

void editor_ui_save_as(editor_ui *e, cmd_context *ctx) {
    const char *path = world_path(ctx->world);
    // A planet never saved: seed 004's extension, so Open lists it with the planets.
    if (!path[0] && world_get_params(ctx->world)->kind == WORLD_PLANET) path = "planet.planet";
    file_browser_show(&e->files, FILE_BROWSER_SAVE, path);
}

void editor_ui_open(editor_ui *e, cmd_context *ctx) {
    file_browser_show(&e->files, FILE_BROWSER_OPEN, world_path(ctx->world));
}

// The file browser for Open and Save as; what it chose runs as load or save.
static void files_dialog(editor_ui *e, ui_context *ui, cmd_context *ctx, ui_rect r) {
    if (!file_browser_draw(&e->files, ui, r)) return;
    if (e->files.mode == FILE_BROWSER_OPEN) {
        snprintf(e->open_path, sizeof e->open_path, "%.1023s", e->files.path);
        editor_ui_request(e, ctx, PENDING_OPEN);
        return;
    }
    if (e->files.mode == FILE_BROWSER_IMPORT || e->files.mode == FILE_BROWSER_EXPORT ||
        e->files.mode == FILE_BROWSER_EXPORT_PLANET) {
        const world_params *p = world_get_params(ctx->world);
        double bounded = p->size > 0 ? (double)(p->size - 1) * p->spacing : 0.0;
        interchange_dialog_show(&e->interchange, e->files.mode != FILE_BROWSER_IMPORT,
                                e->files.path, bounded, p->max_height, e->view_x, e->view_z);
        e->interchange.planet = e->files.mode == FILE_BROWSER_EXPORT_PLANET;
        if (!e->interchange.subdivision[0])
            snprintf(e->interchange.subdivision, sizeof e->interchange.subdivision, "8");
        return;
    }
    char arg[4200], cmd[4300];
    cmd_quote_arg(arg, sizeof arg, e->files.path);
    if (e->files.mode == FILE_BROWSER_SCRIPT) {
        snprintf(cmd, sizeof cmd, "history script %s", arg);
        run_now(e, ctx, cmd);
        return;
    }
    snprintf(cmd, sizeof cmd, "save %s", arg);
    if (run_now(e, ctx, cmd) != 0) return;
    remember_recent(e, world_path(ctx->world));
    if (e->pending != PENDING_NONE) { // saved from the unsaved-changes prompt: go on
        editor_pending a = e->pending;
        e->pending = PENDING_NONE;
        do_action(e, ctx, a);
    }
}

// The keyboard shortcuts (Help > Keyboard shortcuts, F1).
static const char *const help_lines[] = {
    "Left drag: sculpt or paint; with Ctrl inverted, with Shift smoothing",
    "Alt + left drag, middle drag: orbit around the point under the pointer",
    "Right drag: look; with it held W A S D fly, Q E down/up, Shift faster",
    "Wheel: dolly toward the pointer (with right drag: fly speed)",
    "G walk mode, F focus on the pointer, Home reset the view",
    "1-5 shaded, wireframe, levels, height, slope views; R rotates the light",
    "C camera: fly, orbit (right drag orbits the view's centre), walk",
    "L dynamic resolution while moving; Ctrl+= / Ctrl+- more / fewer levels of detail",
    "Over the viewport: U raise, J lower, M smooth, T flatten, H set height, P ramp,",
    "  N noise, K terrace, Y thermal, O hydraulic, I paint, B stamp",
    "Ctrl+Z undo, Ctrl+Shift+Z or Ctrl+Y redo; [ ] brush radius, - = strength",
    "(Slartibartfast's = and - level-of-detail keys are Ctrl+= and Ctrl+- here: - and = are "
    "strength)",
    "Ctrl+S save, Ctrl+Shift+S save as, Ctrl+N new, Ctrl+O open, Ctrl+Q quit",
    "~ console, F1 this help, Esc close menus and dialogs, cancel long work",
};
#define HELP_LINES ((int)(sizeof help_lines / sizeof help_lines[0]))

// A text dialog's rectangle: as wide as its longest line (within the window).
static ui_rect text_dialog_rect(const ui_context *ui, const char *const *lines, int n, float width,
                                float height) {
    float w = ui_em(ui, 20);
    for (int i = 0; i < n; i++)
        w = fmaxf(w, ui_font_text_width(ui_get_font(ui), UI_FACE_SANS, lines[i], strlen(lines[i])));
    return centred(width, height, fminf(width * 0.95f, w + ui_em(ui, 2)),
                   fminf(height * 0.95f, ui_em(ui, 1.45f * (n + 3))));
}

static void text_dialog(ui_context *ui, const char *name, const char *const *lines, int n,
                        int *show, float width, float height) {
    ui_rect r = n == 3 ? centred(width, height, ui_em(ui, 34), ui_em(ui, 1.45f * (3 + 3)))
                       : text_dialog_rect(ui, lines, n, width, height);
    ui_panel_begin(ui, name, r);
    ui_row(ui, 1, NULL, 0);
    for (int i = 0; i < n; i++)
        ui_label(ui, lines[i]);
    if (ui_button(ui, "Close")) *show = 0;
    ui_tooltip(ui, "Close this window (Esc)");
    ui_panel_end(ui);
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
    if (e->offer_recovery) // wide enough for its first line in full
        return centred(width, height, fminf(width * 0.9f, ui_em(ui, 32)), ui_em(ui, 6.5f));
    if (e->confirm_replace)
        return centred(width, height, fminf(width * 0.9f, ui_em(ui, 30)),
                       fminf(height * 0.9f, ui_em(ui, 1.45f * (float)(e->replace_lines + 2) + 1)));
    if (e->pending != PENDING_NONE) return centred(width, height, ui_em(ui, 22), ui_em(ui, 6));
    if (e->show_help) return text_dialog_rect(ui, help_lines, HELP_LINES, width, height);
    if (e->show_about) return centred(width, height, ui_em(ui, 34), ui_em(ui, 1.45f * (3 + 3)));
    return (ui_rect){0, 0, 0, 0};
}

ui_rect editor_ui_build(editor_ui *e, ui_context *ui, cmd_context *ctx, viewport *v,
                        const editor_frame_info *info, float width, float height) {
    {
        size_t steps;
        int64_t when;
        e->offer_recovery = offered_journal(e, ctx, &steps, &when)[0] != 0;
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
    if (e->stamps.open_request) { // the palette's Stamp button shows the browser
        ui_section_set(ui, "Stamps", 1);
        e->stamps.open_request = 0;
    }
    if (ui_section(ui, "Stamps", 0)) stamp_browser_draw(&e->stamps, ui, ctx, &picked);
    if (ui_section(ui, "Layers", 0)) layers_panel(e, ui, ctx, v);
    if (ui_section(ui, "World", 1)) world_panel(e, ui, ctx);
    if (e->history_request) { // Edit > History: the section opens
        ui_section_set(ui, "History", 1);
        e->history_request = 0;
    }
    if (ui_section(ui, "History", 1)) history_panel(e, ui, ctx);
    ui_panel_end(ui);
    status_bar(ui, ctx, v, info, &e->stamps, (ui_rect){0, height - status, width, status});

    ui_rect view = cols[1];
    if (e->console.open) {
        ui_rect c = {view.x, view.y, view.w, roundf(view.h * 0.45f)};
        console_draw(&e->console, ui, ctx, c);
    }
    if (modal.w > 0) ui_dim(ui); // the dialog stands out; the rest waits
    if (e->show_help) {
        text_dialog(ui, "Keyboard shortcuts", help_lines, HELP_LINES, &e->show_help, width, height);
    }
    if (e->show_about) {
        char gl[256];
        snprintf(gl, sizeof gl, "Renderer: %s", info->gl_renderer ? info->gl_renderer : "?");
        char libs[256];
        snprintf(libs, sizeof libs, "GLFW %s; %s; OpenImageIO, stb_truetype, DejaVu fonts",
                 e->glfw_version ? e->glfw_version : "?", tile_store_library_versions());
        const char *about[] = {"Orogen 0.1: a terrain editor", gl, libs};
        text_dialog(ui, "About", about, 3, &e->show_about, width, height);
    }
    e->view_x = v->cam.pos[0];
    e->view_z = v->cam.pos[2];
    if (e->files.open) {
        files_dialog(e, ui, ctx, modal);
    } else if (e->interchange.open) {
        char cmd[4600];
        if (interchange_dialog_draw(&e->interchange, ui, modal, cmd, sizeof cmd))
            editor_ui_run(e, ctx, cmd);
    } else if (e->new_planet.open) {
        if (new_planet_dialog_draw(&e->new_planet, ui, modal, e->planet_command,
                                   sizeof e->planet_command))
            editor_ui_request(e, ctx, PENDING_NEW_PLANET);
    } else if (e->offer_recovery) {
        recover_dialog(e, ui, ctx, modal);
    } else if (e->confirm_replace) {
        replace_dialog(e, ui, ctx, modal);
    } else if (e->pending != PENDING_NONE) {
        unsaved_prompt(e, ui, ctx, width, height);
    }
    // The menu bar last: its menus open over everything.
    menus(e, ui, ctx, v, top);
    if (ui_get_input(ui)->key_pressed[UI_KEY_ESCAPE] && !ui_wants_keyboard(ui)) {
        e->show_help = e->show_about = e->picking_height = e->shape_placing = 0;
        if (e->files.open)
            e->files.open = 0;
        else if (e->interchange.open)
            e->interchange.open = 0;
        else if (e->new_planet.open)
            e->new_planet.open = 0;
        else if (e->offer_recovery) {
            size_t steps;
            int64_t when;
            snprintf(e->recover_dismissed, sizeof e->recover_dismissed, "%s",
                     offered_journal(e, ctx, &steps, &when));
        } else if (e->confirm_replace)
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
