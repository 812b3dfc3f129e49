#include "editor/interchange/export_layers.h"

#include "editor/world/layer_grid.h"
#include "io/image_read.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int check_png(const char *path, og_error *err) {
    const char *dot = strrchr(path, '.');
    if (!dot || strcmp(dot, ".png") != 0)
        return og_error_set(err, "%s: normal maps and material weights are written as .png", path);
    return 0;
}

int export_normal_map(world *w, const char *path, grid_rect r, int bits, char *files,
                      size_t files_len, og_error *err) {
    if (check_png(path, err) != 0) return -1;
    layer_grid g;
    if (layer_grid_init(&g, world_get_params(w), TILE_LAYER_COARSE, 0, err) != 0) return -1;
    const int64_t W = r.x1 - r.x0, D = r.z1 - r.z0;
    // One sample more on each side for central differences (edges repeat at the border).
    grid_rect big = {r.x0 - 1, r.z0 - 1, r.x1 + 1, r.z1 + 1};
    float *h = malloc(sizeof(float) * (size_t)((W + 2) * (D + 2)));
    const double top = bits == 16 ? 65535.0 : 255.0;
    uint16_t *rgb = malloc((size_t)(W * D) * 3 * sizeof *rgb); // 16 bits; narrowed for 8
    int rc = -1;
    if (!h || !rgb) {
        og_error_set(err, "%s: out of memory", path);
        goto done;
    }
    if (layer_grid_read(w, &g, big, h, err) != 0) goto done;
    for (int64_t j = 0; j < D; j++)
        for (int64_t i = 0; i < W; i++) {
            const float *c = h + (j + 1) * (W + 2) + (i + 1);
            double dx = (c[1] - c[-1]) / (2 * g.spacing);
            double dz = (c[W + 2] - c[-(W + 2)]) / (2 * g.spacing);
            double len = sqrt(dx * dx + 1 + dz * dz);
            double n[3] = {-dx / len, -(-dz / len), 1 / len}; // x, toward row 0 (-Z), up
            uint16_t *p = rgb + (size_t)(j * W + i) * 3;
            for (int k = 0; k < 3; k++)
                p[k] = (uint16_t)lround((n[k] * 0.5 + 0.5) * top);
        }
    if (bits == 16) {
        rc = image_write_u16(path, rgb, (int)W, (int)D, 3, err);
    } else {
        unsigned char *narrow = (unsigned char *)rgb; // in place: each byte read before written
        for (size_t k = 0; k < (size_t)(W * D) * 3; k++)
            narrow[k] = (unsigned char)rgb[k];
        rc = image_write_u8(path, narrow, (int)W, (int)D, 3, err);
    }
    if (rc == 0) snprintf(files, files_len, "%s\n", path);
done:
    free(h);
    free(rgb);
    return rc;
}

int export_material_weights(world *w, const char *path, grid_rect r, char *files, size_t files_len,
                            og_error *err) {
    if (check_png(path, err) != 0) return -1;
    layer_grid g;
    if (layer_grid_init(&g, world_get_params(w), TILE_LAYER_MATERIAL, 0, err) != 0) return -1;
    const int64_t W = r.x1 - r.x0, D = r.z1 - r.z0, n = W * D;
    unsigned char *weights = malloc((size_t)n * TILE_MATERIALS);
    unsigned char *rgba = malloc((size_t)n * 4);
    int rc = -1;
    files[0] = 0;
    if (!weights || !rgba) {
        og_error_set(err, "%s: out of memory", path);
        goto done;
    }
    if (layer_grid_read_samples(w, &g, r, weights, err) != 0) goto done;
    const char *dot = strrchr(path, '.');
    for (int first = 0; first < TILE_MATERIALS; first += 4) {
        for (int64_t i = 0; i < n; i++)
            memcpy(rgba + i * 4, weights + i * TILE_MATERIALS + first, 4);
        char one[4200];
        snprintf(one, sizeof one, "%.*s_m%d-%d.png", (int)(dot - path), path, first, first + 3);
        if (image_write_u8(one, rgba, (int)W, (int)D, 4, err) != 0) goto done;
        size_t used = strlen(files);
        snprintf(files + used, files_len - used, "%s\n", one);
    }
    rc = 0;
done:
    free(weights);
    free(rgba);
    return rc;
}
