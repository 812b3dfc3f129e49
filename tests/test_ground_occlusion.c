// Occlusion by nearer ground (renderer/ground_occlusion.h): a solid under the ground
// hides what lies behind it on the screen and farther away, and nothing else: not what
// rises above it, not what is nearer, not what is beside it, and nothing when a point
// is behind the camera.
#include "renderer/ground_occlusion.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

// A camera at the origin, 2 m above flat ground (y = -2), looking along +z, 90 degrees
// across and 60 up and down.
static void begin(ground_occlusion *o) {
    const double eye[3] = {0, 0, 0}, forward[3] = {0, 0, 1}, right[3] = {1, 0, 0},
                 up[3] = {0, 1, 0};
    ground_occlusion_begin(o, eye, forward, right, up, 1.0, 0.57735);
}

// An axis-aligned box as its 8 corners.
static void box(double x0, double x1, double y0, double y1, double z0, double z1,
                double out[8][3]) {
    for (int k = 0; k < 8; k++) {
        out[k][0] = k & 1 ? x1 : x0;
        out[k][1] = k & 2 ? y1 : y0;
        out[k][2] = k & 4 ? z1 : z0;
    }
}

// The ground from 2 m to 100 m ahead, wider than the view, down to 50 m below it.
static void add_near_ground(ground_occlusion *o) {
    double solid[8][3];
    box(-400, 400, -52, -2.5, 2, 100, solid);
    ground_occlusion_add_solid(o, (const double(*)[3])solid, 8);
}

static int hidden(const ground_occlusion *o, double x0, double x1, double y0, double y1, double z0,
                  double z1) {
    double pts[8][3];
    box(x0, x1, y0, y1, z0, z1, pts);
    return ground_occlusion_hidden(o, (const double(*)[3])pts, 8);
}

static void test_hides_what_lies_behind_and_below_its_silhouette(void **state) {
    (void)state;
    ground_occlusion o;
    begin(&o);
    // Before anything is added, nothing is hidden.
    assert_false(hidden(&o, -10, 10, -60, -10, 200, 300));
    add_near_ground(&o);
    // Seen over the near ground's far edge (2.5 m down at 100 m: 1.4 degrees under the
    // horizon), a box 200-300 m out whose top is 10 m down (1.9 degrees or more) is hidden.
    assert_true(hidden(&o, -10, 10, -60, -10, 200, 300));
    // Its top rising into view above that edge: not hidden.
    assert_false(hidden(&o, -10, 10, -60, 10, 200, 300));
}

static void test_never_hides_what_is_nearer_or_beside(void **state) {
    (void)state;
    ground_occlusion o;
    begin(&o);
    add_near_ground(&o);
    // Under the far edge on the screen but within the solid's own depths (50-60 m, the
    // solid reaching 100 m): not known to be behind it.
    assert_false(hidden(&o, -1, 1, -5, -3, 50, 60));
    // Reaching behind the camera: never hidden.
    assert_false(hidden(&o, -10, 10, -60, -10, -5, 300));
    // Off the screen entirely (below the view): not answered as hidden.
    assert_false(hidden(&o, -10, 10, -5000, -4000, 200, 300));
    // A narrow strip of ground straight ahead (10 m either side) covers the middle of
    // the screen, not a box off to its right at the same heights.
    begin(&o);
    double strip[8][3];
    box(-10, 10, -52, -2.5, 2, 100, strip);
    ground_occlusion_add_solid(&o, (const double(*)[3])strip, 8);
    assert_true(hidden(&o, -1, 1, -60, -10, 300, 400));
    assert_false(hidden(&o, 100, 150, -60, -10, 300, 400));
}

static void test_ignores_solids_behind_the_camera(void **state) {
    (void)state;
    ground_occlusion o;
    begin(&o);
    double solid[8][3];
    box(-400, 400, -52, -2.5, -50, 100, solid); // reaches behind the camera
    ground_occlusion_add_solid(&o, (const double(*)[3])solid, 8);
    assert_false(hidden(&o, -10, 10, -60, -10, 200, 300));
}

// Rising ground: solids one after another, each higher, join into one covered run, so
// a box behind the last and under its edge is hidden even where it reaches down past
// the last solid's own silhouette.
static void test_rising_solids_join(void **state) {
    (void)state;
    ground_occlusion o;
    begin(&o);
    for (int k = 0; k < 5; k++) {
        double solid[8][3];
        const double z0 = 2 + 20 * k, top = -2.5 + 0.3 * k;
        box(-400, 400, top - 20, top, z0, z0 + 20, solid);
        ground_occlusion_add_solid(&o, (const double(*)[3])solid, 8);
    }
    assert_true(hidden(&o, -5, 5, -300, -10, 300, 400));
    assert_false(hidden(&o, -5, 5, -300, 5, 300, 400));
}

// A thin slab across the whole view at depth z (to z + 1) covering screen heights s0..s1
// (-1 bottom, 1 top) as seen from the camera of begin().
static void add_slab(ground_occlusion *o, double z, double s0, double s1) {
    const double t = 0.57735; // begin()'s tangent of half the vertical field of view
    double solid[8][3];
    box(-1000, 1000, s0 * z * t, s1 * z * t, z, z + 1, solid);
    ground_occlusion_add_solid(o, (const double(*)[3])solid, 8);
}

// Whether a small box from z0 to z1 straight ahead, at screen heights s0..s1 at z0, is
// hidden.
static int screen_box_hidden(const ground_occlusion *o, double z0, double z1, double s0,
                             double s1) {
    const double t = 0.57735;
    return hidden(o, -5, 5, s0 * z0 * t, s1 * z0 * t, z0, z1);
}

// Each depth keeps one covered run per column: a solid below it leaves it as it is, one
// overlapping it joins it, one apart and above it takes its place (the horizon's side),
// each only for what lies behind that solid.
static void test_runs_stay_join_and_give_way(void **state) {
    (void)state;
    ground_occlusion o;
    begin(&o);
    add_slab(&o, 100, -0.5, -0.2);
    assert_true(screen_box_hidden(&o, 500, 510, -0.45, -0.25));
    assert_false(screen_box_hidden(&o, 500, 510, -0.4, 0.05));
    add_slab(&o, 200, -0.8, -0.6); // below the run: it stays
    assert_true(screen_box_hidden(&o, 500, 510, -0.45, -0.25));
    assert_false(screen_box_hidden(&o, 500, 510, -0.75, -0.65));
    add_slab(&o, 300, -0.25, 0.1); // overlapping its top: one run
    assert_true(screen_box_hidden(&o, 500, 510, -0.4, 0.05));
    add_slab(&o, 400, 0.2, 0.3); // above and apart: behind it, it replaces the run
    assert_true(screen_box_hidden(&o, 500, 510, 0.22, 0.28));
    assert_false(screen_box_hidden(&o, 500, 510, -0.4, 0.05));
    // Nearer than it (but behind the joined run), the run still hides.
    assert_true(screen_box_hidden(&o, 350, 355, -0.4, 0.05));
    assert_false(screen_box_hidden(&o, 350, 355, 0.22, 0.28));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hides_what_lies_behind_and_below_its_silhouette),
        cmocka_unit_test(test_never_hides_what_is_nearer_or_beside),
        cmocka_unit_test(test_ignores_solids_behind_the_camera),
        cmocka_unit_test(test_rising_solids_join),
        cmocka_unit_test(test_runs_stay_join_and_give_way),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
