#include "app/mesh_export_fields.h"

#include <stdio.h>
#include <string.h>

static const char *const extensions[] = {".glb", ".obj", ".ply", ".vdb"};

// The index of path's extension in extensions, or -1.
static int format_of(const char *path) {
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/')) return -1;
    for (int i = 0; i < 4; i++)
        if (!strcmp(dot, extensions[i])) return i;
    return -1;
}

int mesh_export_is_volume(const char *path) {
    return format_of(path) == 3;
}

int mesh_export_known(const char *path) {
    return format_of(path) >= 0;
}

void mesh_export_fields(mesh_export_choices *m, char *path, size_t path_size, ui_context *ui) {
    static const char *const formats[] = {"glTF binary (.glb)", "OBJ (.obj)", "PLY (.ply)",
                                          "OpenVDB volume (.vdb)"};
    int format = format_of(path);
    int shown = format < 0 ? 0 : format;
    ui_row(ui, 1, NULL, 0);
    if (ui_combo(ui, "Format", &shown, formats, 4) || format < 0) {
        // The extension says the format: choosing one renames the file to match.
        char *dot = strrchr(path, '.');
        if (!dot || strchr(dot, '/')) dot = path + strlen(path);
        snprintf(dot, path_size - (size_t)(dot - path), "%s", extensions[shown]);
    }
    ui_tooltip(ui, "glTF for Blender and game engines (heights coloured in its texture), OBJ "
                   "and PLY for any 3D tool, OpenVDB for Houdini's volumes");
    if (mesh_export_is_volume(path)) {
        ui_form_field(ui, "Voxel (m)", "voxel", m->voxel, sizeof m->voxel,
                      "The voxel's size in metres (blank: the world's sample spacing)");
        ui_row(ui, 1, NULL, 0);
        ui_checkbox(ui, "Fog volume (density, not a level set)##fog", &m->fog);
        ui_tooltip(ui, "Density 1 inside the ground of the region, 0 in the air, instead of "
                       "a signed distance");
        return;
    }
    ui_row(ui, 1, NULL, 0);
    ui_checkbox(ui, "Closed solid (walls and a floor)##solid", &m->solid);
    ui_tooltip(ui, "A closed mesh for 3D printing and booleans");
    if (m->solid) {
        ui_row(ui, 1, NULL, 0);
        ui_label_colored(ui, "Every sample: a closed solid is not simplified",
                         ui_get_theme(ui)->text_dim);
    } else {
        ui_form_field(ui, "Simplify (m)", "simplify", m->simplify, sizeof m->simplify,
                      "How far the simplified surface may stray from the terrain, metres "
                      "(blank: every sample)");
    }
    ui_row(ui, 1, NULL, 0);
    ui_checkbox(ui, "Centred at the origin##centred", &m->centred);
    ui_tooltip(ui, "The region's middle at 0, 0 (else at its place in the world)");
}

void mesh_export_options(const mesh_export_choices *m, const char *path, char *out, size_t len) {
    out[0] = 0;
    if (mesh_export_is_volume(path)) {
        snprintf(out, len, "%s%s%s", m->voxel[0] ? " voxel=" : "", m->voxel,
                 m->fog ? " fog=1" : "");
        return;
    }
    const int simplify = !m->solid && m->simplify[0];
    snprintf(out, len, "%s%s%s%s", simplify ? " simplify=" : "", simplify ? m->simplify : "",
             m->solid ? " solid=1" : "", m->centred ? " centred=1" : "");
}
