// The mask editor's live overlay (render_settings.h mask_*). On a planet (planet.frag),
// over the Earth-like preset's ranges from 100 km, drawn once without and once with a
// mask term, each pixel's change is compared with the height above the datum of the
// ground it shows (from the depth buffer):
//  - height=LO,inf: land above LO (by a margin) is tinted (redder, less green), land
//    below it dimmed; invert swaps the two;
//  - curvature: the ground tinted as convex lies higher on average than the ground
//    tinted as concave (ridges over valleys), which fails when the curvature's sign or
//    axes are wrong;
//  - with no term set the picture is the same as without the overlay.
// On a flat world (terrain.frag) the flow term over the field the mask editor reads
// (terrain_histogram_compute_flow): the ground tinted is where the field's upstream area
// lies in the range, pixel for pixel; ground beyond the field is left as it was.
#include "editor/params/planet_presets.h"
#include "editor/world/terrain_histogram.h"
#include "editor/world/world.h"
#include "renderer/camera.h"
#include "renderer/gl_context.h"
#include "renderer/gl_target.h"
#include "renderer/planet_camera.h"
#include "renderer/terrain_renderer.h"

#include <epoxy/gl.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <cmocka.h>

#include "support/test_world.h"

#define W 240
#define H 135

static gl_headless *ctx;
static gl_target target;
static terrain_renderer *renderer;
static world *earth;
static camera cam;

static int setup(void **state) {
    (void)state;
    og_error err = {{0}};
    if (!(ctx = gl_headless_create(&err)) || gl_require_features(&err) != 0 ||
        gl_target_create(&target, W, H, &err) != 0 ||
        !(renderer = terrain_renderer_create(OROGEN_RESOURCE_DIR, &err))) {
        fprintf(stderr, "test_mask_overlay: %s\n", err.msg);
        return -1;
    }
    terrain_renderer_set_view_size(renderer, W, H);
    world_params wp;
    world_params_default(&wp, WORLD_PLANET);
    if (planet_preset_apply(&wp, "earth", &err) != 0) return -1;
    world_settings ws = {.cache_budget_bytes = (size_t)1 << 30, .workers = 2, .warn = test_silent};
    return (earth = world_create(&wp, &ws, &err)) ? 0 : -1;
}

static int teardown(void **state) {
    (void)state;
    world_close(earth);
    terrain_renderer_destroy(renderer);
    gl_target_destroy(&target);
    gl_headless_destroy(ctx);
    return 0;
}

static double now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

// Draws w with s once every tile wanted is there; the colours, and (when pos is not
// NULL) the position each pixel shows (x, y, z; NAN: sky).
static void render(world *w, const render_settings *s, unsigned char *rgb, double (*pos)[3]) {
    og_error err = {{0}};
    const double t0 = now_s();
    int rc;
    while ((rc = terrain_renderer_update(renderer, w, &cam, s, &err)) == 0 && now_s() - t0 < 60) {
        struct timespec nap = {0, 1000000};
        nanosleep(&nap, NULL);
    }
    assert_true(rc >= 0);
    glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
    assert_int_equal(terrain_renderer_draw(renderer, w, &cam, s, NULL, W, H, &err), 0);
    assert_int_equal(gl_target_read_rgb(&target, rgb, &err), 0); // top row first
    if (!pos) return;
    static float depth[W * H];
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, depth); // bottom row first
    double f[3], rt[3], up[3];
    if (world_get_params(w)->kind == WORLD_PLANET)
        planet_camera_basis(&cam, f, rt, up);
    else
        camera_forward(&cam, f), camera_right(&cam, rt), camera_up(&cam, up);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float d = depth[(H - 1 - y) * W + x]; // reversed z: 0 is infinitely far
            double dir[3], *p = pos[y * W + x];
            p[0] = p[1] = p[2] = NAN;
            if (!(d > 0.0f)) continue;
            camera_basis_ray(&cam, rt, up, f, (double)W / H, (x + 0.5) / W, (y + 0.5) / H, dir);
            const double along = cam.near_m / d / (dir[0] * f[0] + dir[1] * f[1] + dir[2] * f[2]);
            for (int a = 0; a < 3; a++)
                p[a] = cam.pos[a] + dir[a] * along;
        }
}

// Tinted: the overlay's pink raised red over green against the plain picture.
static int tinted(const unsigned char *plain, const unsigned char *masked) {
    return (masked[0] - masked[1]) - (plain[0] - plain[1]) > 12;
}

static void set_term(float t[4], double lo, double hi, double edge) {
    t[0] = (float)(lo - edge), t[1] = (float)lo, t[2] = (float)hi, t[3] = (float)(hi + edge);
}

static int by_value(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}
static int by_float(const void *a, const void *b) {
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static void test_planet_overlay(void **state) {
    (void)state;
    static unsigned char plain[W * H * 3], masked[W * H * 3];
    static double pos[W * H][3], height[W * H], land[W * H];
    // Over the big continent's ranges (seed 1337), looking north, 100 km up.
    const double radius = world_get_params(earth)->radius;
    camera_default(&cam);
    planet_position(21.0, 5.7, radius + 1e5, cam.pos);
    cam.yaw = 0, cam.pitch = -25;
    render_settings s;
    render_settings_default(&s);
    render(earth, &s, plain, pos);
    for (int i = 0; i < W * H; i++)
        height[i] =
            sqrt(pos[i][0] * pos[i][0] + pos[i][1] * pos[i][1] + pos[i][2] * pos[i][2]) - radius;
    const double sea = world_params_ocean_height(world_get_params(earth));
    int n = 0;
    for (int i = 0; i < W * H; i++)
        if (height[i] > sea + 20) land[n++] = height[i];
    assert_true(n > W * H / 10);
    qsort(land, (size_t)n, sizeof land[0], by_value);
    const double lo = land[n / 2], margin = 0.05 * (land[n - 1] - land[0]) + 30;

    for (int invert = 0; invert <= 1; invert++) {
        render_settings m = s;
        m.mask_terms = 1, m.mask_invert = invert;
        set_term(m.mask_height, lo, 1e30, 0);
        render(earth, &m, masked, NULL); // the same pose: only the overlay differs
        int agree = 0, counted = 0;
        for (int i = 0; i < W * H; i++) {
            if (!(height[i] > sea + 20) || fabs(height[i] - lo) < margin) continue;
            const int in = (height[i] > lo) != invert;
            agree += tinted(plain + 3 * i, masked + 3 * i) == in;
            counted++;
        }
        printf("height=%.0f,inf invert=%d: %d of %d land pixels agree with their height\n", lo,
               invert, agree, counted);
        assert_true(counted > n / 4);
        assert_true(agree >= counted * 0.9);
    }

    // Convex ground (ridges) lies higher than concave (valleys).
    double mean[2] = {0, 0};
    int count[2] = {0, 0};
    for (int k = 0; k < 2; k++) {
        render_settings m = s;
        m.mask_terms = 4;
        set_term(m.mask_curvature, k == 0 ? 0.002 : -1e30, k == 0 ? 1e30 : -0.002, 0);
        render(earth, &m, masked, NULL);
        for (int i = 0; i < W * H; i++)
            if (height[i] > sea + 20 && tinted(plain + 3 * i, masked + 3 * i))
                mean[k] += height[i], count[k]++;
        mean[k] /= count[k] > 0 ? count[k] : 1;
    }
    printf("convex: %d pixels, mean height %.0f m; concave: %d pixels, %.0f m\n", count[0], mean[0],
           count[1], mean[1]);
    assert_true(count[0] > n / 20 && count[1] > n / 20);
    assert_true(mean[0] > mean[1]);

    // No term: the overlay draws nothing.
    render_settings none = s;
    none.mask_terms = 0;
    render(earth, &none, masked, NULL);
    assert_memory_equal(plain, masked, sizeof plain);
}

static void test_flat_flow(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(512);
    world *w = test_world_open(&p);
    terrain_histogram h;
    terrain_flow_field field = {0};
    og_error err;
    assert_int_equal(terrain_histogram_compute_flow(w, 0, 256, 256, 250, &h, &field, &err), 0);
    const int n = field.w * field.h;
    float *sorted = malloc((size_t)n * sizeof *sorted);
    memcpy(sorted, field.area, (size_t)n * sizeof *sorted);
    qsort(sorted, (size_t)n, sizeof *sorted, by_float);
    const double lo = sorted[n * 9 / 10]; // the channels: the top tenth of the areas
    free(sorted);
    camera_default(&cam); // straight down over the middle
    cam.pos[0] = 256, cam.pos[1] = 500, cam.pos[2] = 256;
    cam.yaw = 0, cam.pitch = -89;
    static unsigned char plain[W * H * 3], masked[W * H * 3];
    static double pos[W * H][3];
    render_settings s;
    render_settings_default(&s);
    render(w, &s, plain, pos);
    render_settings m = s;
    m.mask_terms = 8;
    set_term(m.mask_flow, lo, 1e30, 0);
    m.mask_flow_area = field.area, m.mask_flow_w = field.w, m.mask_flow_h = field.h;
    m.mask_flow_x0 = field.x0, m.mask_flow_z0 = field.z0, m.mask_flow_spacing = field.spacing;
    m.mask_flow_serial = 1;
    render(w, &m, masked, NULL);
    int agree[2] = {0, 0}, counted[2] = {0, 0}; // out of the range, in it
    int beyond = 0, beyond_same = 0;            // ground the field does not reach
    for (int i = 0; i < W * H; i++) {
        if (!isfinite(pos[i][0])) continue;
        // Where the four samples around the point agree (the shader interpolates).
        double fx = (pos[i][0] - field.x0) / field.spacing,
               fz = (pos[i][2] - field.z0) / field.spacing;
        int x = (int)floor(fx), z = (int)floor(fz), ins = 0;
        if (fx < -1 || fz < -1 || fx > field.w || fz > field.h) { // beyond: as it was
            beyond++;
            beyond_same += !memcmp(plain + 3 * i, masked + 3 * i, 3);
        }
        if (x < 0 || z < 0 || x + 1 >= field.w || z + 1 >= field.h) continue;
        for (int k = 0; k < 4; k++)
            ins += field.area[(z + k / 2) * field.w + x + k % 2] >= lo;
        if (ins != 0 && ins != 4) continue;
        agree[ins == 4] += tinted(plain + 3 * i, masked + 3 * i) == (ins == 4);
        counted[ins == 4]++;
    }
    printf("flow=%.0f,inf: tinted %d of %d pixels in the range, untinted %d of %d outside\n", lo,
           agree[1], counted[1], agree[0], counted[0]);
    assert_true(counted[0] > W * H / 3 && counted[1] > counted[0] / 50);
    assert_true(agree[0] >= counted[0] * 0.97 && agree[1] >= counted[1] * 0.9);
    printf("beyond the field: %d of %d pixels as without the overlay\n", beyond_same, beyond);
    assert_true(beyond > 0 && beyond_same == beyond);
    terrain_flow_field_free(&field);
    world_close(w);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_planet_overlay),
                                       cmocka_unit_test(test_flat_flow)};
    return cmocka_run_group_tests(tests, setup, teardown);
}
