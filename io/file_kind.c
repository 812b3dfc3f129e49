#include "io/file_kind.h"

#include <sys/stat.h>

const char *file_kind_special(unsigned mode) {
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return NULL;
}

int file_kind_check_replace(const char *path, og_error *err) {
    struct stat st;
    // stat, not lstat: a symlink to /dev/null is refused like /dev/null. No path: the
    // writer itself reports it.
    if (!path || stat(path, &st) != 0) return 0;
    const char *what = file_kind_special(st.st_mode);
    if (what) return og_error_set(err, "%s is %s, not a file: not replaced", path, what);
    return 0;
}

int file_kind_check_read(const char *path, og_error *err) {
    struct stat st;
    if (!path || stat(path, &st) != 0) return 0;
    const char *what = file_kind_special(st.st_mode);
    if (what) return og_error_set(err, "%s is %s, not a file: not read", path, what);
    if (S_ISDIR(st.st_mode)) return og_error_set(err, "%s is a folder, not a file", path);
    return 0;
}
