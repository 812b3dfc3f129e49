// Layers through files: `export ... layers=NAME` writes one layer's signed change (its
// sidecar says so) that `import ... layer=new blend=add` turns back into the same
// terrain with that layer hidden; `layers=upto=NAME` writes what the composite shows with
// the layers above NAME hidden; `import ... layer=NAME` goes into that layer, one undo
// step; wrong names and kinds are refused.
#include "editor/cmd/commands.h"
#include "editor/world/layer_grid.h"
#include "support/test_support.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void silent(void *user, const char *message) {
    (void)user, (void)message;
}

typedef struct session {
    cmd_context ctx;
    FILE *out;
} session;

static void open_session(session *s) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.generator = GEN_FBM;
    p.seed = 99;
    p.size = 600;
    p.spacing = 1.0;
    p.max_height = 300;
    world_settings set = {.cache_budget_bytes = (size_t)256 << 20, .workers = 2, .warn = silent};
    og_error err;
    world *w = world_create(&p, &set, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    s->out = tmpfile();
    cmd_context_init(&s->ctx, w, &set, s->out, OROGEN_RESOURCE_DIR);
}

static void run(session *s, const char *script) {
    og_error err;
    if (cmd_run(&s->ctx, script, strlen(script), "-c", &err) != 0)
        fail_msg("%s: %s", script, err.msg);
}

static void run_fails(session *s, const char *script, const char *expect) {
    og_error err;
    assert_int_equal(cmd_run(&s->ctx, script, strlen(script), "-c", &err), -1);
    if (!strstr(err.msg, expect))
        fail_msg("'%s' said '%s', expected '%s'", script, err.msg, expect);
}

static float *heights(session *s) {
    layer_grid g;
    og_error err;
    if (layer_grid_init(&g, world_get_params(s->ctx.world), TILE_LAYER_COARSE, 0, &err) != 0)
        fail_msg("%s", err.msg);
    float *out = malloc(sizeof(float) * 600 * 600);
    if (layer_grid_read(s->ctx.world, &g, (grid_rect){0, 0, 600, 600}, out, &err) != 0)
        fail_msg("%s", err.msg);
    return out;
}

static double max_difference(const float *a, const float *b) {
    double worst = 0;
    for (size_t k = 0; k < 600 * 600; k++)
        worst = fmax(worst, fabs((double)a[k] - b[k]));
    return worst;
}

static void run_in(session *s, const char *dir, const char *fmt) {
    char script[1024];
    snprintf(script, sizeof script, fmt, dir, dir, dir, dir);
    run(s, script);
}

static void test_export_import_by_layer(void **state) {
    (void)state;
    const char *dir = test_tmpdir("layer_interchange");
    session s;
    open_session(&s);
    // A masked max layer at part opacity between two add layers.
    run(&s, "tool raise radius=100 strength=0.8; stroke 100 300 500 300; "
            "layer new Cap blend=max opacity=0.7; tool set height=120 radius=90 strength=1; "
            "stroke 150 250 450 350; layer mask Cap slope=0,30,5; layer new Top; "
            "tool raise radius=50 strength=0.5; stroke 300 100 300 500");
    float *all = heights(&s);
    run_in(&s, dir,
           "export %s/cap.exr layers=Cap; export %s/upto.exr layers=upto=Cap; "
           "export %s/all.exr layers=composite");
    char path[512];
    snprintf(path, sizeof path, "%s/cap.exr.json", dir);
    char *json = test_read_file(path, NULL);
    assert_non_null(strstr(json, "\"layers\": \"change\""));
    assert_non_null(strstr(json, "\"edit_layer\": \"Cap\""));
    free(json);
    // Up to Cap: the composite with Top hidden, sample for sample.
    run(&s, "layer set Top visible=0");
    run_in(&s, dir, "export %s/shown.exr");
    size_t la, lb;
    snprintf(path, sizeof path, "%s/upto.exr", dir);
    char *a = test_read_file(path, &la);
    snprintf(path, sizeof path, "%s/shown.exr", dir);
    char *b = test_read_file(path, &lb);
    assert_int_equal(la, lb);
    assert_memory_equal(a, b, la);
    free(a);
    free(b);
    // Cap's change, imported as a new add layer in its place, shows the same terrain.
    run(&s, "layer set Top visible=1; layer set Cap visible=0; layer select Sculpt");
    float *without = heights(&s);
    assert_true(max_difference(all, without) > 1.0); // Cap did something
    run_in(&s, dir, "import %s/cap.exr layer=new blend=add");
    const layer_table *t = &world_get_params(s.ctx.world)->layers;
    assert_int_equal(t->count, 4);
    assert_string_equal(t->layers[t->active].name, "cap");
    assert_int_equal(t->active, 1);
    float *back = heights(&s);
    double worst = max_difference(all, back);
    if (worst > 1e-3) fail_msg("re-imported change differs by %g m", worst);
    // One undo step takes the new layer and its samples away.
    run(&s, "undo");
    assert_int_equal(world_get_params(s.ctx.world)->layers.count, 3);
    float *undone = heights(&s);
    assert_memory_equal(undone, without, sizeof(float) * 600 * 600);
    // Into a named layer: it becomes active and holds the import (Top then carries Cap's
    // change, so the terrain is again what it was with Cap shown).
    run_in(&s, dir, "import %s/cap.exr layer=Top blend=add");
    t = &world_get_params(s.ctx.world)->layers;
    assert_string_equal(t->layers[t->active].name, "Top");
    float *into_top = heights(&s);
    worst = max_difference(all, into_top);
    if (worst > 1e-3) fail_msg("imported into Top: differs by %g m", worst);
    run(&s, "layer new Paint kind=paint");
    char script[600];
    snprintf(script, sizeof script, "import %s/cap.exr layer=Nope", dir);
    run_fails(&s, script, "no layer named 'Nope'");
    snprintf(script, sizeof script, "import %s/cap.exr layer=Paint", dir);
    run_fails(&s, script, "is a paint layer");
    snprintf(script, sizeof script, "export %s/x.exr layers=Paint", dir);
    run_fails(&s, script, "is a paint layer");
    snprintf(script, sizeof script, "export %s/x.exr layers=Nope", dir);
    run_fails(&s, script, "no layer named 'Nope'");
    snprintf(script, sizeof script, "export %s/x.obj layers=Cap", dir);
    run_fails(&s, script, "applies to heightmap exports");
    free(all);
    free(without);
    free(back);
    free(undone);
    free(into_top);
    fclose(s.out);
    world_close(s.ctx.world);
    test_rmtree(dir);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_export_import_by_layer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
