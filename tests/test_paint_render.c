// Painted materials show at every distance (issue 26): a 600 m patch of snow painted on
// the default world is rendered from 1 km, 5 km and 10 km away (the far views draw it
// with clipmap levels 3 to 5, from the material layer's mip levels), and the pixels it
// covers are compared with the same views unpainted (after undo): they must turn white
// (bright, unsaturated) over about the patch's projected area, not stay grass and rock.
#include "editor/cmd/commands.h"
#include "editor/params/world_params.h"
#include "editor/world/world.h"
#include "io/image_read.h"
#include "renderer/camera.h"
#include "support/test_support.h"
#include "view/view_commands.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#define W 480
#define H 270

static void run_ok(cmd_context *ctx, const char *text) {
    og_error err = {{0}};
    if (cmd_run(ctx, text, strlen(text), "test", &err) != 0)
        fail_msg("'%s' failed: %s", text, err.msg);
}

typedef struct view {
    const char *name;
    double pos[3], yaw, pitch;
    // At least this many must turn white: about half the patch's area on screen (5 km
    // away it is some 30 x 7 pixels, 10 km away 15 x 4).
    int min_pixels;
} view;

// The patch: x 2200..2800, z -300..300 metres, where the default world is land.
static const view views[] = {
    {"near", {2500, 500, 900}, 0, -30, 8000},
    {"far", {2500, 1200, 5000}, 0, -15, 100},
    {"farther", {2500, 2500, 10000}, 0, -14, 25},
};
enum { VIEWS = sizeof views / sizeof views[0] };

static unsigned char *shoot(cmd_context *ctx, const char *dir, const view *v, const char *tag) {
    char cmd[8400], path[4200];
    snprintf(path, sizeof path, "%s/%s_%s.png", dir, v->name, tag);
    snprintf(cmd, sizeof cmd, "camera %g %g %g %g %g; screenshot %s %d %d", v->pos[0], v->pos[1],
             v->pos[2], v->yaw, v->pitch, path, W, H);
    run_ok(ctx, cmd);
    unsigned char *rgb = NULL;
    int w = 0, h = 0;
    og_error err = {{0}};
    if (image_read_rgb8(path, &rgb, &w, &h, &err) != 0) fail_msg("%s: %s", path, err.msg);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    return rgb;
}

static void test_paint_shows_far_away(void **state) {
    (void)state;
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    int errors = 0;
    og_error err = {{0}};
    if (world_params_load(OROGEN_RESOURCE_DIR "/default.world", &p, &errors, NULL, NULL, &err) != 0)
        fail_msg("default.world: %s", err.msg);
    world *w = world_create(&p, NULL, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    if (view_commands_register(&err) != 0) fail_msg("view commands: %s", err.msg);
    cmd_context ctx;
    cmd_context_init(&ctx, w, NULL, stdout, OROGEN_RESOURCE_DIR);
    const char *dir = test_tmpdir("paint_render");

    // One stroke back and forth over the patch: one undo step.
    run_ok(&ctx, "tool paint material=4 radius=150 strength=1 falloff=smooth;"
                 "stroke 2200 -300 2800 -300 2800 -150 2200 -150 2200 0 2800 0 2800 150 "
                 "2200 150 2200 300 2800 300");
    unsigned char *painted[VIEWS], *bare[VIEWS];
    for (int i = 0; i < VIEWS; i++)
        painted[i] = shoot(&ctx, dir, &views[i], "painted");
    run_ok(&ctx, "undo");
    for (int i = 0; i < VIEWS; i++)
        bare[i] = shoot(&ctx, dir, &views[i], "bare");

    for (int i = 0; i < VIEWS; i++) {
        // Pixels the paint turned white: much brighter than before and nearly grey.
        size_t white = 0;
        double sum[3] = {0};
        for (size_t k = 0; k < (size_t)W * H; k++) {
            const unsigned char *a = painted[i] + 3 * k, *b = bare[i] + 3 * k;
            int la = a[0] + a[1] + a[2], lb = b[0] + b[1] + b[2];
            int lo = a[0] < a[1] ? a[0] : a[1], hi = a[0] > a[1] ? a[0] : a[1];
            lo = a[2] < lo ? a[2] : lo, hi = a[2] > hi ? a[2] : hi;
            if (la - lb > 90 && hi - lo < 60) {
                white++;
                for (int c = 0; c < 3; c++)
                    sum[c] += a[c];
            }
        }
        double mean = white ? (sum[0] + sum[1] + sum[2]) / (3.0 * white) : 0;
        printf("%s: %zu pixels turned white, mean %.0f (%.0f, %.0f, %.0f)\n", views[i].name, white,
               mean, white ? sum[0] / white : 0, white ? sum[1] / white : 0,
               white ? sum[2] / white : 0);
        if ((int)white < views[i].min_pixels)
            fail_msg("%s view: only %zu pixels turned white (want >= %d): the paint does not "
                     "show there",
                     views[i].name, white, views[i].min_pixels);
        if (mean < 170)
            fail_msg("%s view: the painted pixels average %.0f, not snow", views[i].name, mean);
        // Nothing else changed: the paint lies where the patch is, not all over the view.
        assert_true(white < (size_t)W * H / 2);
        free(painted[i]);
        free(bare[i]);
    }
    if (!getenv("OROGEN_KEEP_IMAGES")) test_rmtree(dir);
    viewport_destroy(ctx.view_state);
    world_close(w);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paint_shows_far_away),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
