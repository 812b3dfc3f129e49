// The shortcut table (app/shortcuts.h) against the README's key table, both ways: every
// README row is a row of the table with the same input and meaning, every table row is
// in the README, and the keys a row names are the keys it binds.
#include "app/shortcuts.h"

#include "support/test_support.h"

#include <GLFW/glfw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

enum { MAX_ROWS = 64 };

typedef struct readme_row {
    char input[256], meaning[1024];
} readme_row;

// One cell of a Markdown table row starting at *p: up to the next unescaped '|', with
// "\|" read as '|' and the spaces around trimmed. Returns 0, or -1 at the row's end.
static int next_cell(const char **p, char *out, size_t size) {
    const char *s = *p;
    if (*s != '|' || s[1] == '\n' || s[1] == 0) return -1;
    s++;
    size_t n = 0;
    for (; *s && *s != '\n' && *s != '|'; s++) {
        if (*s == '\\' && s[1] == '|') s++;
        if (n + 1 < size) out[n++] = *s;
    }
    while (n && out[n - 1] == ' ')
        n--;
    out[n] = 0;
    size_t lead = strspn(out, " ");
    memmove(out, out + lead, n - lead + 1);
    *p = s;
    return 0;
}

// The rows of the README's key table (the one headed "input (over the viewport)").
static int readme_rows(readme_row *rows) {
    size_t len;
    char *text = test_read_file(OROGEN_README, &len);
    assert_non_null(text);
    const char *head = strstr(text, "| input (over the viewport) | action |\n");
    assert_non_null(head);
    const char *line = strchr(head, '\n') + 1;
    assert_int_equal(strncmp(line, "|---|---|", 9), 0);
    line = strchr(line, '\n') + 1;
    int n = 0;
    for (; line[0] == '|' && n < MAX_ROWS; n++) {
        const char *p = line;
        assert_int_equal(next_cell(&p, rows[n].input, sizeof rows[n].input), 0);
        assert_int_equal(next_cell(&p, rows[n].meaning, sizeof rows[n].meaning), 0);
        assert_int_equal(next_cell(&p, (char[8]){0}, 8), -1); // two columns
        line = strchr(line, '\n') + 1;
    }
    free(text);
    return n;
}

static const shortcut_row *table_row(const char *input) {
    for (int i = 0; i < shortcut_row_count(); i++)
        if (strcmp(shortcut_row_at(i)->input, input) == 0) return shortcut_row_at(i);
    return NULL;
}

static void test_readme_rows_are_the_table(void **state) {
    (void)state;
    static readme_row rows[MAX_ROWS];
    int n = readme_rows(rows);
    assert_true(n > 10);
    for (int i = 0; i < n; i++) { // README -> table
        const shortcut_row *r = table_row(rows[i].input);
        if (!r) fail_msg("README row \"%s\" is not in app/shortcuts.c", rows[i].input);
        if (strcmp(r->meaning, rows[i].meaning) != 0)
            fail_msg("\"%s\": the README says \"%s\", app/shortcuts.c \"%s\"", rows[i].input,
                     rows[i].meaning, r->meaning);
    }
    for (int i = 0; i < shortcut_row_count(); i++) { // table -> README
        int found = 0;
        for (int j = 0; j < n; j++)
            found |= strcmp(rows[j].input, shortcut_row_at(i)->input) == 0;
        if (!found) fail_msg("\"%s\" is not in the README's key table", shortcut_row_at(i)->input);
    }
    assert_int_equal(n, shortcut_row_count());
}

static int row_binds(const shortcut_row *r, const char *label) {
    for (int j = 0; j < SHORTCUT_ROW_KEYS && r->keys[j].label; j++)
        if (strcmp(r->keys[j].label, label) == 0) return 1;
    return 0;
}

// A row's input names exactly the keys it binds ("Ctrl+Z, Ctrl+Shift+Z (Ctrl+Y)").
static void test_rows_name_their_keys(void **state) {
    (void)state;
    for (int i = 0; i < shortcut_row_count(); i++) {
        const shortcut_row *r = shortcut_row_at(i);
        char words[256];
        snprintf(words, sizeof words, "%s", r->input);
        for (char *save, *w = strtok_r(words, " ,()", &save); w;
             w = strtok_r(NULL, " ,()", &save)) {
            int key, mods;
            if (shortcut_parse_label(w, &key, &mods) == 0 && !row_binds(r, w))
                fail_msg("\"%s\" names %s but does not bind it", r->input, w);
        }
        for (int j = 0; j < SHORTCUT_ROW_KEYS && r->keys[j].label; j++) {
            snprintf(words, sizeof words, "%s", r->input);
            int named = 0;
            for (char *save, *w = strtok_r(words, " ,()", &save); w;
                 w = strtok_r(NULL, " ,()", &save))
                named |= strcmp(w, r->keys[j].label) == 0;
            if (!named) fail_msg("\"%s\" binds %s without naming it", r->input, r->keys[j].label);
        }
    }
}

// Every key parses, is found by its key and modifiers, and no key is bound twice.
static void test_keys_are_found_and_unique(void **state) {
    (void)state;
    int keys = 0;
    for (int i = 0; i < shortcut_row_count(); i++) {
        const shortcut_row *r = shortcut_row_at(i);
        for (int j = 0; j < SHORTCUT_ROW_KEYS && r->keys[j].label; j++, keys++) {
            const shortcut_key *k = &r->keys[j];
            int key, mods;
            assert_int_equal(shortcut_parse_label(k->label, &key, &mods), 0);
            if (shortcut_find(key, mods) != k) fail_msg("%s is bound twice", k->label);
            if (k->action == SHORTCUT_RUN || k->action == SHORTCUT_TOOL) assert_non_null(k->arg);
        }
    }
    assert_true(keys > 30);
    int key, mods;
    assert_int_equal(shortcut_parse_label("Ctrl+Shift+S", &key, &mods), 0);
    assert_int_equal(key, GLFW_KEY_S);
    assert_int_equal(mods, SHORTCUT_CTRL | SHORTCUT_SHIFT);
    assert_int_equal(shortcut_parse_label("Esc", &key, &mods), -1);
    assert_int_equal(shortcut_parse_label("Ctrl+", &key, &mods), -1);
}

// Ctrl must match; Shift falls back to the key without it (Shift+1 is 1, Ctrl+Shift+O is
// Ctrl+O) unless something is bound with it (Ctrl+Shift+Z redoes, Ctrl+Z undoes).
static void test_lookup(void **state) {
    (void)state;
    const shortcut_key *k = shortcut_find(GLFW_KEY_Z, SHORTCUT_CTRL);
    assert_non_null(k);
    assert_string_equal(k->arg, "undo");
    k = shortcut_find(GLFW_KEY_Z, SHORTCUT_CTRL | SHORTCUT_SHIFT);
    assert_non_null(k);
    assert_string_equal(k->arg, "redo");
    k = shortcut_find(GLFW_KEY_1, SHORTCUT_SHIFT);
    assert_non_null(k);
    assert_string_equal(k->arg, "view shaded");
    k = shortcut_find(GLFW_KEY_O, SHORTCUT_CTRL | SHORTCUT_SHIFT);
    assert_non_null(k);
    assert_int_equal(k->action, SHORTCUT_OPEN);
    k = shortcut_find(GLFW_KEY_Z, 0); // no Ctrl: a tool key or nothing, never undo
    assert_true(!k || k->action != SHORTCUT_RUN);
    assert_null(shortcut_find(GLFW_KEY_W, 0)); // the movement keys are no shortcuts
    assert_null(shortcut_find(GLFW_KEY_W, SHORTCUT_CTRL));
    assert_string_equal(shortcut_label(SHORTCUT_RUN, "redo"), "Ctrl+Shift+Z");
    assert_string_equal(shortcut_label(SHORTCUT_SAVE_AS, NULL), "Ctrl+Shift+S");
    assert_string_equal(shortcut_label(SHORTCUT_TOOL, "stamp"), "B");
    assert_null(shortcut_label(SHORTCUT_TOOL, "fill")); // the volume tools have no key
    char line[256];
    assert_string_equal(
        shortcut_help_line(0, line, sizeof line),
        "left drag: sculpt or paint with the current tool (one undo step per drag)");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_readme_rows_are_the_table),
        cmocka_unit_test(test_rows_name_their_keys),
        cmocka_unit_test(test_keys_are_found_and_unique),
        cmocka_unit_test(test_lookup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
