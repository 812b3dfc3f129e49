// Progress and cancellation of long work (a command the editor runs off its UI
// thread). The thread that runs the work installs a progress record; long loops
// report how far they are and stop when it has been cancelled. A loop nested in
// another reports within the part the outer loop gave it (og_progress_enter), so the
// fraction only grows. Without a record installed every call is a cheap no-op.
#ifndef OROGEN_IO_PROGRESS_H
#define OROGEN_IO_PROGRESS_H

#include <stdatomic.h>
#include <stdint.h>

typedef struct og_progress {
    atomic_int cancel;   // set by any thread; the work stops at its next check
    atomic_int permille; // 0-1000: how far the work is (read by any thread)
    double base, width;  // the part of the whole the current loop reports in (work thread)
} og_progress;

void og_progress_init(og_progress *p);
// Installs p as this thread's progress record (NULL removes it).
void og_progress_install(og_progress *p);
// This thread's record, or NULL.
og_progress *og_progress_current(void);

void og_progress_cancel(og_progress *p);
int og_progress_cancelled(const og_progress *p); // p may be NULL (never cancelled)
// The fraction done, in [0, 1].
double og_progress_fraction(const og_progress *p);

// Reports `done` of `total` steps of the current part. Returns -1 when the work has
// been cancelled (the caller stops, undoes what it did and fails), else 0. p may be NULL.
int og_progress_report(og_progress *p, int64_t done, int64_t total);

// Narrows the current part to its step `index` of `count` for a nested loop; returns
// the part to restore with og_progress_leave. p may be NULL.
typedef struct og_progress_part {
    double base, width;
} og_progress_part;
og_progress_part og_progress_enter(og_progress *p, int64_t index, int64_t count);
void og_progress_leave(og_progress *p, og_progress_part outer);

#endif
