#include "editor/world/layer_grid.h"

#include "editor/params/world_grid.h"

#include <math.h>
#include <string.h>

int layer_grid_init(layer_grid *g, const world_params *p, tile_layer layer, int face,
                    og_error *err) {
    int faces = p->kind == WORLD_PLANET ? 6 : 1;
    if (face < 0 || face >= faces)
        return og_error_set(err, "face %d does not exist (this world has %s)", face,
                            faces == 6 ? "faces 0-5" : "only face 0");
    if (layer != TILE_LAYER_COARSE && layer != TILE_LAYER_DETAIL && layer != TILE_LAYER_MATERIAL)
        return og_error_set(err, "the %s layer cannot be edited", tile_layer_name(layer));
    const int planet = p->kind == WORLD_PLANET;
    int64_t coarse = planet ? world_grid_face_samples(p) : p->size;
    int64_t coarse_z = planet ? coarse : world_params_size_z(p);
    g->layer = layer;
    g->face = face;
    g->spacing = world_grid_sample_metres(p);
    g->extent = coarse;
    g->extent_z = coarse_z;
    if (layer == TILE_LAYER_DETAIL) {
        g->spacing = world_grid_sample_metres(p) / p->detail_ratio;
        g->extent = coarse > 0 ? (coarse - 1) * p->detail_ratio + 1 : 0;
        g->extent_z = coarse_z > 0 ? (coarse_z - 1) * p->detail_ratio + 1 : 0;
    }
    return 0;
}

grid_rect layer_grid_clip(const layer_grid *g, grid_rect r) {
    if (g->extent <= 0) return r;
    return grid_rect_intersect(r, (grid_rect){0, 0, g->extent, g->extent_z});
}

grid_rect layer_grid_disc_rect(const layer_grid *g, double x, double z, double radius) {
    grid_rect r = {(int64_t)ceil((x - radius) / g->spacing),
                   (int64_t)ceil((z - radius) / g->spacing),
                   (int64_t)floor((x + radius) / g->spacing) + 1,
                   (int64_t)floor((z + radius) / g->spacing) + 1};
    return layer_grid_clip(g, r);
}

int layer_grid_read_samples(world *w, const layer_grid *g, grid_rect r, void *out_bytes,
                            og_error *err) {
    unsigned char *out = out_bytes;
    const size_t sample = tile_layer_bytes(g->layer) / TILE_SAMPLES; // 4 (heights) or 8
    int64_t width = r.x1 - r.x0;
    // Read the clipped part tile by tile, then replicate edges outward.
    grid_rect in = layer_grid_clip(g, r);
    if (grid_rect_empty(in)) return og_error_set(err, "the area lies entirely outside the world");
    tile_cache *cache = world_cache(w);
    for (int64_t tz = world_grid_floor_div(in.z0, TILE_SIZE);
         tz <= world_grid_floor_div(in.z1 - 1, TILE_SIZE); tz++) {
        for (int64_t tx = world_grid_floor_div(in.x0, TILE_SIZE);
             tx <= world_grid_floor_div(in.x1 - 1, TILE_SIZE); tx++) {
            tile_key key = {g->layer, g->face, 0, (int32_t)tx, (int32_t)tz};
            tile_view v;
            if (tile_cache_acquire(cache, key, &v, err) != 0) return -1;
            const unsigned char *t = v.data;
            grid_rect tr =
                grid_rect_intersect(in, (grid_rect){tx * TILE_SIZE, tz * TILE_SIZE,
                                                    (tx + 1) * TILE_SIZE, (tz + 1) * TILE_SIZE});
            for (int64_t z = tr.z0; z < tr.z1; z++)
                memcpy(out + ((z - r.z0) * width + (tr.x0 - r.x0)) * sample,
                       t + ((z - tz * TILE_SIZE) * TILE_SIZE + (tr.x0 - tx * TILE_SIZE)) * sample,
                       (size_t)(tr.x1 - tr.x0) * sample);
            tile_cache_release(cache, &v);
        }
    }
    if (in.x0 == r.x0 && in.x1 == r.x1 && in.z0 == r.z0 && in.z1 == r.z1) return 0;
    for (int64_t z = in.z0; z < in.z1; z++) {
        unsigned char *row = out + (z - r.z0) * width * sample;
        for (int64_t x = r.x0; x < in.x0; x++)
            memcpy(row + (x - r.x0) * sample, row + (in.x0 - r.x0) * sample, sample);
        for (int64_t x = in.x1; x < r.x1; x++)
            memcpy(row + (x - r.x0) * sample, row + (in.x1 - 1 - r.x0) * sample, sample);
    }
    for (int64_t z = r.z0; z < r.z1; z++) {
        if (z >= in.z0 && z < in.z1) continue;
        int64_t cz = z < in.z0 ? in.z0 : in.z1 - 1;
        memcpy(out + (z - r.z0) * width * sample, out + (cz - r.z0) * width * sample,
               (size_t)width * sample);
    }
    return 0;
}

int layer_grid_read(world *w, const layer_grid *g, grid_rect r, float *out, og_error *err) {
    if (g->layer == TILE_LAYER_MATERIAL)
        return og_error_set(err, "layer_grid_read: the material layer holds weights, not heights");
    return layer_grid_read_samples(w, g, r, out, err);
}

int layer_grid_check_position(const layer_grid *g, double x, double z, og_error *err) {
    if (!isfinite(x) || !isfinite(z))
        return og_error_set(err, "position (%g, %g) must be finite numbers", x, z);
    double limit = ((double)INT32_MAX - 2) * TILE_SIZE * g->spacing;
    if (fabs(x) > limit || fabs(z) > limit)
        return og_error_set(err, "position (%g, %g) m lies beyond the addressable world (+-%g m)",
                            x, z, limit);
    if (g->extent > 0) {
        double right = (double)(g->extent - 1) * g->spacing;
        double bottom = (double)(g->extent_z - 1) * g->spacing;
        if (x < 0 || z < 0 || x > right || z > bottom)
            return og_error_set(err,
                                "position (%g, %g) m lies outside the world (0 .. %g m along X, "
                                "0 .. %g m along Z)",
                                x, z, right, bottom);
    }
    return 0;
}
