#include "support/test_world.h"

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

uint64_t test_rng_next(uint64_t *state) {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    return *state;
}

double test_rng_unit(uint64_t *state) {
    return (double)(test_rng_next(state) >> 11) / 9007199254740992.0;
}
