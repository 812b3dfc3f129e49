#include "editor/edit/height_window.h"

#include "editor/layers/layer_blend.h"

#include <stdlib.h>
#include <string.h>

grid_rect height_window_grow(grid_rect r, int by) {
    return (grid_rect){r.x0 - by, r.z0 - by, r.x1 + by, r.z1 + by};
}

static size_t rect_samples(grid_rect r) {
    return (size_t)((r.x1 - r.x0) * (r.z1 - r.z0));
}

int height_window_mask_border(const layer_info *l, double spacing) {
    return l->visible && l->kind == LAYER_KIND_HEIGHT && layer_mask_active(&l->mask)
               ? layer_mask_border(&l->mask, spacing)
               : 0;
}

int height_window_coverage(world *w, const layer_info *l, const layer_grid *grid, grid_rect r,
                           float **out, og_error *err) {
    *out = NULL;
    if (!l->mask.painted) return 0;
    float *c = malloc(sizeof(float) * rect_samples(r));
    if (!c) return og_error_set(err, "out of memory reading a painted mask");
    layer_grid g = *grid;
    g.layer = (tile_layer)tile_layer_in_slot(TILE_LAYER_COARSE, layer_coverage_slot(l->id));
    if (layer_grid_read(w, &g, r, c, err) != 0) {
        free(c);
        return -1;
    }
    *out = c;
    return 0;
}

int height_window_mask(world *w, const layer_info *l, const layer_grid *grid, grid_rect r,
                       const float *below, int b, float *out, og_error *err) {
    float *painted;
    if (height_window_coverage(w, l, grid, r, &painted, err) != 0) return -1;
    layer_mask_evaluate(&l->mask, below, (int)(r.x1 - r.x0), (int)(r.z1 - r.z0), b, grid->spacing,
                        painted, out);
    free(painted);
    return 0;
}

int height_window_compose(world *w, const layer_table *t, const layer_grid *grid, grid_rect r,
                          int upto, int extra, int record, float *weights, float **out,
                          og_error *err) {
    int margin = extra;
    for (int i = 0; i < upto; i++)
        margin += height_window_mask_border(&t->layers[i], grid->spacing);
    grid_rect outer = height_window_grow(r, margin);
    int ow = (int)(outer.x1 - outer.x0);
    size_t n = rect_samples(outer);
    // Windows only for what the layers below upto need (none: the base alone).
    int layers = 0, masks = 0;
    for (int i = 0; i < upto; i++) {
        const layer_info *l = &t->layers[i];
        layers |= l->visible && l->kind == LAYER_KIND_HEIGHT;
        masks |= l->visible && l->kind == LAYER_KIND_HEIGHT && layer_mask_active(&l->mask);
    }
    float *acc = malloc(sizeof(float) * n), *val = layers ? malloc(sizeof(float) * n) : NULL;
    float *below = masks ? malloc(sizeof(float) * n) : NULL;
    float *mask = masks ? malloc(sizeof(float) * n) : NULL;
    int rc = acc && (val || !layers) && ((below && mask) || !masks)
                 ? 0
                 : og_error_set(err, "out of memory composing layers");
    layer_grid g = *grid;
    g.layer = (tile_layer)tile_layer_in_slot(TILE_LAYER_COARSE, TILE_SLOT_BASE);
    if (rc == 0) rc = layer_grid_read(w, &g, outer, acc, err);
    for (int i = 0; i < upto && rc == 0; i++) {
        const layer_info *l = &t->layers[i];
        if (!l->visible || l->kind != LAYER_KIND_HEIGHT) continue;
        int b = height_window_mask_border(l, grid->spacing), masked = layer_mask_active(&l->mask);
        grid_rect in = height_window_grow(r, margin), apply = height_window_grow(r, margin - b);
        int iw = (int)(in.x1 - in.x0), ih = (int)(in.z1 - in.z0);
        int aw = (int)(apply.x1 - apply.x0), ah = (int)(apply.z1 - apply.z0);
        g.layer = (tile_layer)tile_layer_in_slot(TILE_LAYER_COARSE, l->id);
        if ((rc = layer_grid_read(w, &g, apply, val, err)) != 0) break;
        float opacity = (float)l->opacity;
        if (masked) {
            for (int z = 0; z < ih; z++) // the composite below it, its window alone
                memcpy(below + (size_t)z * iw,
                       acc + (size_t)(z + in.z0 - outer.z0) * ow + (in.x0 - outer.x0),
                       sizeof(float) * (size_t)iw);
            if ((rc = height_window_mask(w, l, grid, apply, below, b, mask, err)) != 0) break;
        }
        for (int z = 0; z < ah; z++) {
            float *row = acc + (size_t)(z + apply.z0 - outer.z0) * ow + (apply.x0 - outer.x0);
            const float *v = val + (size_t)z * aw;
            if (!masked) {
                layer_blend_row(l->blend, opacity, row, v, row, aw);
                continue;
            }
            for (int x = 0; x < aw; x++)
                row[x] =
                    layer_blend_sample(l->blend, opacity * mask[(size_t)z * aw + x], row[x], v[x]);
        }
        if (i == record && weights) {
            int off = margin - b, rw = (int)(r.x1 - r.x0); // r within apply
            for (int z = 0; z < (int)(r.z1 - r.z0); z++)
                for (int x = 0; x < rw; x++)
                    weights[(size_t)z * rw + x] =
                        masked ? opacity * mask[(size_t)(z + off) * aw + x + off] : opacity;
        }
        margin -= b;
    }
    free(val);
    free(below);
    free(mask);
    if (rc != 0) {
        free(acc);
        return -1;
    }
    // Down to r grown by extra (margin == extra now).
    grid_rect want = height_window_grow(r, extra);
    int ww = (int)(want.x1 - want.x0);
    for (int z = 0; z < (int)(want.z1 - want.z0) && ww != ow; z++) // ww == ow: want is outer
        memmove(acc + (size_t)z * ww,
                acc + (size_t)(z + want.z0 - outer.z0) * ow + (want.x0 - outer.x0),
                sizeof(float) * (size_t)ww);
    *out = acc;
    return 0;
}
