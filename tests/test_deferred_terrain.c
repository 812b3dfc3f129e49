// The shaded flat terrain is shaded in a deferred pass (renderer/deferred_target.h): what
// that pass must keep from drawing the triangles directly. The brush cursor's ring, drawn
// from how its distance changes across the screen, stays on its circle: neighbouring
// pixels across a silhouette or in the sky are not the ground's neighbours (the ring
// showed as dashes along ridges when the screen derivatives were taken across them).
// And the frame's depth is the ground's: what is drawn after the terrain meets it.
#include "renderer/camera.h"
#include "renderer/gl_context.h"
#include "renderer/gl_target.h"
#include "renderer/terrain_renderer.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdlib.h>
#include <time.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "support/test_world.h"

#define W 240
#define H 135

static struct {
    gl_headless *ctx;
    gl_target target;
    terrain_renderer *r;
    world *w;
} S;

static int setup(void **state) {
    (void)state;
    og_error err = {{0}};
    if (!(S.ctx = gl_headless_create(&err)) || gl_require_features(&err) != 0 ||
        gl_target_create(&S.target, W, H, &err) != 0 ||
        !(S.r = terrain_renderer_create(OROGEN_RESOURCE_DIR, &err))) {
        print_error("test_deferred_terrain: %s\n", err.msg);
        return -1;
    }
    terrain_renderer_set_view_size(S.r, W, H);
    world_params p = test_flat_fbm_params(0);
    S.w = test_world_open(&p);
    return 0;
}

static int teardown(void **state) {
    (void)state;
    world_close(S.w);
    terrain_renderer_destroy(S.r);
    gl_target_destroy(&S.target);
    gl_headless_destroy(S.ctx);
    return 0;
}

// Low over the ground looking across it: ridges against farther ground and the sky.
static camera low_camera(void) {
    camera c;
    camera_default(&c);
    double h = 0;
    og_error err;
    assert_int_equal(world_sample(S.w, 0, 40, 60, &h, &err), 0);
    c.pos[0] = 40, c.pos[2] = 60, c.pos[1] = h + 25;
    c.yaw = 20, c.pitch = -6;
    return c;
}

// Draws once every tile is there; rgb (top row first) and depth (bottom row first).
static void draw(const camera *c, const brush_cursor *cursor, unsigned char *rgb, float *depth) {
    og_error err = {{0}};
    render_settings s;
    render_settings_default(&s);
    s.antialias = 0;
    int rc;
    for (int i = 0; (rc = terrain_renderer_update(S.r, S.w, c, &s, &err)) == 0 && i < 60000; i++) {
        struct timespec nap = {0, 1000000};
        nanosleep(&nap, NULL);
    }
    assert_int_equal(rc, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, S.target.fbo);
    assert_int_equal(terrain_renderer_draw(S.r, S.w, c, &s, cursor, W, H, &err), 0);
    assert_int_equal(gl_target_read_rgb(&S.target, rgb, &err), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, S.target.fbo);
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
}

// The ground pixel (x, y) (top row first) shows, from its depth; 0 for the sky.
static int ground_of(const camera *c, const float *depth, int x, int y, double out[3]) {
    const float d = depth[(H - 1 - y) * W + x];
    if (!(d > 0)) return 0;
    float m[16];
    camera_view_projection(c, (double)W / H, m);
    // Solve view_proj * (p, 1) ~ (ndc, d, 1) for p by the matrix's rows (camera-relative).
    const double ndc[3] = {(x + 0.5) / W * 2 - 1, 1 - (y + 0.5) / H * 2, d};
    double a[3][4];
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 4; k++)
            a[r][k] = m[k * 4 + r] - ndc[r] * m[k * 4 + 3];
    // Cramer's rule on a[r][0..2] p = -a[r][3].
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                 a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    for (int i = 0; i < 3; i++) {
        double b[3][3];
        for (int r = 0; r < 3; r++)
            for (int k = 0; k < 3; k++)
                b[r][k] = k == i ? -a[r][3] : a[r][k];
        double di = b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) -
                    b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) +
                    b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]);
        out[i] = di / det + c->pos[i];
    }
    return 1;
}

static void test_cursor_ring_stays_on_its_circle(void **state) {
    (void)state;
    camera c = low_camera();
    unsigned char *plain = malloc(W * H * 3), *with = malloc(W * H * 3);
    float *depth = malloc(sizeof(float) * W * H);
    assert_non_null(plain), assert_non_null(with), assert_non_null(depth);
    draw(&c, NULL, plain, depth);
    // A cursor on the ground seen in the middle of the view, a few pixels wide.
    double centre[3];
    assert_true(ground_of(&c, depth, W / 2, H * 2 / 3, centre));
    brush_cursor cursor = {.visible = 1, .x = centre[0], .z = centre[2], .radius = 6};
    for (int i = 0; i < BRUSH_FALLOFF_SAMPLES; i++)
        cursor.falloff[i] = 1.0f - (float)i / (BRUSH_FALLOFF_SAMPLES - 1);
    draw(&c, &cursor, with, depth);
    int inside = 0, outside = 0, ridges = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double p[3];
            int ground = ground_of(&c, depth, x, y, p);
            // A silhouette: the pixel below is much nearer than this one.
            if (ground && y + 1 < H) {
                double q[3];
                if (!ground_of(&c, depth, x, y + 1, q) ||
                    hypot(q[0] - c.pos[0], q[2] - c.pos[2]) <
                        0.8 * hypot(p[0] - c.pos[0], p[2] - c.pos[2]))
                    ridges++;
            }
            int differs = 0;
            for (int k = 0; k < 3; k++)
                differs |= abs(plain[(y * W + x) * 3 + k] - with[(y * W + x) * 3 + k]) > 2;
            if (!differs) continue;
            // The ring is a pixel or two wide: within a few metres of the circle here.
            double r = ground ? hypot(p[0] - cursor.x, p[2] - cursor.z) : INFINITY;
            if (r < cursor.radius * 1.5 + 1.0)
                inside++;
            else {
                outside++;
                print_message("  changed off the disc: pixel %d %d, %.0f m from its centre\n", x, y,
                              r);
            }
        }
    print_message("cursor: %d pixels changed on its disc, %d elsewhere; %d silhouette pixels\n",
                  inside, outside, ridges);
    assert_true(ridges > 20); // the view has silhouettes the ring could run along
    assert_true(inside > 10);
    assert_int_equal(outside, 0);
    free(plain), free(with), free(depth);
}

// The depth the frame keeps is the ground's: each pixel's depth puts it on the ground
// (the height there within a few centimetres per 100 m of distance), the sky at 0.
static void test_frame_depth_is_the_grounds(void **state) {
    (void)state;
    camera c = low_camera();
    unsigned char *rgb = malloc(W * H * 3);
    float *depth = malloc(sizeof(float) * W * H);
    assert_non_null(rgb), assert_non_null(depth);
    draw(&c, NULL, rgb, depth);
    int ground = 0, sky = 0, checked = 0;
    double worst = 0;
    for (int y = 0; y < H; y += 3)
        for (int x = 0; x < W; x += 3) {
            double p[3], h;
            og_error err;
            if (!ground_of(&c, depth, x, y, p)) {
                sky++;
                continue;
            }
            ground++;
            double dist = hypot(p[0] - c.pos[0], p[2] - c.pos[2]);
            if (dist > 400 || world_sample(S.w, 0, p[0], p[2], &h, &err) != 0) continue;
            // The clipmap's triangles are within a sample or so of the samples' heights.
            worst = fmax(worst, fabs(p[1] - h) / (1.0 + dist / 50.0));
            checked++;
        }
    print_message("depth: %d ground, %d sky pixels; %d checked, worst %.3f m per (1 + d/50 m)\n",
                  ground, sky, checked, worst);
    assert_true(ground > 100), assert_true(sky > 100), assert_true(checked > 100);
    assert_true(worst < 1.0);
    free(rgb), free(depth);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cursor_ring_stays_on_its_circle),
        cmocka_unit_test(test_frame_depth_is_the_grounds),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
