#include "support/test_world.h"

#include "editor/world/layer_grid.h"

#include <stdlib.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

void test_silent(void *user, const char *message) {
    (void)user, (void)message;
}

world_params test_flat_fbm_params(int64_t size) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.generator = GEN_FBM;
    p.seed = 4242;
    p.octaves = 4;
    p.size = size;
    p.spacing = 1.0;
    p.feature_size = 256.0;
    p.max_height = 300;
    return p;
}

world *test_world_open(const world_params *p) {
    world_settings s = {.cache_budget_bytes = (size_t)256 << 20, .workers = 2, .warn = test_silent};
    og_error err;
    world *w = world_create(p, &s, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    return w;
}

float *test_read_slot(world *w, int32_t slot, grid_rect r) {
    layer_grid g;
    og_error err;
    if (layer_grid_init(&g, world_get_params(w), TILE_LAYER_COARSE, 0, &err) != 0)
        fail_msg("%s", err.msg);
    g.layer = (tile_layer)tile_layer_in_slot(TILE_LAYER_COARSE, slot);
    float *out = malloc(sizeof(float) * (size_t)((r.x1 - r.x0) * (r.z1 - r.z0)));
    if (layer_grid_read(w, &g, r, out, &err) != 0) fail_msg("%s", err.msg);
    return out;
}

uint64_t test_rng_next(uint64_t *state) {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    return *state;
}

double test_rng_unit(uint64_t *state) {
    return (double)(test_rng_next(state) >> 11) / 9007199254740992.0;
}
