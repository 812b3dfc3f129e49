// The editor's settings (app/settings.h): recent worlds are kept as absolute paths, so
// File's list opens them from wherever the editor starts next.
#include "app/settings.h"
#include "support/test_support.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

static void test_recent_paths_are_absolute(void **state) {
    (void)state;
    const char *dir = test_tmpdir("settings");
    char real[PATH_MAX], before[PATH_MAX];
    assert_non_null(realpath(dir, real));
    assert_non_null(getcwd(before, sizeof before));
    assert_int_equal(chdir(dir), 0);
    FILE *f = fopen("here.world", "w");
    assert_non_null(f);
    fclose(f);
    static app_settings s;
    app_settings_default(&s);
    app_settings_add_recent(&s, "here.world");    // exists: resolved
    app_settings_add_recent(&s, "later/x.world"); // not yet: joined to the folder
    app_settings_add_recent(&s, "./here.world");  // the same file: moves first, once
    assert_int_equal(chdir(before), 0);
    char want[PATH_MAX + 32];
    assert_int_equal(s.recent_count, 2);
    snprintf(want, sizeof want, "%s/here.world", real);
    assert_string_equal(s.recent[0], want);
    assert_non_null(strstr(s.recent[1], "/later/x.world"));
    assert_true(s.recent[1][0] == '/');
    app_settings_add_recent(&s, "/abs/elsewhere.world"); // absolute: as it is
    assert_string_equal(s.recent[0], "/abs/elsewhere.world");
    test_rmtree(dir);
}

// Each world's camera comes back from the settings file exactly, paths with spaces
// included; a bad line is a warning, not a camera.
static void test_world_cameras_round_trip(void **state) {
    (void)state;
    const char *dir = test_tmpdir("settings_cameras");
    char path[PATH_MAX], world_a[PATH_MAX], world_b[PATH_MAX];
    snprintf(path, sizeof path, "%s/settings", dir);
    snprintf(world_a, sizeof world_a, "%s/my alps.world", dir);
    snprintf(world_b, sizeof world_b, "%s/b.world", dir);
    static app_settings s, back;
    app_settings_default(&s);
    const double a[5] = {1234.5678901234567, -99.25, 1e-3, 33.3, -41.0};
    const double b[5] = {1, 2, 3, 4, 5};
    app_settings_put_camera(&s, world_a, b);
    app_settings_put_camera(&s, world_b, b);
    app_settings_put_camera(&s, world_a, a); // again: replaces, first
    assert_int_equal(s.camera_count, 2);
    og_error err = {{0}};
    assert_int_equal(app_settings_save(&s, path, &err), 0);
    app_settings_default(&back);
    app_settings_load(&back, path);
    double got[5];
    assert_int_equal(app_settings_find_camera(&back, world_a, got), 0);
    assert_memory_equal(got, a, sizeof a);
    assert_int_equal(app_settings_find_camera(&back, world_b, got), 0);
    assert_memory_equal(got, b, sizeof b);
    assert_int_equal(app_settings_find_camera(&back, "/nowhere.world", got), -1);
    assert_int_equal(app_settings_find_camera(&back, "", got), -1);
    for (int i = 0; i < 3 * SETTINGS_CAMERAS; i++) { // the oldest go
        char w[64];
        snprintf(w, sizeof w, "/w%d.world", i);
        app_settings_put_camera(&back, w, b);
    }
    assert_int_equal(back.camera_count, SETTINGS_CAMERAS);
    assert_int_equal(app_settings_find_camera(&back, world_a, got), -1);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("world_camera_0 = 1 2 nan 4 5 /x.world;\nworld_camera_1 = 1 2 3 /y.world;\n", f);
    fclose(f);
    app_settings_default(&back);
    app_settings_load(&back, path);
    assert_int_equal(back.camera_count, 0);
}

// A window bigger than the screen's work area (the 1280 x 800 default on a 1024 x 640
// laptop, or a size kept from a larger monitor) is made to fit and maximised; one that
// fits keeps its size, and its position unless that puts part of it off the area.
static void test_window_fits_the_screen(void **state) {
    (void)state;
    static app_settings s;
    app_settings_default(&s);
    app_settings_fit_to_screen(&s, 0, 0, 1024, 640);
    assert_int_equal(s.width, 1024);
    assert_int_equal(s.height, 640);
    assert_true(s.maximized && s.has_position && s.x == 0 && s.y == 0);

    app_settings_default(&s); // a panel along the top: the area starts below it
    app_settings_fit_to_screen(&s, 0, 27, 1920, 1053);
    assert_true(s.width == 1280 && s.height == 800 && !s.maximized && !s.has_position);
    s.x = 500, s.y = 200, s.has_position = 1; // fits
    app_settings_fit_to_screen(&s, 0, 27, 1920, 1053);
    assert_true(s.has_position && s.x == 500 && s.y == 200);
    s.x = 2500; // kept from a second monitor that is gone
    app_settings_fit_to_screen(&s, 0, 27, 1920, 1053);
    assert_false(s.has_position);

    app_settings_default(&s); // no work area known: as it was
    app_settings_fit_to_screen(&s, 0, 0, 0, 0);
    assert_true(s.width == 1280 && s.height == 800 && !s.maximized);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_recent_paths_are_absolute),
        cmocka_unit_test(test_world_cameras_round_trip),
        cmocka_unit_test(test_window_fits_the_screen),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
