// The World, Layers and History panels of the dock.
#include "app/editor_ui_internal.h"

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

void world_panel(editor_ui *e, ui_context *ui, cmd_context *ctx) {
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
void layers_panel(editor_ui *e, ui_context *ui, cmd_context *ctx, const viewport *v) {
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

void history_panel(editor_ui *e, ui_context *ui, cmd_context *ctx) {
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
    // The steps in a list of their own, at most 8 rows tall: a new step, an undo or a redo
    // scrolls it to the current step (as Photoshop's and Blender's history lists do)
    // without moving the rest of the dock; otherwise it stays where the user left it.
    if (n == 0) return;
    float row = ui_em(ui, 1.4f) + ui_em(ui, 0.2f), pad = ui_em(ui, 0.3f);
    ui_row(ui, 1, NULL, (float)(n < 8 ? n : 8) * row - ui_em(ui, 0.2f) + 2 * pad);
    ui_panel_begin(ui, "Steps", ui_next_cell(ui));
    int reveal = e->history_seen[0] != n || e->history_seen[1] != pos;
    e->history_seen[0] = n, e->history_seen[1] = pos;
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
        if (reveal && i + 1 == (pos ? pos : 1)) ui_reveal_last(ui);
        ui_tooltip(ui, i < pos ? "Applied: click to undo the steps after it"
                               : "Undone: click to redo up to here");
        // The step's memory, and the saved state marked.
        snprintf(line, sizeof line, "%.0f KiB%s##size%zu", s->bytes / 1024.0,
                 saved == (long)i + 1 ? ", saved" : "", i + 1);
        ui_label_colored(ui, line, ui_get_theme(ui)->text_dim);
        ui_tooltip(ui, saved == (long)i + 1 ? "Undo memory of the step; the world was saved here"
                                            : "Undo memory of the step");
    }
    ui_panel_end(ui);
}
