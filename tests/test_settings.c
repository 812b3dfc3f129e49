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

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_recent_paths_are_absolute),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
