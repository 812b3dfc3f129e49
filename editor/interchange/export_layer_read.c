#include "editor/interchange/export_layer_read.h"

#include "editor/edit/height_window.h"

#include <stdlib.h>
#include <string.h>

int export_layers_check(world *w, const char *path, int what, const char *name, tile_layer grid,
                        og_error *err) {
    if (what == EXPORT_READ_COMPOSITE) return 0;
    if (grid != TILE_LAYER_COARSE)
        return og_error_set(err, "%s: layers= exports the coarse heights (no layer=detail)", path);
    const layer_table *t = &world_get_params(w)->layers;
    int i = layer_table_find(t, name);
    if (i < 0) return og_error_set(err, "%s: layers: no layer named '%s'", path, name);
    if (t->layers[i].kind != LAYER_KIND_HEIGHT)
        return og_error_set(
            err, "%s: layers: '%s' is a paint layer: it holds materials, not heights", path, name);
    return 0;
}

int export_layers_read(world *w, const layer_grid *g, int what, const char *name, grid_rect r,
                       float *out, og_error *err) {
    if (what == EXPORT_READ_COMPOSITE) return layer_grid_read(w, g, r, out, err);
    layer_table t = world_get_params(w)->layers;
    int i = layer_table_find(&t, name);
    if (i < 0) return og_error_set(err, "layers: no layer named '%s'", name);
    t.layers[i].visible = 1;
    float *with, *below = NULL;
    if (height_window_compose(w, &t, g, r, i + 1, 0, -1, NULL, &with, err) != 0) return -1;
    size_t n = (size_t)((r.x1 - r.x0) * (r.z1 - r.z0));
    if (what == EXPORT_READ_UPTO) {
        memcpy(out, with, sizeof(float) * n);
        free(with);
        return 0;
    }
    if (height_window_compose(w, &t, g, r, i, 0, -1, NULL, &below, err) != 0) {
        free(with);
        return -1;
    }
    for (size_t k = 0; k < n; k++)
        out[k] = with[k] - below[k];
    free(with);
    free(below);
    return 0;
}
