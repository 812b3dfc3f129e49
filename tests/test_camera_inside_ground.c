// `camera X Y Z YAW PITCH` inside the ground keeps the position (a fly-through, as in
// Blender or Unreal) but says so: a user who typed a height under the terrain saw torn
// slivers in the sky and no hint why. Over the ground and inside a carved tunnel (air)
// it says nothing.
#include "editor/cmd/commands.h"
#include "editor/world/world.h"
#include "support/test_support.h"
#include "support/test_view.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

typedef struct fixture {
    cmd_context ctx;
    char *text;
    size_t size;
} fixture;

// Runs text; returns what it printed (valid until the next call).
static const char *run(fixture *f, const char *text) {
    free(f->text);
    f->text = NULL;
    FILE *out = open_memstream(&f->text, &f->size);
    assert_non_null(out);
    f->ctx.out = out;
    og_error err = {{0}};
    int rc = cmd_run(&f->ctx, text, strlen(text), "test", &err);
    fclose(out);
    f->ctx.out = stdout;
    if (rc != 0) fail_msg("'%s' failed: %s", text, err.msg);
    return f->text;
}

static double ground_at(fixture *f, double x, double z) {
    char cmd[64];
    snprintf(cmd, sizeof cmd, "sample %g %g", x, z);
    return strtod(run(f, cmd), NULL);
}

static int says_inside(const char *printed) {
    return strstr(printed, "note: the camera is inside the ground") != NULL;
}

static void test_under_the_terrain(void **state) {
    fixture *f = *state;
    double g = ground_at(f, 100, 100);
    char cmd[96];
    snprintf(cmd, sizeof cmd, "camera 100 %g 100 0 -10", g - 40);
    const char *printed = run(f, cmd);
    if (!says_inside(printed)) fail_msg("40 m under the ground, no note: '%s'", printed);
    snprintf(cmd, sizeof cmd, "camera 100 %g 100 0 -10; camera", g - 40);
    assert_non_null(strstr(run(f, cmd), "camera 100.000 ")); // the position stands
}

static void test_over_the_terrain(void **state) {
    fixture *f = *state;
    double g = ground_at(f, 100, 100);
    char cmd[96];
    snprintf(cmd, sizeof cmd, "camera 100 %g 100 0 -10", g + 2);
    const char *printed = run(f, cmd);
    if (says_inside(printed)) fail_msg("2 m over the ground, a note: '%s'", printed);
}

static void test_inside_a_tunnel(void **state) {
    fixture *f = *state;
    double g = ground_at(f, 200, 200);
    char cmd[160];
    snprintf(cmd, sizeof cmd, "tunnel 150 %g 200 250 %g 200 radius=6", g - 30, g - 30);
    run(f, cmd);
    snprintf(cmd, sizeof cmd, "camera 200 %g 200 90 0", g - 30);
    const char *printed = run(f, cmd);
    if (says_inside(printed)) fail_msg("in the tunnel's air, a note: '%s'", printed);
    snprintf(cmd, sizeof cmd, "camera 200 %g 200 90 0", g - 50); // under the tunnel's floor
    printed = run(f, cmd);
    if (!says_inside(printed)) fail_msg("under the tunnel, no note: '%s'", printed);
}

static int setup(void **state) {
    fixture *f = calloc(1, sizeof *f);
    test_view_context_open(&f->ctx);
    *state = f;
    return 0;
}

static int teardown(void **state) {
    fixture *f = *state;
    test_view_context_close(&f->ctx);
    free(f->text);
    free(f);
    return 0;
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_under_the_terrain, setup, teardown),
        cmocka_unit_test_setup_teardown(test_over_the_terrain, setup, teardown),
        cmocka_unit_test_setup_teardown(test_inside_a_tunnel, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
