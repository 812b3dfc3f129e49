// The viewport's navigation (app/camera_controls.c) without a window: mouse look and
// orbit directions, fly and walk movement for held keys, the wheel's speed and dolly
// steps, focus and the walk toggle, against analytic ground.
#include "app/camera_controls.h"

#include <math.h>
#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

static void assert_near(double a, double b, double tol) {
    if (!(fabs(a - b) <= tol)) fail_msg("%.12g != %.12g within %g", a, b, tol);
}

static double dist3(const double a[3], const double b[3]) {
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

// Ground rising 0.1 m per metre east, known only for x < 1000.
static int slope_ground(void *user, double x, double z, double *h) {
    (void)z;
    int *calls = user;
    if (calls) ++*calls;
    if (x >= 1000) return -1;
    *h = 0.1 * x + 5;
    return 0;
}

static camera cam_at(double x, double y, double z, double yaw, double pitch) {
    camera c;
    camera_default(&c);
    c.pos[0] = x, c.pos[1] = y, c.pos[2] = z;
    c.yaw = yaw, c.pitch = pitch;
    return c;
}

static void test_look(void **state) {
    (void)state;
    camera_controls cc;
    camera_controls_init(&cc);
    camera c = cam_at(0, 10, 0, 0, 0);
    camera_controls_look(&cc, &c, 50, 0); // mouse right: turn right
    assert_near(c.yaw, 50 * cc.look_deg_per_px, 1e-9);
    camera_controls_look(&cc, &c, 0, 25); // mouse down: look down
    assert_near(c.pitch, -25 * cc.look_deg_per_px, 1e-9);
    camera_controls_look(&cc, &c, -50, -25);
    assert_near(c.yaw, 0, 1e-9);
    assert_near(c.pitch, 0, 1e-9);
    camera_controls_look(&cc, &c, 0, 100000); // clamped
    assert_near(c.pitch, -CAMERA_PITCH_LIMIT, 1e-9);
    assert_near(c.pos[1], 10, 0); // looking never moves
}

static void test_orbit(void **state) {
    (void)state;
    camera_controls cc;
    camera_controls_init(&cc);
    // 100 m south of the pivot, level with it, looking north at it.
    double pivot[3] = {0, 0, 0};
    camera c = cam_at(0, 0, 100, 0, 0);
    camera_controls_orbit(&cc, &c, pivot, 0, -100); // drag up: camera rises over the pivot
    assert_near(dist3(c.pos, pivot), 100, 1e-6);
    assert_true(c.pos[1] > 0);
    assert_near(c.pitch, -100 * cc.orbit_deg_per_px, 1e-6); // looking down at it
    camera d = cam_at(0, 0, 100, 0, 0);
    camera_controls_orbit(&cc, &d, pivot, 0, 100); // drag down: below
    assert_true(d.pos[1] < 0);
    // Drag right: the view turns right and the camera goes to its left (west).
    camera e = cam_at(0, 0, 100, 0, 0);
    camera_controls_orbit(&cc, &e, pivot, 300, 0);
    assert_near(e.yaw, 90, 1e-6);
    assert_near(e.pos[0], -100, 1e-6);
    assert_near(e.pos[2], 0, 1e-6);
    assert_near(dist3(e.pos, pivot), 100, 1e-6);
    // The pivot stays in the centre of the view after any drag.
    camera_controls_orbit(&cc, &e, pivot, 37, -21);
    double f[3];
    camera_forward(&e, f);
    double back[3] = {e.pos[0] + 100 * f[0], e.pos[1] + 100 * f[1], e.pos[2] + 100 * f[2]};
    assert_true(dist3(back, pivot) < 1e-6);
}

static void test_fly(void **state) {
    (void)state;
    camera_controls cc;
    camera_controls_init(&cc);
    camera c = cam_at(0, 100, 0, 90, 0); // looking east
    move_keys none = {0};
    assert_int_equal(camera_controls_move(&cc, &c, &none, slope_ground, NULL), 0);
    move_keys w = {.forward = 0.5}; // W held for half a second
    assert_int_equal(camera_controls_move(&cc, &c, &w, slope_ground, NULL), 1);
    assert_near(c.pos[0], 0.5 * cc.fly_speed, 1e-9); // m/s x s
    assert_near(c.pos[1], 100, 1e-9);                // flying ignores the ground
    move_keys sd = {.back = 1, .right = 1, .fast = 1};
    c = cam_at(0, 100, 0, 0, 0);
    camera_controls_move(&cc, &c, &sd, NULL, NULL);
    assert_near(c.pos[0], cc.fly_speed * cc.fast_factor, 1e-9); // right = east at yaw 0
    assert_near(c.pos[2], cc.fly_speed * cc.fast_factor, 1e-9); // back = south
    move_keys e = {.up = 0.1};
    c = cam_at(0, 100, 0, 0, -60); // up is world up whatever the pitch
    camera_controls_move(&cc, &c, &e, NULL, NULL);
    assert_near(c.pos[1], 100 + 0.1 * cc.fly_speed, 1e-9);
    // Opposite keys cancel for the time both were held.
    move_keys ws = {.forward = 1, .back = 0.25};
    c = cam_at(0, 100, 0, 90, 0);
    camera_controls_move(&cc, &c, &ws, NULL, NULL);
    assert_near(c.pos[0], 0.75 * cc.fly_speed, 1e-9);
    // Forward follows the view down.
    move_keys w1 = {.forward = 1};
    c = cam_at(0, 100, 0, 0, -90);
    camera_controls_move(&cc, &c, &w1, NULL, NULL);
    assert_true(c.pos[1] < 100 - 0.99 * cc.fly_speed);
}

static void test_walk(void **state) {
    (void)state;
    camera_controls cc;
    camera_controls_init(&cc);
    camera c = cam_at(100, 500, 0, 90, -45); // east, looking down
    assert_int_equal(camera_controls_toggle_walk(&cc, &c, slope_ground, NULL), 1);
    assert_near(c.pos[1], 0.1 * 100 + 5 + 1.8, 1e-9); // seated at once
    move_keys w = {.forward = 2};
    camera_controls_move(&cc, &c, &w, slope_ground, NULL);
    // Horizontal: the full walk speed east although the view looks down.
    assert_near(c.pos[0], 100 + 2 * cc.walk_speed, 1e-9);
    assert_near(c.pos[2], 0, 1e-9);
    assert_near(c.pos[1], 0.1 * c.pos[0] + 5 + 1.8, 1e-9);
    // Diagonals are no faster.
    camera d = c;
    move_keys wd = {.forward = 1, .left = 1};
    camera_controls_move(&cc, &d, &wd, slope_ground, NULL);
    double h = hypot(d.pos[0] - c.pos[0], d.pos[2] - c.pos[2]);
    assert_near(h, cc.walk_speed, 1e-9);
    assert_true(d.pos[2] < c.pos[2]); // left of east is north (-Z)
    // Held nothing: the eye still follows the ground (it may have been sculpted).
    c.pos[1] = 0;
    move_keys none = {0};
    assert_int_equal(camera_controls_move(&cc, &c, &none, slope_ground, NULL), 1);
    assert_near(c.pos[1], 0.1 * c.pos[0] + 5 + 1.8, 1e-9);
    // No step onto unknown ground.
    c = cam_at(995, 0, 0, 90, 0);
    move_keys far = {.forward = 10};
    camera_controls_move(&cc, &c, &far, slope_ground, NULL);
    assert_near(c.pos[0], 995, 0);
    assert_near(c.pos[1], 99.5 + 5 + 1.8, 1e-9);
    assert_int_equal(camera_controls_toggle_walk(&cc, &c, slope_ground, NULL), 0);
    // Toggling on over unknown ground keeps the camera where it is.
    c = cam_at(2000, 50, 0, 0, 0);
    camera_controls_toggle_walk(&cc, &c, slope_ground, NULL);
    assert_near(c.pos[1], 50, 0);
}

static void test_wheel(void **state) {
    (void)state;
    camera_controls cc;
    camera_controls_init(&cc);
    double s = cc.fly_speed;
    camera_controls_speed_wheel(&cc, 1);
    assert_near(cc.fly_speed, s * 1.25, 1e-12);
    camera_controls_speed_wheel(&cc, -2);
    assert_near(cc.fly_speed, s / 1.25, 1e-12);
    camera_controls_speed_wheel(&cc, -1000);
    assert_near(cc.fly_speed, 0.01, 0);
    cc.walk = 1;
    double ws = cc.walk_speed;
    camera_controls_speed_wheel(&cc, 1);
    assert_near(cc.walk_speed, ws * 1.25, 1e-12); // the walking speed, separately
    assert_near(cc.fly_speed, 0.01, 0);
    assert_near(camera_controls_speed(&cc), ws * 1.25, 1e-12);

    double pivot[3] = {0, 0, 0};
    camera c = cam_at(0, 30, 40, 0, 0);
    camera_controls_dolly(&cc, &c, pivot, 1); // toward
    assert_near(dist3(c.pos, pivot), 50 * 0.8, 1e-9);
    camera_controls_dolly(&cc, &c, pivot, -2); // away
    assert_near(dist3(c.pos, pivot), 50 / 0.8, 1e-9);
    assert_near(c.pos[1] / c.pos[2], 30.0 / 40.0, 1e-12); // along the same line
}

static void test_focus(void **state) {
    (void)state;
    camera_controls cc;
    camera_controls_init(&cc);
    cc.walk = 1;
    camera c = cam_at(0, 100, 0, 45, -30);
    double p[3] = {500, 20, -300};
    camera_controls_focus(&cc, &c, p, 20);
    assert_int_equal(cc.walk, 0);
    assert_near(dist3(c.pos, p), 60, 1e-9);
    assert_near(c.yaw, 45, 0);
    assert_near(c.pitch, -30, 0);
    camera_controls_focus(&cc, &c, p, 1); // a tiny brush still leaves room
    assert_near(dist3(c.pos, p), 10, 1e-9);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_look), cmocka_unit_test(test_orbit), cmocka_unit_test(test_fly),
        cmocka_unit_test(test_walk), cmocka_unit_test(test_wheel), cmocka_unit_test(test_focus),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
