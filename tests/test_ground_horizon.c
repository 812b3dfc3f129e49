// Occlusion by the ground's horizon (renderer/ground_horizon.h): ground rising ahead of
// a camera 2 m above an Earth-sized planet hides what lies farther in the same
// directions and lower in the view, and nothing else: not what rises above its sight
// lines, not what is nearer or beside it, nothing around the camera's vertical; more
// ground never hides less.
#include "renderer/ground_horizon.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#define RADIUS 6371000.0
#define EYE_HEIGHT 2.0

// A horizon (zeroed, as ground_horizon_begin's first call needs; large for a stack).
static ground_horizon *make(void) {
    ground_horizon *h = calloc(1, sizeof *h);
    assert_non_null(h);
    return h;
}

// The camera 2 m above the datum where +z meets the sphere.
static void begin(ground_horizon *h) {
    const double eye[3] = {0, 0, RADIUS + EYE_HEIGHT};
    ground_horizon_begin(h, eye);
}

// A direction `north` metres ahead (+y) and `east` metres to the side (+x) on the datum.
static void direction(double north, double east, double out[3]) {
    const double a = north / RADIUS, b = east / RADIUS;
    out[0] = sin(b) * cos(a), out[1] = sin(a), out[2] = cos(a) * cos(b);
}

// A patch from n0 to n1 metres ahead and e0 to e1 to the side, as a grid's corners.
static void patch(double n0, double n1, double e0, double e1, double out[4][3]) {
    direction(n0, e0, out[0]);
    direction(n0, e1, out[1]);
    direction(n1, e0, out[2]);
    direction(n1, e1, out[3]);
}

static void add(ground_horizon *h, double n0, double n1, double e0, double e1, double floor_h) {
    double p[4][3];
    patch(n0, n1, e0, e1, p);
    ground_horizon_add_floor(h, (const double(*)[3])p, RADIUS + floor_h);
}

static int hidden(const ground_horizon *h, double n0, double n1, double e0, double e1,
                  double top_h) {
    double p[4][3];
    patch(n0, n1, e0, e1, p);
    return ground_horizon_hidden(h, (const double(*)[3])p, RADIUS + top_h);
}

// A ridge 100-110 m ahead, 60 m either side, its ground nowhere under 5 m (3 m above
// the eye: 1.6 degrees up seen from its far side).
static void add_ridge(ground_horizon *h) {
    add(h, 100, 110, -60, 60, 5);
}

static void test_hides_what_lies_behind_the_crest_below_its_sight_lines(void **state) {
    (void)state;
    ground_horizon *h = make();
    begin(h);
    assert_false(hidden(h, 500, 600, -10, 10, 10)); // nothing added yet
    add_ridge(h);
    // 500-600 m out, 10 m high: 0.9 degrees up at most, under the ridge's 1.6.
    assert_true(hidden(h, 500, 600, -10, 10, 10));
    // The same ground rising to 30 m (3.2 degrees up): seen over the ridge.
    assert_false(hidden(h, 500, 600, -10, 10, 30));
    // What the ridge promises is its lowest sight line: 1.56 degrees over its far side
    // (1.72 over its near side). Ground 16.3 m high 500 m out (1.60 degrees) shows.
    assert_false(hidden(h, 500, 600, -10, 10, 16.3));
    // Ground below the eye, 100-200 m out and 3 m under the datum, promises its near
    // side's 2.9 degrees down (its far side is 1.4 degrees down).
    begin(h);
    add(h, 100, 200, -60, 60, -3);
    assert_true(hidden(h, 500, 600, -10, 10, -30));  // 3.6 degrees down
    assert_false(hidden(h, 500, 600, -10, 10, -15)); // 2.0 degrees down
    free(h);
}

static void test_never_hides_what_is_nearer_beside_or_around_the_camera(void **state) {
    (void)state;
    ground_horizon *h = make();
    begin(h);
    add_ridge(h);
    // Low ground nearer than the ridge's far side (it is in front of the crest).
    assert_false(hidden(h, 50, 60, -10, 10, -5));
    assert_false(hidden(h, 105, 200, -10, 10, -5)); // starting on the ridge itself
    // Behind it but wider than it (past its ends), or off to the side.
    assert_false(hidden(h, 500, 600, -400, 400, 0));
    assert_false(hidden(h, -10, 10, 500, 600, 0));
    // The camera's vertical through a patch: neither hidden nor a floor.
    assert_false(hidden(h, -10, 10, -10, 10, -100));
    begin(h);
    add(h, -20, 200, -200, 200, 50); // would promise a wall all around if used
    assert_false(hidden(h, 500, 600, -10, 10, 0));
    free(h);
}

static void test_neighbouring_floors_cover_only_what_each_spans(void **state) {
    (void)state;
    ground_horizon *h = make();
    begin(h);
    // Two halves of the ridge side by side: together they hide what the whole ridge
    // hides in the middle of each, and nothing past their outer ends.
    add(h, 100, 110, -60, 0, 5);
    add(h, 100, 110, 0, 60, 5);
    assert_true(hidden(h, 500, 600, -200, -50, 10));
    assert_true(hidden(h, 500, 600, 50, 200, 10));
    assert_false(hidden(h, 500, 600, 200, 400, 10));
    free(h);
}

static double uniform(double lo, double hi) {
    return lo + (hi - lo) * (rand() / (double)RAND_MAX);
}

static void test_more_ground_never_hides_less(void **state) {
    (void)state;
    srand(7);
    ground_horizon *some = make(), *all = make();
    int hits = 0; // queries hidden with some of the floors (the test is not vacuous)
    for (int trial = 0; trial < 200; trial++) {
        begin(some);
        begin(all);
        const int floors = 1 + rand() % 200;
        for (int i = 0; i < floors; i++) {
            const double n0 = uniform(-300, 300), e0 = uniform(-300, 300);
            const double size = rand() % 2 ? uniform(0.5, 5) : uniform(5, 100);
            const double floor_h = uniform(-10, 10);
            double p[4][3];
            patch(n0, n0 + size, e0, e0 + size, p);
            ground_horizon_add_floor(all, (const double(*)[3])p, RADIUS + floor_h);
            if (rand() % 2) ground_horizon_add_floor(some, (const double(*)[3])p, RADIUS + floor_h);
        }
        for (int q = 0; q < 50; q++) {
            const double n0 = uniform(-3000, 3000), e0 = uniform(-3000, 3000);
            const double size = uniform(1, 500), top_h = uniform(-20, 20);
            if (hidden(some, n0, n0 + size, e0, e0 + size, top_h)) {
                assert_true(hidden(all, n0, n0 + size, e0, e0 + size, top_h));
                hits++;
            }
        }
    }
    assert_true(hits > 100);
    free(some);
    free(all);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hides_what_lies_behind_the_crest_below_its_sight_lines),
        cmocka_unit_test(test_never_hides_what_is_nearer_beside_or_around_the_camera),
        cmocka_unit_test(test_neighbouring_floors_cover_only_what_each_spans),
        cmocka_unit_test(test_more_ground_never_hides_less),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
