// The material rule stack (editor/layers/material_rules.h): text round trip, bad input,
// the file lines (an old file keeps the default stack, `none` empties it), what the
// shaders get, and rule changes as undo steps that leave the heights alone.
#include "editor/edit/edit.h"
#include "editor/layers/material_rules.h"
#include "editor/params/world_params.h"
#include "editor/world/world.h"
#include "support/test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

static material_rule rule_of(const char *text) {
    material_rule r;
    og_error err = {{0}};
    if (material_rule_parse(&r, text, &err)) fail_msg("'%s': %s", text, err.msg);
    return r;
}

static void text_of(const material_rule *r, char *buf, size_t len) {
    int n = material_rule_format(r, buf, len);
    assert_true(n > 0 && (size_t)n < len);
}

static void test_text_round_trip(void **state) {
    (void)state;
    const char *texts[] = {
        "sand",
        "grass height=1%+6,inf,6",
        "snow height=62%+40,inf,80 slope=0,28.8108,9.849",
        "moss height=-inf,12.5 curvature=-3,-0.25,0.5 breakup=0.35",
        "cliff height=10%-20,90% slope=60,90",
        "gravel height=-5%,250,0.001 slope=0.1,0.2,0.30000000000000004",
    };
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        material_rule r = rule_of(texts[i]), back;
        char text[512];
        text_of(&r, text, sizeof text);
        assert_string_equal(text, texts[i]); // canonical already: the same words come back
        back = rule_of(text);
        material_rules a = {.count = 1, .rule = {r}}, b = {.count = 1, .rule = {back}};
        assert_true(material_rules_equal(&a, &b));
    }
    // Materials by index, and a short buffer counts the whole text.
    material_rule r = rule_of("3 slope=1,2");
    char small[6];
    assert_int_equal(material_rule_format(&r, small, sizeof small), (int)strlen("snow slope=1,2"));
    assert_string_equal(small, "snow ");
}

static void test_bad_rules(void **state) {
    (void)state;
    const struct {
        const char *text, *says;
    } bad[] = {
        {"", "a rule starts with its material"},
        {"lava", "material=lava: expected sand, grass"},
        {"sand height=5", "height=5: expected LO,HI"},
        {"sand height=5,1", "height=5,1: the low end is above the high end"},
        {"sand height=50%,10%", "height=50%,10%: the low end"},
        {"sand height=nan,1", "height=nan,1: expected"},
        {"sand height=1,2,-3", "height=1,2,-3: the edge -3 must be >= 0"},
        {"sand height=5%x,9", "height=5%x,9: expected"},
        {"sand height=inf%,9", "height=inf%,9"},
        {"sand slope=10,100", "slope=10,100: degrees must lie within 0..90"},
        {"sand curvature=1", "curvature=1: expected LO,HI or LO,HI,EDGE"},
        {"sand breakup=2", "breakup=2: expected a number 0..1"},
        {"sand colour=red", "colour=red: unknown rule key"},
        {"sand material=rock", "the material is the rule's first word"},
        {"sand slope", "'slope' is not key=value"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        material_rule r = rule_of("rock slope=30,90");
        material_rule before = r;
        og_error err = {{0}};
        assert_int_equal(material_rule_parse(&r, bad[i].text, &err), -1);
        if (!strstr(err.msg, bad[i].says))
            fail_msg("'%s' said '%s', wanted '%s'", bad[i].text, err.msg, bad[i].says);
        assert_memory_equal(&r, &before, sizeof r); // untouched
    }
}

static void remember(void *user, const char *message) {
    strncat(user, message, 511 - strlen(user));
}

// What a file without rules, with rules and with `none` reads as.
static void test_file_lines(void **state) {
    (void)state;
    material_rules def, r;
    material_rules_default(&def);
    assert_int_equal(def.count, 5);
    assert_true(def.implicit);
    r = def;
    og_error err = {{0}};
    assert_int_equal(material_rules_read_entry(&r, "seed", "3", &err), 1); // not ours
    assert_true(material_rules_equal(&r, &def));
    // Numbered lines, in any order and with gaps: bottom first by number.
    assert_int_equal(material_rules_read_entry(&r, "material_rule_5", "snow height=9,inf", &err),
                     0);
    assert_int_equal(material_rules_read_entry(&r, "material_rule_2", "dirt", &err), 0);
    assert_false(r.implicit); // the first line replaced the default stack
    material_rules_finish(&r);
    assert_int_equal(r.count, 2);
    assert_int_equal(r.rule[0].material, 4);
    assert_int_equal(r.rule[1].material, 3);
    r = def;
    assert_int_equal(material_rules_read_entry(&r, "material_rules", "none", &err), 0);
    material_rules_finish(&r);
    assert_int_equal(r.count, 0);
    assert_int_equal(material_rules_read_entry(&r, "material_rules", "some", &err), -1);
    assert_non_null(strstr(err.msg, "material_rules: expected none"));
    assert_int_equal(material_rules_read_entry(&r, "material_rule_1", "rock x", &err), -1);
    assert_non_null(strstr(err.msg, "material_rule_1: 'x' is not key=value"));
    const char *bad_keys[] = {"material_rule",    "material_rule_0",  "material_rule_17",
                              "material_rule_01", "material_rule_2x", "material_rule_+2"};
    for (size_t i = 0; i < sizeof bad_keys / sizeof bad_keys[0]; i++) {
        assert_int_equal(material_rules_read_entry(&r, bad_keys[i], "sand", &err), -1);
        assert_non_null(strstr(err.msg, "not a rule key (material_rule_1 .. material_rule_16"));
    }
    r = (material_rules){0};
    for (int i = MATERIAL_RULES_MAX; i >= 1; i--) {
        char key[32];
        snprintf(key, sizeof key, "material_rule_%d", i);
        assert_int_equal(material_rules_read_entry(&r, key, i % 2 ? "sand" : "moss", &err), 0);
    }
    material_rules_finish(&r);
    assert_int_equal(r.count, MATERIAL_RULES_MAX);
    assert_int_equal(r.rule[0].material, 0);
    assert_int_equal(r.rule[15].material, 6);

    // Save and load through the parameter file, an old file, an emptied stack.
    char dir[4096], path[4200];
    snprintf(dir, sizeof dir, "%s", test_tmpdir("material-rules"));
    snprintf(path, sizeof path, "%s/w.world", dir);
    world_params p, back;
    world_params_default(&p, WORLD_FLAT);
    material_rules_remove(&p.material_rules, 1);
    material_rule moss = rule_of("moss curvature=-5,-1,0.5 breakup=0.25 height=10%,80%+3,7");
    material_rules_insert(&p.material_rules, 0, &moss, NULL);
    if (world_params_save(path, &p, &err)) fail_msg("%s", err.msg);
    int errors = -1;
    if (world_params_load(path, &back, &errors, NULL, NULL, &err)) fail_msg("%s", err.msg);
    assert_int_equal(errors, 0);
    assert_true(material_rules_equal(&p.material_rules, &back.material_rules));
    assert_false(back.material_rules.implicit);

    static const char old[] = "generator = 1;\nmax_height = 900;\nseed = 7;\n";
    test_write_file(path, old, sizeof old - 1);
    if (world_params_load(path, &back, &errors, NULL, NULL, &err)) fail_msg("%s", err.msg);
    assert_true(material_rules_equal(&back.material_rules, &def));

    p.material_rules.count = 0;
    if (world_params_save(path, &p, &err)) fail_msg("%s", err.msg);
    size_t len;
    char *text = test_read_file(path, &len);
    assert_non_null(strstr(text, "\nmaterial_rules = none;\n"));
    free(text);
    if (world_params_load(path, &back, &errors, NULL, NULL, &err)) fail_msg("%s", err.msg);
    assert_int_equal(back.material_rules.count, 0);

    // A bad line is an error naming the file and line; the others still load.
    static const char bad[] = "seed = 7;\nmaterial_rule_1 = rock slope=30,90;\n"
                              "material_rule_2 = snow slope=0,95;\n";
    test_write_file(path, bad, sizeof bad - 1);
    char seen[512] = "";
    if (world_params_load(path, &back, &errors, remember, seen, &err)) fail_msg("%s", err.msg);
    assert_int_equal(errors, 1);
    assert_int_equal(back.material_rules.count, 1);
    assert_non_null(strstr(seen, "w.world:3: error: material_rule_2: slope=0,95: degrees"));
    test_rmtree(dir);
}

// A planet's rules lay over its own look: none by default, and a planet file saved before
// planets took rules (save wrote the flat default stack) reads as none; rules a person
// wrote stay.
static void test_planet_stack(void **state) {
    (void)state;
    world_params p, back;
    world_params_default(&p, WORLD_PLANET);
    assert_int_equal(p.material_rules.count, 0);
    char dir[4096], path[4200];
    snprintf(dir, sizeof dir, "%s", test_tmpdir("planet-rules"));
    snprintf(path, sizeof path, "%s/p.planet", dir);
    static const char old[] = "radius = 6371000;\nmax_height = 8848;\n"
                              "material_rule_1 = sand;\n"
                              "material_rule_2 = grass height=1%+6,inf,6;\n"
                              "material_rule_3 = rock slope=40.3645,90,11.5537;\n"
                              "material_rule_4 = cliff slope=56.3099,90,8.5836;\n"
                              "material_rule_5 = snow height=62%+40,inf,80 "
                              "slope=0,28.8108,9.849;\n";
    test_write_file(path, old, sizeof old - 1);
    int errors = -1;
    og_error err = {{0}};
    if (world_params_load(path, &back, &errors, NULL, NULL, &err)) fail_msg("%s", err.msg);
    assert_int_equal(errors, 0);
    assert_int_equal(back.kind, WORLD_PLANET);
    assert_int_equal(back.material_rules.count, 0);
    // The same lines in a flat world's file are that world's rules.
    snprintf(path, sizeof path, "%s/w.world", dir);
    test_write_file(path, old, sizeof old - 1);
    if (world_params_load(path, &back, &errors, NULL, NULL, &err)) fail_msg("%s", err.msg);
    assert_int_equal(back.material_rules.count, 5);
    // A planet's own rules survive save and load.
    snprintf(path, sizeof path, "%s/q.planet", dir);
    material_rule snow = rule_of("snow height=3000,inf,50 slope=0,30,5");
    material_rules_insert(&p.material_rules, 0, &snow, NULL);
    if (world_params_save(path, &p, &err)) fail_msg("%s", err.msg);
    if (world_params_load(path, &back, &errors, NULL, NULL, &err)) fail_msg("%s", err.msg);
    assert_int_equal(errors, 0);
    assert_true(material_rules_equal(&back.material_rules, &p.material_rules));
    test_rmtree(dir);
}

// Relative heights follow the world's sea and max_height; corners as the shaders take them.
static void test_resolve(void **state) {
    (void)state;
    material_rules r;
    material_rules_default(&r);
    material_rules_resolved g;
    material_rules_resolve(&r, -400, 1200, &g);
    assert_int_equal(g.count, 5);
    assert_false(g.uses_curvature);
    // grass: the beach at sea + 1% of the relief + 6 m, eased in over 6 m
    assert_true(g.height[1][0] == -384.0f && g.height[1][1] == -378.0f);
    assert_true(g.height[1][2] == 1e30f && g.height[1][3] == 1e30f);
    // snow: 62% of the relief, eased over 40 m each side of it
    assert_true(fabs(g.height[4][0] - 552.0f) < 1e-3 && fabs(g.height[4][1] - 632.0f) < 1e-3);
    // slopes go as rise over run: rock from 0.55 to 0.85 as the shaders always had it
    assert_true(fabs(g.slope[2][0] - 0.55f) < 1e-5 && fabs(g.slope[2][1] - 0.85f) < 1e-5);
    assert_true(g.slope[2][2] == 1e30f);
    assert_true(fabs(g.slope[4][2] - 0.55f) < 1e-5 && fabs(g.slope[4][3] - 0.8f) < 1e-5);
    // terms not set cover everything
    assert_true(g.slope[0][0] == -1e30f && g.curvature[0][3] == 1e30f);
    material_rules_resolve(&r, 0, 3000, &g);
    assert_true(fabs(g.height[4][1] - (1860.0f + 40.0f)) < 1e-3);

    // Live rules: flat lowland draws sand and grass only; a steep peak everything.
    material_rules_resolve(&r, -400, 1200, &g);
    assert_int_equal(material_rules_live(&g, 0, 100, 0.3), 0x3);
    assert_int_equal(material_rules_live(&g, 0, 700, 2.0), 0x1f);
    assert_int_equal(material_rules_live(&g, 0, 560, 0.6), 0x17); // rock and snow, no cliff
    r.rule[3].breakup = 0.5; // breakup can reach past a range: always drawn
    material_rules_resolve(&r, -400, 1200, &g);
    assert_int_equal(material_rules_live(&g, 0, 100, 0.3), 0xb);
}

static void silent(void *user, const char *message) {
    (void)user, (void)message;
}

// A rule change is one undo step; undo and redo give the rules back exactly and never
// touch a height.
static void test_undo(void **state) {
    (void)state;
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.size = 512;
    world_settings s = {.warn = silent};
    og_error err;
    world *w = world_create(&p, &s, &err);
    if (!w) fail_msg("%s", err.msg);
    uint64_t h0, h1, n;
    assert_int_equal(world_hash(w, 0, 0, 0, 1000, 1000, &h0, &n, &err), 0);
    material_rules before = world_get_params(w)->material_rules, next = before;
    og_error why;
    assert_int_equal(material_rule_set_option(&next.rule[4], "height", "500,inf,40", &why), 0);
    assert_int_equal(edit_material_rules(w, &next, "material_rule set 5 height=500,inf,40", &err),
                     0);
    assert_true(material_rules_equal(&world_get_params(w)->material_rules, &next));
    assert_int_equal(world_is_modified(w), 1);
    assert_int_equal(edit_undo(w, &err), 1);
    assert_true(material_rules_equal(&world_get_params(w)->material_rules, &before));
    assert_int_equal(edit_redo(w, &err), 1);
    assert_true(material_rules_equal(&world_get_params(w)->material_rules, &next));
    // `generate` keeps the rules; undoing it too.
    world_params gen = *world_get_params(w);
    gen.seed = 99;
    gen.material_rules = before; // a stale nparams copy must not bring old rules back
    assert_int_equal(edit_generate(w, &gen, &err), 0);
    assert_true(material_rules_equal(&world_get_params(w)->material_rules, &next));
    assert_int_equal(edit_undo(w, &err), 1);
    assert_true(material_rules_equal(&world_get_params(w)->material_rules, &next));
    assert_int_equal(edit_undo(w, &err), 1);
    assert_true(material_rules_equal(&world_get_params(w)->material_rules, &before));
    assert_int_equal(world_hash(w, 0, 0, 0, 1000, 1000, &h1, &n, &err), 0);
    assert_true(h0 == h1);
    world_close(w);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_text_round_trip), cmocka_unit_test(test_bad_rules),
        cmocka_unit_test(test_file_lines),      cmocka_unit_test(test_planet_stack),
        cmocka_unit_test(test_resolve),         cmocka_unit_test(test_undo),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
