// A log's long lines fold into rows of the log's width (ui/log_rows.c): the console cut a
// line longer than its panel at the edge, its end unreadable. Rows break after a space in
// their second half, else between characters (a path), never inside a UTF-8 character;
// folded rows put back together give the line.
#include "ui/log_rows.h"

#include <string.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

// The rows of text at cols, joined by sep into out; returns how many (each row at least
// one byte: no endless loop).
static size_t fold_with(const char *text, size_t cols, const char *sep, char *out) {
    size_t rows = 0;
    out[0] = 0;
    do {
        size_t n = log_row_bytes(text, cols);
        assert_true(n > 0);
        strncat(out, text, n);
        text += n, rows++;
        if (*text) strcat(out, sep);
    } while (*text);
    return rows;
}

static void fold(const char *text, size_t cols, char *out) {
    fold_with(text, cols, "|", out);
}

static void test_short_lines_stay_whole(void **state) {
    (void)state;
    char out[256];
    fold("camera 0 -1500 0", 40, out);
    assert_string_equal(out, "camera 0 -1500 0");
    assert_int_equal(log_rows("camera 0 -1500 0", 40), 1);
    assert_int_equal(log_rows("", 40), 1); // an empty line still takes its row
    fold("exactly ten", 11, out);
    assert_string_equal(out, "exactly ten");
}

static void test_words_break_after_a_space(void **state) {
    (void)state;
    char out[256];
    fold("note: the camera is inside the ground", 16, out);
    assert_string_equal(out, "note: the camera |is inside the |ground");
    assert_int_equal(log_rows("note: the camera is inside the ground", 16), 3);
}

static void test_long_words_break_between_characters(void **state) {
    (void)state;
    char out[256];
    fold("/a/very/long/path/without/spaces.tif", 10, out);
    assert_string_equal(out, "/a/very/lo|ng/path/wi|thout/spac|es.tif");
    fold("x /a/very/long/path", 10, out); // its only space is in the first half: cut
    assert_string_equal(out, "x /a/very/|long/path");
}

static void test_utf8_characters_stay_whole(void **state) {
    (void)state;
    char out[256];
    fold("h\xc3\xa9ight\xc3\xa9\xc3\xa9\xc3\xa9", 4, out); // é is two bytes, one character
    assert_string_equal(out, "h\xc3\xa9ig|ht\xc3\xa9\xc3\xa9|\xc3\xa9");
}

static void test_rows_give_back_the_line(void **state) {
    (void)state;
    const char *line = "imported /work/shared/data/dem/N22W160.hgt: 1201 x 1201 samples "
                       "(SRTMHGT Int16, nodata set), 88.9539 x 88.9539 m apart; heights -34 .. "
                       "1579 m; 4279 voids filled";
    for (size_t cols = 1; cols < 200; cols++) {
        char joined[512];
        size_t rows = fold_with(line, cols, "", joined);
        assert_string_equal(joined, line);
        assert_int_equal(rows, log_rows(line, cols));
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_short_lines_stay_whole),
        cmocka_unit_test(test_words_break_after_a_space),
        cmocka_unit_test(test_long_words_break_between_characters),
        cmocka_unit_test(test_utf8_characters_stay_whole),
        cmocka_unit_test(test_rows_give_back_the_line),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
