// The 3D viewport's camera math, frustum culling and terrain picking: yaw/pitch
// conventions, matrices against hand-computed projections, pixel rays that project back
// to their pixel, the orbit/dolly/focus controls, frustum boxes (reversed-Z never culls
// far), and pick_ray against analytic terrains, near and 10,000 km from the origin.
#include "renderer/camera.h"
#include "renderer/frustum.h"
#include "renderer/pick.h"

#include <math.h>
#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

static const double PI = 3.14159265358979323846;

static double len3(const double v[3]) {
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
static double dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static double dist3(const double a[3], const double b[3]) {
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return len3(d);
}

static void assert_vec(const double a[3], double x, double y, double z, double tol) {
    if (fabs(a[0] - x) > tol || fabs(a[1] - y) > tol || fabs(a[2] - z) > tol)
        fail_msg("(%.9g %.9g %.9g) != (%.9g %.9g %.9g) within %g", a[0], a[1], a[2], x, y, z, tol);
}
static void assert_near(double a, double b, double tol) {
    if (!(fabs(a - b) <= tol)) fail_msg("%.12g != %.12g within %g", a, b, tol);
}

// clip = m * (v, 1) for a column-major float matrix, in double.
static void transform(const float m[16], const double v[3], double clip[4]) {
    for (int r = 0; r < 4; r++)
        clip[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r];
}

static void test_conventions(void **state) {
    (void)state;
    camera c;
    camera_default(&c);
    assert_vec(c.pos, 0, 0, 0, 0);
    assert_near(c.fov_y, 60, 0);
    assert_near(c.near_m, 0.5, 0);
    double f[3], r[3], u[3];
    camera_forward(&c, f);
    assert_vec(f, 0, 0, -1, 1e-12); // yaw 0 looks to -Z
    camera_right(&c, r);
    assert_vec(r, 1, 0, 0, 1e-12);
    camera_up(&c, u);
    assert_vec(u, 0, 1, 0, 1e-12);
    c.yaw = 90;
    camera_forward(&c, f);
    assert_vec(f, 1, 0, 0, 1e-12); // yaw 90 looks to +X
    camera_right(&c, r);
    assert_vec(r, 0, 0, 1, 1e-12);
    c.yaw = 0;
    c.pitch = 30;
    camera_forward(&c, f);
    assert_vec(f, 0, sin(PI / 6), -cos(PI / 6), 1e-12); // positive pitch looks up

    // Pitch 90 clamps; the basis stays orthonormal there and at arbitrary angles.
    camera_look(&c, 0, 60);
    assert_near(c.pitch, CAMERA_PITCH_LIMIT, 0);
    camera_look(&c, 0, -500);
    assert_near(c.pitch, -CAMERA_PITCH_LIMIT, 0);
    const double angles[][2] = {{0, 0}, {37, 12}, {200, -80}, {359, 89.9}, {123, -89.9}};
    for (size_t i = 0; i < sizeof angles / sizeof angles[0]; i++) {
        c.yaw = angles[i][0];
        c.pitch = angles[i][1];
        camera_forward(&c, f);
        camera_right(&c, r);
        camera_up(&c, u);
        assert_near(len3(f), 1, 1e-12);
        assert_near(len3(r), 1, 1e-12);
        assert_near(len3(u), 1, 1e-12);
        assert_near(r[1], 0, 0); // right is horizontal
        assert_near(dot3(f, r), 0, 1e-12);
        assert_near(dot3(f, u), 0, 1e-12);
        assert_near(dot3(r, u), 0, 1e-12);
        assert_true(u[1] > 0); // up never flips below the horizon
    }

    // Yaw wraps into [0, 360).
    c.yaw = 350;
    camera_look(&c, 20, 0);
    assert_near(c.yaw, 10, 1e-9);
    camera_look(&c, -30, 0);
    assert_near(c.yaw, 340, 1e-9);
    camera_look(&c, 720, 0);
    assert_near(c.yaw, 340, 1e-9);
    camera_look(&c, -1e-300, 0);
    assert_true(c.yaw >= 0 && c.yaw < 360);
}

// A point `d` ahead of the camera, `a` right and `b` up lands at NDC (a / (d t aspect),
// b / (d t), near / d) with t = tan(fov / 2).
static void test_view_projection(void **state) {
    (void)state;
    camera c;
    camera_default(&c);
    c.pos[0] = 1e7; // camera-relative: the position never enters the matrices
    c.pos[1] = 1234.5;
    c.pos[2] = -3e6;
    c.yaw = 33;
    c.pitch = -21;
    c.fov_y = 50;
    c.near_m = 0.25;
    const double aspect = 16.0 / 9.0, t = tan(25 * PI / 180);
    float m[16], v[16], p[16];
    camera_view_projection(&c, aspect, m);
    camera_view_matrix(&c, v);
    camera_projection_matrix(&c, aspect, p);
    assert_true(v[12] == 0 && v[13] == 0 && v[14] == 0 && v[15] == 1); // rotation only
    double f[3], r[3], u[3];
    camera_forward(&c, f);
    camera_right(&c, r);
    camera_up(&c, u);
    const double cases[][3] = {{0.25, 0, 0}, {10, 2, -3}, {1000, -300, 250}, {1e5, 1e4, 2e4}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double d = cases[i][0], a = cases[i][1], b = cases[i][2], rel[3], clip[4];
        for (int k = 0; k < 3; k++)
            rel[k] = f[k] * d + r[k] * a + u[k] * b;
        transform(m, rel, clip);
        assert_near(clip[3], d, 1e-5 * d); // w = -z_view = distance along forward
        assert_near(clip[0] / clip[3], a / (d * t * aspect), 1e-5);
        assert_near(clip[1] / clip[3], b / (d * t), 1e-5);
        assert_near(clip[2] / clip[3], c.near_m / d, 1e-6 * c.near_m / d + 1e-12);
        // View alone: forward maps to -Z, right to +X, up to +Y.
        double view[4];
        transform(v, rel, view);
        assert_near(view[0], a, 1e-5 * d);
        assert_near(view[1], b, 1e-5 * d);
        assert_near(view[2], -d, 1e-5 * d);
    }
    // Exactly the documented projection layout.
    assert_near(p[11], -1, 0);
    assert_near(p[14], c.near_m, 1e-7);
    assert_near(p[15], 0, 0);
    assert_near(p[10], 0, 0);
}

static void test_rays(void **state) {
    (void)state;
    camera c;
    camera_default(&c);
    c.pos[0] = -5e6;
    c.yaw = 250;
    c.pitch = 17;
    c.fov_y = 70;
    const double aspect = 4.0 / 3.0;
    double dir[3], f[3];
    camera_ray(&c, aspect, 0.5, 0.5, dir);
    camera_forward(&c, f);
    assert_vec(dir, f[0], f[1], f[2], 1e-12);

    float m[16];
    camera_view_projection(&c, aspect, m);
    const double px[][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.1, 0.8}, {0.73, 0.31}};
    for (size_t i = 0; i < sizeof px / sizeof px[0]; i++) {
        camera_ray(&c, aspect, px[i][0], px[i][1], dir);
        assert_near(len3(dir), 1, 1e-12);
        double rel[3] = {dir[0] * 10, dir[1] * 10, dir[2] * 10}, clip[4];
        transform(m, rel, clip);
        double sx = 0.5 * (clip[0] / clip[3] + 1), sy = 0.5 * (1 - clip[1] / clip[3]);
        assert_near(sx, px[i][0], 1e-5);
        assert_near(sy, px[i][1], 1e-5);
    }
    // The top-left ray leans left and up of forward.
    double r[3], u[3];
    camera_right(&c, r);
    camera_up(&c, u);
    camera_ray(&c, aspect, 0, 0, dir);
    assert_true(dot3(dir, r) < 0 && dot3(dir, u) > 0);
}

static void test_fly_controls(void **state) {
    (void)state;
    camera c;
    camera_default(&c);
    c.yaw = 90;
    c.pitch = 45;
    camera_move_local(&c, 0, 5, 0);
    assert_vec(c.pos, 0, 0, 5, 1e-12); // right at yaw 90 is +Z
    camera_move_local(&c, 0, 0, 3);
    assert_vec(c.pos, 0, 3, 5, 1e-12); // world up, whatever the pitch
    camera_move_local(&c, sqrt(2), 0, 0);
    assert_vec(c.pos, 1, 4, 5, 1e-12); // forward includes the pitch
}

static void assert_looks_at(const camera *c, const double p[3], double tol) {
    double f[3], to[3] = {p[0] - c->pos[0], p[1] - c->pos[1], p[2] - c->pos[2]};
    double l = len3(to);
    camera_forward(c, f);
    assert_vec(f, to[0] / l, to[1] / l, to[2] / l, tol);
}

static void test_orbit(void **state) {
    (void)state;
    for (int far = 0; far < 2; far++) {
        double o = far ? 1e7 : 0;
        camera c;
        camera_default(&c);
        c.pos[0] = o + 100;
        c.pos[1] = 50;
        c.pos[2] = o - 30;
        c.yaw = 10; // not looking at the pivot yet
        c.pitch = 5;
        const double pivot[3] = {o + 20, 5, o + 40};
        double d0 = dist3(c.pos, pivot), p0[3] = {c.pos[0], c.pos[1], c.pos[2]};
        camera_orbit(&c, pivot, 0, 0);
        assert_vec(c.pos, p0[0], p0[1], p0[2], 1e-6); // only turned to face the pivot
        assert_looks_at(&c, pivot, 1e-9);
        double yaw0 = c.yaw, pitch0 = c.pitch;
        camera_orbit(&c, pivot, 30, -10);
        assert_near(dist3(c.pos, pivot), d0, 1e-6);
        assert_looks_at(&c, pivot, 1e-9);
        assert_near(fmod(c.yaw - yaw0 + 360, 360), 30, 1e-9);
        assert_near(c.pitch, pitch0 - 10, 1e-9);
        // The camera swung 30 degrees around the pivot's vertical axis.
        double a0 = atan2(p0[0] - pivot[0], -(p0[2] - pivot[2]));
        double a1 = atan2(c.pos[0] - pivot[0], -(c.pos[2] - pivot[2]));
        assert_near(fmod(a1 - a0 + 4 * PI, 2 * PI), 30 * PI / 180, 1e-9);
        // Going over the top clamps instead of flipping. dpitch is the view's pitch, as
        // in camera_look: looking down from above the pivot is a negative pitch.
        camera_orbit(&c, pivot, 400, -500);
        assert_near(c.pitch, -CAMERA_PITCH_LIMIT, 1e-9);
        assert_true(c.yaw >= 0 && c.yaw < 360);
        assert_near(dist3(c.pos, pivot), d0, 1e-6);
        assert_looks_at(&c, pivot, 1e-9);
        assert_true(c.pos[1] > pivot[1]); // above, looking down
    }
}

static void test_dolly_focus(void **state) {
    (void)state;
    camera c;
    camera_default(&c);
    c.pos[0] = 1e7 + 100;
    c.pos[1] = 100;
    c.pos[2] = 0;
    const double pivot[3] = {1e7, 0, 0};
    camera_orbit(&c, pivot, 0, 0);
    double f0[3], yaw = c.yaw, pitch = c.pitch;
    camera_forward(&c, f0);
    double d0 = dist3(c.pos, pivot);
    camera_dolly(&c, pivot, 0.5);
    assert_near(dist3(c.pos, pivot), 0.5 * d0, 1e-6);
    assert_looks_at(&c, pivot, 1e-9); // moved along the pivot line
    assert_near(c.yaw, yaw, 0);
    assert_near(c.pitch, pitch, 0);
    camera_dolly(&c, pivot, 4);
    assert_near(dist3(c.pos, pivot), 2 * d0, 1e-6);
    camera_dolly(&c, pivot, 1e-9);
    assert_near(dist3(c.pos, pivot), 2 * c.near_m, 1e-6); // never closer than 2 near
    camera_dolly(&c, pivot, 0.5);
    assert_near(dist3(c.pos, pivot), 2 * c.near_m, 1e-6);
    double before[3] = {c.pos[0], c.pos[1], c.pos[2]};
    camera_dolly(&c, pivot, 0);
    camera_dolly(&c, pivot, -2);
    camera_dolly(&c, pivot, NAN);
    assert_vec(c.pos, before[0], before[1], before[2], 0); // bad factors do nothing
    camera_dolly(&c, pivot, 10);
    assert_near(dist3(c.pos, pivot), 20 * c.near_m, 1e-6);

    // Focus keeps the angles and looks at the point from `distance` away.
    c.yaw = 123;
    c.pitch = -35;
    const double pt[3] = {-4e6, 300, 2e6};
    camera_focus(&c, pt, 250);
    assert_near(c.yaw, 123, 0);
    assert_near(c.pitch, -35, 0);
    assert_near(dist3(c.pos, pt), 250, 1e-6);
    assert_looks_at(&c, pt, 1e-9);
}

static int box_visible(const frustum *f, float x0, float y0, float z0, float x1, float y1,
                       float z1) {
    const float mn[3] = {x0, y0, z0}, mx[3] = {x1, y1, z1};
    return frustum_test_aabb(f, mn, mx);
}

static void test_frustum(void **state) {
    (void)state;
    camera c;
    camera_default(&c);
    float m[16];
    frustum f;
    camera_view_projection(&c, 16.0 / 9.0, m);
    frustum_from_matrix(&f, m);
    for (int p = 0; p < 6; p++) {
        double n = sqrt(f.planes[p][0] * f.planes[p][0] + f.planes[p][1] * f.planes[p][1] +
                        f.planes[p][2] * f.planes[p][2]);
        assert_true(fabs(n - 1) < 1e-6 || (n == 0 && f.planes[p][3] > 0));
    }
    assert_true(box_visible(&f, -1, -1, -10, 1, 1, -5));                 // in front
    assert_false(box_visible(&f, -1, -1, 5, 1, 1, 10));                  // behind
    assert_false(box_visible(&f, -1000, -1, -10, -900, 1, -5));          // left
    assert_false(box_visible(&f, 900, -1, -10, 1000, 1, -5));            // right
    assert_false(box_visible(&f, -1, 100, -10, 1, 110, -5));             // above
    assert_false(box_visible(&f, -1, -110, -10, 1, -100, -5));           // below
    assert_false(box_visible(&f, -1, -1, -0.4f, 1, 1, -0.1f));           // before the near plane
    assert_true(box_visible(&f, -1, -1, -0.6f, 1, 1, -0.1f));            // straddles the near plane
    assert_true(box_visible(&f, -1e6f, -1e6f, -1e6f, 1e6f, 1e6f, 1e6f)); // contains the camera
    assert_true(box_visible(&f, -50, -50, -10, 50, 50, -5));             // wider than the view
    // Reversed-Z with an infinite far plane: nothing in front is ever too far.
    assert_true(box_visible(&f, -1, -1, -1e7f, 1, 1, -1e7f + 2));
    assert_true(box_visible(&f, -1e3f, -1e3f, -1e12f, 1e3f, 1e3f, -1e12f + 1e6f));
    // Just inside vs just outside the right edge at 60 degrees fov, aspect 16/9.
    double half_w = 100 * tan(PI / 6) * 16.0 / 9.0;
    assert_true(box_visible(&f, (float)(half_w - 1), 0, -101, (float)(half_w - 0.5), 1, -100));
    assert_false(box_visible(&f, (float)(half_w + 2), 0, -100, (float)(half_w + 3), 1, -99));

    // Turned to yaw 90 and pitched down: +X in front is seen, -X is not.
    c.yaw = 90;
    c.pitch = -30;
    camera_view_projection(&c, 1.0, m);
    frustum_from_matrix(&f, m);
    assert_true(box_visible(&f, 90, -60, -5, 100, -50, 5));
    assert_false(box_visible(&f, -100, -60, -5, -90, -50, 5));
    assert_false(box_visible(&f, 90, 200, -5, 100, 210, 5)); // far above the view
}

// --- Picking against analytic terrains --------------------------------------------

typedef struct terrain {
    int kind;                      // 0 plane, 1 slope, 2 sine
    double level;                  // plane height
    double unknown_x0, unknown_x1; // heights unknown for x in [x0, x1)
    double ox, oz; // sine terrain's local origin (to test far from the world origin)
    long samples;
} terrain;

static double terrain_h(const terrain *t, double x, double z) {
    switch (t->kind) {
    case 0:
        return t->level;
    case 1:
        return t->level + 0.3 * x - 0.2 * z;
    default: {
        double lx = x - t->ox, lz = z - t->oz;
        return t->level + 6 * sin(lx / 40) * cos(lz / 55) + 3 * sin(lx / 17 + lz / 23);
    }
    }
}

static int terrain_fn(void *user, double x, double z, double *h) {
    terrain *t = user;
    t->samples++;
    if (x >= t->unknown_x0 && x < t->unknown_x1) return -1;
    *h = terrain_h(t, x, z);
    return 0;
}

// The first crossing, found by dense sampling and a long bisection.
static double reference_t(const terrain *t, const double o[3], const double d[3], double max) {
    double prev = o[1] - terrain_h(t, o[0], o[2]);
    for (double a = 0; a < max; a += 0.01) {
        double b = a + 0.01;
        double cur = o[1] + b * d[1] - terrain_h(t, o[0] + b * d[0], o[2] + b * d[2]);
        if ((prev > 0) != (cur > 0)) {
            double lo = a, hi = b;
            for (int i = 0; i < 80; i++) {
                double mid = 0.5 * (lo + hi);
                double v = o[1] + mid * d[1] - terrain_h(t, o[0] + mid * d[0], o[2] + mid * d[2]);
                if ((v > 0) == (prev > 0))
                    lo = mid;
                else
                    hi = mid;
            }
            return 0.5 * (lo + hi);
        }
        prev = cur;
    }
    return -1;
}

static void unit(double d[3]) {
    double l = len3(d);
    for (int i = 0; i < 3; i++)
        d[i] /= l;
}

// Picks and checks the hit lies on the ray within step/64 of t_ref and on the terrain.
static void check_pick(terrain *t, const double o[3], const double d[3], double max, double step,
                       double t_ref) {
    double hit[3] = {0, 0, 0};
    assert_int_equal(pick_ray(terrain_fn, t, o, d, max, step, hit), 0);
    double want[3] = {o[0] + t_ref * d[0], o[1] + t_ref * d[1], o[2] + t_ref * d[2]};
    double tol = step / 64;
    if (fabs(hit[0] - want[0]) > tol || fabs(hit[2] - want[2]) > tol ||
        fabs(hit[1] - want[1]) > tol * 4) // the height there: slope <= ~1 times the error
        fail_msg("hit (%.9f %.9f %.9f) vs (%.9f %.9f %.9f), tol %g", hit[0], hit[1], hit[2],
                 want[0], want[1], want[2], tol);
    assert_near(hit[1], terrain_h(t, hit[0], hit[2]), 1e-9 * (1 + fabs(hit[1])));
}

static void test_pick_plane_and_slope(void **state) {
    (void)state;
    terrain flat = {.kind = 0, .level = 10, .unknown_x0 = 1, .unknown_x1 = 0};
    double o[3] = {3, 100, -7}, d[3] = {1, -1, 0.5};
    unit(d);
    double t_ref = (10 - o[1]) / d[1];
    check_pick(&flat, o, d, 1000, 1.0, t_ref);
    check_pick(&flat, o, d, 1000, 0.25, t_ref);
    check_pick(&flat, o, d, 1000, 7.0, t_ref);

    // Straight down, and a grazing ray that meets the plane 5 km away (steps have grown).
    double down[3] = {0, -1, 0};
    check_pick(&flat, o, down, 1000, 1.0, 90);
    double graze[3] = {0.6, -90.0 / 5000, -0.8};
    unit(graze);
    check_pick(&flat, o, graze, 20000, 1.0, (10 - o[1]) / graze[1]);

    // A slope y = 10 + 0.3 x - 0.2 z, solved exactly.
    terrain slope = {.kind = 1, .level = 10, .unknown_x0 = 1, .unknown_x1 = 0};
    double so[3] = {-50, 80, 20}, sd[3] = {0.7, -0.5, -0.3};
    unit(sd);
    double st = (10 + 0.3 * so[0] - 0.2 * so[2] - so[1]) / (sd[1] - 0.3 * sd[0] + 0.2 * sd[2]);
    assert_true(st > 0);
    check_pick(&slope, so, sd, 1000, 1.0, st);
    check_pick(&slope, so, sd, 1000, 3.0, st);
}

static void test_pick_sine(void **state) {
    (void)state;
    terrain sine = {.kind = 2, .level = 0, .unknown_x0 = 1, .unknown_x1 = 0};
    const double dirs[][3] = {{1, -0.2, 0.3}, {-0.4, -0.1, 1}, {0.2, -1, -0.1}, {1, -0.05, 0}};
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        double o[3] = {12, 40, -33}, d[3] = {dirs[i][0], dirs[i][1], dirs[i][2]};
        unit(d);
        double t_ref = reference_t(&sine, o, d, 3000);
        assert_true(t_ref > 0);
        check_pick(&sine, o, d, 3000, 0.5, t_ref);
    }
}

static void test_pick_misses(void **state) {
    (void)state;
    terrain flat = {.kind = 0, .level = 10, .unknown_x0 = 1, .unknown_x1 = 0};
    double o[3] = {0, 100, 0}, hit[3] = {0, 0, 0};
    double up[3] = {0.3, 0.5, 0.1}, level[3] = {1, 0, 0}, down[3] = {0, -1, 0};
    unit(up);
    assert_int_equal(pick_ray(terrain_fn, &flat, o, up, 1e5, 1, hit), -1);
    assert_int_equal(pick_ray(terrain_fn, &flat, o, level, 1e5, 1, hit), -1);
    assert_int_equal(pick_ray(terrain_fn, &flat, o, down, 89, 1, hit), -1); // too short
    assert_int_equal(pick_ray(terrain_fn, &flat, o, down, 91, 1, hit), 0);
    // Unusable arguments.
    const double zero[3] = {0, 0, 0};
    assert_int_equal(pick_ray(terrain_fn, &flat, o, zero, 100, 1, hit), -1);
    assert_int_equal(pick_ray(terrain_fn, &flat, o, down, 100, 0, hit), -1);
    assert_int_equal(pick_ray(terrain_fn, &flat, o, down, 0, 1, hit), -1);
    // Every sample unknown.
    terrain none = {.kind = 0, .level = 10, .unknown_x0 = -INFINITY, .unknown_x1 = INFINITY};
    assert_int_equal(pick_ray(terrain_fn, &none, o, down, 1000, 1, hit), -1);

    // Far terrain costs few samples: 100 km at 1 m steps, far below 100,000.
    flat.samples = 0;
    assert_int_equal(pick_ray(terrain_fn, &flat, o, level, 1e5, 1, hit), -1);
    assert_true(flat.samples > 100 && flat.samples < 3000);
}

static void test_pick_unknown_passes(void **state) {
    (void)state;
    // The ray would meet y = 10 at x = 45, inside the unknown band [0, 100): it passes
    // through the band (no terrain there) and is below ground when it comes out, so it
    // hits the known ground's edge at x = 100 (like the side of a bounded world).
    terrain band = {.kind = 0, .level = 10, .unknown_x0 = 0, .unknown_x1 = 100};
    double o[3] = {-10, 65, 0}, d[3] = {1, -1, 0}, hit[3] = {0, 0, 0};
    unit(d);
    assert_int_equal(pick_ray(terrain_fn, &band, o, d, 500, 1, hit), 0);
    assert_near(hit[0], 100, 1.0 / 64);
    assert_near(hit[1], 10, 0);
    assert_near(hit[2], 0, 1e-12);
    // A shallower ray crosses the band above ground and hits beyond it.
    double d2[3] = {1, -0.2, 0};
    unit(d2);
    double o2[3] = {-10, 40, 3};
    check_pick(&band, o2, d2, 500, 1, (10 - o2[1]) / d2[1]);
    // Climbing out of the band under the ground level, it first meets the edge too; a
    // ray starting under known ground meets the surface from below (any sign change).
    double o3[3] = {50, 0, 0}, d3[3] = {1, 0.1, 0};
    unit(d3);
    assert_int_equal(pick_ray(terrain_fn, &band, o3, d3, 500, 1, hit), 0);
    assert_near(hit[0], 100, 1.0 / 64);
    double o5[3] = {110, 0, 0};
    check_pick(&band, o5, d3, 500, 1, 10 / d3[1]);
    // A narrow hole right at the crossing: still a hit, on known ground, near it.
    terrain hole = {.kind = 0, .level = 10, .unknown_x0 = 44.9, .unknown_x1 = 45.6};
    double o4[3] = {0, 55, 0}, d4[3] = {1, -1, 0};
    unit(d4);
    assert_int_equal(pick_ray(terrain_fn, &hole, o4, d4, 500, 1, hit), 0);
    assert_near(hit[1], 10, 0);
    assert_true(hit[0] < 44.9 || hit[0] >= 45.6);
    assert_near(hit[0], 45, 1);
}

static void test_pick_far_from_origin(void **state) {
    (void)state;
    // The same sine terrain and rays at the origin and 10,000 km away hit the same
    // local points equally accurately.
    const double offs[][2] = {{0, 0}, {1e7, -1e7}, {-1e7, 3e6}};
    double local0[3] = {0, 0, 0};
    for (size_t k = 0; k < sizeof offs / sizeof offs[0]; k++) {
        terrain sine = {.kind = 2,
                        .level = 100,
                        .unknown_x0 = 1,
                        .unknown_x1 = 0,
                        .ox = offs[k][0],
                        .oz = offs[k][1]};
        camera c;
        camera_default(&c);
        c.pos[0] = offs[k][0] + 5;
        c.pos[1] = 160;
        c.pos[2] = offs[k][1] - 8;
        c.yaw = 70;
        c.pitch = -25;
        double d[3], hit[3];
        camera_ray(&c, 1.5, 0.6, 0.55, d);
        double t_ref = reference_t(&sine, c.pos, d, 2000);
        assert_true(t_ref > 0);
        check_pick(&sine, c.pos, d, 2000, 0.5, t_ref);
        assert_int_equal(pick_ray(terrain_fn, &sine, c.pos, d, 2000, 0.5, hit), 0);
        double local[3] = {hit[0] - offs[k][0], hit[1], hit[2] - offs[k][1]};
        if (k == 0)
            for (int i = 0; i < 3; i++)
                local0[i] = local[i];
        else
            assert_vec(local, local0[0], local0[1], local0[2], 0.5 / 64);
    }
}

static void test_walk(void **state) {
    (void)state;
    terrain sl = {.kind = 1, .level = 10, .unknown_x0 = 1000, .unknown_x1 = 2000};
    camera c;
    camera_default(&c);
    c.pos[0] = 20;
    c.pos[1] = 500;
    c.pos[2] = 5;
    c.yaw = 45;
    c.pitch = 10;
    assert_int_equal(camera_walk(&c, terrain_fn, &sl, 1.7), 0);
    assert_near(c.pos[1], 10 + 0.3 * 20 - 0.2 * 5 + 1.7, 1e-12);
    assert_near(c.pos[0], 20, 0);
    assert_near(c.yaw, 45, 0);
    c.pos[0] = 1500;
    c.pos[1] = 7;
    assert_int_equal(camera_walk(&c, terrain_fn, &sl, 1.7), -1);
    assert_vec(c.pos, 1500, 7, 5, 0); // unchanged where the height is unknown
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_conventions),
        cmocka_unit_test(test_view_projection),
        cmocka_unit_test(test_rays),
        cmocka_unit_test(test_fly_controls),
        cmocka_unit_test(test_orbit),
        cmocka_unit_test(test_dolly_focus),
        cmocka_unit_test(test_frustum),
        cmocka_unit_test(test_pick_plane_and_slope),
        cmocka_unit_test(test_pick_sine),
        cmocka_unit_test(test_pick_misses),
        cmocka_unit_test(test_pick_unknown_passes),
        cmocka_unit_test(test_pick_far_from_origin),
        cmocka_unit_test(test_walk),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
