// A small persistent thread pool for editing work that must use every core (a big
// brush dab, mip rebuilds, undo). One job at a time: the caller joins in and returns
// when every task has run.
#ifndef OROGEN_EDITOR_PARALLEL_H
#define OROGEN_EDITOR_PARALLEL_H

#include "io/err.h"

// One task: returns 0, or -1 with err set. err is the task's own (never shared), so
// a task may write it freely.
typedef int (*parallel_task_fn)(void *user, int task, og_error *err);

// Runs fn(user, t, ...) for every t in [0, tasks), spread over the pool's threads and
// the caller; every task runs even after one fails. Returns 0 when all succeeded,
// else -1 with *err holding the first failure's message (first in time, recorded
// under a lock; the others are dropped). Tasks must be independent. Call from one
// thread at a time (the editor's).
int parallel_run(int tasks, parallel_task_fn fn, void *user, og_error *err);

// parallel_run in two halves, so that the caller works on while the pool's workers take
// the job's tasks: parallel_start opens the job and returns at once; parallel_finish
// runs on the caller the tasks no worker took yet, waits for those running, and
// returns as parallel_run does. Meanwhile parallel_run runs its tasks on the caller
// alone, and nothing the tasks read may change. One started job at a time.
void parallel_start(int tasks, parallel_task_fn fn, void *user);
int parallel_finish(og_error *err);

// Threads that parallel_run uses, caller included (the number of online CPUs).
int parallel_threads(void);

#endif
