// The editor's first view of a bounded flat world (viewport_camera_on_land: the window's
// start, File > New world from heightmap, Home) faces land, wherever in the world it is:
//  - an island's heightmap keeps the ocean floor around it as flat ground (SRTM's 0 m sea,
//    over the flat default's -400 m sea). An island 4 km from the centre of such a world
//    (the ring search reaches 3 km): the view's centre meets the island. Before, the flat
//    plain at the centre counted as land and the view showed nothing but it.
//  - a flat world with no relief: the view still faces its centre, as before.
//  - a small world whose search rings reach past its edge: a view, not an error.
//  - a world of 89 m samples is seen from tens of kilometres, not 900 m.
#include "editor/cmd/commands.h"
#include "editor/params/world_params.h"
#include "editor/world/world.h"
#include "renderer/camera.h"
#include "renderer/viewport.h"
#include "support/test_support.h"
#include "support/test_view.h"
#include "view/view_commands.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

// Where the first view's centre ray meets the ground, in hit[].
static void first_view_centre(cmd_context *ctx, double hit[3]) {
    og_error err = {{0}};
    viewport *v = view_commands_viewport(ctx);
    assert_non_null(v);
    if (viewport_camera_on_land(v, ctx->world, &err) != 0) fail_msg("first view: %s", err.msg);
    double dir[3], g = 0;
    camera_ray(&v->cam, 16.0 / 10.0, 0.5, 0.5, dir);
    const world_params *p = world_get_params(ctx->world);
    const double edge = (double)(p->size - 1) * p->spacing;
    for (double t = 0; t < 200000; t += fmax(1.0, t * 1e-3)) {
        for (int a = 0; a < 3; a++)
            hit[a] = v->cam.pos[a] + dir[a] * t;
        if (hit[0] < 0 || hit[2] < 0 || hit[0] > edge || hit[2] > edge) continue;
        if (world_sample(ctx->world, 0, hit[0], hit[2], &g, &err) != 0)
            fail_msg("sample: %s", err.msg);
        if (hit[1] <= g) return;
    }
    fail_msg("the first view's centre meets no ground");
}

static void test_island_far_from_the_centre(void **state) {
    cmd_context *ctx = *state;
    // 8 km across; a mountain 300 m high, 2 km wide, 4 km from the centre (the corner).
    test_view_run(ctx,
                  "new flat; generator flat; size 4096; spacing 2; generate; stamp mountain 6900 "
                  "6900 scale=8 intensity=300");
    double hit[3], top = 0;
    og_error err = {{0}};
    if (world_sample(ctx->world, 0, 6900, 6900, &top, &err) != 0) fail_msg("%s", err.msg);
    first_view_centre(ctx, hit);
    printf("island's top %.0f m; the first view's centre meets the ground at (%.0f, %.0f), "
           "%.1f m high\n",
           top, hit[0], hit[2], hit[1]);
    assert_true(top > 200);
    assert_true(hit[1] > 0.05 * world_get_params(ctx->world)->max_height);
    assert_true(hypot(hit[0] - 6900, hit[2] - 6900) < 2500);
}

static void test_flat_world_faces_its_centre(void **state) {
    cmd_context *ctx = *state;
    test_view_run(ctx, "new flat; generator flat; size 1024; spacing 1; generate");
    double hit[3];
    first_view_centre(ctx, hit);
    printf("flat world: the first view's centre meets the ground at (%.0f, %.0f)\n", hit[0],
           hit[2]);
    assert_true(hypot(hit[0] - 511.5, hit[2] - 511.5) < 50);
}

// The rings searched around the centre reach past a small world's edge: the default fBm
// world of 1024 samples has no gentle land at its centre, and its 600 m ring starts 8 m
// outside the world. Before, the first view failed there ("position (-8.1, 811.5) m lies
// outside the world") and the window kept the last world's camera.
static void test_rings_past_a_small_worlds_edge(void **state) {
    cmd_context *ctx = *state;
    test_view_run(ctx, "new flat; size 1024; spacing 1; generate");
    double hit[3];
    first_view_centre(ctx, hit);
    printf("fBm world of 1024 samples: the first view's centre meets the ground at (%.0f, "
           "%.0f), %.1f m high\n",
           hit[0], hit[2], hit[1]);
    assert_true(hit[1] > world_params_ocean_height(world_get_params(ctx->world)));
}

// A heightmap of coarse samples (SRTM's 90 m): the view stands back far enough to show
// hundreds of them. Before, it stood 900 m from the land, a dozen samples: a green blur.
static void test_coarse_samples_seen_from_afar(void **state) {
    cmd_context *ctx = *state;
    test_view_run(ctx,
                  "new flat; generator flat; size 1201; spacing 89; generate; stamp mountain 53000 "
                  "53000 scale=2 intensity=800");
    viewport *v = view_commands_viewport(ctx);
    double hit[3];
    first_view_centre(ctx, hit);
    double distance = sqrt(pow(hit[0] - v->cam.pos[0], 2) + pow(hit[1] - v->cam.pos[1], 2) +
                           pow(hit[2] - v->cam.pos[2], 2));
    printf("89 m samples: the first view looks at (%.0f, %.0f) from %.0f m (%.0f samples)\n",
           hit[0], hit[2], distance, distance / 89);
    assert_true(distance > 300 * 89.0);
}

static int setup(void **state) {
    static cmd_context ctx;
    test_view_context_open(&ctx);
    *state = &ctx;
    return 0;
}

static int teardown(void **state) {
    test_view_context_close(*state);
    return 0;
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_island_far_from_the_centre),
        cmocka_unit_test(test_flat_world_faces_its_centre),
        cmocka_unit_test(test_rings_past_a_small_worlds_edge),
        cmocka_unit_test(test_coarse_samples_seen_from_afar),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
