#include "app/interchange_dialog.h"

#include "editor/cmd/tokenize.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void interchange_dialog_show(interchange_dialog *d, int exporting, const char *path,
                             double bounded_metres, double max_height, double x, double z) {
    // Keep the user's last choices; set only what depends on this file and view.
    d->open = 1;
    d->exporting = exporting;
    snprintf(d->path, sizeof d->path, "%s", path);
    if (!d->x[0]) snprintf(d->x, sizeof d->x, "%.0f", bounded_metres > 0 ? 0.0 : x);
    if (!d->z[0]) snprintf(d->z, sizeof d->z, "%.0f", bounded_metres > 0 ? 0.0 : z);
    if (!d->min[0]) snprintf(d->min, sizeof d->min, "0");
    if (!d->max[0]) snprintf(d->max, sizeof d->max, "500");
    if (!d->resample) d->resample = 1; // bilinear
    d->whole = bounded_metres > 0;
    if (!d->region[2][0]) {
        const double half = 1000;
        snprintf(d->region[0], sizeof d->region[0], "%.0f", x - half);
        snprintf(d->region[1], sizeof d->region[1], "%.0f", z - half);
        snprintf(d->region[2], sizeof d->region[2], "%.0f", x + half);
        snprintf(d->region[3], sizeof d->region[3], "%.0f", z + half);
    }
    d->max_height = max_height;
    d->layer_name[0] = d->error[0] = 0;
    d->planet = d->mesh = 0; // the caller says which export this is
    d->preview_ok = 0;
    d->preview_error[0] = 0;
    if (exporting) return;
    import_options o;
    import_options_defaults(&o);
    og_error err = {{0}};
    if (import_preview_read(path, &o, &d->preview, &err) == 0)
        d->preview_ok = 1;
    else
        snprintf(d->preview_error, sizeof d->preview_error, "%s", err.msg);
}

// The file's values as a histogram over a bar, and the heights the current mapping
// gives the lowest and highest of them (what the import will make of the file).
static void mapping_preview(interchange_dialog *d, ui_context *ui) {
    const ui_theme *theme = ui_get_theme(ui);
    ui_row(ui, 1, NULL, 0);
    if (!d->preview_ok) {
        ui_label_wrapped(ui, d->preview_error, theme->text_error);
        return;
    }
    const import_preview *p = &d->preview;
    const raster *r = &p->header;
    static const char *const kinds[] = {"unsigned", "signed", "float"};
    char line[300];
    snprintf(line, sizeof line, "%d x %d samples, %d-bit %s%s", r->width, r->height, r->bits,
             kinds[r->kind], p->has_sidecar ? ", with sidecar" : "");
    if (r->voids)
        snprintf(line + strlen(line), sizeof line - strlen(line), ", %lld voids",
                 (long long)r->voids);
    ui_label(ui, line);
    ui_tooltip(ui, r->description);
    // The histogram: one bar per bin, scaled to the fullest (log, so few values show).
    ui_row(ui, 1, NULL, ui_em(ui, 2.2f));
    ui_rect cell = ui_next_cell(ui);
    ui_draw_list *dl = ui_draw_target(ui);
    ui_draw_rect(dl, cell, theme->panel_alt);
    int most = 1;
    for (int i = 0; i < IMPORT_PREVIEW_BINS; i++)
        if (p->histogram[i] > most) most = p->histogram[i];
    const float bw = cell.w / IMPORT_PREVIEW_BINS;
    for (int i = 0; i < IMPORT_PREVIEW_BINS; i++) {
        if (!p->histogram[i]) continue;
        float f = (float)(log1p((double)p->histogram[i]) / log1p((double)most));
        float bh = fmaxf(1.0f, f * (cell.h - 2));
        ui_draw_rect(dl, (ui_rect){cell.x + i * bw, cell.y + cell.h - 1 - bh, fmaxf(1, bw - 1), bh},
                     theme->accent);
    }
    // The mapping the fields give now.
    import_options o;
    import_options_defaults(&o);
    og_error err = {{0}};
    if (d->map_heights) {
        char *end_lo, *end_hi;
        o.min = strtod(d->min, &end_lo);
        o.max = strtod(d->max, &end_hi);
        if (end_lo == d->min || *end_lo || end_hi == d->max || *end_hi) {
            ui_row(ui, 1, NULL, 0);
            ui_label_colored(ui, "Lowest and highest must be numbers (metres)", theme->text_error);
            return;
        }
        o.has_min_max = 3;
    }
    double scale = 1, offset = 0;
    char how[200];
    ui_row(ui, 1, NULL, 0);
    if (import_preview_mapping(d->path, p, &o, d->max_height, &scale, &offset, how, sizeof how,
                               &err) != 0) {
        ui_label_wrapped(ui, err.msg, theme->text_error);
        return;
    }
    snprintf(line, sizeof line, "Stored %.6g .. %.6g become %.6g .. %.6g m", p->stored_min,
             p->stored_max, p->stored_min * scale + offset, p->stored_max * scale + offset);
    ui_label_wrapped(ui, line, theme->text);
    ui_tooltip(ui, how);
}

// What the import will cover at the spacing given: metres, the world's samples and their
// memory (4 bytes each), and whether one import may take that many.
static void import_extent(interchange_dialog *d, ui_context *ui) {
    if (!d->preview_ok) return;
    const ui_theme *theme = ui_get_theme(ui);
    const raster *r = &d->preview.header;
    double sx = 0, sz = 0;
    char *end;
    ui_row(ui, 1, NULL, 0);
    if (d->spacing[0]) {
        sx = sz = strtod(d->spacing, &end);
        if (end == d->spacing || *end || !(sx > 0) || !isfinite(sx)) {
            ui_label_colored(ui, "The spacing must be a number of metres above 0",
                             theme->text_error);
            return;
        }
    } else if (r->spacing_x > 0) {
        sx = r->spacing_x, sz = r->spacing_z > 0 ? r->spacing_z : r->spacing_x;
    } else if (d->preview.has_sidecar && d->preview.sc.spacing > 0) {
        sx = sz = d->preview.sc.spacing;
    } else {
        sx = sz = d->world_spacing; // one world sample per pixel
    }
    char line[300];
    if (!(sx > 0)) {
        ui_label(ui, "One world sample per pixel");
        return;
    }
    double w = (r->width - 1) * sx, h = (r->height - 1) * sz;
    int n = snprintf(line, sizeof line, "%.4g x %.4g km at %.4g m", w / 1000, h / 1000, sx);
    double samples = 0;
    if (d->world_spacing > 0) {
        samples = (floor(w / d->world_spacing) + 1) * (floor(h / d->world_spacing) + 1);
        snprintf(line + n, sizeof line - (size_t)n, ": %.4g M world samples, %.4g MiB",
                 samples / 1e6, samples * 4 / 1048576.0);
    }
    ui_label_wrapped(ui, line, theme->text);
    ui_tooltip(ui, "The area the file will cover, and the world's samples it writes");
    if (samples > (double)IMPORT_MAX_SAMPLES) {
        ui_label_wrapped(ui,
                         "Too many for one import: give a larger spacing, or File > New world "
                         "from heightmap",
                         theme->text_error);
    }
}

// A label and its text field in one row; the field is named `name` (labels are listed
// by their text, so the field needs a name of its own for tests to find it).
static void import_fields(interchange_dialog *d, ui_context *ui) {
    ui_form_field(ui, "X (m)", "x", d->x, sizeof d->x,
                  "Where the first sample (row 0, column 0) goes");
    ui_form_field(ui, "Z (m)", "z", d->z, sizeof d->z,
                  "Where the first sample goes (rows run toward +Z)");
    ui_row(ui, 1, NULL, 0);
    ui_checkbox(ui, "Centre it on X, Z##centre", &d->centre);
    ui_tooltip(ui, "Put the heightmap's middle at X, Z, not its first corner");
    static const char *const layers[] = {"Coarse heights", "Detail heights"};
    ui_combo(ui, "Layer", &d->layer, layers, 2);
    ui_tooltip(ui, "Coarse terrain or fine detail");
    ui_checkbox(ui, "Map 8/16-bit values to heights##map", &d->map_heights);
    ui_tooltip(ui, "8/16-bit files: lowest and highest value in metres");
    if (d->map_heights) {
        ui_form_field(ui, "Lowest (m)", "min", d->min, sizeof d->min,
                      "Height in metres of the lowest stored value (0)");
        ui_form_field(ui, "Highest (m)", "max", d->max, sizeof d->max,
                      "Height in metres of the highest stored value (65535 in 16-bit)");
    }
    mapping_preview(d, ui);
    ui_form_field(ui, "Spacing (m)", "spacing", d->spacing, sizeof d->spacing,
                  "Metres between the file's samples (blank: its georeferencing or sidecar, "
                  "else one world sample per pixel)");
    import_extent(d, ui);
    ui_row(ui, 1, NULL, 0);
    static const char *const blends[] = {"Replace", "Add", "Max", "Min"};
    ui_combo(ui, "Blend", &d->blend, blends, 4);
    ui_tooltip(ui, "Replace the terrain, add to it, or keep the higher / lower");
    static const char *const resamples[] = {"Nearest", "Bilinear", "Bicubic"};
    ui_combo(ui, "Resample", &d->resample, resamples, 3);
    ui_tooltip(ui, "Sampling when the file's spacing differs from the world's");
    ui_slider(ui, "Edge falloff (m)##falloff", &d->falloff, 0, 2000, "%.0f m");
    ui_tooltip(ui, "Fade the edges into the terrain over this distance");
}

// Seed 004's export: the cube's subdivision (with what it makes) and the face images.
static void planet_fields(interchange_dialog *d, ui_context *ui) {
    ui_form_field(ui, "Subdivision", "subdivision", d->subdivision, sizeof d->subdivision,
                  "N: the cube's faces split until there are 12 x 2^N triangles (0 .. 20)");
    ui_row(ui, 1, NULL, 0);
    char *end;
    long n = strtol(d->subdivision, &end, 10);
    char line[160];
    if (end != d->subdivision && !*end && n >= 0 && n <= 20)
        snprintf(line, sizeof line, "%zu vertices, %zu triangles", ((size_t)6 << n) + 2,
                 (size_t)12 << n);
    else
        snprintf(line, sizeof line, "the subdivision is a whole number 0 .. 20");
    ui_label(ui, line);
    ui_form_field(ui, "Image size", "image_size", d->image_size, sizeof d->image_size,
                  "Pixels per side of the six height and six normal maps (blank: the face "
                  "grid's own, up to 8192)");
}

// An edit layer's export: the file typed, its format (the extension, 16-bit TIFF) and
// what of the stack it holds.
static void layer_export_fields(interchange_dialog *d, ui_context *ui) {
    ui_form_field(ui, "File", "path", d->path, sizeof d->path,
                  "Where to write it (its .json sidecar goes beside it)");
    static const char *const formats[] = {"EXR (float)", "TIFF (float)", "TIFF (16-bit)",
                                          "PNG (16-bit)", "R16 (16-bit raw)"};
    static const char *const extensions[] = {".exr", ".tif", ".tif", ".png", ".r16"};
    char *dot = strrchr(d->path, '.');
    if (dot && strchr(dot, '/')) dot = NULL;
    int format = 0;
    for (int i = 0; i < 5; i++)
        if (dot && !strcmp(dot, extensions[i]) && (i != 1 || !d->bits16)) {
            format = i;
            break;
        }
    ui_row(ui, 1, NULL, 0);
    if (ui_combo(ui, "Format", &format, formats, 5)) {
        if (!dot) dot = d->path + strlen(d->path);
        snprintf(dot, sizeof d->path - (size_t)(dot - d->path), "%s", extensions[format]);
        d->bits16 = format == 2;
    }
    ui_tooltip(ui, "The file's format: float metres, or 16-bit values with their mapping in "
                   "the sidecar");
    char change[120], upto[120];
    snprintf(change, sizeof change, "%s's change (signed)", d->layer_name);
    snprintf(upto, sizeof upto, "The stack up to %s", d->layer_name);
    const char *whats[] = {change, upto, "The composite"};
    ui_combo(ui, "Layers", &d->layer_what, whats, 3);
    ui_tooltip(ui, "What it holds: what the layer adds to the ones below (layers=NAME), the "
                   "composite of the layers up to it (layers=upto=NAME), or everything");
}

static void export_fields(interchange_dialog *d, ui_context *ui) {
    if (d->planet) {
        planet_fields(d, ui);
        return;
    }
    if (d->layer_name[0]) layer_export_fields(d, ui);
    ui_row(ui, 1, NULL, 0);
    ui_checkbox(ui, "The whole world##whole", &d->whole);
    ui_tooltip(ui, "Every sample of a bounded world (else the region below)");
    if (!d->whole) {
        static const char *const labels[] = {"West X0 (m)", "North Z0 (m)", "East X1 (m)",
                                             "South Z1 (m)"};
        static const char *const names[] = {"x0", "z0", "x1", "z1"};
        static const char *const tips[] = {
            "The region's west edge, metres", "The region's north edge (smaller Z), metres",
            "The region's east edge, metres", "The region's south edge, metres"};
        for (int i = 0; i < 4; i++)
            ui_form_field(ui, labels[i], names[i], d->region[i], sizeof d->region[i], tips[i]);
    }
    if (d->mesh) {
        mesh_export_fields(&d->mesh_choices, d->path, sizeof d->path, ui);
        return;
    }
    if (!d->layer_name[0])
        ui_form_field(ui, "Tiles", "tiles", d->tiles, sizeof d->tiles,
                      "C x R files sharing their edge samples, as tiled landscape imports "
                      "expect, e.g. 2x2 (blank: one file)");
    ui_row(ui, 1, NULL, 0);
    static const char *const presets[] = {"None",    "Unreal", "Unity", "Godot Terrain3D",
                                          "Houdini", "Blender"};
    ui_combo(ui, "Preset", &d->preset, presets, 6);
    ui_tooltip(ui, "Check the format and resample each file to a size the engine imports; "
                   "its settings go to the console");
    const char *dot = strrchr(d->path, '.');
    if (!d->layer_name[0] && dot && (!strcmp(dot, ".tif") || !strcmp(dot, ".tiff"))) {
        ui_checkbox(ui, "16-bit TIFF (not float)##bits16", &d->bits16);
        ui_tooltip(ui, "16-bit values and a mapping, not float metres");
    }
}

int interchange_dialog_rows(const interchange_dialog *d) {
    // The most it can show (ticking a box must not push the buttons out of view).
    if (d->exporting && d->planet) return 5; // title, subdivision, counts, images, buttons
    // title, error, whole, 4 region edges, format, solid (or voxel), simplify or its note
    // (or fog), centred, buttons
    if (d->exporting && d->mesh) return 12;
    // title, (layer: error, file, format, layers), whole, 4 region edges, tiles, preset,
    // 16-bit TIFF, buttons
    if (d->exporting) return d->layer_name[0] ? 13 : 10;
    // title x z centre layer map min max, file, histogram (about 1.5 rows), heights,
    // spacing, extent, its warning (the last three may wrap), blend resample falloff
    // buttons
    return 21;
}

int interchange_dialog_draw(interchange_dialog *d, ui_context *ui, ui_rect r, char *cmd,
                            size_t cmd_len) {
    // The fields scroll when the window is small (or the UI large); the buttons stay at
    // the bottom, always in view.
    float foot_h = ui_em(ui, 1.4f) + 2 * ui_em(ui, 0.3f);
    ui_rect body = {r.x, r.y, r.w, r.h - foot_h}, foot = {r.x, r.y + body.h, r.w, foot_h};
    ui_panel_begin(ui, d->exporting ? "Export options" : "Import options", body);
    ui_row(ui, 1, NULL, 0);
    const char *slash = strrchr(d->path, '/');
    char title[600];
    snprintf(title, sizeof title, "%s %.500s", d->exporting ? "Export to" : "Import",
             slash ? slash + 1 : d->path);
    ui_label(ui, title);
    if (d->error[0]) ui_label_wrapped(ui, d->error, ui_get_theme(ui)->text_error);
    if (d->exporting)
        export_fields(d, ui);
    else
        import_fields(d, ui);
    ui_panel_end(ui);
    ui_panel_begin(ui, d->exporting ? "Export options##buttons" : "Import options##buttons", foot);
    float bottom[2] = {-0.5f, 0};
    ui_row(ui, 2, bottom, 0);
    int go = ui_button(ui, d->exporting ? "Export##go" : "Import##go");
    ui_tooltip(ui, !d->exporting ? "Import it as one undo step"
                   : d->planet   ? "Write the mesh and its twelve face images"
                                 : "Write the file (and its .json sidecar)");
    if (ui_button(ui, "Cancel")) d->open = 0;
    ui_tooltip(ui, "Close without doing anything (Esc)");
    ui_panel_end(ui);
    if (!go) return 0;
    char path[4200];
    cmd_quote_arg(path, sizeof path, d->path);
    static const char *const blends[] = {"replace", "add", "max", "min"};
    static const char *const resamples[] = {"nearest", "bilinear", "bicubic"};
    static const char *const presets[] = {"none", "unreal", "unity", "godot", "houdini", "blender"};
    if (d->exporting && d->planet) {
        snprintf(cmd, cmd_len, "export %s %s%s%s", d->subdivision, path,
                 d->image_size[0] ? " size=" : "", d->image_size);
    } else if (d->exporting) {
        char region[200] = "";
        if (!d->whole)
            snprintf(region, sizeof region, " region=%s,%s,%s,%s", d->region[0], d->region[1],
                     d->region[2], d->region[3]);
        const char *tif = strrchr(d->path, '.');
        int bits16 = d->bits16 && tif && (!strcmp(tif, ".tif") || !strcmp(tif, ".tiff"));
        char layers[120] = "";
        if (d->layer_name[0] && d->layer_what < 2)
            snprintf(layers, sizeof layers, " layers=%s%s", d->layer_what ? "upto=" : "",
                     d->layer_name);
        char tiles[40] = "", mesh[120] = "";
        if (d->mesh)
            mesh_export_options(&d->mesh_choices, d->path, mesh, sizeof mesh);
        else if (d->tiles[0] && !d->layer_name[0])
            snprintf(tiles, sizeof tiles, " tiles=%s", d->tiles);
        const int preset = d->mesh ? 0 : d->preset;
        snprintf(cmd, cmd_len, "export %s%s%s%s%s%s%s%s", path, region, tiles,
                 preset ? " preset=" : "", preset ? presets[preset] : "",
                 bits16 && !d->mesh ? " bits=16" : "", layers, mesh);
    } else {
        char mapping[100] = "";
        if (d->map_heights) snprintf(mapping, sizeof mapping, " min=%s max=%s", d->min, d->max);
        char spacing[64] = "";
        if (d->spacing[0]) snprintf(spacing, sizeof spacing, " spacing=%s", d->spacing);
        snprintf(cmd, cmd_len, "import %s x=%s z=%s%s layer=%s%s%s blend=%s resample=%s falloff=%g",
                 path, d->x, d->z, d->centre ? " anchor=centre" : "",
                 d->layer ? "detail" : "coarse", mapping, spacing, blends[d->blend],
                 resamples[d->resample], d->falloff);
    }
    d->open = 0;
    return 1;
}
