// The status bar and the dialogs: unsaved changes, recovery, replacing a world,
// files, text.
#include "app/editor_ui_internal.h"

void status_bar(ui_context *ui, cmd_context *ctx, viewport *v, const editor_frame_info *info,
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
    char why[160];
    int refused = !stamps->active && editor_ui_tool_refused(ctx, why, sizeof why);
    if (refused) snprintf(tool, sizeof tool, "%.90s", why); // the active layer's refusal
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
    // large UI scale) the least important go first.
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
    for (int i = 0; i < 5; i++)
        sum += need[i];
    // The tool and the frame time always stay; the cache, the camera and the point
    // under the pointer go first, in that order.
    int keep[5] = {1, 1, 1, 1, 1}, shown = 5;
    static const int drop_order[3] = {4, 1, 0};
    for (int k = 0; k < 3 && sum > room; k++) {
        keep[drop_order[k]] = 0;
        sum -= need[drop_order[k]];
        shown--;
    }
    float cols[5] = {0};
    int order[5], n = 0;
    for (int i = 0; i < 5; i++)
        if (keep[i]) order[n++] = i;
    for (int i = 0; i + 1 < n; i++)
        cols[i] = need[order[i]] + fmaxf(room - sum, 0) / (float)shown;
    ui_row(ui, shown, cols, r.h - 2 * ui_em(ui, 0.3f)); // the panel's padding above and below
    for (int i = 0; i < n; i++) {
        if (refused && order[i] == 2)
            ui_label_colored(ui, texts[2], ui_get_theme(ui)->text_error);
        else
            ui_label(ui, texts[order[i]]);
        ui_tooltip(ui, tips[order[i]]);
    }
    ui_panel_end(ui);
}

ui_rect centred(float width, float height, float w, float h) {
    return (ui_rect){roundf((width - w) * 0.5f), roundf((height - h) * 0.4f), w, h};
}

void unsaved_prompt(editor_ui *e, ui_context *ui, cmd_context *ctx, float width, float height) {
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
        // Only an explicit discard drops the crash journal of these edits.
        if (world_session_journaled(ctx->world)) run_now(e, ctx, "recover discard");
        do_action(e, ctx, a);
    }
    ui_tooltip(ui, world_session_journaled(ctx->world)
                       ? "Go on without saving: the changes and their recovery journal are lost"
                       : "Go on without saving: the changes are lost");
    if (ui_button(ui, "Cancel")) e->pending = PENDING_NONE;
    ui_tooltip(ui, "Keep working");
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
void replace_dialog(editor_ui *e, ui_context *ui, cmd_context *ctx, ui_rect r) {
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
    // A world never saved: a name to start from (an empty field left a newcomer guessing
    // the extension); a planet gets seed 004's, so Open lists it with the planets.
    if (!path[0])
        path = world_get_params(ctx->world)->kind == WORLD_PLANET ? "planet.planet" : "world.world";
    file_browser_show(&e->files, FILE_BROWSER_SAVE, path);
}

void editor_ui_open(editor_ui *e, cmd_context *ctx) {
    file_browser_show(&e->files, FILE_BROWSER_OPEN, world_path(ctx->world));
}

// The file browser for Open and Save as; what it chose runs as load or save.
void files_dialog(editor_ui *e, ui_context *ui, cmd_context *ctx, ui_rect r) {
    if (!file_browser_draw(&e->files, ui, r)) return;
    if (e->files.mode == FILE_BROWSER_OPEN || e->files.mode == FILE_BROWSER_NEW_FROM) {
        snprintf(e->open_path, sizeof e->open_path, "%.1023s", e->files.path);
        editor_ui_request(e, ctx,
                          e->files.mode == FILE_BROWSER_OPEN ? PENDING_OPEN : PENDING_NEW_FROM);
        return;
    }
    if (e->files.mode == FILE_BROWSER_IMPORT || e->files.mode == FILE_BROWSER_EXPORT ||
        e->files.mode == FILE_BROWSER_EXPORT_PLANET || e->files.mode == FILE_BROWSER_EXPORT_MESH) {
        const world_params *p = world_get_params(ctx->world);
        double bounded = p->size > 0 ? (double)(p->size - 1) * p->spacing : 0.0;
        interchange_dialog_show(&e->interchange, e->files.mode != FILE_BROWSER_IMPORT,
                                e->files.path, bounded, p->max_height, e->view_x, e->view_z);
        e->interchange.planet = e->files.mode == FILE_BROWSER_EXPORT_PLANET;
        e->interchange.mesh = e->files.mode == FILE_BROWSER_EXPORT_MESH;
        e->interchange.world_spacing = p->spacing;
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
    if (run_now(e, ctx, cmd) != 0) return; // the window puts the world in front of the recent ones
    if (e->pending != PENDING_NONE) {      // saved from the unsaved-changes prompt: go on
        editor_pending a = e->pending;
        e->pending = PENDING_NONE;
        do_action(e, ctx, a);
    }
}

// A text dialog's rectangle: as wide as its longest line (within the window).
ui_rect text_dialog_rect(const ui_context *ui, const char *const *lines, int n, float width,
                         float height) {
    float w = ui_em(ui, 20);
    for (int i = 0; i < n; i++)
        w = fmaxf(w, ui_font_text_width(ui_get_font(ui), UI_FACE_SANS, lines[i], strlen(lines[i])));
    return centred(width, height, fminf(width * 0.95f, w + ui_em(ui, 2)),
                   fminf(height * 0.95f, ui_em(ui, 1.45f * (n + 3))));
}

void text_dialog(ui_context *ui, const char *name, const char *const *lines, int n, int *show,
                 float width, float height) {
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
