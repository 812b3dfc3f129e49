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
#include "renderer/planet_camera.h"
#include "renderer/terrain_renderer.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "support/planet_view.h"

#include "support/test_world.h"

#define W 240
#define H 135

static planet_view view;
static camera cam;

static int setup(void **state) {
    (void)state;
    return planet_view_open(&view, W, H, "test_mask_overlay");
}

static int teardown(void **state) {
    (void)state;
    planet_view_close(&view);
    return 0;
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
    const double radius = world_get_params(view.earth)->radius;
    camera_default(&cam);
    planet_position(21.0, 5.7, radius + 1e5, cam.pos);
    cam.yaw = 0, cam.pitch = -25;
    render_settings s;
    render_settings_default(&s);
    planet_view_draw(&view, view.earth, &cam, &s, plain, pos, NULL);
    for (int i = 0; i < W * H; i++)
        height[i] =
            sqrt(pos[i][0] * pos[i][0] + pos[i][1] * pos[i][1] + pos[i][2] * pos[i][2]) - radius;
    const double sea = world_params_ocean_height(world_get_params(view.earth));
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
        planet_view_draw(&view, view.earth, &cam, &m, masked, NULL,
                         NULL); // the same pose: only the overlay differs
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
        planet_view_draw(&view, view.earth, &cam, &m, masked, NULL, NULL);
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
    planet_view_draw(&view, view.earth, &cam, &none, masked, NULL, NULL);
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
    planet_view_draw(&view, w, &cam, &s, plain, pos, NULL);
    render_settings m = s;
    m.mask_terms = 8;
    set_term(m.mask_flow, lo, 1e30, 0);
    m.mask_flow_area = field.area, m.mask_flow_w = field.w, m.mask_flow_h = field.h;
    m.mask_flow_x0 = field.x0, m.mask_flow_z0 = field.z0, m.mask_flow_spacing = field.spacing;
    m.mask_flow_serial = 1;
    planet_view_draw(&view, w, &cam, &m, masked, NULL, NULL);
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
