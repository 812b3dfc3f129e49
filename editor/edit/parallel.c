#include "editor/edit/parallel.h"

#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <unistd.h>

// Workers sleep on a condition variable between jobs; a job hands out task
// numbers through an atomic counter so uneven tasks balance themselves. A worker
// joins a job only while it is open, so the caller never waits for a late wake-up.
static struct {
    pthread_once_t once;
    pthread_mutex_t lock;
    pthread_cond_t start, done;
    int threads; // including the caller
    unsigned generation;
    int busy;   // workers that joined the current job and are still inside it
    int closed; // the caller ran out of tasks: workers waking later stay out of the job
    parallel_task_fn fn;
    void *user;
    int tasks;
    atomic_int next;
    int failed;      // under lock: a task of the current job failed
    og_error *first; // where the first failure's message goes
} pool = {.once = PTHREAD_ONCE_INIT,
          .lock = PTHREAD_MUTEX_INITIALIZER,
          .start = PTHREAD_COND_INITIALIZER,
          .done = PTHREAD_COND_INITIALIZER};

// Keeps the first failure's message; any later one is dropped.
static void record_failure(const og_error *e) {
    pthread_mutex_lock(&pool.lock);
    if (!pool.failed) {
        pool.failed = 1;
        if (pool.first) *pool.first = *e;
    }
    pthread_mutex_unlock(&pool.lock);
}

static void drain(void) {
    for (;;) {
        int t = atomic_fetch_add(&pool.next, 1);
        if (t >= pool.tasks) return;
        og_error e; // 1 KB: an empty message, not a zeroed buffer, per task
        e.msg[0] = '\0';
        if (pool.fn(pool.user, t, &e) != 0) record_failure(&e);
    }
}

static void *worker(void *arg) {
    (void)arg;
    // Woken, a worker does not preempt the thread that woke it (SCHED_BATCH: no wake-up
    // preemption, the same share of CPU): with the other core busy (another program),
    // the worker a commit woke for its level-0 undo deltas took the committing thread's
    // core for their 16 us, and the commit waited (edit_record_start: 24 us instead of
    // 3). Not woken in time, its tasks are the caller's (close_job).
    struct sched_param batch = {0};
    pthread_setschedparam(pthread_self(), SCHED_BATCH, &batch);
    unsigned seen = 0;
    pthread_mutex_lock(&pool.lock);
    for (;;) {
        while (pool.generation == seen)
            pthread_cond_wait(&pool.start, &pool.lock);
        seen = pool.generation;
        // Woken too late (a loaded machine): the job is over, or done by the others.
        if (pool.closed) continue;
        pool.busy++;
        pthread_mutex_unlock(&pool.lock);
        drain();
        pthread_mutex_lock(&pool.lock);
        if (--pool.busy == 0) pthread_cond_signal(&pool.done);
    }
    return NULL;
}

static void start_pool(void) {
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    pool.threads = n < 1 ? 1 : n > 64 ? 64 : (int)n;
    for (int i = 1; i < pool.threads; i++) {
        pthread_t t;
        pthread_attr_t attr;
        pthread_attr_init(&attr);
        pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
        if (pthread_create(&t, &attr, worker, NULL) != 0) {
            pool.threads = i; // run with what we have
            pthread_attr_destroy(&attr);
            break;
        }
        pthread_attr_destroy(&attr);
    }
}

int parallel_threads(void) {
    pthread_once(&pool.once, start_pool);
    return pool.threads;
}

// A job parallel_start opened: the caller's own state (parallel_run and parallel_start
// are called from one thread). Its failure goes to async_err, copied out at the finish.
static struct {
    int open;
    og_error err;
} async;

static int run_here(int tasks, parallel_task_fn fn, void *user, og_error *err) {
    int failed = 0;
    for (int t = 0; t < tasks; t++) {
        og_error e;
        e.msg[0] = '\0';
        if (fn(user, t, &e) != 0 && !failed++ && err) *err = e;
    }
    return failed ? -1 : 0;
}

static void open_job(int tasks, parallel_task_fn fn, void *user, og_error *err) {
    pthread_mutex_lock(&pool.lock);
    pool.fn = fn;
    pool.user = user;
    pool.tasks = tasks;
    pool.failed = 0;
    pool.first = err;
    atomic_store(&pool.next, 0);
    pool.busy = 0;
    pool.closed = 0;
    pool.generation++;
    pthread_mutex_unlock(&pool.lock);
    pthread_cond_broadcast(&pool.start); // unlocked: a woken worker need not wait for it
}

// The caller takes the tasks left, then waits for the workers inside the job.
static int close_job(void) {
    drain();
    // Every task is taken: wait only for the workers running one, not for those the
    // scheduler has yet to wake (on a busy machine that can take milliseconds).
    pthread_mutex_lock(&pool.lock);
    pool.closed = 1;
    while (pool.busy > 0)
        pthread_cond_wait(&pool.done, &pool.lock);
    int failed = pool.failed;
    pool.first = NULL;
    pthread_mutex_unlock(&pool.lock);
    return failed ? -1 : 0;
}

int parallel_run(int tasks, parallel_task_fn fn, void *user, og_error *err) {
    if (tasks <= 0) return 0;
    pthread_once(&pool.once, start_pool);
    // With a started job open, the pool is its: this one runs on the caller alone.
    if (tasks == 1 || pool.threads == 1 || async.open) return run_here(tasks, fn, user, err);
    open_job(tasks, fn, user, err);
    return close_job();
}

void parallel_start(int tasks, parallel_task_fn fn, void *user) {
    pthread_once(&pool.once, start_pool);
    async.err = (og_error){{0}};
    if (tasks <= 0) return;
    async.open = 1;
    open_job(tasks, fn, user, &async.err);
}

int parallel_finish(og_error *err) {
    if (!async.open) return 0;
    int rc = close_job();
    async.open = 0;
    if (rc != 0 && err) *err = async.err;
    return rc;
}
