// Long work off the editor's UI thread: runs command text (cmd_run) on a thread of
// its own, with a progress record the work reports into and a cancel switch. While a
// job runs its thread owns the command context and the world: the caller must not
// touch either until cmd_job_finish. A cancelled command fails with "cancelled" and,
// like any failing command, leaves no undo step (a stroke it was part of stays open
// for the caller to cancel).
#ifndef OROGEN_EDITOR_CMD_JOB_H
#define OROGEN_EDITOR_CMD_JOB_H

#include "editor/cmd/context.h"
#include "io/err.h"

typedef struct cmd_job cmd_job;

// Starts running text. Only text of the language's own commands may run this way
// (cmd_text_is_builtin). on_done(user) is called from the job's thread when it has
// finished (to wake the caller's event loop); it may be NULL.
cmd_job *cmd_job_start(cmd_context *ctx, const char *text, const char *label,
                       void (*on_done)(void *user), void *user, og_error *err);

// 1 once the job's work has finished (cmd_job_finish will not block).
int cmd_job_done(cmd_job *j);
// Waits up to ms milliseconds for the job to finish; returns cmd_job_done.
int cmd_job_wait(cmd_job *j, double ms);
// How far the work is, in [0, 1] (long loops report; short work stays at 0).
double cmd_job_progress(cmd_job *j);
// Milliseconds since the job started.
double cmd_job_elapsed_ms(cmd_job *j);
// The label and text it runs.
const char *cmd_job_text(const cmd_job *j);
void cmd_job_cancel(cmd_job *j);
int cmd_job_cancelled(cmd_job *j);

// Waits for the job, frees it and returns what cmd_run returned (err set on failure).
int cmd_job_finish(cmd_job *j, og_error *err);

#endif
