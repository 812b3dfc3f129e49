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

#define W 256
#define H 144
#define MARGIN 40.0 // metres either side of the rule's edge left unjudged

static planet_view view;

static int setup(void **state) {
    (void)state;
    return planet_view_open(&view, W, H, "test_planet_rules");
}

static int teardown(void **state) {
    (void)state;
    planet_view_close(&view);
    return 0;
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
    const world_params *p = world_get_params(view.earth);
    planet_position(21.0, 5.7, p->radius + 1e5, c.pos);
    c.yaw = 0, c.pitch = -25;
    static unsigned char before[W * H * 3], ruled[W * H * 3], undone[W * H * 3];
    static double height[W * H], land[W * H];
    planet_view_draw(&view, view.earth, &c, NULL, before, NULL, height);
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
    assert_int_equal(edit_material_rules(view.earth, &rules, "material_rule add sand", &err), 0);
    planet_view_draw(&view, view.earth, &c, NULL, ruled, NULL, NULL);

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

    assert_int_equal(edit_undo(view.earth, &err), 1);
    planet_view_draw(&view, view.earth, &c, NULL, undone, NULL, NULL);
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
