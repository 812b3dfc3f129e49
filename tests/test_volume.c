// The volume layer and its tools: exact shapes, edits across brick edges equal to the
// same edit on one plain array, undo/redo, save/load, memory that follows the edits
// (also 10^6 m from the origin), edits that stay put when the heightfield changes,
// and refusals that change nothing.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "editor/edit/edit.h"
#include "editor/tools/brush.h"
#include "editor/tools/stroke.h"
#include "editor/tools/volume_brush.h"
#include "editor/tools/volume_shapes.h"
#include "editor/world/volume_grid.h"
#include "support/test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void silent(void *user, const char *message) {
    (void)user, (void)message;
}

static world_params flat_params(int64_t size, int volume_ratio) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.generator = GEN_FLAT;
    p.base_height = 0;
    p.spacing = 1;
    p.size = size;
    p.volume_ratio = volume_ratio;
    return p;
}

static world *open_world(const world_params *p) {
    world_settings s = {.cache_budget_bytes = (size_t)512 << 20, .workers = 2, .warn = silent};
    og_error err;
    world *w = world_create(p, &s, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    return w;
}

static brush tool(brush_tool t, double radius, brush_falloff falloff) {
    brush b;
    brush_defaults(&b, t);
    b.radius = radius;
    b.falloff = falloff;
    return b;
}

static void apply(world *w, const brush *b, const double (*pts)[3], size_t n) {
    og_error err;
    if (volume_brush_apply(w, b, pts, NULL, n, &err) != 0) fail_msg("%s", err.msg);
}

static void pair_at(world *w, int64_t i, int64_t j, int64_t k, int16_t out[2]) {
    tile_key key = volume_brick_key(i, j, k);
    tile_view v;
    og_error err;
    if (tile_cache_acquire(world_cache(w), key, &v, &err) != 0) fail_msg("%s", err.msg);
    const int16_t *p = (const int16_t *)v.data + 2 * volume_brick_offset(key, i, j, k);
    out[0] = p[0];
    out[1] = p[1];
    tile_cache_release(world_cache(w), &v);
}

static double vsample(world *w, double x, double y, double z) {
    double p[3] = {x, y, z}, d = 0;
    og_error err;
    if (volume_sample(w, p, &d, &err) != 0) fail_msg("vsample: %s", err.msg);
    return d;
}

// ---------------------------------------------------------------------------
// A plain-array reference of the volume tools (the formulas of volume_brush.h)
// ---------------------------------------------------------------------------

typedef struct ref_grid {
    volume_box box;
    double voxel;
    int16_t *pairs; // 2 per voxel, x fastest, then z, then y
} ref_grid;

static ref_grid ref_create(volume_box box, double voxel) {
    ref_grid r = {box, voxel, NULL};
    size_t n = (size_t)volume_box_voxels(box);
    r.pairs = malloc(2 * n * sizeof *r.pairs);
    assert_non_null(r.pairs);
    for (size_t i = 0; i < 2 * n; i++)
        r.pairs[i] = VOLUME_FAR;
    return r;
}

static int16_t *ref_pair(ref_grid *r, int64_t i, int64_t j, int64_t k) {
    volume_box b = r->box;
    return r->pairs + 2 * (((j - b.j0) * (b.k1 - b.k0) + (k - b.k0)) * (b.i1 - b.i0) + (i - b.i0));
}

static float ref_smin(float a, float b, float k) {
    if (k <= 0) return fminf(a, b);
    float h = fmaxf(k - fabsf(a - b), 0.0f) / k;
    return fminf(a, b) - h * h * k * 0.25f;
}

static double ref_capsule(const double p[3], const double (*pts)[3], size_t n, double radius) {
    double best = INFINITY;
    for (size_t s = 0; s < (n > 1 ? n - 1 : 1); s++) {
        const double *a = pts[s], *c = pts[n > 1 ? s + 1 : s];
        double ab[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
        double len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
        double t = len2 > 0 ? (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / len2 : 0;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        double d[3] = {ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
        best = fmin(best, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - radius);
    }
    return best;
}

// fill / carve on the reference.
static void ref_shape(ref_grid *r, const brush *b, const double (*pts)[3], size_t n) {
    float k = b->falloff == FALLOFF_CONSTANT
                  ? 0.0f
                  : (float)(b->radius * (1.0 - brush_falloff_weight(b, 0.5f)) * 0.5);
    double margin = VOLUME_EXACT_VOXELS * r->voxel + k;
    for (int64_t j = r->box.j0; j < r->box.j1; j++)
        for (int64_t kk = r->box.k0; kk < r->box.k1; kk++)
            for (int64_t i = r->box.i0; i < r->box.i1; i++) {
                double p[3] = {i * r->voxel, j * r->voxel, kk * r->voxel};
                double d = ref_capsule(p, pts, n, b->radius * b->strength);
                if (d > margin) continue;
                int16_t *pair = ref_pair(r, i, j, kk);
                float add = volume_to_metres(pair[0], r->voxel);
                float sub = volume_to_metres(pair[1], r->voxel);
                if (b->tool == BRUSH_FILL) {
                    add = ref_smin(add, (float)d, k);
                    sub = -ref_smin(-sub, (float)d, k);
                } else {
                    sub = ref_smin(sub, (float)d, k);
                    add = -ref_smin(-add, (float)d, k);
                }
                pair[0] = volume_from_metres(add, r->voxel);
                pair[1] = volume_from_metres(sub, r->voxel);
            }
}

// Every voxel of the reference's box equals the world's.
static void assert_matches_reference(world *w, ref_grid *r) {
    long long differ = 0, checked = 0;
    for (int64_t j = r->box.j0; j < r->box.j1; j++)
        for (int64_t k = r->box.k0; k < r->box.k1; k++)
            for (int64_t i = r->box.i0; i < r->box.i1; i++) {
                int16_t got[2];
                pair_at(w, i, j, k, got);
                const int16_t *want = ref_pair(r, i, j, k);
                if (got[0] != want[0] || got[1] != want[1]) {
                    if (differ < 5)
                        print_error("voxel (%lld,%lld,%lld): got %d %d, want %d %d\n", (long long)i,
                                    (long long)j, (long long)k, got[0], got[1], want[0], want[1]);
                    differ++;
                }
                checked++;
            }
    print_message("%lld voxels compared with the plain-array reference\n", checked);
    assert_int_equal(differ, 0);
}

// ---------------------------------------------------------------------------
// Tests
// ---------------------------------------------------------------------------

// A ball of fill floating in the air: the signed distance is exact at its centre and
// surface, and the seam-crossing edit (centre at a brick corner) equals the reference.
static void test_fill_ball_across_brick_corner(void **state) {
    (void)state;
    world_params p = flat_params(0, 1);
    world *w = open_world(&p);
    brush b = tool(BRUSH_FILL, 6, FALLOFF_CONSTANT);
    // Brick corner (32, 64, 32) voxels: the ball spans 8 bricks.
    const double c[1][3] = {{31.6, 63.7, 32.2}};
    apply(w, &b, c, 1);
    assert_float_equal(vsample(w, 31.6 + 3, 63.7, 32.2), -3.0,
                       0.1); // trilinear: a tenth of a voxel
    assert_float_equal(vsample(w, 31.6, 63.7 - 4, 32.2), -2.0, 0.1);
    assert_float_equal(vsample(w, 31.6 + 6, 63.7, 32.2), 0.0, 0.1);
    assert_float_equal(vsample(w, 31.6, 63.7 + 8, 32.2), 2.0, 0.1);
    // Far above the ground and away from the ball: the ground's distance.
    assert_float_equal(vsample(w, 200, 50, 200), 50.0, 1e-3);

    volume_box box = {16, 48, 16, 48, 80, 48};
    ref_grid r = ref_create(box, 1.0);
    ref_shape(&r, &b, c, 1);
    assert_matches_reference(w, &r);
    free(r.pairs);
    world_close(w);
}

// A carve stroke (capsules) through several bricks, then a fill with a smooth seam
// and finer voxels: equal to the reference voxel for voxel.
static void test_stroke_and_blend_equal_plain_array(void **state) {
    (void)state;
    world_params p = flat_params(0, 2); // voxel 0.5 m
    world *w = open_world(&p);
    brush carve = tool(BRUSH_CARVE, 3, FALLOFF_CONSTANT);
    const double path[3][3] = {{2, -4, 3}, {20, -6, 12}, {31, -2, 40}};
    apply(w, &carve, path, 3);
    brush fill = tool(BRUSH_FILL, 4, FALLOFF_SMOOTH);
    fill.strength = 0.75;
    const double dab[1][3] = {{17, -5, 15}};
    apply(w, &fill, dab, 1);

    volume_box box = {-10, -30, -10, 80, 10, 100};
    ref_grid r = ref_create(box, 0.5);
    ref_shape(&r, &carve, path, 3);
    ref_shape(&r, &fill, dab, 1);
    assert_matches_reference(w, &r);
    free(r.pairs);

    // Inside the tunnel is air, in the filled ball solid, the ground elsewhere solid.
    assert_true(vsample(w, 2, -4, 3) > 2.5);
    assert_true(vsample(w, 31, -2, 40) > 1.5);
    assert_true(vsample(w, 17, -5, 15) < -2.5);
    assert_true(vsample(w, 60, -5, 60) < -4.5);
    world_close(w);
}

static uint64_t volume_digest(world *w) {
    tile_key *keys;
    size_t n;
    og_error err;
    if (volume_list_bricks(w, &keys, &n, &err) != 0) fail_msg("%s", err.msg);
    uint64_t h = 1469598103934665603ULL;
    for (size_t b = 0; b < n; b++) {
        tile_view v;
        if (tile_cache_acquire(world_cache(w), keys[b], &v, &err) != 0) fail_msg("%s", err.msg);
        const int16_t *d = v.data;
        int pristine = 1;
        for (size_t i = 0; i < 2 * (size_t)TILE_SAMPLES && pristine; i++)
            pristine = d[i] == VOLUME_FAR;
        if (!pristine) { // bricks undone back to no edit count as absent
            const unsigned char *bytes = v.data;
            for (size_t i = 0; i < sizeof keys[b]; i++)
                h = (h ^ ((const unsigned char *)&keys[b])[i]) * 1099511628211ULL;
            for (size_t i = 0; i < tile_layer_bytes(TILE_LAYER_VOLUME); i++)
                h = (h ^ bytes[i]) * 1099511628211ULL;
        }
        tile_cache_release(world_cache(w), &v);
    }
    free(keys);
    return h;
}

static void test_undo_redo_exact(void **state) {
    (void)state;
    world_params p = flat_params(0, 1);
    world *w = open_world(&p);
    uint64_t empty = volume_digest(w);
    brush carve = tool(BRUSH_CARVE, 5, FALLOFF_SMOOTH);
    const double a[2][3] = {{0, 0, 0}, {40, -3, 5}};
    apply(w, &carve, a, 2);
    uint64_t one = volume_digest(w);
    brush smooth = tool(BRUSH_VSMOOTH, 4, FALLOFF_SMOOTH);
    smooth.strength = 1;
    const double s[2][3] = {{10, 0, 1}, {30, -1, 4}};
    apply(w, &smooth, s, 2);
    uint64_t two = volume_digest(w);
    assert_true(empty != one && one != two);
    og_error err;
    assert_int_equal(edit_undo(w, &err), 1);
    assert_true(volume_digest(w) == one);
    assert_int_equal(edit_undo(w, &err), 1);
    assert_true(volume_digest(w) == empty);
    assert_int_equal(edit_redo(w, &err), 1);
    assert_true(volume_digest(w) == one);
    assert_int_equal(edit_redo(w, &err), 1);
    assert_true(volume_digest(w) == two);
    world_close(w);
}

static void test_save_load_round_trip(void **state) {
    (void)state;
    const char *dir = test_tmpdir("volume-save");
    char path[1024];
    snprintf(path, sizeof path, "%s/caves.world", dir);
    world_params p = flat_params(0, 2);
    world *w = open_world(&p);
    brush carve = tool(BRUSH_CARVE, 4, FALLOFF_CONSTANT);
    const double a[3][3] = {{5, -2, 5}, {25, -8, 9}, {40, -3, 30}};
    apply(w, &carve, a, 3);
    brush fill = tool(BRUSH_FILL, 3, FALLOFF_LINEAR);
    const double arch[2][3] = {{60, 4, 60}, {75, 6, 62}};
    apply(w, &fill, arch, 2);
    uint64_t before = volume_digest(w);
    double cave = vsample(w, 25, -8, 9), arch_d = vsample(w, 68, 5, 61);
    og_error err;
    if (world_save(w, path, 0, &err) != 0) fail_msg("save: %s", err.msg);
    world_close(w);

    world_settings s = {.workers = 2, .warn = silent};
    int errors = 0;
    w = world_load(path, &s, &errors, &err);
    if (!w) fail_msg("load: %s", err.msg);
    assert_int_equal(errors, 0);
    assert_int_equal(world_get_params(w)->volume_ratio, 2);
    assert_true(volume_digest(w) == before);
    assert_float_equal(vsample(w, 25, -8, 9), cave, 0);
    assert_float_equal(vsample(w, 68, 5, 61), arch_d, 0);
    assert_true(cave > 3.9 && arch_d < -2.0);
    assert_true(tile_store_count(world_store(w), TILE_LAYER_VOLUME) > 0);
    world_close(w);
    test_rmtree(dir);
}

static size_t last_step_tiles(world *w) {
    history *h = world_history(w);
    const history_step *s = history_at(h, history_position(h) - 1);
    return s->tile_count;
}

// The same edit 10^6 m from the origin touches as many bricks as at the origin, and
// the world holds nothing but those.
static void test_memory_follows_edits(void **state) {
    (void)state;
    world_params p = flat_params(0, 1);
    world *w = open_world(&p);
    brush carve = tool(BRUSH_CARVE, 8, FALLOFF_SMOOTH);
    const double near[2][3] = {{3, -5, 4}, {30, -9, 7}};
    apply(w, &carve, near, 2);
    size_t tiles_near = last_step_tiles(w);
    const double far[2][3] = {{1e6 + 3, -5, 1e6 + 4}, {1e6 + 30, -9, 1e6 + 7}};
    apply(w, &carve, far, 2);
    size_t tiles_far = last_step_tiles(w);
    print_message("bricks: %zu near the origin, %zu at 10^6 m\n", tiles_near, tiles_far);
    assert_int_equal(tiles_near, tiles_far);
    assert_true(tiles_near <= 12); // 3 x 2 x 2 bricks around the capsule
    tile_key *keys;
    size_t n;
    og_error err;
    assert_int_equal(volume_list_bricks(w, &keys, &n, &err), 0);
    assert_int_equal(n, tiles_near + tiles_far);
    free(keys);
    assert_float_equal(vsample(w, 1e6 + 30, -9, 1e6 + 7), vsample(w, 30, -9, 7), 1e-3);
    world_close(w);
}

// Volume edits are in world space: raising the ground over a cave leaves the cave.
static void test_heightfield_edit_keeps_volume_in_place(void **state) {
    (void)state;
    world_params p = flat_params(0, 1);
    world *w = open_world(&p);
    brush carve = tool(BRUSH_CARVE, 4, FALLOFF_CONSTANT);
    const double cave[1][3] = {{50, -10, 50}};
    apply(w, &carve, cave, 1);
    assert_float_equal(vsample(w, 50, -10, 50), 4.0, 0.02);
    assert_true(vsample(w, 50, 3, 50) > 0); // air above the ground

    brush raise;
    brush_defaults(&raise, BRUSH_RAISE);
    raise.radius = 30;
    raise.amount = 20;
    raise.strength = 1;
    raise.falloff = FALLOFF_CONSTANT;
    og_error err;
    stroke *s = stroke_begin(w, &raise, &err);
    assert_non_null(s);
    assert_int_equal(stroke_to(s, 50, 50, 1.0, &err), 0);
    assert_int_equal(stroke_end(s, &err), 0);
    assert_true(vsample(w, 50, 3, 50) < 0);                 // now inside the ground
    assert_float_equal(vsample(w, 50, -10, 50), 4.0, 0.02); // the cave is still there
    assert_true(vsample(w, 50, -10 + 6, 50) < 0);           // solid above the cave
    world_close(w);
}

// vflatten makes a level floor; vsmooth wears a spike down.
// A stroke laid point by point (the viewport's drag) equals the same points in one call.
static void test_stroke_point_by_point(void **state) {
    (void)state;
    world_params p = flat_params(0, 1);
    world *a = open_world(&p), *b = open_world(&p);
    brush carve = tool(BRUSH_CARVE, 4, FALLOFF_CONSTANT);
    const double path[4][3] = {{3, -2, 3}, {15, -4, 9}, {30, -3, 12}, {42, 0, 30}};
    apply(a, &carve, path, 4);
    og_error err;
    stroke *s = stroke_begin(b, &carve, &err);
    assert_non_null(s);
    for (int i = 0; i < 4; i++)
        assert_int_equal(stroke_to_3d(s, path[i], 1.0, &err), 0);
    assert_int_equal(stroke_end(s, &err), 0);
    assert_true(volume_digest(a) == volume_digest(b));
    assert_int_equal(history_count(world_history(b)), 1);
    world_close(a);
    world_close(b);
}

static void test_flatten_and_smooth(void **state) {
    (void)state;
    world_params p = flat_params(0, 1);
    world *w = open_world(&p);
    brush flat = tool(BRUSH_VFLATTEN, 6, FALLOFF_CONSTANT);
    flat.strength = 1;
    flat.has_height = 1;
    flat.height = 3;
    const double at[1][3] = {{20, 1, 20}};
    apply(w, &flat, at, 1);
    assert_float_equal(vsample(w, 20, 2, 20), -1.0, 0.02); // solid up to 3 m now
    assert_float_equal(vsample(w, 20, 4, 20), 1.0, 0.02);

    brush fill = tool(BRUSH_FILL, 1.5, FALLOFF_CONSTANT);
    const double spike[2][3] = {{60, 0, 60}, {60, 6, 60}};
    apply(w, &fill, spike, 2);
    assert_true(vsample(w, 60, 6.5, 60) < 0);
    brush smooth = tool(BRUSH_VSMOOTH, 5, FALLOFF_SMOOTH);
    smooth.strength = 1;
    const double s[1][3] = {{60, 6, 60}};
    for (int i = 0; i < 4; i++)
        apply(w, &smooth, s, 1);
    assert_true(vsample(w, 60, 6.5, 60) > 0); // the tip is worn away
    world_close(w);
}

// The shape generators: an arch stands over air, a tunnel follows its radius profile, a
// hoodoo's cap overhangs its column, an overhang juts out over the lower side of a cliff.
static void test_shapes(void **state) {
    (void)state;
    world_params p = flat_params(0, 1);
    world *w = open_world(&p);
    og_error err;
    const double a[3] = {0, 0, 0}, b[3] = {40, 0, 0};
    assert_int_equal(volume_arch(w, a, b, 20, 4, &err), 0);
    assert_true(vsample(w, 20, 20, 0) < -1.5); // the apex is rock
    assert_true(vsample(w, 20, 10, 0) > 5);    // under it, air
    assert_true(vsample(w, 3, 4, 0) < 0);      // a foot

    const double path[3][3] = {{100, -20, 0}, {130, -20, 0}, {160, -20, 0}};
    const double radius[3] = {3, 8, 3};
    assert_int_equal(volume_tunnel(w, path, radius, 3, &err), 0);
    assert_float_equal(vsample(w, 130, -20 + 7, 0), 1.0, 0.1); // 1 m inside the 8 m bore
    assert_float_equal(vsample(w, 100, -20 + 2, 0), 1.0, 0.1); // 1 m inside the 3 m bore
    assert_true(vsample(w, 100, -20 + 4, 0) < 0);

    const double foot[3] = {200, 0, 0};
    assert_int_equal(volume_spire(w, foot, 30, 5, 0.3, 6, &err), 0);
    assert_true(vsample(w, 200, 15, 0) < -2);                       // the column
    assert_true(vsample(w, 205, 31, 0) < 0);                        // the cap reaches out 5 m...
    assert_true(vsample(w, 205, 25, 0) > 1);                        // ...over air
    assert_int_equal(volume_spire(w, foot, 30, 5, 2, 0, &err), -1); // taper > 1
    assert_non_null(strstr(err.msg, "taper"));

    // A 20 m plateau of radius 30 at (300, 0); its cliff faces +x at x = 330.
    brush set;
    brush_defaults(&set, BRUSH_SET);
    set.radius = 30, set.strength = 1, set.falloff = FALLOFF_CONSTANT;
    set.has_height = 1, set.height = 20;
    stroke *st = stroke_begin(w, &set, &err);
    assert_non_null(st);
    assert_int_equal(stroke_to(st, 300, 0, 1.0, &err), 0);
    assert_int_equal(stroke_end(st, &err), 0);
    assert_true(vsample(w, 335, 18, 0) > 0); // air beyond the cliff
    assert_int_equal(volume_overhang(w, 326, -8, 326, 8, 10, 4, &err), 0);
    assert_true(vsample(w, 334, 18, 0) < 0); // the shelf, out past the cliff
    assert_true(vsample(w, 334, 12, 0) > 0); // and air under it
    size_t steps = history_count(world_history(w));
    assert_int_equal(steps, 5); // arch, tunnel, spire, set stroke, overhang; the bad spire: none
    world_close(w);
}

static void test_refusals_change_nothing(void **state) {
    (void)state;
    world_params p = flat_params(512, 1);
    world *w = open_world(&p);
    history *h = world_history(w);
    og_error err;
    brush fill = tool(BRUSH_FILL, 5, FALLOFF_CONSTANT);
    const double nan_point[1][3] = {{NAN, 0, 0}};
    assert_int_equal(volume_brush_apply(w, &fill, nan_point, NULL, 1, &err), -1);
    assert_non_null(strstr(err.msg, "finite"));
    const double outside[1][3] = {{-5, 0, 20}};
    assert_int_equal(volume_brush_apply(w, &fill, outside, NULL, 1, &err), -1);
    assert_non_null(strstr(err.msg, "outside the world"));
    const double ok[1][3] = {{20, 0, 20}};
    double bad_pressure = 2;
    assert_int_equal(volume_brush_apply(w, &fill, ok, &bad_pressure, 1, &err), -1);
    assert_non_null(strstr(err.msg, "pressure"));
    brush huge = tool(BRUSH_FILL, 5000, FALLOFF_CONSTANT);
    assert_int_equal(volume_brush_apply(w, &huge, ok, NULL, 1, &err), -1);
    assert_non_null(strstr(err.msg, "voxels"));
    brush raise;
    brush_defaults(&raise, BRUSH_RAISE);
    assert_int_equal(volume_brush_apply(w, &raise, ok, NULL, 1, &err), -1);
    assert_non_null(strstr(err.msg, "not a volume tool"));
    assert_int_equal(volume_brush_apply(w, &fill, ok, NULL, 0, &err), -1);
    // A typo'd coordinate: a piece far too long for the cache, or for vsmooth's dabs.
    world_params open_p = flat_params(0, 1);
    world *wide = open_world(&open_p);
    const double diagonal[2][3] = {{0, 0, 0}, {3e6, 0, 3e6}};
    assert_int_equal(volume_brush_apply(wide, &fill, diagonal, NULL, 2, &err), -1);
    assert_non_null(strstr(err.msg, "bricks"));
    brush smooth = tool(BRUSH_VSMOOTH, 2, FALLOFF_SMOOTH);
    const double long_way[2][3] = {{0, 0, 0}, {1e6, 0, 0}};
    assert_int_equal(volume_brush_apply(wide, &smooth, long_way, NULL, 2, &err), -1);
    assert_non_null(strstr(err.msg, "dabs"));
    assert_int_equal(history_count(world_history(wide)), 0);
    world_close(wide);
    // The voxel size cannot change under volume edits (they would move and stretch).
    world *edited = open_world(&p);
    const double cave[1][3] = {{20, -5, 20}};
    brush carve = tool(BRUSH_CARVE, 4, FALLOFF_CONSTANT);
    apply(edited, &carve, cave, 1);
    world_params finer = p;
    finer.volume_ratio = 2;
    assert_int_equal(edit_generate(edited, &finer, &err), -1);
    assert_non_null(strstr(err.msg, "volume edits"));
    assert_int_equal(world_get_params(edited)->volume_ratio, 1);
    assert_int_equal(edit_undo(edited, &err), 1); // no edit left: now it may
    assert_int_equal(edit_generate(edited, &finer, &err), 0);
    world_close(edited);
    // A small cache cannot hold a big dab's bricks.
    world_settings small = {.cache_budget_bytes = (size_t)8 << 20, .workers = 2, .warn = silent};
    world *tight = world_create(&p, &small, &err);
    assert_non_null(tight);
    brush big = tool(BRUSH_FILL, 200, FALLOFF_CONSTANT);
    const double mid[1][3] = {{256, 0, 256}};
    assert_int_equal(volume_brush_apply(tight, &big, mid, NULL, 1, &err), -1);
    assert_non_null(strstr(err.msg, "MiB"));
    assert_int_equal(history_count(world_history(tight)), 0);
    world_close(tight);
    // A stroke of a volume tool refuses 2D points (and a 2D tool's, 3D points); planets
    // refuse volume edits.
    stroke *s = stroke_begin(w, &fill, &err);
    assert_non_null(s);
    assert_int_equal(stroke_to(s, 20, 20, 1.0, &err), -1);
    assert_non_null(strstr(err.msg, "X Y Z"));
    stroke_cancel(s);
    brush raise2;
    brush_defaults(&raise2, BRUSH_RAISE);
    s = stroke_begin(w, &raise2, &err);
    assert_non_null(s);
    assert_int_equal(stroke_to_3d(s, ok[0], 1.0, &err), -1);
    assert_non_null(strstr(err.msg, "X Z"));
    stroke_cancel(s);
    assert_int_equal(history_count(h), 0);
    assert_false(world_is_modified(w));
    world_close(w);

    world_params planet;
    world_params_default(&planet, WORLD_PLANET);
    world *pw = open_world(&planet);
    assert_int_equal(volume_brush_apply(pw, &fill, ok, NULL, 1, &err), -1);
    assert_non_null(strstr(err.msg, "planet"));
    world_close(pw);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fill_ball_across_brick_corner),
        cmocka_unit_test(test_stroke_and_blend_equal_plain_array),
        cmocka_unit_test(test_undo_redo_exact),
        cmocka_unit_test(test_save_load_round_trip),
        cmocka_unit_test(test_memory_follows_edits),
        cmocka_unit_test(test_heightfield_edit_keeps_volume_in_place),
        cmocka_unit_test(test_stroke_point_by_point),
        cmocka_unit_test(test_flatten_and_smooth),
        cmocka_unit_test(test_shapes),
        cmocka_unit_test(test_refusals_change_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
