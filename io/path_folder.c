#include "io/path_folder.h"

#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

void path_folder(const char *path, char *out, size_t len) {
    if (len == 0) return;
    const char *slash = strrchr(path, '/');
    if (!slash) {
        snprintf(out, len, ".");
        return;
    }
    // A file at the root keeps its slash: its folder is "/", not "".
    int keep = slash == path ? 1 : (int)(slash - path);
    snprintf(out, len, "%.*s", keep, path);
}

int path_sync_folder(const char *path) {
    char dir[4200];
    path_folder(path, dir, sizeof dir);
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return -1;
    int rc = fsync(fd);
    close(fd);
    return rc;
}
