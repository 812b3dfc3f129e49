#include "editor/cmd/cmd_job.h"

#include "editor/cmd/commands.h"
#include "io/progress.h"

#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

struct cmd_job {
    cmd_context *ctx;
    cmd_work work;
    char *text; // for the progress line
    char label[64];
    void (*on_done)(void *user);
    void *user;
    og_progress progress;
    pthread_mutex_t lock;
    pthread_cond_t changed;
    int done;     // under lock: the work has finished
    int released; // under lock: on_done has returned; the job thread is done with it
    int rc;
    og_error err;
    struct timespec started;
    cmd_job *next; // the job thread's queue
};

// The one job thread, started with the first job and waiting for the next one after.
static pthread_once_t worker_once = PTHREAD_ONCE_INIT;
static pthread_mutex_t worker_lock = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t worker_wake = PTHREAD_COND_INITIALIZER;
static cmd_job *worker_head, *worker_tail; // under worker_lock
static int worker_error;                   // pthread_create's error, when it failed

static double since_ms(const struct timespec *t0) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)(t.tv_sec - t0->tv_sec) * 1e3 + (double)(t.tv_nsec - t0->tv_nsec) * 1e-6;
}

void cmd_work_free(cmd_work *w) {
    cmd_script_free(&w->script);
    free(w->points);
    w->points = NULL;
    w->point_count = 0;
}

static int run_points(cmd_job *j) {
    og_error inner = {{0}};
    for (size_t i = 0; i < j->work.point_count; i++)
        if (cmd_stroke_to_point(j->ctx, &j->work.points[i], &inner) != 0)
            return og_error_set(&j->err, "%s:%zu: error: %s", j->label, i + 1, inner.msg);
    return 0;
}

static void run_job(cmd_job *j) {
    og_progress_install(&j->progress);
    j->rc = j->work.points ? run_points(j) : cmd_script_run(j->ctx, &j->work.script, &j->err);
    og_progress_install(NULL);
    pthread_mutex_lock(&j->lock);
    j->done = 1;
    pthread_cond_broadcast(&j->changed);
    pthread_mutex_unlock(&j->lock);
    if (j->on_done) j->on_done(j->user);
    pthread_mutex_lock(&j->lock);
    j->released = 1;
    pthread_cond_broadcast(&j->changed);
    pthread_mutex_unlock(&j->lock);
}

static void *worker_main(void *arg) {
    (void)arg;
    for (;;) {
        pthread_mutex_lock(&worker_lock);
        while (!worker_head)
            pthread_cond_wait(&worker_wake, &worker_lock);
        cmd_job *j = worker_head;
        worker_head = j->next;
        if (!worker_head) worker_tail = NULL;
        pthread_mutex_unlock(&worker_lock);
        run_job(j);
    }
    return NULL;
}

static void worker_start(void) {
    pthread_t thread;
    worker_error = pthread_create(&thread, NULL, worker_main, NULL);
    if (worker_error == 0) pthread_detach(thread); // it lives as long as the program
}

// "a b; c d": what the job runs, for the progress line.
static char *script_text(const cmd_script *s) {
    size_t n = 1;
    for (size_t i = 0; i < s->count; i++)
        for (int a = 0; a < s->calls[i].argc; a++)
            n += strlen(s->calls[i].argv[a]) + 2;
    char *text = malloc(n), *at = text;
    if (!text) return NULL;
    *at = 0;
    for (size_t i = 0; i < s->count; i++)
        for (int a = 0; a < s->calls[i].argc; a++)
            at += sprintf(at, "%s%s", i && !a ? "; " : a ? " " : "", s->calls[i].argv[a]);
    return text;
}

static cmd_job *start(cmd_context *ctx, cmd_work *work, char *text, const char *label,
                      void (*on_done)(void *user), void *user, og_error *err) {
    if (!work->points && !cmd_script_is_builtin(&work->script)) {
        og_error_set(err, "%s: only the command language's own commands run in the background",
                     label);
        free(text);
        cmd_work_free(work);
        return NULL;
    }
    pthread_once(&worker_once, worker_start);
    cmd_job *j = worker_error ? NULL : calloc(1, sizeof *j);
    if (!j || !text) {
        if (worker_error)
            og_error_set(err, "cannot start the job thread: %s", strerror(worker_error));
        else
            og_error_set(err, "out of memory");
        free(j);
        free(text);
        cmd_work_free(work);
        return NULL;
    }
    j->ctx = ctx;
    j->work = *work;
    memset(work, 0, sizeof *work);
    j->text = text;
    snprintf(j->label, sizeof j->label, "%s", label);
    j->on_done = on_done;
    j->user = user;
    og_progress_init(&j->progress);
    pthread_mutex_init(&j->lock, NULL);
    pthread_cond_init(&j->changed, NULL);
    clock_gettime(CLOCK_MONOTONIC, &j->started);
    pthread_mutex_lock(&worker_lock);
    if (worker_tail)
        worker_tail->next = j;
    else
        worker_head = j;
    worker_tail = j;
    pthread_cond_signal(&worker_wake);
    pthread_mutex_unlock(&worker_lock);
    return j;
}

cmd_job *cmd_job_run(cmd_context *ctx, cmd_work *work, const char *label,
                     void (*on_done)(void *user), void *user, og_error *err) {
    char *text = work->points ? strdup("stroke_to ...") : script_text(&work->script);
    return start(ctx, work, text, label, on_done, user, err);
}

cmd_job *cmd_job_start(cmd_context *ctx, const char *text, const char *label,
                       void (*on_done)(void *user), void *user, og_error *err) {
    cmd_work work = {0};
    if (cmd_script_parse(&work.script, text, strlen(text), label, err) != 0) return NULL;
    return start(ctx, &work, strdup(text), label, on_done, user, err);
}

int cmd_job_done(cmd_job *j) {
    pthread_mutex_lock(&j->lock);
    int done = j->done;
    pthread_mutex_unlock(&j->lock);
    return done;
}

int cmd_job_wait(cmd_job *j, double ms) {
    struct timespec until;
    clock_gettime(CLOCK_REALTIME, &until);
    long long ns = until.tv_nsec + (long long)(ms * 1e6);
    until.tv_sec += (time_t)(ns / 1000000000LL);
    until.tv_nsec = (long)(ns % 1000000000LL);
    pthread_mutex_lock(&j->lock);
    while (!j->done && pthread_cond_timedwait(&j->changed, &j->lock, &until) != ETIMEDOUT) {
    }
    int done = j->done;
    pthread_mutex_unlock(&j->lock);
    return done;
}

double cmd_job_progress(cmd_job *j) {
    return og_progress_fraction(&j->progress);
}

double cmd_job_elapsed_ms(cmd_job *j) {
    return since_ms(&j->started);
}

const char *cmd_job_text(const cmd_job *j) {
    return j->text;
}

void cmd_job_cancel(cmd_job *j) {
    og_progress_cancel(&j->progress);
}

int cmd_job_cancelled(cmd_job *j) {
    return og_progress_cancelled(&j->progress);
}

int cmd_job_finish(cmd_job *j, og_error *err) {
    pthread_mutex_lock(&j->lock);
    while (!j->released)
        pthread_cond_wait(&j->changed, &j->lock);
    pthread_mutex_unlock(&j->lock);
    int rc = j->rc;
    if (rc != 0 && err) *err = j->err;
    pthread_mutex_destroy(&j->lock);
    pthread_cond_destroy(&j->changed);
    cmd_work_free(&j->work);
    free(j->text);
    free(j);
    return rc;
}
