// Editing a planet across its cube faces: a dab at a face's edge and at a corner where
// three faces meet changes every face its cap reaches exactly as the same operation
// evaluated on the sphere directly (each sample's great-circle distance to the dab's
// centre through the falloff), for every pointwise tool and the ramp; smoothing reaches
// over the edge and erosion flows over it as one simulation; one undo restores all
// faces; the change notifications name each face.
#include "editor/cmd/commands.h"
#include "editor/cmd/context.h"
#include "editor/edit/edit.h"
#include "editor/gen/gen_noise.h"
#include "editor/params/world_grid.h"
#include "editor/tools/brush.h"
#include "editor/tools/stamp.h"
#include "editor/tools/stamp_shapes.h"
#include "editor/tools/stroke.h"
#include "editor/world/layer_grid.h"
#include "editor/world/world.h"
#include "editor/world/world_events.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#define N 512 // samples per face side (radius 20 km at 100 m: 2 x 2 tiles)
// Metres per sample (face-local): the datum's arc, pi/2 x radius over N (61.4 m), not
// the nominal spacing of 100 (world_grid_sample_metres).
#define SPACING (M_PI / 2.0 * RADIUS / N)
#define RADIUS 20000.0

static void silent(void *u, const char *m) {
    (void)u, (void)m;
}

static world *planet_of(const char *generator) {
    world_params p;
    world_params_default(&p, WORLD_PLANET);
    p.radius = RADIUS;
    p.ocean_level = RADIUS;
    p.octaves = 5;
    og_error e;
    if (world_params_set(&p, "generator", generator, &e) != 0) fail_msg("%s", e.msg);
    world_settings s = {.cache_budget_bytes = (size_t)256 << 20, .workers = 2, .warn = silent};
    og_error err;
    world *w = world_create(&p, &s, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    assert_int_equal(world_grid_face_samples(&p), N);
    return w;
}

static world *planet(void) {
    return planet_of("fbm_advanced");
}

// All six faces' coarse heights.
static float *read_faces(world *w) {
    float *h = malloc(sizeof(float) * 6 * N * N);
    og_error err;
    for (int f = 0; f < 6; f++) {
        layer_grid g;
        assert_int_equal(layer_grid_init(&g, world_get_params(w), TILE_LAYER_COARSE, f, &err), 0);
        assert_int_equal(
            layer_grid_read(w, &g, (grid_rect){0, 0, N, N}, h + (size_t)f * N * N, &err), 0);
    }
    return h;
}

static void direction(int face, double i, double j, double d[3]) {
    world_grid_face_direction(face, (i + 0.5) / N * 2.0 - 1.0, (j + 0.5) / N * 2.0 - 1.0, d);
}

static double angle_between(const double a[3], const double b[3]) {
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return 2.0 * asin(fmin(1.0, 0.5 * sqrt(dx * dx + dy * dy + dz * dz)));
}

static void one_dab(world *w, const brush *b, double x, double z) {
    og_error err;
    stroke *s = stroke_begin(w, b, &err);
    if (!s) fail_msg("stroke_begin: %s", err.msg);
    if (stroke_to(s, x, z, 1.0, &err) != 0) fail_msg("stroke_to: %s", err.msg);
    if (stroke_end(s, &err) != 0) fail_msg("stroke_end: %s", err.msg);
}

static double terrace_of(const brush *b, double h) {
    double step = b->terrace_step, k = floor(h / step), f = h / step - k;
    double p = 1.0 + 15.0 * b->terrace_sharpness * b->terrace_sharpness;
    return (k + pow(f, p)) * step;
}

// The operation on the sphere: what sample h at direction d becomes.
static double reference(const brush *b, const double centre[3], const double d[3], double h) {
    double t = angle_between(d, centre) * RADIUS / b->radius;
    double w = brush_falloff_weight(b, (float)t) * b->strength;
    if (w <= 0) return h;
    switch (b->tool) {
    case BRUSH_RAISE:
        return h + w * (b->invert ? -b->amount : b->amount);
    case BRUSH_SET:
    case BRUSH_FLATTEN:
        return h + w * (b->height - h);
    case BRUSH_TERRACE:
        return h + w * (terrace_of(b, h) - h);
    case BRUSH_NOISE: {
        gen_fractal f = {GEN_FRACTAL_FBM, b->seed, b->noise_octaves, 0.5, 2.0, 1.0};
        double m = RADIUS / b->noise_scale;
        return h + w * b->amount * gen_fractal3(&f, d[0] * m, d[1] * m, d[2] * m);
    }
    default:
        return h;
    }
}

typedef struct place {
    const char *name;
    double x, z; // face 4's face-local metres: on its +s edge, and at its (+s, +t) corner
    int faces;   // faces the cap must reach
} place;

static const place PLACES[2] = {{"edge", (N - 0.5) * SPACING, 0.5 * N *SPACING, 2},
                                {"corner", (N - 0.5) * SPACING, (N - 0.5) * SPACING, 3}};

static void check_tool(brush_tool tool, const char *key, const char *value) {
    for (int k = 0; k < 2; k++) {
        world *w = planet();
        brush b;
        brush_defaults(&b, tool);
        og_error err;
        assert_int_equal(brush_set(&b, "face", "4", &err), 0);
        if (key) assert_int_equal(brush_set(&b, key, value, &err), 0);
        b.radius = 2500; // 41 samples
        b.strength = 0.8;
        if (tool == BRUSH_RAISE || tool == BRUSH_NOISE) b.amount = 40;
        float *before = read_faces(w);
        one_dab(w, &b, PLACES[k].x, PLACES[k].z);
        float *after = read_faces(w);
        double centre[3];
        direction(4, PLACES[k].x / SPACING, PLACES[k].z / SPACING, centre);
        double worst = 0;
        int touched[6] = {0};
        for (int f = 0; f < 6; f++)
            for (int j = 0; j < N; j++)
                for (int i = 0; i < N; i++) {
                    double d[3];
                    direction(f, i, j, d);
                    size_t at = (size_t)f * N * N + (size_t)j * N + i;
                    double want = reference(&b, centre, d, before[at]);
                    worst = fmax(worst, fabs(want - after[at]));
                    if (after[at] != before[at]) touched[f] = 1;
                }
        int faces = 0;
        for (int f = 0; f < 6; f++)
            faces += touched[f];
        print_message("%s at the %s: %d faces changed, largest difference from the sphere "
                      "reference %.3g m\n",
                      brush_tool_name(tool), PLACES[k].name, faces, worst);
        assert_int_equal(faces, PLACES[k].faces);
        assert_true(worst < 2e-3); // float heights of a few hundred metres
        free(before);
        free(after);
        world_close(w);
    }
}

static void test_raise(void **state) {
    (void)state;
    check_tool(BRUSH_RAISE, NULL, NULL);
}

static void test_lower(void **state) {
    (void)state;
    check_tool(BRUSH_RAISE, "invert", "1");
}

static void test_set(void **state) {
    (void)state;
    check_tool(BRUSH_SET, "height", "150");
}

static void test_flatten(void **state) {
    (void)state;
    check_tool(BRUSH_FLATTEN, "height", "-75");
}

static void test_terrace(void **state) {
    (void)state;
    check_tool(BRUSH_TERRACE, "step", "40");
}

static void test_noise(void **state) {
    (void)state;
    check_tool(BRUSH_NOISE, "scale", "300");
}

// Smoothing and erosion have no closed form to compare with, but they must reach over
// the edge: a dab at the corner changes all three faces, and the seam stays continuous
// (the samples either side of an edge move by about the same amount).
static void test_neighbourhood_tools_cross(void **state) {
    (void)state;
    const brush_tool tools[3] = {BRUSH_SMOOTH, BRUSH_THERMAL, BRUSH_HYDRAULIC};
    for (int k = 0; k < 3; k++) {
        world *w = planet();
        brush b;
        brush_defaults(&b, tools[k]);
        og_error err;
        assert_int_equal(brush_set(&b, "face", "4", &err), 0);
        b.radius = 2500;
        b.strength = 1;
        brush bump; // a steep hill on the corner first, for them to work on
        brush_defaults(&bump, BRUSH_RAISE);
        assert_int_equal(brush_set(&bump, "face", "4", &err), 0);
        bump.radius = 1800;
        bump.amount = 1500;
        bump.strength = 1;
        one_dab(w, &bump, PLACES[1].x, PLACES[1].z);
        float *before = read_faces(w);
        one_dab(w, &b, PLACES[1].x, PLACES[1].z);
        float *after = read_faces(w);
        int touched[6] = {0};
        for (size_t at = 0; at < (size_t)6 * N * N; at++)
            if (after[at] != before[at]) touched[at / ((size_t)N * N)] = 1;
        print_message("%s at the corner: faces 0 %d, 2 %d, 4 %d changed\n",
                      brush_tool_name(tools[k]), touched[0], touched[2], touched[4]);
        assert_true(touched[4] && touched[0] && touched[2]);
        assert_false(touched[1] || touched[3] || touched[5]);
        // The seam between faces 4 and 0 (face 4's last column meets face 0's first,
        // row for row): the change either side of it differs by no more than it does
        // between two neighbouring samples inside face 4.
        double seam = 0, inside = 0;
        for (int j = N - 60; j < N; j++) {
            size_t a = (size_t)4 * N * N + (size_t)j * N + (N - 1), c = (size_t)j * N;
            double d4 = after[a] - before[a], d0 = after[c] - before[c];
            double d4b = after[a - 1] - before[a - 1];
            seam = fmax(seam, fabs(d4 - d0));
            inside = fmax(inside, fabs(d4 - d4b));
        }
        print_message("  seam step %.3g m, step inside the face %.3g m\n", seam, inside);
        if (tools[k] == BRUSH_SMOOTH) assert_true(seam <= 2.0 * inside + 1e-3);
        free(before);
        free(after);
        world_close(w);
    }
}

// The height at direction d from the faces' samples (bilinear on the face it lands on).
static double height_at(const float *faces, const double d[3]) {
    int f;
    double s, t;
    world_grid_direction_face(d, &f, &s, &t);
    double u = (s + 1.0) * 0.5 * N - 0.5, v = (t + 1.0) * 0.5 * N - 0.5;
    int i = (int)floor(u), j = (int)floor(v);
    assert_true(i >= 0 && j >= 0 && i + 1 < N && j + 1 < N);
    const float *h = faces + (size_t)f * N * N;
    double a = u - i, b = v - j;
    return (h[j * N + i] * (1 - a) + h[j * N + i + 1] * a) * (1 - b) +
           (h[(j + 1) * N + i] * (1 - a) + h[(j + 1) * N + i + 1] * a) * b;
}

// The point a fraction f of the way from a to b along their great circle.
static void slerp(const double a[3], const double b[3], double f, double out[3]) {
    double ang = acos(fmin(1.0, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]));
    double wa = sin((1 - f) * ang) / sin(ang), wb = sin(f * ang) / sin(ang);
    for (int k = 0; k < 3; k++)
        out[k] = wa * a[k] + wb * b[k];
}

// The ramp on the sphere, over an edge (face 4 onto face 0) and over a corner: the
// great-circle segment between its ends at the heights there, each sample weighted by
// its angle from the segment through the falloff. The reference finds the nearest
// point of the segment by walking it, then a golden-section search.
static void test_ramp_over_the_edge_and_corner(void **state) {
    (void)state;
    for (int k = 0; k < 2; k++) {
        world *w = planet();
        og_error err;
        brush b;
        brush_defaults(&b, BRUSH_RAMP);
        assert_int_equal(brush_set(&b, "face", "4", &err), 0);
        b.radius = 1500;
        b.strength = 0.8;
        const double ai = N - 40.5, aj = k ? N - 40.5 : 0.5 * N;
        const double bi = N + 25.5, bj = k ? N + 12.5 : 0.5 * N + 12;
        float *before = read_faces(w);
        stroke *st = stroke_begin(w, &b, &err);
        if (!st) fail_msg("stroke_begin: %s", err.msg);
        if (stroke_to(st, ai * SPACING, aj * SPACING, 1.0, &err) != 0 ||
            stroke_to(st, bi * SPACING, bj * SPACING, 1.0, &err) != 0 || stroke_end(st, &err) != 0)
            fail_msg("ramp: %s", err.msg);
        float *after = read_faces(w);
        double A[3], B[3];
        direction(4, ai, aj, A);
        direction(4, bi, bj, B);
        const double ha = height_at(before, A), hb = height_at(before, B);
        double worst = 0;
        int touched[6] = {0};
        for (int f = 0; f < 6; f++)
            for (int j = 0; j < N; j++)
                for (int i = 0; i < N; i++) {
                    double d[3], p[3];
                    direction(f, i, j, d);
                    size_t at = (size_t)f * N * N + (size_t)j * N + i;
                    if (after[at] != before[at]) touched[f] = 1;
                    if (angle_between(d, A) > 0.4) { // far away: unchanged
                        if (after[at] != before[at]) fail_msg("face %d (%d, %d) changed", f, i, j);
                        continue;
                    }
                    int best = 0;
                    double best_ang = 10;
                    for (int m = 0; m <= 200; m++) {
                        slerp(A, B, m / 200.0, p);
                        double ang = angle_between(d, p);
                        if (ang < best_ang) best_ang = ang, best = m;
                    }
                    double lo = fmax(0.0, (best - 1) / 200.0), hi = fmin(1.0, (best + 1) / 200.0);
                    for (int it = 0; it < 60; it++) {
                        double m1 = hi - (hi - lo) * 0.618, m2 = lo + (hi - lo) * 0.618, p2[3];
                        slerp(A, B, m1, p);
                        slerp(A, B, m2, p2);
                        if (angle_between(d, p) < angle_between(d, p2))
                            hi = m2;
                        else
                            lo = m1;
                    }
                    const double along = 0.5 * (lo + hi);
                    slerp(A, B, along, p);
                    double t = angle_between(d, p) * RADIUS / b.radius;
                    double wgt = brush_falloff_weight(&b, (float)t) * b.strength;
                    double h = before[at];
                    double want = wgt > 0 ? h + wgt * (ha + along * (hb - ha) - h) : h;
                    worst = fmax(worst, fabs(want - after[at]));
                }
        int faces = touched[0] + touched[1] + touched[2] + touched[3] + touched[4] + touched[5];
        print_message("ramp over the %s: %d faces changed, largest difference from the sphere "
                      "reference %.3g m\n",
                      k ? "corner" : "edge", faces, worst);
        assert_int_equal(faces, k ? 3 : 2);
        assert_true(worst < 2e-3);
        free(before);
        free(after);
        world_close(w);
    }
}

// Erosion is one simulation over every face its cap reaches: thermal erosion of a
// cliff that runs across the edge between faces 4 and 0 moves material over the
// edge, conserving it (the heights' sum, cells being of nearly equal area there), and
// the change is as continuous across the seam as inside a face.
static void test_erosion_flows_across_the_edge(void **state) {
    (void)state;
    const brush_tool tools[2] = {BRUSH_THERMAL, BRUSH_HYDRAULIC};
    for (int k = 0; k < 2; k++) {
        world *w = planet_of("flat"); // the cliff alone
        og_error err;
        brush cliff; // a plateau on face 4 whose wall crosses the edge into face 0
        brush_defaults(&cliff, BRUSH_RAISE);
        assert_int_equal(brush_set(&cliff, "face", "4", &err), 0);
        assert_int_equal(brush_set(&cliff, "falloff", "constant", &err), 0);
        cliff.radius = 3000;
        cliff.amount = 400;
        cliff.strength = 1;
        one_dab(w, &cliff, (N - 40.5) * SPACING, 0.5 * N * SPACING);
        brush b;
        brush_defaults(&b, tools[k]);
        assert_int_equal(brush_set(&b, "face", "4", &err), 0);
        b.radius = 2500;
        b.strength = 1;
        float *before = read_faces(w);
        one_dab(w, &b, PLACES[0].x, PLACES[0].z);
        float *after = read_faces(w);
        double sum = 0, moved = 0, onto0 = 0;
        for (size_t at = 0; at < (size_t)6 * N * N; at++) {
            double d = (double)after[at] - (double)before[at];
            sum += d, moved += fabs(d);
            if (at < (size_t)N * N) onto0 += d;
        }
        // The eroded surface across the seam (face 4's last column against face 0's
        // first, row for row) against the step between face 4's last two columns, over
        // the rows where the cliff stood: as smooth across the edge as inside the face.
        double seam = 0, inside = 0;
        for (int j = N / 2 - 45; j < N / 2 + 45; j++) {
            size_t a = (size_t)4 * N * N + (size_t)j * N + (N - 1), c = (size_t)j * N;
            if (after[a] == before[a] && after[c] == before[c]) continue;
            seam = fmax(seam, fabs(after[a] - after[c]));
            inside = fmax(inside, fabs(after[a] - after[a - 1]));
        }
        print_message("%s across the edge: net %.3g of %.3g m moved, face 0 gains %.3g; the "
                      "eroded surface's step across the seam %.3g m, inside %.3g m\n",
                      brush_tool_name(tools[k]), sum, moved, onto0, seam, inside);
        assert_true(moved > 1.0);
        if (tools[k] == BRUSH_THERMAL) {
            assert_true(fabs(sum) < 0.02 * moved);
            assert_true(onto0 > 0.01 * moved); // material came down over the edge
        }
        assert_true(seam <= 2.0 * inside + 1e-3);
        free(before);
        free(after);
        world_close(w);
    }
}

// One undo step over three faces, and a change notification for each.
static void test_undo_and_notifications(void **state) {
    (void)state;
    world *w = planet();
    world_subscription *sub = world_events_subscribe(world_event_hub(w), NULL, NULL);
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    og_error err;
    assert_int_equal(brush_set(&b, "face", "4", &err), 0);
    b.radius = 2500;
    b.amount = 30;
    float *before = read_faces(w);
    world_event e[64];
    while (world_subscription_take(sub, e, 64) > 0) {
    }
    one_dab(w, &b, PLACES[1].x, PLACES[1].z);
    int seen[6] = {0};
    size_t n;
    while ((n = world_subscription_take(sub, e, 64)) > 0)
        for (size_t i = 0; i < n; i++)
            if (e[i].kind == WORLD_EVENT_AREA && e[i].layer == TILE_LAYER_COARSE && e[i].level == 0)
                seen[e[i].face] = 1;
    assert_true(seen[0] && seen[2] && seen[4]);
    assert_false(seen[1] || seen[3] || seen[5]);
    assert_int_equal(edit_undo(w, &err), 1);
    float *undone = read_faces(w);
    assert_memory_equal(before, undone, sizeof(float) * 6 * N * N);
    free(before);
    free(undone);
    world_events_unsubscribe(sub);
    world_close(w);
}

// A stroke may run over the edge (positions past the face are its neighbours').
static void test_stroke_over_the_edge(void **state) {
    (void)state;
    world *w = planet();
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    og_error err;
    assert_int_equal(brush_set(&b, "face", "4", &err), 0);
    b.radius = 1500;
    b.amount = 25;
    float *before = read_faces(w);
    stroke *s = stroke_begin(w, &b, &err);
    assert_non_null(s);
    assert_int_equal(stroke_to(s, (N - 40) * SPACING, 0.5 * N * SPACING, 1.0, &err), 0);
    assert_int_equal(stroke_to(s, (N + 40) * SPACING, 0.5 * N * SPACING, 1.0, &err), 0);
    assert_int_equal(stroke_end(s, &err), 0);
    float *after = read_faces(w);
    // 30 samples into face 0 (its x runs away from face 4's +s edge), mid height: raised.
    size_t at = (size_t)0 * N * N + (size_t)(N / 2) * N + 30;
    print_message("30 samples into face 0: %.2f -> %.2f m\n", before[at], after[at]);
    assert_true(after[at] - before[at] > 10);
    // Too far past the face is refused by name.
    s = stroke_begin(w, &b, &err);
    assert_non_null(s);
    assert_int_equal(stroke_to(s, 2.0 * N * SPACING, 0, 1.0, &err), -1);
    assert_non_null(strstr(err.msg, "too far past face 4"));
    stroke_cancel(s);
    free(before);
    free(after);
    world_close(w);
}

// A stamp over the corner: laid on the sphere around its centre (metres along great
// circles), so inside its inscribed circle a radial shape is the sphere reference.
static void test_stamp_over_the_corner(void **state) {
    (void)state;
    world *w = planet();
    stamp_source src;
    og_error err;
    assert_int_equal(stamp_find("gaussian", OROGEN_RESOURCE_DIR, NULL, &src, &err), 0);
    stamp_placement p;
    stamp_placement_defaults(&p);
    p.x = PLACES[1].x, p.z = PLACES[1].z, p.face = 4, p.scale = 0.5, p.intensity = 60;
    float *before = read_faces(w);
    if (stamp_apply(w, &src, &p, &err) != 0) fail_msg("stamp_apply: %s", err.msg);
    float *after = read_faces(w);
    const double half = 0.5 * STAMP_FUNCTIONAL_SAMPLES * p.scale * SPACING;
    double centre[3], worst = 0;
    direction(4, PLACES[1].x / SPACING, PLACES[1].z / SPACING, centre);
    int touched[6] = {0}, checked = 0;
    for (int f = 0; f < 6; f++)
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                size_t at = (size_t)f * N * N + (size_t)j * N + i;
                if (after[at] != before[at]) touched[f] = 1;
                double d[3];
                direction(f, i, j, d);
                double u = angle_between(d, centre) * RADIUS / half;
                if (u >= 0.98) continue; // the square's corners: not radial
                double want = before[at] + p.intensity * stamp_shape_value(src.shape, (float)u, 0);
                worst = fmax(worst, fabs(want - after[at]));
                checked++;
            }
    print_message("stamp at the corner: faces 0 %d, 2 %d, 4 %d; %d samples inside its circle, "
                  "largest difference from the sphere reference %.3g m\n",
                  touched[0], touched[2], touched[4], checked, worst);
    assert_true(touched[0] && touched[2] && touched[4]);
    assert_true(checked > 1000);
    assert_true(worst < 1e-3);
    assert_int_equal(edit_undo(w, &err), 1);
    float *undone = read_faces(w);
    assert_memory_equal(before, undone, sizeof(float) * 6 * N * N);
    free(before);
    free(after);
    free(undone);
    stamp_source_free(&src);
    world_close(w);
}

// ---- paint layers across faces ---------------------------------------------------

// All six faces' material weights (TILE_MATERIALS bytes a sample).
static uint8_t *read_materials(world *w) {
    uint8_t *m = malloc((size_t)6 * N * N * TILE_MATERIALS);
    og_error err;
    for (int f = 0; f < 6; f++) {
        layer_grid g;
        assert_int_equal(layer_grid_init(&g, world_get_params(w), TILE_LAYER_MATERIAL, f, &err), 0);
        assert_int_equal(layer_grid_read_samples(w, &g, (grid_rect){0, 0, N, N},
                                                 m + (size_t)f * N * N * TILE_MATERIALS, &err),
                         0);
    }
    return m;
}

static void command(world *w, const char *text) {
    cmd_context ctx;
    FILE *out = tmpfile();
    cmd_context_init(&ctx, w, NULL, out, OROGEN_RESOURCE_DIR);
    og_error err;
    if (cmd_run(&ctx, text, strlen(text), "test", &err) != 0) fail_msg("%s: %s", text, err.msg);
    fclose(out);
}

static brush paint_brush(float radius, float strength) {
    brush b;
    brush_defaults(&b, BRUSH_PAINT);
    og_error err;
    assert_int_equal(brush_set(&b, "face", "4", &err), 0);
    assert_int_equal(brush_set(&b, "material", "3", &err), 0); // snow
    b.radius = radius;
    b.strength = strength;
    return b;
}

// A paint layer's dab at a face's edge and at a corner: every face its cap reaches shows
// the dab as evaluated on the sphere (from the automatic ground, material 3 takes the
// coverage strength x falloff of each sample's great-circle distance, within a unit of
// 255 for rounding; the automatic channel the rest), the others nothing; and a stroke
// over the corner on a paint layer shows what the same stroke shows on a planet without
// paint layers.
static void test_paint_layer_across_faces(void **state) {
    (void)state;
    for (int k = 0; k < 2; k++) {
        world *w = planet_of("flat");
        command(w, "layer new Paint kind=paint");
        brush b = paint_brush(2500, 0.8f);
        one_dab(w, &b, PLACES[k].x, PLACES[k].z);
        uint8_t *m = read_materials(w);
        double centre[3];
        direction(4, PLACES[k].x / SPACING, PLACES[k].z / SPACING, centre);
        int touched[6] = {0}, worst = 0;
        for (int f = 0; f < 6; f++)
            for (int j = 0; j < N; j++)
                for (int i = 0; i < N; i++) {
                    double d[3];
                    direction(f, i, j, d);
                    const uint8_t *s = m + ((size_t)f * N * N + (size_t)j * N + i) * TILE_MATERIALS;
                    double t = angle_between(d, centre) * RADIUS / b.radius;
                    double c = b.strength * brush_falloff_weight(&b, (float)t);
                    int want = (int)lround(255.0 * c), off = abs(s[3] - want);
                    int rest = 0;
                    for (int ch = 1; ch < TILE_MATERIALS; ch++)
                        rest += ch == 3 ? 0 : s[ch];
                    if (rest || s[0] + s[3] != 255) off = 255;
                    worst = off > worst ? off : worst;
                    if (s[3]) touched[f] = 1;
                }
        int faces = 0;
        for (int f = 0; f < 6; f++)
            faces += touched[f];
        print_message("paint layer dab at the %s: %d faces painted, largest difference from the "
                      "sphere reference %d of 255\n",
                      PLACES[k].name, faces, worst);
        assert_int_equal(faces, PLACES[k].faces);
        assert_true(worst <= 1);
        free(m);
        world_close(w);
    }
    // A stroke over the corner: a paint layer's composite is what painting the ground shows.
    world *layered = planet_of("flat"), *single = planet_of("flat");
    command(layered, "layer new Paint kind=paint");
    brush b = paint_brush(1500, 0.6f);
    og_error err;
    for (world *w = layered; w; w = w == layered ? single : NULL) {
        stroke *s = stroke_begin(w, &b, &err);
        assert_non_null(s);
        assert_int_equal(stroke_to(s, (N - 40) * SPACING, (N - 10) * SPACING, 1.0, &err), 0);
        assert_int_equal(stroke_to(s, (N + 30) * SPACING, (N + 25) * SPACING, 1.0, &err), 0);
        assert_int_equal(stroke_end(s, &err), 0);
    }
    uint8_t *a = read_materials(layered), *c = read_materials(single);
    int faces = 0;
    for (int f = 0; f < 6; f++) {
        const uint8_t *face = a + (size_t)f * N * N * TILE_MATERIALS;
        for (size_t k = 0; k < (size_t)N * N; k++)
            if (face[k * TILE_MATERIALS + 3]) {
                faces++;
                break;
            }
    }
    assert_int_equal(faces, 3);
    assert_memory_equal(a, c, (size_t)6 * N * N * TILE_MATERIALS);
    free(a);
    free(c);
    world_close(layered);
    world_close(single);
}

// A paint layer's slope mask reads the heights across face edges: over a raised dab at a
// corner (a flat planet, so the dab's profile is the only slope: its slope known in
// closed form from the falloff), a paint layer masked to slopes over 5 degrees shows its
// paint where the sphere's slope is over 6.5 and none under 2.5 (on the dab's top, and
// past its rim where the paint still reaches), on samples next to the edges as everywhere (a mask
// reading a face's edge samples twice would halve the slope there).
static void test_paint_mask_across_faces(void **state) {
    (void)state;
    world *w = planet_of("flat");
    brush raise;
    brush_defaults(&raise, BRUSH_RAISE);
    og_error err;
    assert_int_equal(brush_set(&raise, "face", "4", &err), 0);
    raise.radius = 2500;
    raise.strength = 1;
    raise.amount = 400;
    one_dab(w, &raise, PLACES[1].x, PLACES[1].z);
    command(w, "layer new Snow kind=paint; layer mask Snow slope=5,90,1");
    brush b = paint_brush(4000, 1.0f);
    one_dab(w, &b, PLACES[1].x, PLACES[1].z);
    uint8_t *m = read_materials(w);
    double centre[3];
    direction(4, PLACES[1].x / SPACING, PLACES[1].z / SPACING, centre);
    int steep = 0, gentle = 0, steep_edge = 0, gentle_edge = 0, wrong = 0, wrong_edge = 0;
    for (int f = 0; f < 6; f++)
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                double d[3];
                direction(f, i, j, d);
                double t = angle_between(d, centre) * RADIUS / raise.radius;
                if (t > 0.95 && t < 1.05) continue; // the dab's rim
                const float e = 1e-3f;
                double dh = t >= 1.0 ? 0.0 // flat ground past the dab
                                     : raise.amount *
                                           (brush_falloff_weight(&raise, (float)t + e) -
                                            brush_falloff_weight(&raise, (float)t - e)) /
                                           (2.0 * e) / raise.radius;
                double slope = atan(fabs(dh)) * 180.0 / M_PI;
                int edge = i < 2 || j < 2 || i >= N - 2 || j >= N - 2;
                const uint8_t *s = m + ((size_t)f * N * N + (size_t)j * N + i) * TILE_MATERIALS;
                double paint_t = angle_between(d, centre) * RADIUS / b.radius;
                int painted = s[3] > 0, full = brush_falloff_weight(&b, (float)paint_t) > 0.02;
                if (!full) continue; // the paint does not reach
                if (slope > 6.5) {
                    steep++, steep_edge += edge;
                    if (!painted) wrong++, wrong_edge += edge;
                } else if (slope < 2.5) {
                    gentle++, gentle_edge += edge;
                    if (painted) wrong++, wrong_edge += edge;
                }
            }
    print_message("slope mask over the corner: %d steep samples (%d by an edge), %d gentle (%d "
                  "by an edge), %d wrong (%d by an edge)\n",
                  steep, steep_edge, gentle, gentle_edge, wrong, wrong_edge);
    assert_true(steep_edge > 100 && gentle_edge > 100);
    assert_int_equal(wrong, 0);
    free(m);
    world_close(w);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_raise),
        cmocka_unit_test(test_lower),
        cmocka_unit_test(test_set),
        cmocka_unit_test(test_flatten),
        cmocka_unit_test(test_terrace),
        cmocka_unit_test(test_noise),
        cmocka_unit_test(test_neighbourhood_tools_cross),
        cmocka_unit_test(test_erosion_flows_across_the_edge),
        cmocka_unit_test(test_ramp_over_the_edge_and_corner),
        cmocka_unit_test(test_undo_and_notifications),
        cmocka_unit_test(test_stroke_over_the_edge),
        cmocka_unit_test(test_stamp_over_the_corner),
        cmocka_unit_test(test_paint_layer_across_faces),
        cmocka_unit_test(test_paint_mask_across_faces),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
