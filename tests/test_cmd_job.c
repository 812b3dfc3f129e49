// Long work off the UI thread (editor/cmd/cmd_job.c, io/progress.c): a job runs
// command text on its own thread and returns what cmd_run returns; its progress only
// grows; a cancelled stroke, dab or stamp fails with "cancelled" and leaves the
// world's hash and undo history as they were; text with a registered command is
// refused; the progress parts nest.
#include "editor/cmd/cmd_job.h"
#include "editor/cmd/commands.h"
#include "editor/params/world_params.h"
#include "editor/world/world.h"
#include "io/progress.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

static world *flat_world(int64_t size) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.size = size;
    og_error err = {{0}};
    world *w = world_create(&p, NULL, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    return w;
}

// Runs text on this thread; returns what it printed (malloc'd). It must succeed.
static char *run_ok(cmd_context *ctx, const char *text) {
    char *printed = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&printed, &len);
    assert_non_null(mem);
    ctx->out = mem;
    og_error err = {{0}};
    int rc = cmd_run(ctx, text, strlen(text), "test", &err);
    fclose(mem);
    ctx->out = stdout;
    if (rc != 0) fail_msg("'%s' failed: %s", text, err.msg);
    return printed;
}

static void test_progress_parts(void **state) {
    (void)state;
    og_progress p;
    og_progress_init(&p);
    assert_int_equal(og_progress_report(NULL, 1, 2), 0); // no record: nothing to do
    assert_int_equal(og_progress_cancelled(NULL), 0);
    assert_int_equal(og_progress_report(&p, 1, 4), 0);
    assert_true(og_progress_fraction(&p) == 0.25);
    og_progress_part outer = og_progress_enter(&p, 2, 4); // the third quarter: 0.5-0.75
    og_progress_report(&p, 1, 2);
    assert_true(og_progress_fraction(&p) == 0.625);
    og_progress_leave(&p, outer);
    og_progress_report(&p, 1, 4); // never back
    assert_true(og_progress_fraction(&p) == 0.625);
    og_progress_report(&p, 9, 4); // clamped
    assert_true(og_progress_fraction(&p) == 1.0);
    og_progress_cancel(&p);
    assert_int_equal(og_progress_report(&p, 1, 1), -1);
    assert_int_equal(og_progress_cancelled(&p), 1);
}

static void test_job_runs_and_reports(void **state) {
    (void)state;
    cmd_context ctx;
    cmd_context_init(&ctx, flat_world(512), NULL, stdout, OROGEN_RESOURCE_DIR);
    char *before = run_ok(&ctx, "sample 100 100");
    og_error err = {{0}};
    cmd_job *j = cmd_job_start(&ctx, "tool raise radius=20; dab 100 100", "test", NULL, NULL, &err);
    assert_non_null(j);
    assert_string_equal(cmd_job_text(j), "tool raise radius=20; dab 100 100");
    assert_int_equal(cmd_job_wait(j, 60000), 1);
    assert_int_equal(cmd_job_done(j), 1);
    assert_int_equal(cmd_job_finish(j, &err), 0);
    char *after = run_ok(&ctx, "sample 100 100");
    assert_true(atof(after) > atof(before) + 0.1); // the dab raised the ground there
    free(before), free(after);
    // A failing command: cmd_run's error, with the label and line.
    j = cmd_job_start(&ctx, "seed 1\nseed x", "console", NULL, NULL, &err);
    assert_non_null(j);
    assert_int_equal(cmd_job_finish(j, &err), -1);
    assert_non_null(strstr(err.msg, "console:2: error: seed"));
    // Text the tokenizer rejects, and unknown commands, are not run off the thread.
    assert_null(cmd_job_start(&ctx, "seed \"1", "console", NULL, NULL, &err));
    assert_null(cmd_job_start(&ctx, "frobnicate", "console", NULL, NULL, &err));
    assert_non_null(strstr(err.msg, "only the command language's own commands"));
    assert_int_equal(cmd_text_is_builtin("seed 1; tool raise", 18), 1);
    assert_int_equal(cmd_text_is_builtin("seed 1; frobnicate", 18), 0);
    world_close(ctx.world);
}

static int done_calls;
static void on_done(void *user) {
    (void)user;
    __atomic_add_fetch(&done_calls, 1, __ATOMIC_SEQ_CST);
}

// Starts text that runs for minutes, waits until its progress moves, cancels it and
// checks that it failed with "cancelled", leaving hash and history as before.
static void cancel_leaves_no_trace(cmd_context *ctx, const char *setup, const char *text) {
    free(run_ok(ctx, setup));
    char *hash_before = run_ok(ctx, "hash 0 0 1000 1000");
    char *steps_before = run_ok(ctx, "history");
    og_error err = {{0}};
    done_calls = 0;
    cmd_job *j = cmd_job_start(ctx, text, "test", on_done, NULL, &err);
    assert_non_null(j);
    for (int i = 0; i < 6000 && cmd_job_progress(j) == 0.0; i++)
        cmd_job_wait(j, 10);
    double seen = cmd_job_progress(j);
    if (!(seen > 0.0 && seen < 0.5)) fail_msg("'%s': progress %g before the cancel", text, seen);
    assert_int_equal(cmd_job_done(j), 0);
    cmd_job_cancel(j);
    assert_int_equal(cmd_job_cancelled(j), 1);
    assert_int_equal(cmd_job_wait(j, 60000), 1);
    assert_true(cmd_job_elapsed_ms(j) > 0);
    assert_int_equal(cmd_job_finish(j, &err), -1);
    if (!strstr(err.msg, "cancelled")) fail_msg("'%s': error '%s'", text, err.msg);
    assert_int_equal(__atomic_load_n(&done_calls, __ATOMIC_SEQ_CST), 1);
    if (ctx->stroke) free(run_ok(ctx, "stroke_cancel"));
    char *hash_after = run_ok(ctx, "hash 0 0 1000 1000");
    char *steps_after = run_ok(ctx, "history");
    assert_string_equal(hash_after, hash_before);
    assert_string_equal(steps_after, steps_before);
    free(hash_before), free(hash_after), free(steps_before), free(steps_after);
}

static void test_cancel(void **state) {
    (void)state;
    cmd_context ctx;
    cmd_context_init(&ctx, flat_world(512), NULL, stdout, OROGEN_RESOURCE_DIR);
    free(run_ok(&ctx, "generator fbm; generate; dab 200 200"));
    // One hydraulic dab of a million droplets (seconds of work).
    cancel_leaves_no_trace(&ctx, "tool hydraulic radius=500 droplets=1000000", "dab 512 512");
    // Thermal erosion, 1000 iterations over a 500 m radius.
    cancel_leaves_no_trace(&ctx, "tool thermal radius=500 iterations=1000", "dab 512 512");
    // A stroke: its dabs so far are undone by the stroke_cancel the window runs.
    cancel_leaves_no_trace(&ctx, "tool hydraulic radius=200 droplets=1000000",
                           "stroke_begin; stroke_to 300 300; stroke_to 700 700");
    world_close(ctx.world);
}

// An export cancelled while it reads the world (most of its time: tiles are generated)
// writes nothing but whole files named allowed_prefix* (tiles finished before the
// cancel, NULL: none): no temp file, no set's sidecar.
static void cancel_export(cmd_context *ctx, const char *dir, const char *text,
                          const char *allowed_prefix) {
    og_error err = {{0}};
    cmd_job *j = cmd_job_start(ctx, text, "test", NULL, NULL, &err);
    assert_non_null(j);
    for (int i = 0; i < 6000 && cmd_job_progress(j) == 0.0; i++)
        cmd_job_wait(j, 10);
    double seen = cmd_job_progress(j);
    if (!(seen > 0.0 && seen < 0.5)) fail_msg("'%s': progress %g before the cancel", text, seen);
    cmd_job_cancel(j);
    assert_int_equal(cmd_job_wait(j, 60000), 1);
    assert_int_equal(cmd_job_finish(j, &err), -1);
    if (!strstr(err.msg, "cancelled")) fail_msg("'%s': error '%s'", text, err.msg);
    DIR *d = opendir(dir);
    assert_non_null(d);
    for (struct dirent *e; (e = readdir(d));)
        if (e->d_name[0] != '.' &&
            (!allowed_prefix || strncmp(e->d_name, allowed_prefix, strlen(allowed_prefix)) ||
             strstr(e->d_name, ".tmp")))
            fail_msg("'%s': cancelled, yet %s/%s was written", text, dir, e->d_name);
    closedir(d);
}

static void test_cancel_export(void **state) {
    (void)state;
    char dir[] = "/tmp/orogen-export-cancel-XXXXXX";
    assert_non_null(mkdtemp(dir));
    cmd_context ctx;
    cmd_context_init(&ctx, flat_world(0), NULL, stdout, OROGEN_RESOURCE_DIR);
    free(run_ok(&ctx, "generator fbm"));
    char text[512];
    // One file of 6000 x 6000 samples of generated terrain (seconds of generating).
    snprintf(text, sizeof text, "export %s/big.exr region=0,0,6000,6000", dir);
    cancel_export(&ctx, dir, text, NULL);
    // Tiles: those finished before the cancel stay, each whole with its sidecar.
    snprintf(text, sizeof text, "export %s/t.exr region=0,0,6000,6000 tiles=3x3", dir);
    cancel_export(&ctx, dir, text, "t_x");
    world_close(ctx.world);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    assert_int_equal(system(cmd), 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_progress_parts),
        cmocka_unit_test(test_job_runs_and_reports),
        cmocka_unit_test(test_cancel),
        cmocka_unit_test(test_cancel_export),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
