#include "editor/edit/parallel.h"

#include <pthread.h>
#include <stdatomic.h>
#include <unistd.h>

// Workers sleep on a condition variable between jobs; a job hands out task
// numbers through an atomic counter so uneven tasks balance themselves.
static struct {
    pthread_once_t once;
    pthread_mutex_t lock;
    pthread_cond_t start, done;
    int threads;     // including the caller
    unsigned generation;
    int busy;        // workers still inside the current job
    void (*fn)(void *, int);
    void *user;
    int tasks;
    atomic_int next;
} pool = {.once = PTHREAD_ONCE_INIT,
          .lock = PTHREAD_MUTEX_INITIALIZER,
          .start = PTHREAD_COND_INITIALIZER,
          .done = PTHREAD_COND_INITIALIZER};

static void drain(void) {
    for (;;) {
        int t = atomic_fetch_add(&pool.next, 1);
        if (t >= pool.tasks) return;
        pool.fn(pool.user, t);
    }
}

static void *worker(void *arg) {
    (void)arg;
    unsigned seen = 0;
    pthread_mutex_lock(&pool.lock);
    for (;;) {
        while (pool.generation == seen) pthread_cond_wait(&pool.start, &pool.lock);
        seen = pool.generation;
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

void parallel_run(int tasks, void (*fn)(void *user, int task), void *user) {
    if (tasks <= 0) return;
    pthread_once(&pool.once, start_pool);
    if (tasks == 1 || pool.threads == 1) {
        for (int t = 0; t < tasks; t++) fn(user, t);
        return;
    }
    pthread_mutex_lock(&pool.lock);
    pool.fn = fn;
    pool.user = user;
    pool.tasks = tasks;
    atomic_store(&pool.next, 0);
    pool.busy = pool.threads - 1;
    pool.generation++;
    pthread_cond_broadcast(&pool.start);
    pthread_mutex_unlock(&pool.lock);
    drain();
    pthread_mutex_lock(&pool.lock);
    while (pool.busy > 0) pthread_cond_wait(&pool.done, &pool.lock);
    pthread_mutex_unlock(&pool.lock);
}
