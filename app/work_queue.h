// The window's queue of commands, run in order: text tokenised once when it is queued,
// and a drag's stroke points as numbers. The queue knows no command words. The
// command language's own
// commands (edits, strokes, stamps, undo, generate, save...) run on a job thread
// (editor/cmd/cmd_job.h), so long work never freezes the window: while a job runs the
// window shows its progress and a Cancel button, and touches neither the command
// context nor the world. Registered commands (view, render, window) hold GL state and
// run on the UI thread. Output and errors go to the console (and stdout / stderr).
#ifndef OROGEN_APP_WORK_QUEUE_H
#define OROGEN_APP_WORK_QUEUE_H

#include "app/console.h"
#include "app/notices.h"
#include "editor/cmd/cmd_job.h"

#define WORK_QUEUE_MAX 256
#define WORK_QUEUE_UI_ROOM 16

typedef enum work_flags {
    WORK_ECHO = 1,         // echo the text in the console before it runs
    WORK_STROKE = 2,       // part of a mouse stroke: dropped when no stroke is open
    WORK_STROKE_BEGIN = 4, // opens the mouse stroke (runs with none open)
} work_flags;

typedef struct work_item {
    cmd_work work; // commands, or a stroke's points (consecutive ones run as one job)
    char *echo;    // the text as queued, for the console (WORK_ECHO), else NULL
    char label[16];
    int flags;
} work_item;

typedef struct work_queue {
    cmd_context *ctx;
    console *console;
    void (*wake)(void *user); // called from the job's thread when it ends
    void *wake_user;
    work_item items[WORK_QUEUE_MAX]; // waiting, oldest first
    int count;
    cmd_job *job; // the running job (NULL: none)
    work_item running;
    char *out; // the running job's output, captured for the console
    size_t out_len;
    FILE *mem, *keep_out;
    int stroke_cancelled; // a cancelled job ended the mouse stroke (the window resets its drag)
    int ran;              // something ran since the last work_queue_take_ran
    // When set, what failed that the console did not start (a menu, a shortcut, a drop,
    // a dialog) is also shown here until dismissed, where the user looks.
    notices *notices;
} work_queue;

void work_queue_init(work_queue *q, cmd_context *ctx, console *c, void (*wake)(void *), void *user);
// Cancels a running job and waits for it; drops what is queued.
void work_queue_free(work_queue *q);

// Queues text (tokenised here, once). Returns -1 when the queue is full (the text is
// reported and dropped).
int work_queue_add(work_queue *q, const char *text, const char *label, int flags);
// Queues a point of the open mouse stroke (it joins points still waiting). -1 as above.
int work_queue_add_point(work_queue *q, const cmd_stroke_point *p);
// Finishes a job that has ended, then runs queued text until the queue is empty or a
// job is still running after wait_ms.
void work_queue_pump(work_queue *q, double wait_ms);
// A job is running: the command context and the world are its own.
// Whether the queue is nearly full: the console stops reading its input (the writer waits)
// and leaves the last WORK_QUEUE_UI_ROOM places to the window's own buttons and strokes.
int work_queue_filling(const work_queue *q);
int work_queue_busy(const work_queue *q);
int work_queue_idle(const work_queue *q); // nothing running, nothing queued
// Stops the running job at its next check (it fails with "cancelled", and a stroke it
// was part of is undone whole).
void work_queue_cancel(work_queue *q);
// 1 once after something ran (the window redraws what it shows of the world).
int work_queue_take_ran(work_queue *q);

#endif
