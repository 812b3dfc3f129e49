// Ground exactly at the sea's level is under water. A DEM's sea is stored as 0 m, so a
// coastal tile under ocean_level 0 has its whole sea at the water plane's height: the
// ground's equal depth won, and the sea showed as beach sand torn by stripes of water
// from every distance. A flat world at 0 m under ocean_level 0 is rendered from 200 m,
// 1 km and 2.5 km up: no pixel may be ground-coloured (red above blue, as sand and grass
// are; sky and water are blue above red). The same views with the sea 1 m lower show the
// ground, so the count tells the two apart.
#include "editor/cmd/commands.h"
#include "editor/world/world.h"
#include "io/image_read.h"
#include "support/test_support.h"
#include "support/test_view.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#define W 320
#define H 180

typedef struct view {
    const char *name;
    double height, pitch;
} view;

static const view views[] = {{"low", 200, -30}, {"high", 1000, -45}, {"far", 2500, -60}};
enum { VIEWS = sizeof views / sizeof views[0] };

// The share of the picture whose colour is ground's (red at least 10 above blue).
static double ground_share(cmd_context *ctx, const char *dir, const view *v, const char *tag) {
    char cmd[8400], path[4200];
    snprintf(path, sizeof path, "%s/%s_%s.png", dir, v->name, tag);
    snprintf(cmd, sizeof cmd, "camera 300 %g 200 20 %g; screenshot %s %d %d", v->height, v->pitch,
             path, W, H);
    test_view_run(ctx, cmd);
    unsigned char *rgb = NULL;
    int w = 0, h = 0;
    og_error err = {{0}};
    if (image_read_rgb8(path, &rgb, &w, &h, &err) != 0) fail_msg("%s: %s", path, err.msg);
    assert_true(w == W && h == H);
    size_t ground = 0;
    for (size_t k = 0; k < (size_t)W * H; k++)
        ground += rgb[3 * k] >= rgb[3 * k + 2] + 10;
    free(rgb);
    return (double)ground / ((double)W * H);
}

static void test_ground_at_the_sea_level_is_under_water(void **state) {
    (void)state;
    cmd_context ctx;
    test_view_context_open(&ctx);
    const char *dir = test_tmpdir("sea_level_render");
    test_view_run(&ctx,
                  "generator flat; set base_height 0; ocean_level -1; generate; sample 300 200");
    double above[VIEWS];
    for (int i = 0; i < VIEWS; i++)
        above[i] = ground_share(&ctx, dir, &views[i], "sea_below");
    test_view_run(&ctx, "ocean_level 0; generate");
    for (int i = 0; i < VIEWS; i++) {
        double under = ground_share(&ctx, dir, &views[i], "sea_at");
        printf("%s: ground-coloured %.1f%% with the sea 1 m below, %.3f%% with it at the "
               "ground\n",
               views[i].name, 100 * above[i], 100 * under);
        if (above[i] < 0.3)
            fail_msg("%s view: with the sea 1 m below, only %.1f%% of the picture is ground: the "
                     "detector cannot tell",
                     views[i].name, 100 * above[i]);
        if (under > 0.001)
            fail_msg("%s view: %.2f%% of the picture shows ground that lies at the sea's level "
                     "(it must be under water)",
                     views[i].name, 100 * under);
    }
    if (!getenv("OROGEN_KEEP_IMAGES")) test_rmtree(dir);
    test_view_context_close(&ctx);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ground_at_the_sea_level_is_under_water),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
