// One writer per world (io/file_lock.c, editor/world/world.c): a world another live
// process has open loads read-only with that process named, refuses to save over its
// files even forced, and saves elsewhere; once that process is killed (kill -9 leaves
// its lock file behind) the lock is taken over, with a word about it.
#include "editor/world/world.h"
#include "io/file_lock.h"
#include "support/test_support.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

typedef struct messages {
    char text[8][1024];
    int count;
} messages;

static void collect(void *user, const char *message) {
    messages *m = user;
    if (m->count < 8) snprintf(m->text[m->count++], sizeof m->text[0], "%s", message);
}

static int has_message(const messages *m, const char *part) {
    for (int i = 0; i < m->count; i++)
        if (strstr(m->text[i], part)) return 1;
    return 0;
}

static world_settings settings_with(messages *m) {
    return (world_settings){.workers = 1, .warn = collect, .warn_user = m};
}

// A child process that opens the world and keeps it open until killed. Returns its pid
// once it has the world open.
static pid_t open_in_child(const char *path) {
    int ready[2];
    assert_int_equal(pipe(ready), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        close(ready[0]);
        messages m = {0};
        world_settings s = settings_with(&m);
        og_error err;
        world *w = world_load(path, &s, NULL, &err);
        char ok = w && !world_read_only(w)[0] ? 'y' : 'n';
        if (write(ready[1], &ok, 1) != 1) _exit(2);
        for (;;)
            pause();
    }
    close(ready[1]);
    char ok = 0;
    assert_int_equal(read(ready[0], &ok, 1), 1);
    close(ready[0]);
    assert_int_equal(ok, 'y');
    return pid;
}

// A new world saved at path, then closed (no threads of ours run while a child forks).
static void save_new_world(const char *path, world_settings *s) {
    og_error err = {{0}};
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    world *w = world_create(&p, s, &err);
    assert_non_null(w);
    assert_int_equal(world_save(w, path, 0, &err), 0);
    world_close(w);
}

static void test_second_process_is_read_only(void **state) {
    (void)state;
    const char *dir = test_tmpdir("lock");
    char path[4200], other[4200], lock[4300], text[64];
    snprintf(path, sizeof path, "%s/w.world", dir);
    snprintf(other, sizeof other, "%s/copy.world", dir);
    snprintf(lock, sizeof lock, "%s/w.tiles.lock", dir);
    messages m = {0};
    world_settings s = settings_with(&m);
    og_error err = {{0}};
    save_new_world(path, &s);
    assert_int_equal(access(lock, F_OK), -1); // a closed world leaves no lock behind

    pid_t child = open_in_child(path);
    world *w = world_load(path, &s, NULL, &err);
    assert_non_null(w);
    snprintf(text, sizeof text, "is open in process %ld: opened read-only", (long)child);
    assert_true(has_message(&m, text));
    assert_non_null(strstr(world_read_only(w), "open in process"));
    // Not over its files, not even forced; elsewhere, yes.
    assert_int_equal(world_save(w, NULL, 0, &err), -1);
    snprintf(text, sizeof text, "is open in process %ld", (long)child);
    assert_non_null(strstr(err.msg, text));
    assert_int_equal(world_save(w, path, 1, &err), -1);
    assert_int_equal(world_save(w, other, 0, &err), 0);
    world_close(w);

    // kill -9: its lock file stays, nobody holds it; the next load takes it over.
    kill(child, SIGKILL);
    waitpid(child, NULL, 0);
    assert_int_equal(access(lock, F_OK), 0);
    m.count = 0;
    w = world_load(path, &s, NULL, &err);
    assert_non_null(w);
    assert_string_equal(world_read_only(w), "");
    snprintf(text, sizeof text, "took over the lock of process %ld", (long)child);
    assert_true(has_message(&m, text));
    assert_int_equal(world_save(w, NULL, 0, &err), 0);
    world_close(w);
    test_rmtree(dir);
}

// A read-only world whose other owner went away saves over its files after all.
static void test_save_after_owner_left(void **state) {
    (void)state;
    const char *dir = test_tmpdir("lock");
    char path[4200];
    snprintf(path, sizeof path, "%s/w.world", dir);
    messages m = {0};
    world_settings s = settings_with(&m);
    og_error err = {{0}};
    save_new_world(path, &s);
    pid_t child = open_in_child(path);
    world *w = world_load(path, &s, NULL, &err);
    assert_non_null(strstr(world_read_only(w), "open in process"));
    kill(child, SIGKILL);
    waitpid(child, NULL, 0);
    if (world_save(w, NULL, 0, &err) != 0) fail_msg("%s", err.msg);
    assert_string_equal(world_read_only(w), "");
    world_close(w);
    test_rmtree(dir);
}

// The lock itself: the pid is written; a second holder in this process is refused (a
// flock belongs to an open file); release removes the file.
static void test_file_lock(void **state) {
    (void)state;
    const char *dir = test_tmpdir("lock");
    char path[4200];
    snprintf(path, sizeof path, "%s/x.lock", dir);
    file_lock a, b;
    long owner = -1, stale = -1;
    og_error err = {{0}};
    assert_int_equal(file_lock_acquire(&a, path, &owner, &stale, &err), FILE_LOCK_ACQUIRED);
    assert_int_equal(stale, 0);
    assert_int_equal(file_lock_acquire(&b, path, &owner, &stale, &err), FILE_LOCK_HELD);
    assert_int_equal(owner, (long)getpid());
    file_lock_release(&a);
    assert_int_equal(access(path, F_OK), -1);
    // A lock file nobody holds is stale, whatever pid it names.
    test_write_file(path, "999999\n", 7);
    assert_int_equal(file_lock_acquire(&b, path, &owner, &stale, &err), FILE_LOCK_ACQUIRED);
    assert_int_equal(stale, 999999);
    file_lock_release(&b);
    test_rmtree(dir);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_file_lock),
        cmocka_unit_test(test_second_process_is_read_only),
        cmocka_unit_test(test_save_after_owner_left),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
