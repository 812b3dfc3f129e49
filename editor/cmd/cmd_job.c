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
    char *text;
    char label[64];
    void (*on_done)(void *user);
    void *user;
    og_progress progress;
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t finished;
    int done; // under lock
    int rc;
    og_error err;
    struct timespec started;
};

static double since_ms(const struct timespec *t0) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)(t.tv_sec - t0->tv_sec) * 1e3 + (double)(t.tv_nsec - t0->tv_nsec) * 1e-6;
}

static void *job_main(void *arg) {
    cmd_job *j = arg;
    og_progress_install(&j->progress);
    j->rc = cmd_run(j->ctx, j->text, strlen(j->text), j->label, &j->err);
    og_progress_install(NULL);
    pthread_mutex_lock(&j->lock);
    j->done = 1;
    pthread_cond_broadcast(&j->finished);
    pthread_mutex_unlock(&j->lock);
    if (j->on_done) j->on_done(j->user);
    return NULL;
}

cmd_job *cmd_job_start(cmd_context *ctx, const char *text, const char *label,
                       void (*on_done)(void *user), void *user, og_error *err) {
    if (!cmd_text_is_builtin(text, strlen(text))) {
        og_error_set(err, "%s: only the command language's own commands run in the background",
                     label);
        return NULL;
    }
    cmd_job *j = calloc(1, sizeof *j);
    if (!j || !(j->text = strdup(text))) {
        free(j);
        og_error_set(err, "out of memory");
        return NULL;
    }
    j->ctx = ctx;
    snprintf(j->label, sizeof j->label, "%s", label);
    j->on_done = on_done;
    j->user = user;
    og_progress_init(&j->progress);
    pthread_mutex_init(&j->lock, NULL);
    pthread_cond_init(&j->finished, NULL);
    clock_gettime(CLOCK_MONOTONIC, &j->started);
    int rc = pthread_create(&j->thread, NULL, job_main, j);
    if (rc != 0) {
        pthread_mutex_destroy(&j->lock);
        pthread_cond_destroy(&j->finished);
        free(j->text);
        free(j);
        og_error_set(err, "cannot start a thread for '%s': %s", text, strerror(rc));
        return NULL;
    }
    return j;
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
    while (!j->done && pthread_cond_timedwait(&j->finished, &j->lock, &until) != ETIMEDOUT) {
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
    pthread_join(j->thread, NULL);
    int rc = j->rc;
    if (rc != 0 && err) *err = j->err;
    pthread_mutex_destroy(&j->lock);
    pthread_cond_destroy(&j->finished);
    free(j->text);
    free(j);
    return rc;
}
