// One writer per file: an advisory lock file (flock) that holds the owner's pid, so a
// second process is told who has the file open, and a lock left by a process that
// died (kill -9, a crash, a power cut) is noticed and taken over: the kernel drops a
// flock with its process, so a lock file nobody holds is stale whatever it says.
#ifndef OROGEN_IO_FILE_LOCK_H
#define OROGEN_IO_FILE_LOCK_H

#include "io/err.h"

typedef struct file_lock {
    int fd; // -1 when not held
    char path[4200];
} file_lock;

#define FILE_LOCK_NONE                                                                             \
    { .fd = -1 }

typedef enum file_lock_result {
    FILE_LOCK_ACQUIRED = 0,
    FILE_LOCK_HELD = 1,        // another live process holds it: *owner is its pid (0: unknown)
    FILE_LOCK_UNAVAILABLE = 2, // the folder cannot hold a lock file (read-only): nobody can
                               // write there, so there is nothing to guard
    FILE_LOCK_REFUSED = 3,     // the path is not a plain file (a symlink, a FIFO, a device):
                               // never written through; err says what it is
    FILE_LOCK_ERROR = -1,      // err says why
} file_lock_result;

// Takes the lock at path (created if needed) and writes our pid into it. *stale gets
// the pid a dead owner left in it (0 when the file was new or empty). A symlink, FIFO,
// device or socket at path is refused, never followed or written.
file_lock_result file_lock_acquire(file_lock *l, const char *path, long *owner, long *stale,
                                   og_error *err);
// Removes the lock file and releases the lock (nothing when not held).
void file_lock_release(file_lock *l);

#endif
