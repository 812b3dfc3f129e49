#include "editor/world/journal_files.h"

#include "io/path_folder.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

// Moves from to to unless something is at to (EEXIST then). renameat2's NOREPLACE where
// the file system has it, else a hard link and an unlink (both refuse an existing to).
static int move_no_replace(const char *from, const char *to) {
    if (renameat2(AT_FDCWD, from, AT_FDCWD, to, RENAME_NOREPLACE) == 0) return 0;
    if (errno != EINVAL && errno != ENOSYS) return -1;
    if (link(from, to) != 0) return -1;
    if (unlink(from) != 0) {
        int e = errno;
        unlink(to); // both names: undo, so the journal is still found where it was
        errno = e;
        return -1;
    }
    return 0;
}

int journal_files_set_aside(const char *path, char *aside, size_t len, og_error *err) {
    for (int n = 1; n < 1000; n++) {
        if (n == 1)
            snprintf(aside, len, "%s.old", path);
        else
            snprintf(aside, len, "%s.old%d", path, n);
        if (move_no_replace(path, aside) == 0) return 0;
        if (errno != EEXIST && errno != ENOTEMPTY)
            return og_error_set(err, "cannot set the journal %s aside as %s: %s", path, aside,
                                strerror(errno));
    }
    return og_error_set(err, "cannot set the journal %s aside: %s.old to %s.old999 are all taken",
                        path, path, path);
}

static int by_name(const void *a, const void *b) {
    const char *x = *(char *const *)a, *y = *(char *const *)b;
    size_t lx = strlen(x), ly = strlen(y); // .old2 before .old10
    return lx != ly ? (lx < ly ? -1 : 1) : strcmp(x, y);
}

// Whether name is base + ".old" + digits (none, or 2 and up).
static int is_set_aside(const char *name, const char *base) {
    size_t n = strlen(base);
    if (strncmp(name, base, n) != 0 || strncmp(name + n, ".old", 4) != 0) return 0;
    for (const char *c = name + n + 4; *c; c++)
        if (*c < '0' || *c > '9') return 0;
    return 1;
}

size_t journal_files_each(const char *own_path, void (*fn)(void *user, const char *path),
                          void *user) {
    struct stat st;
    size_t count = 0;
    if (lstat(own_path, &st) == 0) {
        fn(user, own_path);
        count++;
    }
    char dir[4400];
    path_folder(own_path, dir, sizeof dir);
    const char *slash = strrchr(own_path, '/');
    const char *base = slash ? slash + 1 : own_path;
    char base_name[1024];
    snprintf(base_name, sizeof base_name, "%s", base);
    DIR *d = opendir(dir);
    if (!d) return count;
    char **names = NULL;
    size_t n = 0, cap = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (!is_set_aside(e->d_name, base_name)) continue;
        if (n == cap) {
            cap = cap ? cap * 2 : 8;
            char **grown = realloc(names, cap * sizeof *names);
            if (!grown) break;
            names = grown;
        }
        if (!(names[n] = strdup(e->d_name))) break;
        n++;
    }
    closedir(d);
    if (n) qsort(names, n, sizeof *names, by_name);
    for (size_t i = 0; i < n; i++) {
        char path[4700];
        snprintf(path, sizeof path, "%s%s%s", slash ? dir : "", slash ? "/" : "", names[i]);
        if (slash == dir) snprintf(path, sizeof path, "/%s", names[i]);
        fn(user, path);
        count++;
        free(names[i]);
    }
    free(names);
    return count;
}
