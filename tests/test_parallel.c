// The editing thread pool (editor/edit/parallel.c): zero and negative task counts,
// one task, many more tasks than threads (every task exactly once), real concurrency,
// errors from several tasks (one message, intact, every task still run), every task
// failing, err == NULL, no stale error or stale err pointer after a failing run, and
// thousands of small jobs in a row; a started job (parallel_start ... parallel_finish)
// with parallel_run jobs inside it, its failures, and many in a row.
#include "editor/edit/parallel.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

// ---- a configurable job --------------------------------------------------------------

typedef struct job {
    int tasks;
    atomic_int calls;    // tasks run
    atomic_int *slots;   // times each task ran
    const int *failing;  // tasks that fail, ended by -1 (NULL: none)
    int fail_all;        // every task fails
    int work;            // busy-loop iterations per task
    atomic_int inflight; // tasks running right now
    atomic_int peak;     // most tasks seen running at once
    atomic_int outside;  // calls with a task number outside [0, tasks)
} job;

static job *job_new(int tasks, int work) {
    job *j = calloc(1, sizeof *j);
    j->tasks = tasks;
    j->slots = calloc((size_t)(tasks > 0 ? tasks : 1), sizeof *j->slots);
    j->work = work;
    return j;
}

static void job_free(job *j) {
    free(j->slots);
    free(j);
}

// A task's failure message: long and made of the task's own digits, so that a
// message torn between two tasks (or written over) cannot pass for either.
static void failure_message(int t, char *buf, size_t len) {
    int n = snprintf(buf, len, "task %d failed:", t);
    char digit = (char)('0' + t % 10);
    while ((size_t)n + 2 < len && n < 600)
        buf[n++] = digit;
    buf[n] = 0;
}

static atomic_uint sink; // keeps the busy loops from being optimised away (atomic: tasks share it)

static int task(void *user, int t, og_error *err) {
    job *j = user;
    if (t < 0 || t >= j->tasks) { // no cmocka assertion here: this may be a pool thread
        atomic_fetch_add(&j->outside, 1);
        return 0;
    }
    int now = atomic_fetch_add(&j->inflight, 1) + 1;
    for (int p = atomic_load(&j->peak);
         now > p && !atomic_compare_exchange_weak(&j->peak, &p, now);)
        ;
    atomic_fetch_add(&j->calls, 1);
    atomic_fetch_add(&j->slots[t], 1);
    unsigned x = (unsigned)t; // a little work, so that several threads run at once
    for (int i = 0; i < j->work; i++)
        x = x * 1103515245u + 12345u;
    atomic_store_explicit(&sink, x, memory_order_relaxed);
    int fail = j->fail_all;
    for (const int *f = j->failing; f && *f >= 0; f++)
        fail |= *f == t;
    atomic_fetch_sub(&j->inflight, 1);
    if (fail) {
        char msg[700];
        failure_message(t, msg, sizeof msg);
        return og_error_set(err, "%s", msg);
    }
    return 0;
}

// Every task ran exactly once.
static void assert_each_once(const job *j) {
    assert_int_equal(atomic_load(&j->outside), 0);
    assert_int_equal(atomic_load(&j->calls), j->tasks);
    for (int t = 0; t < j->tasks; t++)
        if (atomic_load(&j->slots[t]) != 1)
            fail_msg("%d tasks: task %d ran %d times", j->tasks, t, atomic_load(&j->slots[t]));
}

// The task whose intact failure message msg is, or -1.
static int message_owner(const char *msg) {
    int t = -1;
    if (sscanf(msg, "task %d failed:", &t) != 1 || t < 0) return -1;
    char want[700];
    failure_message(t, want, sizeof want);
    return strcmp(msg, want) == 0 ? t : -1;
}

static const char *SENTINEL = "untouched sentinel";

static void set_sentinel(og_error *e) {
    memset(e, 0, sizeof *e);
    snprintf(e->msg, sizeof e->msg, "%s", SENTINEL);
}

// ---- tests ---------------------------------------------------------------------------

static void test_threads(void **state) {
    (void)state;
    int n = parallel_threads();
    print_message("parallel_threads() = %d\n", n);
    assert_true(n >= 1 && n <= 64);
    assert_int_equal(parallel_threads(), n); // stable
}

static void test_no_tasks(void **state) {
    (void)state;
    int counts[] = {0, -1, -1000, -2147483647 - 1};
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        job *j = job_new(0, 0);
        j->fail_all = 1; // would fail if ever called
        og_error err;
        set_sentinel(&err);
        assert_int_equal(parallel_run(counts[i], task, j, &err), 0);
        assert_int_equal(atomic_load(&j->calls), 0);
        assert_string_equal(err.msg, SENTINEL);
        assert_int_equal(parallel_run(counts[i], task, j, NULL), 0);
        assert_int_equal(atomic_load(&j->calls), 0);
        job_free(j);
    }
}

static void test_one_task(void **state) {
    (void)state;
    job *j = job_new(1, 100);
    og_error err;
    set_sentinel(&err);
    assert_int_equal(parallel_run(1, task, j, &err), 0);
    assert_each_once(j);
    assert_string_equal(err.msg, SENTINEL);
    job_free(j);
    // One failing task: its message, intact.
    static const int zero[] = {0, -1};
    j = job_new(1, 100);
    j->failing = zero;
    assert_int_equal(parallel_run(1, task, j, &err), -1);
    assert_int_equal(message_owner(err.msg), 0);
    assert_each_once(j);
    assert_int_equal(parallel_run(1, task, j, NULL), -1);
    assert_int_equal(atomic_load(&j->calls), 2);
    job_free(j);
}

static void test_more_tasks_than_threads(void **state) {
    (void)state;
    int counts[] = {2, 3, parallel_threads(), parallel_threads() + 1, 64, 65, 1000, 4099};
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        job *j = job_new(counts[i], 3000);
        og_error err;
        set_sentinel(&err);
        assert_int_equal(parallel_run(counts[i], task, j, &err), 0);
        assert_each_once(j);
        assert_string_equal(err.msg, SENTINEL); // success leaves err alone
        if (counts[i] == 1000)
            print_message("1000 tasks: at most %d at once\n", atomic_load(&j->peak));
        job_free(j);
    }
}

// Every thread of the pool takes part: parallel_threads() tasks that each wait until
// all of them are running at once can only finish if as many threads run them.
typedef struct rendezvous {
    int want;
    atomic_int arrived;
    atomic_int timed_out;
} rendezvous;

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static int meet(void *user, int t, og_error *err) {
    (void)t, (void)err;
    rendezvous *r = user;
    atomic_fetch_add(&r->arrived, 1);
    double limit = now_seconds() + 5.0; // generous: the machine may be busy
    while (atomic_load(&r->arrived) < r->want)
        if (now_seconds() > limit) {
            atomic_store(&r->timed_out, 1);
            break;
        }
    return 0;
}

static void test_threads_really_run_at_once(void **state) {
    (void)state;
    rendezvous r = {.want = parallel_threads()};
    og_error err;
    set_sentinel(&err);
    assert_int_equal(parallel_run(r.want, meet, &r, &err), 0);
    assert_int_equal(atomic_load(&r.arrived), r.want);
    if (atomic_load(&r.timed_out))
        fail_msg("%d tasks never ran at the same time on %d threads", r.want, r.want);
}

static void test_errors_from_several_tasks(void **state) {
    (void)state;
    static const int failing[] = {3, 500, 999, -1};
    for (int round = 0; round < 20; round++) {
        job *j = job_new(1000, 2000);
        j->failing = failing;
        og_error err;
        set_sentinel(&err);
        assert_int_equal(parallel_run(1000, task, j, &err), -1);
        assert_each_once(j); // the failures stopped nothing
        int owner = message_owner(err.msg);
        if (owner != 3 && owner != 500 && owner != 999)
            fail_msg("the error is not one failing task's intact message: '%.80s...'", err.msg);
        job_free(j);
    }
}

static void test_every_task_fails(void **state) {
    (void)state;
    int counts[] = {2, 7, 1000};
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        job *j = job_new(counts[i], 1000);
        j->fail_all = 1;
        og_error err;
        set_sentinel(&err);
        assert_int_equal(parallel_run(counts[i], task, j, &err), -1);
        assert_each_once(j);
        int owner = message_owner(err.msg);
        if (owner < 0 || owner >= counts[i])
            fail_msg("%d failing tasks: the error is not one task's intact message: '%.80s...'",
                     counts[i], err.msg);
        job_free(j);
    }
}

static void test_err_may_be_null(void **state) {
    (void)state;
    // parallel.c checks err before writing it (record_failure tests pool.first, the
    // one-thread path tests err), so NULL is allowed on both paths.
    static const int some[] = {0, 5, 99, -1};
    job *j = job_new(100, 500);
    j->failing = some;
    assert_int_equal(parallel_run(100, task, j, NULL), -1);
    assert_each_once(j);
    job_free(j);
    j = job_new(100, 500);
    assert_int_equal(parallel_run(100, task, j, NULL), 0);
    assert_each_once(j);
    job_free(j);
}

static void test_failure_then_clean_run(void **state) {
    (void)state;
    static const int failing[] = {1, 17, -1};
    job *j = job_new(200, 500);
    j->failing = failing;
    og_error first;
    set_sentinel(&first);
    assert_int_equal(parallel_run(200, task, j, &first), -1);
    int owner = message_owner(first.msg);
    assert_true(owner == 1 || owner == 17);
    job_free(j);
    // The next run succeeds and says nothing about the old failure.
    j = job_new(200, 500);
    og_error second;
    set_sentinel(&second);
    assert_int_equal(parallel_run(200, task, j, &second), 0);
    assert_string_equal(second.msg, SENTINEL);
    assert_each_once(j);
    job_free(j);
    // A failing run with err == NULL writes nowhere, in particular not into the err
    // of an earlier run (the pool must not keep that pointer).
    set_sentinel(&first);
    j = job_new(200, 500);
    j->failing = failing;
    assert_int_equal(parallel_run(200, task, j, NULL), -1);
    assert_string_equal(first.msg, SENTINEL);
    job_free(j);
    // And a clean run after that one still returns 0.
    j = job_new(200, 500);
    assert_int_equal(parallel_run(200, task, j, &second), 0);
    assert_string_equal(second.msg, SENTINEL);
    job_free(j);
}

static void test_many_small_jobs(void **state) {
    (void)state;
    double start = now_seconds();
    for (int round = 0; round < 2000; round++) {
        int n = round % 37 - 2; // -2 .. 34, the one-task path included
        job *j = job_new(n > 0 ? n : 0, 200 + round % 7 * 100);
        int fail_at[] = {round % 5 == 0 ? round % (n > 0 ? n : 1) : -1, -1};
        j->failing = fail_at;
        og_error err;
        set_sentinel(&err);
        int want_fail = n > 0 && fail_at[0] >= 0;
        int rc = parallel_run(n, task, j, round % 11 == 0 ? NULL : &err);
        if (rc != (want_fail ? -1 : 0)) fail_msg("round %d (%d tasks): rc %d", round, n, rc);
        assert_each_once(j);
        if (round % 11 != 0) {
            if (want_fail)
                assert_int_equal(message_owner(err.msg), fail_at[0]);
            else
                assert_string_equal(err.msg, SENTINEL);
        }
        job_free(j);
    }
    print_message("2000 jobs in %.3f s\n", now_seconds() - start);
}

// Tasks may take very different times: the counter hands out work as threads free up.
static int uneven(void *user, int t, og_error *err) {
    (void)err;
    atomic_int *slots = user;
    unsigned x = (unsigned)t;
    int work = t % 50 == 0 ? 200000 : 100;
    for (int i = 0; i < work; i++)
        x = x * 1664525u + 1013904223u;
    atomic_store_explicit(&sink, x, memory_order_relaxed);
    atomic_fetch_add(&slots[t], 1);
    return 0;
}

static void test_uneven_tasks(void **state) {
    (void)state;
    atomic_int *slots = calloc(500, sizeof *slots);
    assert_int_equal(parallel_run(500, uneven, slots, NULL), 0);
    for (int t = 0; t < 500; t++)
        assert_int_equal(atomic_load(&slots[t]), 1);
    free(slots);
}

// A started job runs each task once while the caller runs parallel_run jobs of its own
// (on the caller alone: the pool is the started job's), and its failure comes back
// from parallel_finish, intact, or not at all.
static void test_started_job(void **state) {
    (void)state;
    for (int round = 0; round < 300; round++) {
        int n = 1 + round % 9;
        job *started = job_new(n, 3000);
        int fail_at[] = {round % 4 == 0 ? round % n : -1, -1};
        started->failing = fail_at;
        parallel_start(n, task, started);
        for (int k = 0; k < round % 3; k++) { // the caller's own jobs meanwhile
            job *inner = job_new(5 + k * 20, 300);
            og_error err;
            set_sentinel(&err);
            assert_int_equal(parallel_run(inner->tasks, task, inner, &err), 0);
            assert_each_once(inner);
            assert_int_equal(atomic_load(&inner->peak), 1);
            assert_string_equal(err.msg, SENTINEL);
            job_free(inner);
        }
        og_error err;
        set_sentinel(&err);
        int rc = parallel_finish(round % 7 == 0 ? NULL : &err);
        assert_int_equal(rc, fail_at[0] >= 0 ? -1 : 0);
        assert_each_once(started);
        if (round % 7 != 0) {
            if (fail_at[0] >= 0)
                assert_int_equal(message_owner(err.msg), fail_at[0]);
            else
                assert_string_equal(err.msg, SENTINEL);
        }
        assert_int_equal(parallel_finish(&err), 0); // nothing open
        job_free(started);
    }
    // After them, parallel_run uses the pool again.
    job *j = job_new(1000, 2000);
    assert_int_equal(parallel_run(1000, task, j, NULL), 0);
    assert_each_once(j);
    job_free(j);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_threads),
        cmocka_unit_test(test_no_tasks),
        cmocka_unit_test(test_one_task),
        cmocka_unit_test(test_more_tasks_than_threads),
        cmocka_unit_test(test_threads_really_run_at_once),
        cmocka_unit_test(test_errors_from_several_tasks),
        cmocka_unit_test(test_every_task_fails),
        cmocka_unit_test(test_err_may_be_null),
        cmocka_unit_test(test_failure_then_clean_run),
        cmocka_unit_test(test_many_small_jobs),
        cmocka_unit_test(test_uneven_tasks),
        cmocka_unit_test(test_started_job),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
