#include "app/export_check.h"

#include "editor/interchange/export.h"
#include "editor/interchange/export_layer_read.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int is_heightmap(const char *path) {
    const char *dot = strrchr(path, '.');
    static const char *const ext[] = {".png", ".tif", ".tiff", ".exr", ".r16"};
    for (int i = 0; dot && i < 5; i++)
        if (!strcmp(dot, ext[i])) return 1;
    return 0;
}

int export_check(world *w, const interchange_dialog *d, og_error *err) {
    if (!d->path[0]) return og_error_set(err, "File: no file name given");
    char folder[4096];
    snprintf(folder, sizeof folder, "%s", d->path);
    char *slash = strrchr(folder, '/');
    if (slash == folder)
        folder[1] = 0; // the root
    else if (slash)
        *slash = 0;
    else
        snprintf(folder, sizeof folder, ".");
    if (slash && !slash[1]) return og_error_set(err, "File: no file name after %s", d->path);
    struct stat st;
    if (stat(folder, &st) != 0 || !S_ISDIR(st.st_mode))
        return og_error_set(err, "File: the folder %s does not exist", folder);
    if (access(folder, W_OK) != 0)
        return og_error_set(err, "File: the folder %s is not writable", folder);
    const int one_layer = d->layer_name[0] && d->layer_what < 2;
    if (one_layer && !is_heightmap(d->path))
        return og_error_set(err,
                            "%s: a layer's change or the stack up to it is written as a "
                            "heightmap (.exr .tif .png .r16)",
                            d->path);
    export_options o;
    export_options_defaults(&o);
    // The fields the dialog passes as typed, checked as the command will check them.
    if (d->mesh) {
        const mesh_export_choices *m = &d->mesh_choices;
        if (!mesh_export_known(d->path))
            return og_error_set(err, "%s: a mesh is .glb, .obj or .ply, a volume .vdb", d->path);
        const int volume = mesh_export_is_volume(d->path);
        if (volume && m->voxel[0] && export_options_set(&o, "voxel", m->voxel, err) != 0) return -1;
        if (!volume && !m->solid && m->simplify[0] &&
            export_options_set(&o, "simplify", m->simplify, err) != 0)
            return -1;
    } else if (d->tiles[0] && !d->layer_name[0] &&
               export_options_set(&o, "tiles", d->tiles, err) != 0) {
        return -1;
    }
    if (!d->whole) {
        char region[160];
        snprintf(region, sizeof region, "%s,%s,%s,%s", d->region[0], d->region[1], d->region[2],
                 d->region[3]);
        if (export_options_set(&o, "region", region, err) != 0) return -1;
    }
    if (one_layer)
        return export_layers_check(w, d->path,
                                   d->layer_what ? EXPORT_READ_UPTO : EXPORT_READ_CHANGE,
                                   d->layer_name, TILE_LAYER_COARSE, err);
    return 0;
}

int export_check_accept(interchange_dialog *d, world *w) {
    if (!d->exporting || d->planet) return 1;
    og_error err = {{0}};
    if (export_check(w, d, &err) == 0) {
        d->error[0] = 0;
        return 1;
    }
    snprintf(d->error, sizeof d->error, "%s", err.msg);
    d->open = 1;
    return 0;
}
