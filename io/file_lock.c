#include "io/file_lock.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

// The pid written in the lock file, or 0.
static long read_pid(int fd) {
    char buf[32] = "";
    ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
    if (n <= 0) return 0;
    buf[n] = 0;
    long pid = strtol(buf, NULL, 10);
    return pid > 0 ? pid : 0;
}

file_lock_result file_lock_acquire(file_lock *l, const char *path, long *owner, long *stale,
                                   og_error *err) {
    *owner = *stale = 0;
    l->fd = -1;
    if (snprintf(l->path, sizeof l->path, "%s", path) >= (int)sizeof l->path) {
        og_error_set(err, "%s: path too long for a lock file", path);
        return FILE_LOCK_ERROR;
    }
    // A few rounds: the file we locked may have been removed by its releasing owner
    // between our open and our flock; then a new one must be made and locked.
    for (int round = 0; round < 8; round++) {
        // O_NOFOLLOW: a symlink planted as the lock would have our pid written into its
        // target; O_NONBLOCK: a FIFO there must not hang the open.
        int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
        if (fd < 0 && errno == ELOOP) {
            og_error_set(err, "%s is a symbolic link, not a lock file: not followed (remove it)",
                         path);
            return FILE_LOCK_REFUSED;
        }
        if (fd < 0 && (errno == ENXIO || errno == ENODEV || errno == ETXTBSY)) {
            og_error_set(err, "%s is not a plain file (%s): not written (remove it)", path,
                         strerror(errno));
            return FILE_LOCK_REFUSED;
        }
        if (fd < 0) {
            // A read-only folder, or a full disk: nobody can write there, so there is
            // nothing to guard (the store then opens read-only, saying why).
            if (errno == EACCES || errno == EROFS || errno == EPERM || errno == ENOSPC ||
                errno == EDQUOT)
                return FILE_LOCK_UNAVAILABLE;
            og_error_set(err, "%s: cannot create the lock file: %s", path, strerror(errno));
            return FILE_LOCK_ERROR;
        }
        struct stat kind;
        if (fstat(fd, &kind) != 0 || !S_ISREG(kind.st_mode)) {
            og_error_set(err, "%s is not a plain file (a %s): not written (remove it)", path,
                         S_ISFIFO(kind.st_mode)                           ? "FIFO"
                         : S_ISCHR(kind.st_mode) || S_ISBLK(kind.st_mode) ? "device"
                         : S_ISDIR(kind.st_mode)                          ? "folder"
                                                                          : "special file");
            close(fd);
            return FILE_LOCK_REFUSED;
        }
        if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
            int e = errno;
            if (e == EWOULDBLOCK) *owner = read_pid(fd);
            close(fd);
            if (e == EWOULDBLOCK) return FILE_LOCK_HELD;
            og_error_set(err, "%s: cannot lock: %s", path, strerror(e));
            return FILE_LOCK_ERROR;
        }
        struct stat held, named;
        if (fstat(fd, &held) != 0 || stat(path, &named) != 0 || held.st_ino != named.st_ino ||
            held.st_dev != named.st_dev) {
            close(fd); // locked a file that is no longer the one at path
            continue;
        }
        *stale = read_pid(fd);
        char pid[32];
        int n = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
        // The flock is the guard; the pid only names the holder: a full disk that
        // cannot take it leaves the lock held, nameless.
        if ((ftruncate(fd, 0) != 0 || pwrite(fd, pid, (size_t)n, 0) != n) && errno != ENOSPC &&
            errno != EDQUOT) {
            og_error_set(err, "%s: cannot write the lock file: %s", path, strerror(errno));
            unlink(path);
            close(fd);
            return FILE_LOCK_ERROR;
        }
        l->fd = fd;
        return FILE_LOCK_ACQUIRED;
    }
    og_error_set(err, "%s: the lock file keeps changing; is another process starting?", path);
    return FILE_LOCK_ERROR;
}

void file_lock_release(file_lock *l) {
    if (!l || l->fd < 0) return;
    // Unlink while still holding it: a process that opened this file meanwhile then
    // sees that the path names another file (or none) and tries again.
    unlink(l->path);
    close(l->fd);
    l->fd = -1;
}
