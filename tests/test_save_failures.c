// Saves that cannot be done: a disk that fills up in the middle of a save (a file
// size limit, RLIMIT_FSIZE, with SIGXFSZ ignored) and a parameter file its owner made
// read-only. The save fails with an error naming a path and the reason, the old files
// stay byte-identical, and the world stays unsaved in memory, so saving elsewhere keeps
// every edit.
#include "editor/cmd/commands.h"
#include "editor/cmd/context.h"
#include "io/path_folder.h"
#include "support/test_support.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#define AREA "hash -1000 -1000 1000 1000"

static int run(cmd_context *ctx, const char *text, char *printed, size_t len, og_error *err) {
    FILE *mem = fmemopen(printed, len, "w");
    assert_non_null(mem);
    ctx->out = mem;
    int rc = cmd_run(ctx, text, strlen(text), "test", err);
    fclose(mem);
    ctx->out = stdout;
    return rc;
}

static void run_ok(cmd_context *ctx, const char *text, char *printed, size_t len) {
    og_error err = {{0}};
    if (run(ctx, text, printed, len, &err) != 0) fail_msg("'%s' failed: %s", text, err.msg);
}

static char *slurp(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *data = malloc((size_t)n + 1);
    assert_int_equal(fread(data, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    *len = (size_t)n;
    return data;
}

static void assert_same_file(const char *path, const char *data, size_t len) {
    size_t now_len;
    char *now = slurp(path, &now_len);
    assert_int_equal(now_len, len);
    assert_memory_equal(now, data, len);
    free(now);
}

static void test_full_disk_keeps_old_files(void **state) {
    (void)state;
    const char *dir = test_tmpdir("savefail");
    char path[4200], tiles[4200], other[4200], text[8600], out[4096];
    snprintf(path, sizeof path, "%s/w.world", dir);
    snprintf(tiles, sizeof tiles, "%s/w.tiles", dir);
    snprintf(other, sizeof other, "%s/elsewhere.world", dir);
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    og_error err = {{0}};
    cmd_context ctx;
    cmd_context_init(&ctx, world_create(&p, NULL, &err), NULL, stdout, OROGEN_RESOURCE_DIR);
    snprintf(text, sizeof text, "tool raise radius=40 strength=1; dab 100 100; save %s", path);
    run_ok(&ctx, text, out, sizeof out);
    size_t world_len, tiles_len;
    char *world_bytes = slurp(path, &world_len), *tiles_bytes = slurp(tiles, &tiles_len);
    // Noise over many tiles: megabytes the store must take.
    run_ok(&ctx, "tool noise radius=900 strength=1 amount=80; dab 0 0; dab 600 -600", out,
           sizeof out);
    char edited[32];
    run_ok(&ctx, AREA, edited, sizeof edited);

    // The disk is full a little past the store's size.
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit old, lim;
    getrlimit(RLIMIT_FSIZE, &old);
    lim = old;
    lim.rlim_cur = (rlim_t)tiles_len + 64 * 1024;
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
    int rc = run(&ctx, "save", out, sizeof out, &err);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &old), 0);
    assert_int_equal(rc, -1);
    print_message("full disk: %s\n", err.msg);
    assert_true(strstr(err.msg, "tiles") != NULL);
    assert_true(strstr(err.msg, "File too large") || strstr(err.msg, "disk full") ||
                strstr(err.msg, "too large"));
    assert_same_file(path, world_bytes, world_len);
    assert_same_file(tiles, tiles_bytes, tiles_len);

    // Unsaved in memory, every edit there: saving elsewhere keeps them.
    run_ok(&ctx, "info", out, sizeof out);
    assert_non_null(strstr(out, "unsaved_changes=1"));
    char now[32];
    run_ok(&ctx, AREA, now, sizeof now);
    assert_string_equal(now, edited);
    snprintf(text, sizeof text, "save %s; load %s", other, other);
    run_ok(&ctx, text, out, sizeof out);
    run_ok(&ctx, AREA, now, sizeof now);
    assert_string_equal(now, edited);
    // And the old world still loads as it was saved.
    snprintf(text, sizeof text, "load %s; " AREA, path);
    run_ok(&ctx, text, out, sizeof out);
    assert_null(strstr(out, edited));

    // The disk fills while a save merges into the old store (saving over it from
    // another file): the old files stay as they were too.
    snprintf(text, sizeof text, "load %s; save %s", other, path);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
    rc = run(&ctx, text, out, sizeof out, &err);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &old), 0);
    assert_int_equal(rc, -1);
    print_message("full disk, merging: %s\n", err.msg);
    assert_non_null(strstr(err.msg, tiles));
    assert_same_file(path, world_bytes, world_len);
    snprintf(text, sizeof text, "load %s; " AREA, path);
    run_ok(&ctx, text, out, sizeof out);
    assert_null(strstr(out, edited));

    free(world_bytes);
    free(tiles_bytes);
    world_close(ctx.world);
    test_rmtree(dir);
}

static void test_read_only_file_refused(void **state) {
    (void)state;
    const char *dir = test_tmpdir("savefail");
    char path[4200], text[4400], out[4096];
    snprintf(path, sizeof path, "%s/w.world", dir);
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    og_error err = {{0}};
    cmd_context ctx;
    cmd_context_init(&ctx, world_create(&p, NULL, &err), NULL, stdout, OROGEN_RESOURCE_DIR);
    snprintf(text, sizeof text, "save %s", path);
    run_ok(&ctx, text, out, sizeof out);
    size_t len;
    char *bytes = slurp(path, &len);
    assert_int_equal(chmod(path, 0444), 0);
    run_ok(&ctx, "dab 10 10", out, sizeof out);
    assert_int_equal(run(&ctx, "save force=1", out, sizeof out, &err), -1);
    snprintf(text, sizeof text, "save: %s is read-only", path);
    assert_non_null(strstr(err.msg, text));
    assert_same_file(path, bytes, len);
    run_ok(&ctx, "info", out, sizeof out);
    assert_non_null(strstr(out, "unsaved_changes=1"));
    assert_int_equal(chmod(path, 0644), 0);
    run_ok(&ctx, "save", out, sizeof out);
    free(bytes);
    world_close(ctx.world);
    test_rmtree(dir);
}

// The folder each failure message and durability sync names: the root keeps its slash,
// a bare name lives in ".", and a short buffer cuts rather than overflows.
static void test_folder_of_path(void **state) {
    (void)state;
    char dir[16];
    path_folder("/a/b/w.orogen", dir, sizeof dir);
    assert_string_equal(dir, "/a/b");
    path_folder("/w.orogen", dir, sizeof dir);
    assert_string_equal(dir, "/");
    path_folder("w.orogen", dir, sizeof dir);
    assert_string_equal(dir, ".");
    path_folder("rel/w.orogen", dir, sizeof dir);
    assert_string_equal(dir, "rel");
    path_folder("/a/very/long/folder/name/w", dir, 8);
    assert_string_equal(dir, "/a/very");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_folder_of_path),
        cmocka_unit_test(test_full_disk_keeps_old_files),
        cmocka_unit_test(test_read_only_file_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
