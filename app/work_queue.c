#include "app/work_queue.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void work_queue_init(work_queue *q, cmd_context *ctx, console *c, void (*wake)(void *),
                     void *user) {
    memset(q, 0, sizeof *q);
    q->ctx = ctx;
    q->console = c;
    q->wake = wake;
    q->wake_user = user;
}

static void report_error(work_queue *q, const char *msg) {
    fprintf(stderr, "%s\n", msg);
    console_add(q->console, CONSOLE_ERROR, msg);
}

static void drop_item(work_item *it) {
    cmd_work_free(&it->work);
    free(it->echo);
    it->echo = NULL;
}

static work_item *new_item(work_queue *q, const char *what, const char *label, int flags) {
    if (q->count == WORK_QUEUE_MAX) {
        char msg[256];
        snprintf(msg, sizeof msg, "%s: too much work waiting; '%.80s' was dropped", label, what);
        report_error(q, msg);
        return NULL;
    }
    work_item *it = &q->items[q->count++];
    memset(it, 0, sizeof *it);
    snprintf(it->label, sizeof it->label, "%s", label);
    it->flags = flags;
    return it;
}

int work_queue_add(work_queue *q, const char *text, const char *label, int flags) {
    cmd_script script;
    og_error err = {{0}};
    if (cmd_script_parse(&script, text, strlen(text), label, &err) != 0) {
        report_error(q, err.msg);
        return -1;
    }
    char *echo = (flags & WORK_ECHO) ? strdup(text) : NULL;
    work_item *it = (flags & WORK_ECHO) && !echo ? NULL : new_item(q, text, label, flags);
    if (!it) {
        if ((flags & WORK_ECHO) && !echo) report_error(q, "out of memory");
        cmd_script_free(&script);
        free(echo);
        return -1;
    }
    it->work.script = script;
    it->echo = echo;
    return 0;
}

int work_queue_add_point(work_queue *q, const cmd_stroke_point *p) {
    // Points that arrive while a job runs join the last waiting ones: one job lays them.
    work_item *it = q->count ? &q->items[q->count - 1] : NULL;
    if (!it || !it->work.points) {
        it = new_item(q, "a stroke's point", "sculpt", WORK_STROKE);
        if (!it) return -1;
    }
    cmd_work *w = &it->work;
    cmd_stroke_point *grown = realloc(w->points, (w->point_count + 1) * sizeof *grown);
    if (!grown) {
        if (!w->points) q->count--; // the item just made
        report_error(q, "sculpt: out of memory; a stroke's point was dropped");
        return -1;
    }
    w->points = grown;
    w->points[w->point_count++] = *p;
    return 0;
}

static void capture_begin(work_queue *q) {
    q->out = NULL;
    q->out_len = 0;
    q->mem = open_memstream(&q->out, &q->out_len);
    q->keep_out = q->ctx->out;
    if (q->mem) q->ctx->out = q->mem;
}

static void capture_end(work_queue *q) {
    q->ctx->out = q->keep_out;
    if (!q->mem) return;
    fclose(q->mem);
    q->mem = NULL;
    if (q->out_len) {
        fwrite(q->out, 1, q->out_len, q->keep_out);
        fflush(q->keep_out);
        console_add(q->console, CONSOLE_OUTPUT, q->out);
    }
    free(q->out);
    q->out = NULL;
}

// Drops waiting stroke text (a cancelled stroke's later points and its end).
static void drop_stroke_items(work_queue *q) {
    int kept = 0;
    for (int i = 0; i < q->count; i++) {
        if (q->items[i].flags & WORK_STROKE)
            drop_item(&q->items[i]);
        else
            q->items[kept++] = q->items[i];
    }
    q->count = kept;
}

// After the running text ended (on whichever thread): output, errors, and a cancelled
// stroke undone whole.
static void finished(work_queue *q, int rc, const og_error *err, int cancelled) {
    capture_end(q);
    q->ran = 1;
    if (rc != 0) report_error(q, err->msg);
    const cmd_script *script = &q->running.work.script;
    if (rc != 0 && q->notices && strcmp(q->running.label, "console") != 0 &&
        !(cancelled && (q->running.flags & WORK_STROKE)))
        notices_add_failure(q->notices, script->count ? script->calls[0].argv[0] : "", err->msg,
                            notices_now());
    if (rc == 0 && q->notices && notices_user_action(q->running.label))
        notices_clear_passing(q->notices);
    if (rc != 0 && cancelled) {
        cmd_cancel_stroke(q->ctx); // (a failing stroke_to has already abandoned it)
        if (q->running.flags & WORK_STROKE) report_error(q, "cancelled: the stroke was undone");
        drop_stroke_items(q);
        q->stroke_cancelled = 1;
    }
    drop_item(&q->running);
}

static void finish_job(work_queue *q) {
    og_error err = {{0}};
    int cancelled = cmd_job_cancelled(q->job);
    int rc = cmd_job_finish(q->job, &err);
    q->job = NULL;
    finished(q, rc, &err, cancelled);
}

void work_queue_pump(work_queue *q, double wait_ms) {
    if (q->job) {
        if (!cmd_job_done(q->job)) return;
        finish_job(q);
    }
    while (q->count > 0 && !q->ctx->exit_requested) {
        q->running = q->items[0];
        memmove(q->items, q->items + 1, (size_t)(q->count - 1) * sizeof q->items[0]);
        q->count--;
        work_item *it = &q->running;
        // Points of a stroke that never began (or was cancelled) have nothing to go to.
        if ((it->flags & WORK_STROKE) && !(it->flags & WORK_STROKE_BEGIN) &&
            !cmd_stroke_is_open(q->ctx)) {
            drop_item(it);
            continue;
        }
        if (it->echo) {
            char echo[CONSOLE_INPUT + 4];
            snprintf(echo, sizeof echo, "> %s", it->echo);
            console_add(q->console, CONSOLE_ECHO, echo);
        }
        capture_begin(q);
        og_error err = {{0}};
        if (!it->work.points && !cmd_script_is_builtin(&it->work.script)) { // GL or window state
            int rc = cmd_script_run(q->ctx, &it->work.script, &err);
            finished(q, rc, &err, 0);
            continue;
        }
        q->job = cmd_job_run(q->ctx, &it->work, it->label, q->wake, q->wake_user, &err);
        if (!q->job) {
            finished(q, -1, &err, 0);
            continue;
        }
        if (!cmd_job_wait(q->job, wait_ms)) return; // long work: the window shows it
        finish_job(q);
    }
}

int work_queue_filling(const work_queue *q) {
    return q->count >= WORK_QUEUE_MAX - WORK_QUEUE_UI_ROOM;
}

int work_queue_busy(const work_queue *q) {
    return q->job != NULL;
}

int work_queue_idle(const work_queue *q) {
    return !q->job && q->count == 0;
}

void work_queue_cancel(work_queue *q) {
    if (q->job) cmd_job_cancel(q->job);
}

int work_queue_take_ran(work_queue *q) {
    int ran = q->ran;
    q->ran = 0;
    return ran;
}

void work_queue_free(work_queue *q) {
    if (q->job) {
        cmd_job_cancel(q->job);
        finish_job(q);
    }
    for (int i = 0; i < q->count; i++)
        drop_item(&q->items[i]);
    q->count = 0;
}
