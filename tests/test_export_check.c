// The export dialog's checks before an export is queued (app/export_check.h): what the
// export command would refuse at once is said, naming the field: no file name, a folder
// that is not there, a layer export to a format that is no heightmap, a region that is
// not four numbers, a layer not in the stack; a good choice passes, and a refusal leaves
// the dialog open with the reason in it.
#include "app/export_check.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "support/test_world.h"

static void expect_refused(world *w, const interchange_dialog *d, const char *says) {
    og_error err = {{0}};
    assert_int_equal(export_check(w, d, &err), -1);
    if (!strstr(err.msg, says)) fail_msg("'%s' does not say '%s'", err.msg, says);
}

static void test_checks(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(0);
    world *w = test_world_open(&p);
    interchange_dialog d = {0};
    d.exporting = 1;
    snprintf(d.layer_name, sizeof d.layer_name, "Sculpt");
    for (int i = 0; i < 4; i++)
        snprintf(d.region[i], sizeof d.region[i], "%d", i < 2 ? 0 : 64);
    og_error err = {{0}};
    snprintf(d.path, sizeof d.path, "/tmp/Sculpt.exr");
    assert_int_equal(export_check(w, &d, &err), 0);
    d.layer_what = 1; // the stack up to it
    assert_int_equal(export_check(w, &d, &err), 0);

    d.path[0] = 0;
    expect_refused(w, &d, "File: no file name");
    snprintf(d.path, sizeof d.path, "/tmp/");
    expect_refused(w, &d, "no file name after /tmp/");
    snprintf(d.path, sizeof d.path, "/tmp/no-such-folder-orogen/Sculpt.exr");
    expect_refused(w, &d, "the folder /tmp/no-such-folder-orogen does not exist");
    snprintf(d.path, sizeof d.path, "/tmp/Sculpt.obj");
    expect_refused(w, &d, "heightmap");
    d.layer_what = 2; // the composite: any format the command writes
    assert_int_equal(export_check(w, &d, &err), 0);
    d.layer_what = 0;
    snprintf(d.path, sizeof d.path, "/tmp/Sculpt.exr");
    snprintf(d.region[2], sizeof d.region[2], "east");
    expect_refused(w, &d, "region");
    d.whole = 1; // the region is not asked
    assert_int_equal(export_check(w, &d, &err), 0);
    snprintf(d.layer_name, sizeof d.layer_name, "Nope");
    expect_refused(w, &d, "Nope");

    // After Export: refused, the dialog open again with the reason; then accepted.
    d.open = 0;
    assert_int_equal(export_check_accept(&d, w), 0);
    assert_int_equal(d.open, 1);
    assert_non_null(strstr(d.error, "Nope"));
    snprintf(d.layer_name, sizeof d.layer_name, "Sculpt");
    d.open = 0;
    assert_int_equal(export_check_accept(&d, w), 1);
    assert_int_equal(d.open, 0);
    assert_string_equal(d.error, "");
    world_close(w);
}

// File > Export mesh... and the heightmap's Tiles: the typed numbers are checked as the
// command checks them, and the command carries each choice.
static void test_mesh_and_tiles(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(0);
    world *w = test_world_open(&p);
    interchange_dialog d = {0};
    d.exporting = 1;
    d.whole = 1;
    og_error err = {{0}};
    snprintf(d.path, sizeof d.path, "/tmp/relief.ply");
    snprintf(d.tiles, sizeof d.tiles, "2x");
    expect_refused(w, &d, "tiles");
    snprintf(d.tiles, sizeof d.tiles, "2x2");
    assert_int_equal(export_check(w, &d, &err), 0);

    d.mesh = 1; // tiles belong to heightmaps: not asked, not passed
    snprintf(d.mesh_choices.simplify, sizeof d.mesh_choices.simplify, "-1");
    expect_refused(w, &d, "simplify");
    d.mesh_choices.solid = 1; // a closed solid is not simplified: the field is not used
    assert_int_equal(export_check(w, &d, &err), 0);
    d.mesh_choices.solid = 0;
    snprintf(d.mesh_choices.simplify, sizeof d.mesh_choices.simplify, "0.5");
    d.mesh_choices.centred = 1;
    assert_int_equal(export_check(w, &d, &err), 0);
    snprintf(d.path, sizeof d.path, "/tmp/relief.stl");
    expect_refused(w, &d, "a mesh is .glb, .obj or .ply");
    snprintf(d.path, sizeof d.path, "/tmp/relief.vdb");
    snprintf(d.mesh_choices.voxel, sizeof d.mesh_choices.voxel, "0");
    expect_refused(w, &d, "voxel");
    snprintf(d.mesh_choices.voxel, sizeof d.mesh_choices.voxel, "2");
    d.mesh_choices.fog = 1;
    assert_int_equal(export_check(w, &d, &err), 0);
    char opts[200];
    mesh_export_options(&d.mesh_choices, d.path, opts, sizeof opts);
    assert_string_equal(opts, " voxel=2 fog=1");
    snprintf(d.path, sizeof d.path, "/tmp/relief.glb");
    mesh_export_options(&d.mesh_choices, d.path, opts, sizeof opts);
    assert_string_equal(opts, " simplify=0.5 centred=1");
    world_close(w);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_checks),
                                       cmocka_unit_test(test_mesh_and_tiles)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
