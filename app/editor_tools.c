// The tool palette (icons, keys) and the current tool's options.
#include "app/brush_size.h"
#include "editor/params/world_grid.h"
#include "app/editor_ui_internal.h"
#include "app/shortcuts.h"

typedef struct tool_entry {
    const char *name;  // as `tool` takes it
    const char *label; // on the button
    const char *tip;
} tool_entry; // its key over the viewport is in the shortcut table (app/shortcuts.c)

static const tool_entry tools[] = {
    {"raise", "Raise", "Raise the terrain by amount metres per dab"},
    {"lower", "Lower", "Lower the terrain by amount metres per dab"},
    {"smooth", "Smooth",
     "Blend toward a blur that widens with the radius; invert sharpens; Shift while "
     "dragging smooths with any tool"},
    {"flatten", "Flatten", "Blend toward a height, or the height under the stroke's start"},
    {"set", "Set height", "Blend toward the height you give"},
    {"ramp", "Ramp", "A ramp from the stroke's first point to its last"},
    {"noise", "Noise", "Add fractal noise"},
    {"terrace", "Terrace", "Blend toward terraces of a step height"},
    {"thermal", "Thermal", "Thermal erosion down to the talus angle"},
    {"hydraulic", "Hydraulic", "Droplet erosion: water carves and deposits"},
    {"paint", "Paint", "Paint a material; invert removes it"},
    {"fill", "Fill",
     "Add rock in 3D: a ball per dab, a tube along a drag (overhangs, arches; "
     "Ctrl carves instead)"},
    {"carve", "Carve",
     "Cut rock away in 3D: a ball per dab, a tube along a drag (caves, "
     "undercuts; Ctrl fills instead)"},
    {"vsmooth", "Smooth 3D", "Smooth the surface in 3D, overhangs included"},
    {"vflatten", "Flatten 3D",
     "Flatten the surface in 3D to a level plane (height, or the "
     "first point's)"},
};
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

int editor_ui_tool_index(const char *name) {
    for (size_t i = 0; i < TOOL_COUNT; i++)
        if (strcmp(tools[i].name, name) == 0) return (int)i;
    return strcmp(name, "stamp") == 0 ? (int)TOOL_COUNT : -1;
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
        stamp_browser_deactivate(&e->stamps);
    } else if (index == (int)TOOL_COUNT) { // the stamp tool: the browser shows its stamps
        stamp_browser_activate(&e->stamps, ctx);
    }
}

void palette(editor_ui *e, ui_context *ui, cmd_context *ctx, ui_rect r) {
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
        const char *key = shortcut_label(SHORTCUT_TOOL, stamp ? "stamp" : tools[i].name);
        char key_note[32] = "";
        if (key) snprintf(key_note, sizeof key_note, " (key %s)", key);
        snprintf(tip, sizeof tip, "%s%s%s%s", names ? "" : label, names ? "" : ": ",
                 stamp ? "Place a stamp (a shape or heightmap) with a click in the viewport"
                       : tools[i].tip,
                 key_note);
        ui_tooltip(ui, tip);
        if (clicked) editor_ui_pick_tool(e, ctx, (int)i);
    }
    ui_panel_end(ui);
}

// The current tool's name as `tool` takes it.
const char *current_tool(const brush *b) {
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

void tool_options(editor_ui *e, ui_context *ui, cmd_context *ctx) {
    const brush *b = &ctx->brush;
    if (!brush_tool_is_volume(b->tool)) e->shape_placing = 0; // its buttons are gone
    const char *t = current_tool(b);
    ui_row(ui, 1, NULL, 0);
    double top = brush_radius_slider_max(world_grid_sample_metres(world_get_params(ctx->world)));
    slider_key(e, ui, ctx, "Radius", "radius", b->radius, 0.5, top, "%.1f m",
               "Brush radius in metres ([ and ] change it)");
    slider_key(e, ui, ctx, "Strength", "strength", b->strength, 0, 1, "%.2f",
               "How much of the tool's effect one dab applies");
    slider_key(e, ui, ctx, "Spacing", "spacing", b->spacing, 0.05, 2, "%.2f x radius",
               "Distance between dabs along a stroke, as a fraction of the radius");
    falloff_options(e, ui, ctx, t);
    int own = ctx->tool_size_per_tool;
    if (ui_checkbox(ui, "Size per tool", &own))
        runf(e, ctx, "tool %s memory=%s", t, own ? "per_tool" : "shared");
    ui_tooltip(ui, "Each tool keeps its own radius and strength (off: shared by all tools)");
    if (brush_tool_is_volume(b->tool)) {
        volume_options(e, ui, ctx, t);
        return;
    }
    if (b->tool != BRUSH_RAMP) {
        int hold = b->hold;
        if (ui_checkbox(ui, "Hold", &hold)) runf(e, ctx, "tool %s hold=%d", t, hold);
        ui_tooltip(ui, "Held still, the brush keeps applying, 2 / spacing dabs a second");
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
