// The map view's image: composed without waiting, final once every tile arrived,
// deterministic, showing water and land, dark outside a bounded world.
#include "renderer/map_image.h"

#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

enum { W = 320, H = 200 };

static int compose_final(world *w, const map_view *v, uint8_t *px) {
    int first = map_image_compose(w, v, W, H, px), pending = first;
    for (int i = 0; i < 3000 && pending > 0; i++) {
        usleep(2000);
        pending = map_image_compose(w, v, W, H, px);
    }
    assert_int_equal(pending, 0);
    return first;
}

static void test_default_world_map(void **state) {
    (void)state;
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.generator = GEN_FBM_ADVANCED;
    og_error err;
    world *w = world_create(&p, NULL, &err);
    assert_non_null(w);
    map_view v = map_view_default(w);
    v.mpp = 32.0;
    uint8_t *a = malloc(W * H * 4), *b = malloc(W * H * 4);
    int first = compose_final(w, &v, a);
    assert_true(first > 0); // a fresh cache: the first image could not wait for tiles
    assert_int_equal(map_image_compose(w, &v, W, H, b), 0);
    assert_memory_equal(a, b, W * H * 4);
    int water = 0, land = 0;
    for (int k = 0; k < W * H; k++) {
        const uint8_t *c = a + 4 * k;
        water += c[2] > c[1] && c[2] > c[0];
        land += c[1] >= c[2];
    }
    assert_true(water > W * H / 50);
    assert_true(land > W * H / 10);
    world_close(w);
    free(a), free(b);
}

static void test_bounded_world_edges_are_dark(void **state) {
    (void)state;
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.size = 512;
    p.spacing = 2.0;
    og_error err;
    world *w = world_create(&p, NULL, &err);
    map_view v = {0.0, 0.0, 4.0, 0}; // the world's corner at the image centre
    uint8_t *px = malloc(W * H * 4);
    compose_final(w, &v, px);
    const uint8_t *outside = px + 4 * (10 * W + 10), *inside = px + 4 * ((H - 10) * W + W - 10);
    assert_true(outside[0] == 24 && outside[1] == 24 && outside[2] == 24);
    assert_false(inside[0] == 24 && inside[1] == 24 && inside[2] == 24);
    world_close(w);
    free(px);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_world_map),
        cmocka_unit_test(test_bounded_world_edges_are_dark),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
