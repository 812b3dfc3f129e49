// The sea's ripples, seen as a user flies low over open water:
//  - no moire: in three views (toward the horizon from 30 m, toward the sun's glint from
//    300 m, from 100 m), the picture at 320 x 200 matches the same view drawn at 8x the
//    resolution and averaged down (what the eye sees: each pixel the mean of what it
//    covers) within RMSE 2.5. Before, ripples finer than a pixel were point-sampled into
//    rings and speckles toward the horizon: RMSE 3.7, 3.2 and 3.9 (now 1.6, 1.3, 1.3).
//  - the ripples belong to the world: the camera moved 20 m sideways, each far row of the
//    water moves across the picture by the parallax of its distance (+-1.5 px; 35 of 38 rows
//    did). Before, ripples were computed from camera-relative positions and flew with the
//    camera: no row moved.
#include "editor/cmd/commands.h"
#include "editor/world/world.h"
#include "io/image_compare.h"
#include "io/image_read.h"
#include "support/test_support.h"
#include "support/test_view.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

// Renders the view `camera` at w x h and reads it back (caller frees).
static unsigned char *render(cmd_context *ctx, const char *camera, const char *name, int w, int h) {
    char cmd[8400], path[4200];
    snprintf(path, sizeof path, "%s/%s.png", test_folder(), name);
    snprintf(cmd, sizeof cmd, "camera %s; screenshot %s %d %d", camera, path, w, h);
    test_view_run(ctx, cmd);
    unsigned char *rgb = NULL;
    int iw = 0, ih = 0;
    og_error err = {{0}};
    if (image_read_rgb8(path, &rgb, &iw, &ih, &err) != 0) fail_msg("%s: %s", path, err.msg);
    assert_true(iw == w && ih == h);
    return rgb;
}

// Open sea to the horizon everywhere: a flat world 10 m under the water.
static void open_sea(cmd_context *ctx) {
    test_view_run(ctx, "new flat; generator flat; set ocean_level 10; generate");
}

static void test_no_moire(void **state) {
    cmd_context *ctx = *state;
    open_sea(ctx);
    enum { W = 320, H = 200, K = 8 };
    static const char *const views[][2] = {
        {"horizon", "0 30 0 20 -4"}, {"glint", "0 300 0 160 -15"}, {"low", "0 100 0 180 -3"}};
    int failed = 0;
    for (int v = 0; v < 3; v++) {
        char big_name[64];
        snprintf(big_name, sizeof big_name, "%s_%dx", views[v][0], K);
        unsigned char *small = render(ctx, views[v][1], views[v][0], W, H);
        unsigned char *big = render(ctx, views[v][1], big_name, W * K, H * K);
        unsigned char *down = malloc((size_t)W * H * 3);
        assert_non_null(down);
        image_box_down_rgb8(big, W, H, K, down);
        double rmse = image_rmse_rgb8(small, down, (size_t)W * H);
        printf("sea, %s view at %dx%d vs %dx drawn and averaged down: RMSE %.2f (at most 2.5)\n",
               views[v][0], W, H, K, rmse);
        failed += !(rmse <= 2.5);
        free(small), free(big), free(down);
    }
    assert_int_equal(failed, 0);
}

// The horizontal shift (pixels, within +-limit) that best maps row y of a onto row y of b:
// b[x - shift] = a[x], over the middle half of the row.
static int row_shift(const unsigned char *a, const unsigned char *b, int w, int y, int limit) {
    int best = 0;
    double best_ssd = INFINITY;
    for (int s = -limit; s <= limit; s++) {
        double ssd = 0;
        for (int x = w / 4; x < 3 * w / 4; x++)
            for (int c = 0; c < 3; c++) {
                double d = (double)a[3 * (y * w + x) + c] - b[3 * (y * w + x - s) + c];
                ssd += d * d;
            }
        if (ssd < best_ssd) best_ssd = ssd, best = s;
    }
    return best;
}

static void test_ripples_stay_with_the_world(void **state) {
    cmd_context *ctx = *state;
    open_sea(ctx);
    enum { W = 320, H = 200, LIMIT = 30 };
    const double above = 40 - 10, pitch = -30, dx = 20.0; // metres over the water; degrees
    unsigned char *a = render(ctx, "0 40 0 0 -30", "side_a", W, H);
    char view[128];
    snprintf(view, sizeof view, "%.17g 40 0 0 -30", dx);
    unsigned char *b = render(ctx, view, "side_b", W, H);
    // Row y's ray: angle a below the optical axis; it meets the water at depth (along the
    // axis) above cos(a) / sin(a - pitch), where a point moves dx f / depth pixels.
    const double t = tan(30.0 * M_PI / 180.0), f = 0.5 * H / t;
    int rows = 0, followed = 0, still = 0;
    for (int y = 0; y < H; y++) {
        double axis = atan(((y + 0.5) - 0.5 * H) / (0.5 * H) * t);
        double depth = above * cos(axis) / sin(axis - pitch * M_PI / 180.0);
        double expect = dx * f / depth;
        // The far rows, where the ripples show (nearer, the ground under the water shows
        // through and the shift outgrows the search).
        if (expect < 4 || expect > LIMIT - 4) continue;
        int got = row_shift(a, b, W, y, LIMIT);
        rows++;
        followed += fabs(got - expect) <= 1.5;
        still += got == 0;
    }
    printf("camera moved %.0f m sideways: %d of %d water rows moved by their parallax (+-1.5 px), "
           "%d did not move\n",
           dx, followed, rows, still);
    assert_true(rows >= 20);
    assert_true(followed >= rows * 3 / 4);
    free(a), free(b);
}

static int setup(void **state) {
    static cmd_context ctx;
    if (test_folder_setup(state) != 0) return -1;
    test_view_context_open(&ctx);
    *state = &ctx;
    return 0;
}

static int teardown(void **state) {
    test_view_context_close(*state);
    return test_folder_teardown(state);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_moire),
        cmocka_unit_test(test_ripples_stay_with_the_world),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
