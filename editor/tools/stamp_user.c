#include "editor/tools/stamp_user.h"

#include "editor/tools/stamp.h"
#include "editor/tools/stamp_shapes.h"
#include "io/param_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

// Larger files are not images a stamp can use (and would be read whole).
#define STAMP_FILE_MAX (512LL << 20)

static int make_folders(const char *dir) {
    char path[4096];
    snprintf(path, sizeof path, "%s", dir);
    for (char *p = path + 1; *p; p++) {
        if (*p != '/') continue;
        *p = 0;
        if (mkdir(path, 0777) != 0 && errno != EEXIST) return -1;
        *p = '/';
    }
    return mkdir(path, 0777) != 0 && errno != EEXIST ? -1 : 0;
}

static int valid_name(const char *n) {
    if (!*n) return 0;
    for (const char *c = n; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') ||
              *c == '_' || *c == '-'))
            return 0;
    return 1;
}

// A user stamp with this name already exists (in any image format).
static int user_stamp_exists(const char *user_dir, const char *name) {
    stamp_source s;
    og_error ignored;
    if (stamp_find(name, NULL, user_dir, &s, &ignored) != 0) return 0;
    stamp_source_free(&s);
    return 1;
}

static char *read_all(const char *path, size_t *len, og_error *err) {
    FILE *f = fopen(path, "rb");
    if (!f) return og_error_set(err, "%s: %s", path, strerror(errno)), NULL;
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size > STAMP_FILE_MAX) {
        fclose(f);
        og_error_set(err, "%s: not an image file a stamp can use (a regular file up to 512 MiB)",
                     path);
        return NULL;
    }
    char *data = malloc((size_t)st.st_size + 1);
    size_t got = data ? fread(data, 1, (size_t)st.st_size, f) : 0;
    fclose(f);
    if (!data || got != (size_t)st.st_size) {
        free(data);
        og_error_set(err, "%s: cannot be read", path);
        return NULL;
    }
    *len = got;
    return data;
}

int stamp_user_add(const char *path, const char *name, const char *resource_dir,
                   const char *user_dir, char *out_name, size_t out_size, og_error *err) {
    if (!user_dir || !*user_dir)
        return og_error_set(err, "stamp_add: there is no user stamp folder (set OROGEN_STAMP_DIR)");
    if (!stamp_is_image_file(path))
        return og_error_set(err, "%s: not an image (stamps are PNG, TIFF, EXR, ... files)", path);
    const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    const char *ext = strrchr(base, '.');
    char stem[200];
    if (name && *name)
        snprintf(stem, sizeof stem, "%s", name);
    else
        snprintf(stem, sizeof stem, "%.*s", (int)(ext - base < 150 ? ext - base : 150), base);
    if (!valid_name(stem))
        return og_error_set(err, "stamp_add: '%s' cannot name a stamp (letters, digits, _ and -)",
                            stem);
    stamp_source s;
    og_error ignored;
    if (stamp_shape_from_name(stem) >= 0 ||
        (resource_dir && stamp_find(stem, resource_dir, NULL, &s, &ignored) == 0 &&
         (stamp_source_free(&s), 1)))
        return og_error_set(err, "stamp_add: '%s' is a built-in stamp: give the new one a NAME",
                            stem);
    // The file must read as an image before it is taken in.
    if (stamp_find(path, NULL, NULL, &s, err) != 0) return -1;
    stamp_source_free(&s);
    char chosen[220];
    snprintf(chosen, sizeof chosen, "%s", stem);
    for (int k = 2; user_stamp_exists(user_dir, chosen); k++) {
        if (k > 999) return og_error_set(err, "stamp_add: too many stamps named '%s'", stem);
        snprintf(chosen, sizeof chosen, "%s_%d", stem, k);
    }
    if (make_folders(user_dir) != 0)
        return og_error_set(err, "stamp_add: cannot create %s: %s", user_dir, strerror(errno));
    size_t len = 0;
    char *data = read_all(path, &len, err);
    if (!data) return -1;
    char dest[8300];
    snprintf(dest, sizeof dest, "%s/%s%s", user_dir, chosen, ext);
    int rc = param_file_write_atomic(dest, data, len, err);
    free(data);
    if (rc != 0) return -1;
    snprintf(out_name, out_size, "%s", chosen);
    return 0;
}
