// Material rules on a planet (issue 30): the rules lay over the planet's own look, so a
// rule changes the view where it applies and nowhere else. Over the Earth-like preset's
// mountains from 100 km, a rule "sand above T" (T: the frame's median land height, a hard
// edge; the climate puts no sand on mountains) must change no pixel of ground under
// T - 40 m (by more than a level: near_pixel), nor the sea or the sky, and nearly all the
// ground above T + 40 m; undoing it brings the frame back (a few dozen pixels a level
// off, as after any redraw of changed parameters). Heights come from the depth buffer.
#include "editor/edit/edit.h"
#include "editor/layers/material_rules.h"
#include "editor/params/planet_presets.h"
#include "editor/world/world.h"
#include "io/image_read.h"
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

#define W 256
#define H 144
#define MARGIN 40.0 // metres either side of the rule's edge left unjudged

static gl_headless *ctx;
static gl_target target;
static terrain_renderer *renderer;
static world *earth;

static void quiet(void *u, const char *m) {
    (void)u, (void)m;
}

static int setup(void **state) {
    (void)state;
    og_error err = {{0}};
    if (!(ctx = gl_headless_create(&err)) || gl_require_features(&err) != 0 ||
        gl_target_create(&target, W, H, &err) != 0 ||
        !(renderer = terrain_renderer_create(OROGEN_RESOURCE_DIR, &err))) {
        fprintf(stderr, "test_planet_rules: %s\n", err.msg);
        return -1;
    }
    terrain_renderer_set_view_size(renderer, W, H);
    world_params wp;
    world_params_default(&wp, WORLD_PLANET);
    if (planet_preset_apply(&wp, "earth", &err) != 0) return -1;
    world_settings ws = {.cache_budget_bytes = (size_t)1 << 30, .workers = 2, .warn = quiet};
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

// Draws the pose once every chunk wanted is there and reads back its colours and, when
// height is given, the height above the datum of the ground each pixel shows (NAN: sky).
static void render(const camera *c, unsigned char *rgb, double *height) {
    og_error err = {{0}};
    render_settings s;
    render_settings_default(&s);
    const double t0 = now_s();
    int rc;
    while ((rc = terrain_renderer_update(renderer, earth, c, &s, &err)) == 0 && now_s() - t0 < 60) {
        struct timespec nap = {0, 1000000};
        nanosleep(&nap, NULL);
    }
    assert_true(rc >= 0);
    glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
    assert_int_equal(terrain_renderer_draw(renderer, earth, c, &s, NULL, W, H, &err), 0);
    assert_int_equal(gl_target_read_rgb(&target, rgb, &err), 0); // top row first
    if (!height) return;
    static float depth[W * H];
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, depth); // bottom row first
    double f[3], rt[3], up[3];
    planet_camera_basis(c, f, rt, up);
    const double radius = world_get_params(earth)->radius;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float d = depth[(H - 1 - y) * W + x]; // reversed z: 0 is infinitely far
            height[y * W + x] = NAN;
            if (!(d > 0.0f)) continue;
            double dir[3], pos[3];
            camera_basis_ray(c, rt, up, f, (double)W / H, (x + 0.5) / W, (y + 0.5) / H, dir);
            const double along = c->near_m / d / (dir[0] * f[0] + dir[1] * f[1] + dir[2] * f[2]);
            for (int a = 0; a < 3; a++)
                pos[a] = c->pos[a] + dir[a] * along;
            height[y * W + x] = sqrt(pos[0] * pos[0] + pos[1] * pos[1] + pos[2] * pos[2]) - radius;
        }
}

static int by_value(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int same_pixel(const unsigned char *a, const unsigned char *b, int i) {
    return !memcmp(a + 3 * i, b + 3 * i, 3);
}

// Within one level per channel: the rules' program is another compilation of the same
// shading, and llvmpipe may order its arithmetic otherwise (a dozen pixels of 36,864 are
// one level off; a rule's colour is tens of levels away).
static int near_pixel(const unsigned char *a, const unsigned char *b, int i) {
    for (int k = 0; k < 3; k++)
        if (abs(a[3 * i + k] - b[3 * i + k]) > 1) return 0;
    return 1;
}

static void test_rule_changes_only_where_it_applies(void **state) {
    (void)state;
    camera c;
    camera_default(&c);
    const world_params *p = world_get_params(earth);
    planet_position(21.0, 5.7, p->radius + 1e5, c.pos);
    c.yaw = 0, c.pitch = -25;
    static unsigned char before[W * H * 3], ruled[W * H * 3], undone[W * H * 3];
    static double height[W * H], land[W * H];
    render(&c, before, height);
    const double sea = world_params_ocean_height(p);
    int n = 0;
    for (int i = 0; i < W * H; i++)
        if (height[i] > sea + 1.0) land[n++] = height[i];
    assert_true(n > W * H / 4);
    qsort(land, (size_t)n, sizeof land[0], by_value);
    const double t = land[n / 2];

    material_rules rules = p->material_rules;
    assert_int_equal(rules.count, 0); // a planet's default: its own look
    char text[128];
    snprintf(text, sizeof text, "sand height=%.1f,inf,0", t);
    material_rule sand;
    og_error err = {{0}};
    if (material_rule_parse(&sand, text, &err)) fail_msg("%s", err.msg);
    assert_int_equal(material_rules_insert(&rules, 0, &sand, &err), 0);
    assert_int_equal(edit_material_rules(earth, &rules, "material_rule add sand", &err), 0);
    render(&c, ruled, NULL);

    int below = 0, below_changed = 0, above = 0, above_changed = 0, sky_changed = 0;
    for (int i = 0; i < W * H; i++) {
        const int changed = !same_pixel(before, ruled, i);
        if (isnan(height[i]))
            sky_changed += changed;
        else if (height[i] < t - MARGIN)
            below++, below_changed += !near_pixel(before, ruled, i);
        else if (height[i] > t + MARGIN)
            above++, above_changed += changed;
    }
    printf("sand above %.0f m: %d of %d pixels under it changed, %d of %d over it, %d of the "
           "sky\n",
           t, below_changed, below, above_changed, above, sky_changed);
    assert_true(below > W * H / 8 && above > W * H / 8);
    assert_int_equal(below_changed, 0);
    assert_int_equal(sky_changed, 0);
    assert_true(above_changed >= 0.95 * above);

    assert_int_equal(edit_undo(earth, &err), 1);
    render(&c, undone, NULL);
    int differ = 0, far = 0;
    for (int i = 0; i < W * H; i++)
        differ += !same_pixel(before, undone, i), far += !near_pixel(before, undone, i);
    printf("undone: %d pixels differ, %d by more than a level\n", differ, far);
    assert_int_equal(far, 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_rule_changes_only_where_it_applies)};
    return cmocka_run_group_tests(tests, setup, teardown);
}
