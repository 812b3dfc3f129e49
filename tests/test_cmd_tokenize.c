// The command language's tokenizer (editor/cmd/tokenize.c) and its driver: blanks,
// separators, comments, quotes and escapes, NUL bytes, line numbers, very long and
// very many arguments; and through cmd_run, strokes of any length and interactive
// strokes that equal one-shot ones.
#include "editor/cmd/commands.h"
#include "editor/cmd/edit_commands.h"
#include "editor/cmd/tokenize.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

// Tokenizes text (len bytes) into "cmd|arg|arg;cmd|arg;" in out; returns the last rc.
static int flatten(const char *text, size_t len, char *out, size_t size, og_error *err) {
    cmd_tokenizer t;
    cmd_tokenizer_init(&t, text, len, "t");
    int argc, line, rc;
    char **argv;
    out[0] = 0;
    while ((rc = cmd_tokenizer_next(&t, &argc, &argv, &line, err)) == 1) {
        for (int i = 0; i < argc; i++) {
            strncat(out, argv[i], size - strlen(out) - 1);
            strncat(out, i + 1 < argc ? "|" : ";", size - strlen(out) - 1);
        }
        assert_null(argv[argc]);
    }
    cmd_tokenizer_free(&t);
    return rc;
}

static void expect(const char *text, const char *want) {
    char out[4096];
    og_error err = {{0}};
    int rc = flatten(text, strlen(text), out, sizeof out, &err);
    if (rc != 0) fail_msg("'%s': error %s", text, err.msg);
    if (strcmp(out, want) != 0) fail_msg("'%s' tokenized as '%s', wanted '%s'", text, out, want);
}

static void expect_error(const char *text, size_t len, const char *want) {
    char out[4096];
    og_error err = {{0}};
    int rc = flatten(text, len, out, sizeof out, &err);
    assert_int_equal(rc, -1);
    if (!strstr(err.msg, want)) fail_msg("error '%s' lacks '%s'", err.msg, want);
}

static void test_blanks_and_separators(void **state) {
    (void)state;
    expect("a b\tc\r\n", "a|b|c;");
    expect("  a   b  ", "a|b;");
    expect("a;b c\nd", "a;b|c;d;");
    expect(";;\n\n  ;a;;", "a;");
    expect("", "");
    expect("   \n\t\n", "");
}

static void test_comments(void **state) {
    (void)state;
    expect("# all comment\na", "a;");
    expect("a b # the rest; c\nd", "a|b;d;");
    expect("a#b c", "a#b|c;"); // '#' inside a word is part of it
    expect("a \"#b\" c", "a|#b|c;");
}

static void test_quotes_and_escapes(void **state) {
    (void)state;
    expect("say \"a b; c\"", "say|a b; c;");
    expect("x \"\"", "x|;");
    expect("ab\"c d\"e", "abc de;");
    expect("x \"q\\\"uote\"", "x|q\"uote;");
    expect("x \"back\\\\slash\"", "x|back\\slash;");
    expect("x \"a\\nb\"", "x|a\\nb;"); // other escapes stay literal
    expect("x a\\\"b\"", "x|a\\b;");   // outside quotes a backslash is literal, the quote opens
}

static void test_errors_and_lines(void **state) {
    (void)state;
    expect_error("a\nb \"open", 9, "t:2: error: unterminated");
    const char nul[] = "a\nb\nc \0 d";
    expect_error(nul, sizeof nul - 1, "t:3: error: NUL byte");
    // Line numbers: commands on later lines, and after a quoted newline.
    cmd_tokenizer t;
    const char *text = "a\n\nb \"x\ny\"\nc";
    cmd_tokenizer_init(&t, text, strlen(text), "t");
    int argc, line;
    char **argv;
    og_error err = {{0}};
    int lines[3], n = 0;
    while (cmd_tokenizer_next(&t, &argc, &argv, &line, &err) == 1)
        lines[n++] = line;
    cmd_tokenizer_free(&t);
    assert_int_equal(n, 3);
    assert_int_equal(lines[0], 1);
    assert_int_equal(lines[1], 3);
    assert_int_equal(lines[2], 5);
    // After an error the tokenizer gives nothing more.
    cmd_tokenizer_init(&t, "\"x\nb", 4, "t");
    assert_int_equal(cmd_tokenizer_next(&t, &argc, &argv, &line, &err), -1);
    assert_int_equal(cmd_tokenizer_next(&t, &argc, &argv, &line, &err), 0);
    cmd_tokenizer_free(&t);
}

static void test_long_and_many(void **state) {
    (void)state;
    size_t n = CMD_MAX_TOKEN - 1;
    char *text = malloc(n + 16);
    memcpy(text, "x ", 2);
    memset(text + 2, 'a', n);
    text[2 + n] = 0;
    char *out = malloc(n + 64);
    og_error err = {{0}};
    assert_int_equal(flatten(text, strlen(text), out, n + 64, &err), 0);
    assert_int_equal(strlen(out), n + 3);
    text[2 + n] = 'a', text[3 + n] = 0; // one byte more
    assert_int_equal(flatten(text, strlen(text), out, n + 64, &err), -1);
    assert_non_null(strstr(err.msg, "longer than"));
    free(text);
    free(out);
    // 10,000 arguments, in order.
    size_t count = 10000, cap = count * 8 + 16, len = 0;
    char *many = malloc(cap);
    len += (size_t)sprintf(many, "cmd");
    for (size_t i = 0; i < count; i++)
        len += (size_t)sprintf(many + len, " %zu", i);
    cmd_tokenizer t;
    cmd_tokenizer_init(&t, many, len, "t");
    int argc, line;
    char **argv;
    assert_int_equal(cmd_tokenizer_next(&t, &argc, &argv, &line, &err), 1);
    assert_int_equal(argc, (int)count + 1);
    for (size_t i = 0; i < count; i++)
        assert_int_equal(atoi(argv[i + 1]), (int)i);
    cmd_tokenizer_free(&t);
    free(many);
    // Past the limit: refused, not cut.
    size_t too = CMD_MAX_ARGS + 1;
    char *huge = malloc(too * 2 + 8);
    len = 0;
    for (size_t i = 0; i < too; i++)
        huge[len++] = 'a', huge[len++] = ' ';
    char small[8];
    assert_int_equal(flatten(huge, len, small, sizeof small, &err), -1);
    assert_non_null(strstr(err.msg, "too many arguments"));
    free(huge);
}

// ---- through cmd_run ---------------------------------------------------------------

static world *small_world(void) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.size = 1024;
    og_error err = {{0}};
    world *w = world_create(&p, NULL, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    return w;
}

// Runs text and returns what it printed (static storage).
static const char *run(cmd_context *ctx, const char *text, int want_rc) {
    static char *buf;
    static size_t len;
    free(buf);
    buf = NULL;
    FILE *mem = open_memstream(&buf, &len);
    ctx->out = mem;
    og_error err = {{0}};
    int rc = cmd_run(ctx, text, strlen(text), "s", &err);
    fclose(mem);
    ctx->out = stdout;
    if (rc != want_rc) fail_msg("'%.60s' returned %d (%s)", text, rc, err.msg);
    return buf;
}

static void test_cmd_run(void **state) {
    (void)state;
    cmd_context ctx;
    cmd_context_init(&ctx, small_world(), NULL, stdout, OROGEN_RESOURCE_DIR);
    assert_string_equal(run(&ctx, "seed 5; seed", 0), "5\n");
    FILE *mem;
    char *buf = NULL;
    size_t len;
    mem = open_memstream(&buf, &len);
    ctx.out = mem;
    og_error err = {{0}};
    assert_int_equal(cmd_run(&ctx, "seed 6\nfrobnicate\nseed 7", 23, "script", &err), -1);
    fclose(mem);
    free(buf);
    assert_non_null(strstr(err.msg, "script:2: error: unknown command 'frobnicate'"));
    ctx.out = stdout;
    assert_string_equal(run(&ctx, "seed", 0), "6\n"); // the run stopped at line 2
    // stroke_to without stroke_begin names itself.
    mem = open_memstream(&buf, &len);
    ctx.out = mem;
    assert_int_equal(cmd_run(&ctx, "stroke_to 1 2", 13, "s", &err), -1);
    fclose(mem);
    free(buf);
    assert_non_null(strstr(err.msg, "stroke_to: no stroke in progress"));
    world_close(ctx.world);
}

static void test_long_strokes(void **state) {
    (void)state;
    // 200 points in one stroke command, and the same drag as an interactive stroke.
    size_t cap = 200 * 40 + 64, len = 0;
    char *one = malloc(cap), *steps = malloc(cap * 2);
    len += (size_t)sprintf(one, "tool raise radius=5; stroke");
    size_t slen = (size_t)sprintf(steps, "tool raise radius=5; stroke_begin");
    for (int i = 0; i < 200; i++) {
        double x = 100 + i * 3.5, z = 300 + 80 * sin(i * 0.1);
        len += (size_t)sprintf(one + len, " %.17g %.17g", x, z);
        slen += (size_t)sprintf(steps + slen, "; stroke_to %.17g %.17g", x, z);
    }
    sprintf(steps + slen, "; stroke_end");
    const char *hash = "; hash 0 0 1023 1023; history";
    char *a = malloc(len + 64), *b = malloc(slen + 64);
    sprintf(a, "%s%s", one, hash);
    sprintf(b, "%s%s", steps, hash);
    cmd_context c1, c2;
    cmd_context_init(&c1, small_world(), NULL, stdout, OROGEN_RESOURCE_DIR);
    cmd_context_init(&c2, small_world(), NULL, stdout, OROGEN_RESOURCE_DIR);
    char out1[4096], out2[4096];
    snprintf(out1, sizeof out1, "%s", run(&c1, a, 0));
    snprintf(out2, sizeof out2, "%s", run(&c2, b, 0));
    // Same heights, and each is one undo step.
    assert_string_equal(out1, out2);
    assert_non_null(strstr(out1, "steps=1 "));
    char unedited[64];
    cmd_context c3;
    cmd_context_init(&c3, small_world(), NULL, stdout, OROGEN_RESOURCE_DIR);
    snprintf(unedited, sizeof unedited, "%s", run(&c3, "hash 0 0 1023 1023", 0));
    assert_true(strncmp(out1, unedited, 16) != 0); // the stroke changed the terrain
    world_close(c1.world);
    world_close(c2.world);
    world_close(c3.world);
    free(one), free(steps), free(a), free(b);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_blanks_and_separators), cmocka_unit_test(test_comments),
        cmocka_unit_test(test_quotes_and_escapes),    cmocka_unit_test(test_errors_and_lines),
        cmocka_unit_test(test_long_and_many),         cmocka_unit_test(test_cmd_run),
        cmocka_unit_test(test_long_strokes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
