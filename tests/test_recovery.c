// Crash recovery (editor/world/recovery_journal.c, editor/edit/recover.c), through the
// command language: a session's journal, as a crash leaves it, restores the exact
// terrain (hash) with its steps undoable; a torn or damaged journal restores the
// longest valid prefix, never part of a step; a journal of an older save is not
// replayed; a new session's first edit sets an unrecovered journal aside; discard
// removes it; a quit removes this session's journal when its edits were all undone.
// The journal's records are written on its writer thread: an append returns with the
// record before it in the file, and every record there once waited for, intact.
#include "editor/cmd/commands.h"
#include "editor/edit/recover.h"
#include "editor/cmd/context.h"
#include "editor/world/recovery_journal.h"
#include "support/test_support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#define AREA "hash -100 -100 700 700"

typedef struct session {
    cmd_context ctx;
    char dir[4096], world[4200], journal[4300], backup[4300];
} session;

// Runs text; returns what it printed (malloc'd). It must succeed unless may_fail.
static char *run_maybe(session *s, const char *text, int may_fail, og_error *err) {
    char *printed = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&printed, &len);
    assert_non_null(mem);
    s->ctx.out = mem;
    int rc = cmd_run(&s->ctx, text, strlen(text), "test", err);
    fclose(mem);
    s->ctx.out = stdout;
    if (rc != 0 && !may_fail) fail_msg("'%s' failed: %s", text, err->msg);
    if (rc != 0) {
        free(printed);
        return NULL;
    }
    return printed;
}

// The recovery folder for a test's never-saved worlds, then back to the program's own
// (ctest's, or test_support's private one: never the user's).
static char previous_recover_dir[4200];

static void recover_dir_set(const char *dir) {
    snprintf(previous_recover_dir, sizeof previous_recover_dir, "%s",
             getenv("OROGEN_RECOVER_DIR") ? getenv("OROGEN_RECOVER_DIR") : "");
    setenv("OROGEN_RECOVER_DIR", dir, 1);
}

static void recover_dir_restore(void) {
    if (previous_recover_dir[0])
        setenv("OROGEN_RECOVER_DIR", previous_recover_dir, 1);
    else
        unsetenv("OROGEN_RECOVER_DIR");
}

static void run(session *s, const char *text) {
    og_error err = {{0}};
    free(run_maybe(s, text, 0, &err));
}

// The digest of the area as the hash command prints it (16 hex digits).
static void hash(session *s, char out[17]) {
    og_error err = {{0}};
    char *printed = run_maybe(s, AREA, 0, &err);
    snprintf(out, 17, "%.16s", printed);
    free(printed);
}

static long info_value(session *s, const char *key) {
    og_error err = {{0}};
    char *printed = run_maybe(s, "info", 0, &err);
    const char *at = strstr(printed, key);
    long v = at ? strtol(at + strlen(key), NULL, 10) : -1;
    free(printed);
    return v;
}

static void copy_file(const char *from, const char *to, long cut) {
    FILE *f = fopen(from, "rb");
    assert_non_null(f);
    static char data[1 << 22];
    size_t n = fread(data, 1, sizeof data, f);
    fclose(f);
    if (cut > 0) n -= (size_t)cut;
    test_write_file(to, data, n);
}

static long file_size(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

// A session's folder (a fresh temporary one named after tag), its world's file, the
// world's journal and where a test keeps a copy of it; the context on a new default
// flat world.
static void session_begin(session *s, const char *tag) {
    snprintf(s->dir, sizeof s->dir, "%s", test_tmpdir(tag));
    snprintf(s->world, sizeof s->world, "%s/w.world", s->dir);
    snprintf(s->journal, sizeof s->journal, "%s.recover", s->world);
    snprintf(s->backup, sizeof s->backup, "%s/crash.recover", s->dir);
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    og_error err = {{0}};
    world *w = world_create(&p, NULL, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    cmd_context_init(&s->ctx, w, NULL, stdout, OROGEN_RESOURCE_DIR);
}

// A saved world, loaded again; a session of five journal records, the hash after each
// in h[1..5] (h[0]: the saved state); the journal as a kill at that moment leaves it,
// in s->backup; then the session quits without saving.
static void crashed_session(session *s, char h[6][17]) {
    session_begin(s, "recovery");
    char text[4400];
    snprintf(text, sizeof text, "tool raise radius=30 strength=1; dab 400 400; save %s", s->world);
    run(s, text);
    snprintf(text, sizeof text, "load %s", s->world);
    run(s, text);
    hash(s, h[0]);
    run(s, "tool raise radius=30 strength=1; dab 100 100");
    hash(s, h[1]);
    run(s, "dab 200 200");
    hash(s, h[2]);
    run(s, "undo");
    hash(s, h[3]);
    run(s, "seed 99; generate");
    hash(s, h[4]);
    run(s, "stroke 0 0 300 300");
    hash(s, h[5]);
    assert_string_equal(h[3], h[1]);
    assert_string_not_equal(h[4], h[3]);
    assert_string_not_equal(h[5], h[4]);
    // What a kill -9 leaves once the last record's write (on the journal's thread, tens
    // of microseconds) is done.
    world_journal_wait(s->ctx.world);
    copy_file(s->journal, s->backup, 0);
    run(s, "new flat"); // quits the world without saving: the journal stays
    assert_int_equal(file_size(s->journal), file_size(s->backup));
}

static void reopen(session *s) {
    char text[4400];
    snprintf(text, sizeof text, "load %s", s->world);
    run(s, text);
}

static void finish(session *s) {
    world_close(s->ctx.world);
    test_rmtree(s->dir);
}

static void test_recover_exact(void **state) {
    (void)state;
    session s;
    char h[6][17], now[17];
    crashed_session(&s, h);
    copy_file(s.backup, s.journal, 0);
    reopen(&s);
    assert_int_equal(info_value(&s, "recoverable_steps="), 5);
    hash(&s, now);
    assert_string_equal(now, h[0]); // nothing happens before 'recover'
    run(&s, "recover");
    hash(&s, now);
    assert_string_equal(now, h[5]);
    assert_int_equal(info_value(&s, "unsaved_changes="), 1);
    assert_int_equal(info_value(&s, "recoverable_steps="), 0);
    // The steps are undoable: back through the stroke and the generate.
    run(&s, "undo");
    hash(&s, now);
    assert_string_equal(now, h[4]);
    run(&s, "undo");
    hash(&s, now);
    assert_string_equal(now, h[3]);
    run(&s, "redo; redo");
    hash(&s, now);
    assert_string_equal(now, h[5]);
    // This session's steps follow in the same journal: a second crash recovers all.
    run(&s, "dab 250 250");
    char after[17];
    hash(&s, after);
    world_journal_wait(s.ctx.world);
    copy_file(s.journal, s.backup, 0);
    run(&s, "new flat");
    copy_file(s.backup, s.journal, 0);
    reopen(&s);
    run(&s, "recover");
    hash(&s, now);
    assert_string_equal(now, after);
    // save keeps them and ends the journal.
    run(&s, "save");
    assert_int_equal(access(s.journal, F_OK), -1);
    reopen(&s);
    hash(&s, now);
    assert_string_equal(now, after);
    assert_int_equal(info_value(&s, "recoverable_steps="), 0);
    finish(&s);
}

// Volume edits (a carved cave, an arch) come back from the journal like any other.
static void test_recover_volume(void **state) {
    (void)state;
    session s;
    session_begin(&s, "recovery-volume");
    og_error err = {{0}};
    char text[4400];
    snprintf(text, sizeof text, "set generator flat; generate; save %s", s.world);
    run(&s, text);
    reopen(&s);
    const char *probe = "vsample 50 -4 50; vsample 80 13 80";
    char *before = run_maybe(&s, probe, 0, &err);
    run(&s, "tool carve radius=6 falloff=constant; dab 50 -4 50; arch 70 0 70 90 0 90 rise=12");
    char *after = run_maybe(&s, probe, 0, &err);
    assert_string_not_equal(before, after);
    world_journal_wait(s.ctx.world); // its last record's write done, as for a kill after it
    copy_file(s.journal, s.backup, 0);
    run(&s, "new flat");
    copy_file(s.backup, s.journal, 0);
    reopen(&s);
    char *reloaded = run_maybe(&s, probe, 0, &err);
    assert_string_equal(reloaded, before);
    run(&s, "recover");
    char *recovered = run_maybe(&s, probe, 0, &err);
    assert_string_equal(recovered, after);
    free(before);
    free(after);
    free(reloaded);
    free(recovered);
    finish(&s);
}

// A journal cut anywhere in its last record, or damaged in one, gives the steps before.
static void test_recover_prefix(void **state) {
    (void)state;
    session s;
    char h[6][17], now[17];
    crashed_session(&s, h);
    long size = file_size(s.backup);
    copy_file(s.backup, s.journal, 7); // a torn last record
    reopen(&s);
    assert_int_equal(info_value(&s, "recoverable_steps="), 4);
    run(&s, "recover");
    hash(&s, now);
    assert_string_equal(now, h[4]);
    run(&s, "new flat");

    // A flipped byte in the middle of the file: some prefix, never a torn step.
    copy_file(s.backup, s.journal, 0);
    FILE *f = fopen(s.journal, "r+b");
    assert_non_null(f);
    fseek(f, size / 2, SEEK_SET);
    int c = fgetc(f);
    fseek(f, size / 2, SEEK_SET);
    fputc(c ^ 0x5a, f);
    fclose(f);
    reopen(&s);
    long steps = info_value(&s, "recoverable_steps=");
    assert_true(steps >= 0 && steps < 5);
    if (steps > 0) run(&s, "recover");
    hash(&s, now);
    assert_string_equal(now, h[steps]);
    finish(&s);
}

// A journal of another saved state is not replayed; the first edit of a session that
// did not recover sets the old journal aside; discard removes it.
static void test_recover_stale_aside_discard(void **state) {
    (void)state;
    session s;
    char h[6][17], now[17], text[4400];
    crashed_session(&s, h);
    copy_file(s.backup, s.journal, 0);
    reopen(&s);
    run(&s, "dab 10 10"); // a new session's first edit
    snprintf(text, sizeof text, "%s.old", s.journal);
    assert_int_equal(access(text, F_OK), 0);
    run(&s, "save"); // a new saved state
    copy_file(s.backup, s.journal, 0);
    reopen(&s);
    assert_int_equal(info_value(&s, "recoverable_steps="), 0);
    og_error err = {{0}};
    assert_null(run_maybe(&s, "recover", 1, &err));
    assert_non_null(strstr(err.msg, "no unsaved edits to recover"));
    hash(&s, now);
    run(&s, "recover discard");
    assert_int_equal(access(s.journal, F_OK), -1);
    char after[17];
    hash(&s, after);
    assert_string_equal(now, after);
    finish(&s);
}

// A world that was never saved journals in the recovery folder, onto the parameters it
// was made with; `recover JOURNAL` makes that world again with its steps.
static void test_recover_never_saved(void **state) {
    (void)state;
    session s;
    snprintf(s.dir, sizeof s.dir, "%s", test_tmpdir("recovery"));
    char rec[4200], text[8800], h[3][17], now[17];
    snprintf(rec, sizeof rec, "%s/rec", s.dir);
    recover_dir_set(rec);
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.seed = 4242;
    og_error err = {{0}};
    cmd_context_init(&s.ctx, world_create(&p, NULL, &err), NULL, stdout, OROGEN_RESOURCE_DIR);
    hash(&s, h[0]);
    run(&s, "tool raise radius=30 strength=1; dab 100 100");
    hash(&s, h[1]);
    run(&s, "seed 7; generate; dab 200 200");
    hash(&s, h[2]);
    char journal[4400];
    recovery_scan scan;
    assert_int_equal(edit_find_unsaved_journal(journal, sizeof journal, &scan), 0); // ours: live
    snprintf(s.backup, sizeof s.backup, "%s/crash.recover", s.dir);
    snprintf(text, sizeof text, "%s", world_recovery_path(s.ctx.world));
    world_journal_wait(s.ctx.world);
    copy_file(text, s.backup, 0);
    run(&s, "new flat"); // quits that world: its journal stays
    assert_int_equal(file_size(text), file_size(s.backup));
    snprintf(journal, sizeof journal, "%s/unsaved-1-1-0.recover", rec);
    assert_int_equal(rename(text, journal), 0); // as a kill of another process leaves it
    char found[4400];
    assert_int_equal(edit_find_unsaved_journal(found, sizeof found, &scan), 1);
    assert_string_equal(found, journal);
    assert_int_equal(scan.records, 3);
    og_error e2 = {{0}};
    char *printed = run_maybe(&s, "recover", 1, &e2); // the world's own: none, but points there
    assert_null(printed);
    assert_non_null(strstr(e2.msg, journal));
    snprintf(text, sizeof text, "recover %s", journal);
    run(&s, text);
    hash(&s, now);
    assert_string_equal(now, h[2]);
    assert_int_equal(access(journal, F_OK), -1); // taken over under this process's name
    run(&s, "undo; undo");
    hash(&s, now);
    assert_string_equal(now, h[1]);
    run(&s, "undo");
    hash(&s, now);
    assert_string_equal(now, h[0]);
    recover_dir_restore();
    finish(&s);
}

// Finding 1 of issue 27: a session that edits without recovering sets the crashed
// session's journal aside, and it stays reachable: listed, and restored by name, also
// when a folder holds the first name; nothing of it is lost.
static void test_recover_set_aside_reachable(void **state) {
    (void)state;
    session s;
    char h[6][17], now[17], text[8800], old[4400], old2[4400];
    crashed_session(&s, h);
    snprintf(old, sizeof old, "%s.old", s.journal);
    snprintf(old2, sizeof old2, "%s.old2", s.journal);
    assert_int_equal(mkdir(old, 0755), 0); // the first name is taken
    reopen(&s);
    run(&s, "dab 10 10"); // a new session's first edit
    assert_int_equal(file_size(old2), file_size(s.backup));
    run(&s, "new flat"); // that session quits without saving
    reopen(&s);
    og_error err = {{0}};
    char *listed = run_maybe(&s, "recover list", 0, &err);
    assert_non_null(strstr(listed, old2));
    assert_non_null(strstr(listed, "5 steps"));
    free(listed);
    snprintf(text, sizeof text, "recover %s", old2);
    run(&s, text);
    hash(&s, now);
    assert_string_equal(now, h[5]);
    assert_int_equal(access(s.journal, F_OK), 0); // the other session's stays
    // Recovered, then left without saving: the journal stays (finding 2).
    run(&s, "new flat");
    assert_int_equal(file_size(old2), file_size(s.backup));
    snprintf(text, sizeof text, "load %s; recover %s", s.world, old2);
    run(&s, text);
    hash(&s, now);
    assert_string_equal(now, h[5]);
    // An edit after recovering: a journal cannot be replayed on it, and says so.
    snprintf(text, sizeof text, "recover %s", s.journal);
    assert_null(run_maybe(&s, text, 1, &err));
    assert_non_null(strstr(err.msg, "edits of its own"));
    // From another world, `recover FILE` opens the journal's world.
    snprintf(text, sizeof text, "new flat; recover %s", s.journal);
    run(&s, text);
    assert_string_equal(world_path(s.ctx.world), s.world);
    // save keeps the recovered session's edits and removes only its journal.
    run(&s, "save");
    assert_int_equal(access(s.journal, F_OK), -1);
    assert_int_equal(file_size(old2), file_size(s.backup));
    rmdir(old);
    finish(&s);
}

// Found by the fault harness (issue 27): a dab whose edge touches a never-edited tile
// without changing it, then `generate`: the live session kept that tile's old terrain
// (it had been written back unchanged), while a replay, which has no record of it,
// regenerated it. Both now regenerate it: recovering gives exactly the live terrain.
static void test_recover_untouched_edge_then_generate(void **state) {
    (void)state;
    session s;
    char live[17], now[17], text[4400];
    session_begin(&s, "recovery-edge");
    snprintf(text, sizeof text, "tool raise radius=40 strength=1; dab 450 450; save %s", s.world);
    run(&s, text);
    reopen(&s);
    run(&s, "tool raise radius=74 strength=1; dab 443 39; seed 421; generate");
    hash(&s, live);
    reopen(&s); // leaves without saving: the journal stays
    run(&s, "recover");
    hash(&s, now);
    assert_string_equal(now, live);
    finish(&s);
}

// A session whose edits were all undone has nothing unsaved: quitting it removes the
// journal it began (a saved world's and a never-saved one's), so the next start offers
// nothing to recover; one more edit left unundone keeps it.
static void test_undone_session_leaves_no_journal(void **state) {
    (void)state;
    session s;
    session_begin(&s, "recovery");
    char rec[4200], text[8800], unsaved[4400];
    snprintf(rec, sizeof rec, "%s/rec", s.dir);
    recover_dir_set(rec);
    run(&s, "tool raise radius=30 strength=1; dab 100 100; undo");
    snprintf(unsaved, sizeof unsaved, "%s", world_recovery_path(s.ctx.world));
    assert_int_equal(access(unsaved, F_OK), 0); // the dab was journaled, then its undo
    snprintf(text, sizeof text, "save %s", s.world);
    run(&s, text);
    assert_int_equal(access(unsaved, F_OK), -1);
    reopen(&s);
    run(&s, "dab 200 200; dab 300 300; undo; undo");
    assert_int_equal(access(s.journal, F_OK), 0);
    reopen(&s); // leaves without saving, nothing changed: the journal goes
    assert_int_equal(access(s.journal, F_OK), -1);
    run(&s, "dab 200 200; dab 300 300; undo");
    reopen(&s); // one dab stays unsaved: so does its journal
    assert_int_equal(access(s.journal, F_OK), 0);
    run(&s, "recover discard");
    run(&s, "new flat; dab 100 100; undo");
    snprintf(unsaved, sizeof unsaved, "%s", world_recovery_path(s.ctx.world));
    assert_int_equal(access(unsaved, F_OK), 0);
    run(&s, "new flat"); // a never-saved world back to what it was made as
    assert_int_equal(access(unsaved, F_OK), -1);
    recover_dir_restore();
    finish(&s);
}

// ---- the writer thread ----------------------------------------------------------------

typedef struct read_back {
    history_step *steps[8];
    size_t count;
} read_back;

static int keep_step(void *user, recovery_kind kind, uint64_t session_id, history_step *step,
                     og_error *err) {
    (void)kind, (void)session_id, (void)err;
    read_back *r = user;
    if (r->count == 8) {
        history_step_free(step);
        return -1;
    }
    r->steps[r->count++] = step;
    return 0;
}

static size_t records_in(const char *path, read_back *r) {
    recovery_scan scan;
    og_error err = {{0}};
    if (r) memset(r, 0, sizeof *r);
    if (recovery_journal_read(path, &scan, r ? keep_step : NULL, r, &err) != 0)
        fail_msg("%s", err.msg);
    // Read back once waited for: the whole file is valid (a read meanwhile may see the
    // last record's write under way).
    if (r) assert_int_equal(scan.dropped_bytes, 0);
    return scan.records;
}

// Steps of deltas growing, then shrinking (the writer's buffer is reused for smaller
// records and replaced for larger ones), each filled with bytes of its own: the journal
// holds every record in order, each exactly as appended, and an append returns only once
// the record before it is in the file (a kill loses at most the last step).
static void test_journal_writer_thread(void **state) {
    (void)state;
    char dir[4096], path[4200];
    snprintf(dir, sizeof dir, "%s", test_tmpdir("recovery-writer"));
    snprintf(path, sizeof path, "%s/w.recover", dir);
    og_error err = {{0}};
    recovery_journal *j = recovery_journal_open(path, "", NULL, NULL, 0, &err);
    if (!j) fail_msg("%s", err.msg);
    static const size_t sizes[6] = {70000, 300000, 1000, 90000, 5, 400000};
    history_step *made[6];
    for (int i = 0; i < 6; i++) {
        made[i] = history_step_new("step");
        assert_non_null(made[i]);
        for (int t = 0; t < 2; t++) {
            size_t n = sizes[i] / (t + 1) + 1;
            uint8_t *d = malloc(n);
            assert_non_null(d);
            for (size_t k = 0; k < n; k++)
                d[k] = (uint8_t)(k * 31 + (size_t)i * 7 + (size_t)t);
            tile_key key = {TILE_LAYER_COARSE, 0, t, i, -i};
            assert_int_equal(history_step_add_delta(made[i], key, t, d, n), 0);
        }
        assert_int_equal(recovery_journal_append(j, RECOVERY_STEP, made[i], &err), 0);
        assert_true(records_in(path, NULL) >= (size_t)i); // every one before it, written
    }
    assert_int_equal(recovery_journal_wait(j, &err), 0);
    read_back r;
    assert_int_equal(records_in(path, &r), 6);
    for (int i = 0; i < 6; i++) {
        assert_int_equal(r.steps[i]->tile_count, 2);
        for (int t = 0; t < 2; t++) {
            const history_tile *a = &made[i]->tiles[t], *b = &r.steps[i]->tiles[t];
            assert_true(tile_key_equal(a->key, b->key));
            assert_int_equal(a->bytes, b->bytes);
            assert_memory_equal(a->delta, b->delta, a->bytes);
        }
        history_step_free(r.steps[i]);
        history_step_free(made[i]);
    }
    recovery_journal_close(j);
    test_rmtree(dir);
}

// A command after a step prints only once the step's record is in the journal (the
// writer thread writes it after the commit): the steps `history` shows are all there for
// `recover` after a kill at that moment (e2e_faults kills at random such moments).
static void test_printed_steps_are_journaled(void **state) {
    (void)state;
    session s;
    session_begin(&s, "recovery-printed");
    char text[4400];
    snprintf(text, sizeof text, "tool raise radius=30 strength=1; dab 400 400; save %s", s.world);
    run(&s, text);
    reopen(&s);
    run(&s, "tool raise radius=60 strength=1");
    for (int i = 0; i < 20; i++) {
        snprintf(text, sizeof text, "dab %d %d", 50 + 30 * i, 300 - 10 * i);
        run(&s, text);
        og_error err = {{0}};
        free(run_maybe(&s, "history", 0, &err)); // printed: so journaled
        assert_int_equal(records_in(s.journal, NULL), (size_t)i + 1);
    }
    finish(&s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_recover_exact),
        cmocka_unit_test(test_recover_volume),
        cmocka_unit_test(test_recover_prefix),
        cmocka_unit_test(test_recover_stale_aside_discard),
        cmocka_unit_test(test_recover_never_saved),
        cmocka_unit_test(test_recover_set_aside_reachable),
        cmocka_unit_test(test_recover_untouched_edge_then_generate),
        cmocka_unit_test(test_undone_session_leaves_no_journal),
        cmocka_unit_test(test_journal_writer_thread),
        cmocka_unit_test(test_printed_steps_are_journaled),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
