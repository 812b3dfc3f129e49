// The editing thread pool (editor/edit/parallel.c): every task runs exactly once
// whatever the count, errors from several tasks give one intact message (the first
// recorded), a failure does not leak into the next run, and repeated jobs stay sound.
#include "editor/edit/parallel.h"

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

typedef struct job {
    atomic_int calls;
    atomic_int *seen;   // per task
    int fail_every;     // tasks t with t % fail_every == fail_every - 1 fail (0: none)
    const int *failing; // or this list (ended by -1)
} job;

static volatile double sink;

static int task(void *user, int t, og_error *err) {
    job *j = user;
    atomic_fetch_add(&j->calls, 1);
    atomic_fetch_add(&j->seen[t], 1);
    double x = 0; // a little work, so several threads run at once
    for (int i = 0; i < 2000; i++)
        x += i * 0.5;
    sink = x;
    int fail = j->fail_every && t % j->fail_every == j->fail_every - 1;
    for (const int *f = j->failing; f && *f >= 0; f++)
        fail |= *f == t;
    if (fail)
        return og_error_set(err, "task %d failed: a message long enough to show interleaving %d", t,
                            t);
    return 0;
}

static job make(int tasks) {
    job j = {0};
    j.seen = calloc((size_t)(tasks > 0 ? tasks : 1), sizeof *j.seen);
    return j;
}

static void test_counts(void **state) {
    (void)state;
    int counts[] = {0, -3, 1, 2, 7, 1000};
    for (size_t k = 0; k < sizeof counts / sizeof counts[0]; k++) {
        int n = counts[k];
        job j = make(n);
        og_error err = {{0}};
        assert_int_equal(parallel_run(n, task, &j, &err), 0);
        assert_int_equal(atomic_load(&j.calls), n > 0 ? n : 0);
        for (int t = 0; t < n; t++)
            if (atomic_load(&j.seen[t]) != 1)
                fail_msg("%d tasks: task %d ran %d times", n, t, j.seen[t]);
        free(j.seen);
    }
    assert_true(parallel_threads() >= 1);
}

static void test_errors(void **state) {
    (void)state;
    const int failing[] = {3, 500, 999, -1};
    job j = make(1000);
    j.failing = failing;
    og_error err = {{0}};
    assert_int_equal(parallel_run(1000, task, &j, &err), -1);
    assert_int_equal(atomic_load(&j.calls), 1000); // every task ran anyway
    int matched = 0;
    for (int i = 0; i < 3; i++) {
        char want[128];
        snprintf(want, sizeof want, "task %d failed: a message long enough to show interleaving %d",
                 failing[i], failing[i]);
        matched += strcmp(err.msg, want) == 0;
    }
    if (matched != 1) fail_msg("the error is not one task's intact message: '%s'", err.msg);
    free(j.seen);
    // Every task failing: still one intact message; NULL err is allowed.
    j = make(64);
    j.fail_every = 1;
    assert_int_equal(parallel_run(64, task, &j, &err), -1);
    assert_non_null(strstr(err.msg, "task "));
    assert_int_equal(parallel_run(64, task, &j, NULL), -1);
    free(j.seen);
    // A clean run after a failing one reports nothing.
    j = make(100);
    memset(&err, 0, sizeof err);
    assert_int_equal(parallel_run(100, task, &j, &err), 0);
    assert_string_equal(err.msg, "");
    free(j.seen);
}

static void test_repeated_jobs(void **state) {
    (void)state;
    for (int round = 0; round < 2000; round++) {
        int n = 1 + round % 17;
        job j = make(n);
        j.fail_every = round % 5 == 0 ? 4 : 0;
        og_error err = {{0}};
        int rc = parallel_run(n, task, &j, &err);
        assert_int_equal(rc, j.fail_every && n >= 4 ? -1 : 0);
        assert_int_equal(atomic_load(&j.calls), n);
        free(j.seen);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_counts),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_repeated_jobs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
