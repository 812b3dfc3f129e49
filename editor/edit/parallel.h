// A small persistent thread pool for editing work that must use every core (a big
// brush dab, mip rebuilds). One job at a time: the caller joins in and returns when
// every task has run.
#ifndef OROGEN_EDITOR_PARALLEL_H
#define OROGEN_EDITOR_PARALLEL_H

// Runs fn(user, t) for t in [0, tasks), spread over the pool's threads and the caller.
// Tasks must be independent. Safe to call from one thread at a time (the editor's).
void parallel_run(int tasks, void (*fn)(void *user, int task), void *user);

// Threads that parallel_run uses, caller included (the number of online CPUs).
int parallel_threads(void);

#endif
