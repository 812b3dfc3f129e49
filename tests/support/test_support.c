#include "support/test_support.h"

#include <errno.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

const char *test_tmpdir(const char *tag) {
    static char path[4096];
    const char *base = getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/orogen-%s-XXXXXX", base && *base ? base : "/tmp", tag);
    assert_non_null(mkdtemp(path));
    return path;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw) {
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

void test_rmtree(const char *path) {
    nftw(path, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

static char folder[4096];

int test_folder_setup(void **state) {
    (void)state;
    snprintf(folder, sizeof folder, "%s", test_tmpdir(program_invocation_short_name));
    return 0;
}

int test_folder_teardown(void **state) {
    (void)state;
    test_rmtree(folder);
    return 0;
}

const char *test_folder(void) {
    return folder;
}

const char *test_in_folder(const char *name) {
    static char path[4][4200];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", folder, name);
    return path[k];
}

void test_write_file(const char *path, const void *data, size_t len) {
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, len, f), len);
    assert_int_equal(fclose(f), 0);
}

char *test_read_file(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    size_t got = fread(buf, 1, (size_t)n, f);
    fclose(f);
    buf[got] = 0;
    if (len) *len = got;
    return buf;
}

// Tests edit unsaved worlds, and an unsaved world's edits are journaled in the recovery
// folder until saved. ctest gives each test a folder of its own; a test program run by
// hand would leave its journals in the user's folder (gigabytes after a day of work),
// each offered for recovery at the editor's next start. It gets a private one instead.
static char private_recover_dir[4096];

static void remove_private_recover_dir(void) {
    test_rmtree(private_recover_dir);
}

__attribute__((constructor)) static void use_private_recover_dir(void) {
    if (getenv("OROGEN_RECOVER_DIR")) return;
    const char *base = getenv("TMPDIR");
    snprintf(private_recover_dir, sizeof private_recover_dir, "%s/orogen-recover-XXXXXX",
             base && *base ? base : "/tmp");
    if (!mkdtemp(private_recover_dir)) return;
    setenv("OROGEN_RECOVER_DIR", private_recover_dir, 1);
    atexit(remove_private_recover_dir);
}
