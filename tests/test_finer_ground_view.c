// A coarse clipmap level shades the ground its pixels' rays meet. Its surface, from samples
// 2^L apart, stands off the full-resolution ground, so at a grazing view the place a pixel
// shows on it lies far along the ray from the full-resolution ground there; the shader
// steps each pixel onto the finer heights along its ray (terrain.frag
// toward_finer_ground). The height view colours a pixel by the height it shows (the
// colour ramp's hue; the sun only scales it), so that height is read back from the
// picture and compared with where the pixel's ray meets the world's full-resolution
// samples (renderer/pick.h on world_sample), and so is the sun's light (its brightness)
// with the light on the full-resolution normal there, over the pixels whose ground lies
// on the coarse levels: beyond 1.5 km from 120 m above the ground looking nearly level
// (the step), beyond 2.5 km from 1.5 km up looking 35 degrees down (seen from above, the
// finer slopes' differences half a texel apart: terrain.frag gradient_at).
#include "editor/cmd/commands.h"
#include "editor/params/world_params.h"
#include "editor/world/world.h"
#include "io/image_read.h"
#include "renderer/camera.h"
#include "renderer/lighting.h"
#include "renderer/render_settings.h"
#include "renderer/pick.h"
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

#define W 480
#define H 270

static int full_resolution_height(void *user, double x, double z, double *h) {
    og_error err;
    return world_sample(user, 0, x, z, h, &err);
}

// The height view's colour ramp (resources/shaders/colour_ramp.glsl) at t in [0, 1].
static void ramp(double t, double out[3]) {
    static const double c[5][3] = {
        {0.1, 0.2, 0.7}, {0.1, 0.65, 0.25}, {0.95, 0.85, 0.2}, {0.85, 0.25, 0.1}, {1, 1, 1}};
    t = fmin(fmax(t, 0.0), 1.0);
    int i = t < 0.25 ? 0 : t < 0.5 ? 1 : t < 0.75 ? 2 : 3;
    double f = t * 4.0 - i;
    for (int a = 0; a < 3; a++)
        out[a] = c[i][a] + (c[i + 1][a] - c[i][a]) * f;
}

// The ramp's t whose colour points the way rgb does (the sun scales the colour, not its
// direction).
static double ramp_t_of(const unsigned char *rgb, double *shade) {
    double best = -1, best_t = 0;
    double len = sqrt((double)rgb[0] * rgb[0] + (double)rgb[1] * rgb[1] + (double)rgb[2] * rgb[2]);
    for (int k = 0; k <= 4000; k++) {
        double c[3], t = k / 4000.0;
        ramp(t, c);
        double cos_ = (c[0] * rgb[0] + c[1] * rgb[1] + c[2] * rgb[2]) /
                      (len * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]));
        if (cos_ > best) {
            best = cos_, best_t = t;
            *shade = (c[0] * rgb[0] + c[1] * rgb[1] + c[2] * rgb[2]) /
                     (255.0 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]));
        }
    }
    return best_t;
}

// The mean difference between the sun's light the height view shows and the light on
// the full-resolution normal where each pixel's ray meets the full-resolution ground,
// over the pixels whose ground lies beyond min_dist metres (every second pixel each way),
// from `above` metres over the ground at (x, z) looking along yaw and pitch.
static double far_light_error(cmd_context *ctx, const char *dir, double x, double z, double above,
                              double yaw, double pitch, double min_dist) {
    const world_params *p = world_get_params(ctx->world);
    const double max_height = p->max_height;
    camera c;
    camera_default(&c);
    c.pos[0] = x, c.pos[2] = z;
    double ground;
    og_error err = {{0}};
    if (world_sample(ctx->world, 0, x, z, &ground, &err) != 0) fail_msg("sample: %s", err.msg);
    c.pos[1] = ground + above, c.yaw = yaw, c.pitch = pitch;
    char cmd[8400], path[4200];
    snprintf(path, sizeof path, "%s/height_%g.png", dir, above);
    snprintf(cmd, sizeof cmd, "view height; camera %.17g %.17g %.17g %g %g; screenshot %s %d %d",
             c.pos[0], c.pos[1], c.pos[2], c.yaw, c.pitch, path, W, H);
    test_view_run(ctx, cmd);
    unsigned char *rgb = NULL;
    int w = 0, h = 0;
    if (image_read_rgb8(path, &rgb, &w, &h, &err) != 0) fail_msg("%s: %s", path, err.msg);
    assert_true(w == W && h == H);
    render_settings rs;
    render_settings_default(&rs);
    float sun[3];
    render_sun_direction(&rs, sun);
    double sum = 0, sum_shade = 0;
    int n = 0;
    for (int py = 0; py < H; py += 2)
        for (int px = 0; px < W; px += 2) {
            double ray[3], hit[3];
            camera_ray(&c, (double)W / H, (px + 0.5) / W, (py + 0.5) / H, ray);
            if (pick_ray(full_resolution_height, ctx->world, c.pos, ray, 30000, p->spacing, hit) !=
                0)
                continue;
            if (hypot(hit[0] - c.pos[0], hit[2] - c.pos[2]) < min_dist) continue;
            double shade = 0, shown = ramp_t_of(&rgb[3 * ((size_t)py * W + px)], &shade);
            shown = shown * 2 * max_height - max_height;
            // The light on the full-resolution normal there (central differences a sample
            // apart, as the full-resolution mesh's vertex normals).
            double l, r, d, u, e = p->spacing;
            if (full_resolution_height(ctx->world, hit[0] - e, hit[2], &l) != 0 ||
                full_resolution_height(ctx->world, hit[0] + e, hit[2], &r) != 0 ||
                full_resolution_height(ctx->world, hit[0], hit[2] - e, &d) != 0 ||
                full_resolution_height(ctx->world, hit[0], hit[2] + e, &u) != 0)
                continue;
            double nx = -(r - l) / (2 * e), nz = -(u - d) / (2 * e),
                   len = sqrt(nx * nx + 1 + nz * nz);
            double lit = (nx * sun[0] + sun[1] + nz * sun[2]) / len;
            sum_shade += fabs(shade - (0.55 + 0.45 * fmax(lit, 0.0)));
            sum += fabs(shown - hit[1]);
            n++;
        }
    free(rgb);
    printf("%.0f m up, pitch %g: %d pixels on ground beyond %.0f m: the height shown is off by "
           "%.2f m on average (max_height %.0f m), the sun's light by %.4f\n",
           above, pitch, n, min_dist, sum / n, max_height, sum_shade / n);
    if (n < W * H / 4 / 10) fail_msg("only %d pixels on far ground: the view misses its aim", n);
    return sum_shade / n;
}

static void test_coarse_levels_shade_the_ground_their_rays_meet(void **state) {
    (void)state;
    cmd_context ctx;
    test_view_context_open(&ctx);
    const char *dir = test_tmpdir("finer_ground_view");
    // Nearly level from 120 m: shaded on the coarse surface's place, 0.0203; on the finer
    // ground the ray meets, 0.0150.
    double grazing = far_light_error(&ctx, dir, 2000, 0, 120, 30, -4, 1500);
    if (grazing > 0.018)
        fail_msg("the far ground's light is %.4f off on average: shaded where the ray meets "
                 "the coarse surface, not the finer ground",
                 grazing);
    // From 1.5 km up looking 35 degrees down: the finer slopes' differences a texel apart,
    // 0.0282; half a texel (the mean slope under one), 0.0242.
    double steep = far_light_error(&ctx, dir, 2000, 0, 1500, 30, -35, 2500);
    if (steep > 0.026)
        fail_msg("seen from above, the far ground's light is %.4f off on average: its finer "
                 "slopes are not the mean slope under their texels",
                 steep);
    if (!getenv("OROGEN_KEEP_IMAGES")) test_rmtree(dir);
    test_view_context_close(&ctx);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_coarse_levels_shade_the_ground_their_rays_meet),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
