// Long work off the editor's UI thread: one long-lived job thread runs commands,
// tokenised (cmd_script.h), or a stroke's typed points (cmd_stroke_to_point), with a
// progress record the work reports into and a cancel switch. While a job runs the job
// thread owns the command context and the world: the caller must not touch either
// until cmd_job_finish. A cancelled command fails with "cancelled" and, like any
// failing command, leaves no undo step (a stroke it was part of stays open for the
// caller to cancel, cmd_cancel_stroke).
#ifndef OROGEN_EDITOR_CMD_JOB_H
#define OROGEN_EDITOR_CMD_JOB_H

#include "editor/cmd/cmd_script.h"
#include "editor/cmd/context.h"
#include "editor/cmd/edit_commands.h"
#include "io/err.h"

typedef struct cmd_job cmd_job;

// What a job runs: a script, or points for the open stroke. The job takes what it
// holds (the caller's copy is emptied).
typedef struct cmd_work {
    cmd_script script;
    cmd_stroke_point *points;
    size_t point_count;
} cmd_work;

void cmd_work_free(cmd_work *w);

// Starts the work. Only the language's own commands may run this way
// (cmd_script_is_builtin); a malformed script is refused. on_done(user) is called from
// the job thread when the work has finished (to wake the caller's event loop); it may
// be NULL. Jobs started while one runs wait for it.
cmd_job *cmd_job_run(cmd_context *ctx, cmd_work *work, const char *label,
                     void (*on_done)(void *user), void *user, og_error *err);
// The same for command text (tokenised here, once).
cmd_job *cmd_job_start(cmd_context *ctx, const char *text, const char *label,
                       void (*on_done)(void *user), void *user, og_error *err);

// 1 once the job's work has finished (cmd_job_finish will not block long).
int cmd_job_done(cmd_job *j);
// Waits up to ms milliseconds for the job to finish; returns cmd_job_done.
int cmd_job_wait(cmd_job *j, double ms);
// How far the work is, in [0, 1] (long loops report; short work stays at 0).
double cmd_job_progress(cmd_job *j);
// Milliseconds since the job started.
double cmd_job_elapsed_ms(cmd_job *j);
// The text it runs, for the progress line (for a stroke's points: "stroke_to ...").
const char *cmd_job_text(const cmd_job *j);
void cmd_job_cancel(cmd_job *j);
int cmd_job_cancelled(cmd_job *j);

// Waits for the job (and its on_done), frees it and returns what running it returned
// (err set on failure: "label:line: error: ..." as cmd_run's).
int cmd_job_finish(cmd_job *j, og_error *err);

#endif
