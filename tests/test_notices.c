// Notices (app/notices.h): failures shown over the viewport (file actions' until
// dismissed, other refusals passing).
#include "app/notices.h"

#include <stdio.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#define SANS_TTF "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#define MONO_TTF "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf"

static void test_add_and_dismiss(void **state) {
    (void)state;
    static notices n;
    memset(&n, 0, sizeof n);
    notices_add(&n, "a failed");
    notices_add(&n, "a failed"); // the same again: once
    notices_add(&n, "b failed");
    assert_int_equal(n.count, 2);
    notices_dismiss(&n, 0);
    assert_int_equal(n.count, 1);
    assert_string_equal(n.text[0], "b failed");
    notices_dismiss(&n, 5); // none such: nothing
    assert_int_equal(n.count, 1);
    for (int i = 0; i < NOTICES_MAX + 3; i++) {
        char t[32];
        snprintf(t, sizeof t, "failure %d", i);
        notices_add(&n, t);
    }
    assert_int_equal(n.count, NOTICES_MAX); // the oldest went
    assert_string_equal(n.text[NOTICES_MAX - 1], "failure 8");
}

// A refusal passes (after NOTICES_PASS_SECONDS, or at the next action of the user's that
// works); a file action's failure stays until dismissed.
static void test_refusals_pass(void **state) {
    (void)state;
    static notices n;
    memset(&n, 0, sizeof n);
    notices_add_failure(&n, "load /etc/passwd", "open: /etc/passwd is not a parameter file", 100);
    notices_add_failure(&n, "tool raise radius=abc", "radius: 'abc' is not a number", 100);
    assert_int_equal(n.count, 2);
    assert_int_equal(notices_due(&n, 100 + NOTICES_PASS_SECONDS - 0.1), 0);
    assert_int_equal(notices_expire(&n, 100 + NOTICES_PASS_SECONDS - 0.1), 0);
    assert_int_equal(n.count, 2);
    assert_int_equal(notices_due(&n, 100 + NOTICES_PASS_SECONDS), 1);
    assert_int_equal(notices_expire(&n, 100 + NOTICES_PASS_SECONDS), 1);
    assert_int_equal(n.count, 1); // the file's failure stays
    assert_string_equal(n.text[0], "open: /etc/passwd is not a parameter file");
    assert_int_equal(notices_expire(&n, 1e9), 0);
    // The same refusal again shows from then; an action that works ends it.
    notices_add_failure(&n, "  set seed=x", "seed: 'x' is not a number", 200);
    notices_add_failure(&n, "set seed=x", "seed: 'x' is not a number", 203);
    assert_int_equal(n.count, 2);
    assert_int_equal(notices_expire(&n, 200 + NOTICES_PASS_SECONDS + 1), 0);
    notices_clear_passing(&n);
    assert_int_equal(n.count, 1);
    assert_string_equal(n.text[0], "open: /etc/passwd is not a parameter file");
    // Each file command's failure stays; the window's own commands are not the user's.
    const char *files[] = {
        "save /x",           "import /x.png", "export /x.exr",   "new flat from=/x.tif",
        "history script /x", "recover /x",    "stamp_add /x.png"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        notices_add_failure(&n, files[i], files[i], 0);
        assert_true(n.passes_at[n.count - 1] == 0);
    }
    assert_int_equal(notices_user_action("ui"), 1);
    assert_int_equal(notices_user_action("sculpt"), 1);
    assert_int_equal(notices_user_action("console"), 0);
    assert_int_equal(notices_user_action("radius"), 0);
}

// Drawn: the whole message is listed (as ui_messages shows it) and Dismiss closes it.
static void test_draw_and_dismiss(void **state) {
    (void)state;
    char why[256] = "";
    ui_font *font = ui_font_create(SANS_TTF, MONO_TTF, 16, why, sizeof why);
    if (!font) fail_msg("font: %s", why);
    ui_context *ui = ui_create(font);
    ui_set_strict_ids(ui, 1);
    static notices n;
    memset(&n, 0, sizeof n);
    const char *msg = "/tmp/work/some/long/path/N45E007.hgt: it covers 6001 x 6001 samples of "
                      "the world (2 m apart), over the limit of 134217728 in one import: give a "
                      "larger spacing= or make a world from it (new flat from=FILE)";
    notices_add(&n, msg);
    notices_add(&n, "open: /etc/passwd is not a parameter file");
    ui_input in = {.mouse_x = -100, .mouse_y = -100};
    ui_rect view = {100, 30, 500, 400};
    for (int frame = 0; frame < 2; frame++) {
        ui_begin(ui, &in, 800, 600);
        notices_draw(&n, ui, view);
        ui_end(ui);
    }
    assert_int_equal(ui_message_count(ui), 2);
    assert_string_equal(ui_message_at(ui, 0)->text, msg);
    assert_string_equal(ui_message_at(ui, 0)->where, "Notices");
    const ui_widget_info *d = ui_widget_find(ui, "Notices/Dismiss");
    assert_non_null(d);
    assert_true(d->rect.y + d->rect.h <= view.y + view.h);
    in.mouse_x = d->rect.x + d->rect.w / 2, in.mouse_y = d->rect.y + d->rect.h / 2;
    in.mouse_pressed[0] = in.mouse_down[0] = 1;
    ui_begin(ui, &in, 800, 600);
    notices_draw(&n, ui, view);
    ui_end(ui);
    in.mouse_pressed[0] = in.mouse_down[0] = 0, in.mouse_released[0] = 1;
    ui_begin(ui, &in, 800, 600);
    notices_draw(&n, ui, view);
    ui_end(ui);
    assert_int_equal(n.count, 1);
    assert_string_equal(n.text[0], "open: /etc/passwd is not a parameter file");
    ui_destroy(ui);
    ui_font_destroy(font);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_add_and_dismiss),
        cmocka_unit_test(test_refusals_pass),
        cmocka_unit_test(test_draw_and_dismiss),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
