// A new planet opens with the whole disc lit in view (issue 29), for every preset, through
// the command a user types (`new planet preset=NAME`, which File > New planet... sends),
// in a wide view and in a view taller than wide:
//  - the disc's outline lies inside the frame: no pixel of the frame's border sees the
//    planet (its radius plus its highest peak) and those pixels are drawn as space;
//  - the disc is large: at least MIN_DISC of the frame;
//  - the disc is lit: at least MIN_LIT of the pixels whose ray meets the sphere are
//    brighter than LIT_LUMINANCE (the night side draws below 10).
// The first view before (half a radius up, oblique, the limb across the top) failed the
// first measure on every preset: the ground ran off the bottom and both sides.
#include "editor/cmd/commands.h"
#include "editor/params/planet_presets.h"
#include "editor/params/world_params.h"
#include "editor/world/world.h"
#include "io/image_read.h"
#include "renderer/planet_camera.h"
#include "support/test_support.h"
#include "support/test_view.h"
#include "view/view_commands.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#define MIN_DISC 0.2
#define MIN_LIT 0.9
#define LIT_LUMINANCE 30.0
#define SPACE_LUMINANCE 12.0

// Distance along the unit ray from pos to the sphere of radius r, or -1 when it misses.
static double ray_sphere(const double pos[3], const double dir[3], double r) {
    const double b = pos[0] * dir[0] + pos[1] * dir[1] + pos[2] * dir[2];
    const double c = pos[0] * pos[0] + pos[1] * pos[1] + pos[2] * pos[2] - r * r;
    const double disc = b * b - c;
    if (disc < 0) return -1;
    const double t = -b - sqrt(disc);
    return t > 0 ? t : -1;
}

static double luminance(const unsigned char *p) {
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

typedef struct first_view {
    int border_on_planet; // border pixels whose ray meets the planet
    int border_drawn;     // border pixels drawn brighter than space
    int disc, lit;        // pixels whose ray meets the datum sphere; of them, lit
} first_view;

static first_view measure(const camera *c, const world_params *p, const unsigned char *rgb, int W,
                          int H) {
    first_view m = {0};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double dir[3];
            planet_camera_ray(c, (double)W / H, (x + 0.5) / W, (y + 0.5) / H, dir);
            const unsigned char *px = rgb + 3 * (y * W + x);
            if (x == 0 || y == 0 || x == W - 1 || y == H - 1) {
                m.border_on_planet += ray_sphere(c->pos, dir, p->radius + p->max_height) > 0;
                m.border_drawn += luminance(px) > SPACE_LUMINANCE;
            }
            if (ray_sphere(c->pos, dir, p->radius) > 0) {
                m.disc++;
                m.lit += luminance(px) > LIT_LUMINANCE;
            }
        }
    return m;
}

static void test_new_planet_shows_the_lit_disc(void **state) {
    (void)state;
    og_error err = {{0}};
    cmd_context ctx;
    test_view_context_open(&ctx);
    const char *dir = test_tmpdir("planet_first_view");
    int failed = 0;
    // Every preset wide, then the first one tall.
    for (size_t k = 0; k <= planet_preset_count(); k++) {
        const size_t i = k % planet_preset_count();
        const int W = k < planet_preset_count() ? 320 : 144, H = 180;
        const char *name = planet_preset_name(i);
        char cmd[8400], path[4200];
        snprintf(path, sizeof path, "%s/%s_%dx%d.png", dir, name, W, H);
        // The flat world's camera first: the planet must not keep it.
        snprintf(cmd, sizeof cmd,
                 "camera 400 -50 600 30 -25; new planet preset=%s; screenshot %s %d %d", name, path,
                 W, H);
        test_view_run(&ctx, cmd);
        unsigned char *rgb = NULL;
        int iw = 0, ih = 0;
        if (image_read_rgb8(path, &rgb, &iw, &ih, &err) != 0) fail_msg("%s: %s", path, err.msg);
        assert_int_equal(iw, W);
        assert_int_equal(ih, H);
        const camera cam = view_commands_viewport(&ctx)->cam;
        const first_view m = measure(&cam, world_get_params(ctx.world), rgb, W, H);
        const double disc = (double)m.disc / (W * H), lit = m.disc ? (double)m.lit / m.disc : 0;
        const int ok =
            m.border_on_planet == 0 && m.border_drawn == 0 && disc >= MIN_DISC && lit >= MIN_LIT;
        printf("%-9s %dx%d: border pixels on the planet %d, drawn %d; disc %.0f%% of the frame "
               "(>= %.0f%%), lit %.1f%% (>= %.0f%%)%s\n",
               name, W, H, m.border_on_planet, m.border_drawn, 100 * disc, 100 * MIN_DISC,
               100 * lit, 100 * MIN_LIT, ok ? "" : "  FAIL");
        fflush(stdout);
        failed += !ok;
        free(rgb);
    }
    if (!failed && !getenv("OROGEN_KEEP_IMAGES")) test_rmtree(dir);
    test_view_context_close(&ctx);
    assert_int_equal(failed, 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_new_planet_shows_the_lit_disc),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
