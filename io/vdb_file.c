#include "io/vdb_file.h"

#include "io/crc32c.h"
#include "io/file_kind.h"
#include "io/file_mode.h"
#include "io/module_load.h"
#include "io/path_folder.h"

#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef void *(*create_fn)(double, float, char *, size_t);
typedef int (*column_fn)(void *, int, int, int, int, const float *, int);
typedef int (*merge_fn)(void *, void *);
typedef long long (*active_fn)(void *);
typedef int (*fill_fn)(void *, const int *);
typedef int (*sign_fn)(void *, const int *, int (*)(void *, int, int, int), void *);
typedef int (*write_fn)(void *, const char *, int, const char *const *, int, char *, size_t);
typedef void (*free_fn)(void *);

static struct {
    pthread_once_t once;
    create_fn create;
    column_fn column;
    merge_fn merge;
    active_fn active;
    fill_fn fill_inside;
    sign_fn sign;
    write_fn write;
    free_fn release;
    char why[1024];
} module = {.once = PTHREAD_ONCE_INIT};

static void load_module(void) {
    void *h = module_open("OROGEN_VDB_MODULE", "liborogen_vdb.so",
#ifdef OROGEN_VDB_MODULE_PATH
                          OROGEN_VDB_MODULE_PATH,
#else
                          NULL,
#endif
                          module.why, sizeof module.why);
    if (!h) return;
    module.create = (create_fn)dlsym(h, "orogen_vdb_module_create");
    module.column = (column_fn)dlsym(h, "orogen_vdb_module_set_column");
    module.merge = (merge_fn)dlsym(h, "orogen_vdb_module_merge");
    module.active = (active_fn)dlsym(h, "orogen_vdb_module_active_voxels");
    module.fill_inside = (fill_fn)dlsym(h, "orogen_vdb_module_fill_inside");
    module.sign = (sign_fn)dlsym(h, "orogen_vdb_module_sign");
    module.write = (write_fn)dlsym(h, "orogen_vdb_module_write");
    module.release = (free_fn)dlsym(h, "orogen_vdb_module_free");
    if (module.create && module.column && module.merge && module.active && module.fill_inside &&
        module.sign && module.write && module.release)
        return;
    snprintf(module.why, sizeof module.why, "liborogen_vdb.so is not Orogen's OpenVDB module");
    module.create = NULL;
}

vdb_level_set *vdb_level_set_create(double voxel, float background, og_error *err) {
    pthread_once(&module.once, load_module);
    if (!module.create) {
        og_error_set(err, "OpenVDB support is unavailable: %s", module.why);
        return NULL;
    }
    char why[512] = "";
    void *g = module.create(voxel, background, why, sizeof why);
    if (!g) og_error_set(err, "OpenVDB: %s", why);
    return g;
}

int vdb_level_set_column(vdb_level_set *ls, int32_t i, int32_t k, int32_t j0, int32_t n,
                         const float *values, int overwrite, og_error *err) {
    if (module.column(ls, i, k, j0, n, values, overwrite) != 0)
        return og_error_set(err, "OpenVDB: out of memory building the level set");
    return 0;
}

int vdb_level_set_merge(vdb_level_set *dst, vdb_level_set *src, og_error *err) {
    if (module.merge(dst, src) != 0)
        return og_error_set(err, "OpenVDB: out of memory merging level sets");
    return 0;
}

int vdb_level_set_fill_inside(vdb_level_set *ls, const int32_t box[6], og_error *err) {
    int b[6];
    for (int a = 0; a < 6; a++)
        b[a] = box[a];
    if (module.fill_inside(ls, b) != 0)
        return og_error_set(err, "OpenVDB: out of memory filling the interior");
    return 0;
}

int vdb_level_set_sign(vdb_level_set *ls, const int32_t box[6],
                       int (*inside)(void *user, int i, int j, int k), void *user, og_error *err) {
    int b[6];
    for (int c = 0; c < 6; c++)
        b[c] = box[c];
    if (module.sign(ls, b, inside, user) != 0)
        return og_error_set(err, "OpenVDB: could not sign the level set's inactive values");
    return 0;
}

long long vdb_level_set_active_voxels(vdb_level_set *ls) {
    return module.active(ls);
}

static int fsync_path(const char *path, int flags) {
    int fd = open(path, O_RDONLY | flags);
    if (fd < 0) return -1;
    int rc = fsync(fd);
    close(fd);
    return rc;
}

// OpenVDB stamps every file with a random UUID (36 characters after the 21-byte
// header start); it only tags the file, so it becomes a hash of the file's other bytes
// and the same level set always makes the same bytes.
enum { UUID_AT = 21, UUID_LEN = 36 };

static int stamp_content_uuid(const char *path) {
    int fd = open(path, O_RDWR);
    if (fd < 0) return -1;
    unsigned char head[UUID_AT + UUID_LEN], buf[1 << 16];
    int rc = -1;
    if (pread(fd, head, sizeof head, 0) != (ssize_t)sizeof head || memcmp(head, " BDV", 4) != 0 ||
        head[UUID_AT + 8] != '-' || head[UUID_AT + 13] != '-')
        goto done;
    uint32_t h[4] = {1, 2, 3, 4};
    for (int k = 0; k < 4; k++)
        h[k] = crc32c_update(h[k] * 0x9e3779b9u, head, UUID_AT);
    for (off_t at = UUID_AT + UUID_LEN;;) {
        ssize_t n = pread(fd, buf, sizeof buf, at);
        if (n < 0) goto done;
        if (n == 0) break;
        for (int k = 0; k < 4; k++)
            h[k] = crc32c_update(h[k], buf, (size_t)n);
        at += n;
    }
    char uuid[UUID_LEN + 1];
    snprintf(uuid, sizeof uuid, "%08x-%04x-%04x-%04x-%04x%08x", h[0], h[1] >> 16, h[1] & 0xffff,
             h[2] >> 16, h[2] & 0xffff, h[3]);
    if (pwrite(fd, uuid, UUID_LEN, UUID_AT) == UUID_LEN) rc = 0;
done:
    close(fd);
    return rc;
}

int vdb_level_set_write(vdb_level_set *ls, const char *path, int fog, const char *const *meta,
                        int meta_count, og_error *err) {
    if (file_kind_check_replace(path, err) != 0) return -1;
    size_t len = strlen(path);
    char *tmp = malloc(len + 16);
    if (!tmp) return og_error_set(err, "%s: out of memory", path);
    snprintf(tmp, len + 16, "%s.tmp-XXXXXX", path);
    int rc = -1;
    int fd = mkstemp(tmp);
    if (fd < 0) {
        og_error_set(err, "%s: cannot write there: %s", path, strerror(errno));
        goto done;
    }
    fchmod(fd, og_new_file_mode()); // mkstemp's 0600 would carry over to the final file
    close(fd);
    char why[512] = "";
    if (module.write(ls, tmp, fog, meta, meta_count, why, sizeof why) != 0) {
        og_error_set(err, "%s: OpenVDB could not write it: %s", path, why);
    } else if (stamp_content_uuid(tmp) != 0) {
        og_error_set(err, "%s: cannot stamp the file's tag: %s", path, strerror(errno));
    } else if (fsync_path(tmp, 0) != 0) {
        og_error_set(err, "%s: cannot flush the file to disk: %s", path, strerror(errno));
    } else if (rename(tmp, path) != 0) {
        og_error_set(err, "%s: cannot rename the temp file into place: %s", path, strerror(errno));
    } else {
        path_sync_folder(path); // best effort: the file itself is durable
        rc = 0;
    }
    if (rc != 0) unlink(tmp);
done:
    free(tmp);
    return rc;
}

void vdb_level_set_free(vdb_level_set *ls) {
    if (ls) module.release(ls);
}
