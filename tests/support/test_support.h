// Small helpers shared by the unit tests: scratch folders and file writing.
#ifndef OROGEN_TEST_SUPPORT_H
#define OROGEN_TEST_SUPPORT_H

#include <stddef.h>

// A fresh empty folder under $TMPDIR (or /tmp), removed by test_rmtree. The
// returned string is static storage valid until the next call.
const char *test_tmpdir(const char *tag);
// Removes a folder and everything in it.
void test_rmtree(const char *path);
// Writes len bytes to path (asserts on failure).
void test_write_file(const char *path, const void *data, size_t len);
// One scratch folder for a whole test program, as cmocka group fixtures:
// cmocka_run_group_tests(tests, test_folder_setup, test_folder_teardown).
int test_folder_setup(void **state);
int test_folder_teardown(void **state);
// The folder, and a file in it (static storage: the last four names stay valid).
const char *test_folder(void);
const char *test_in_folder(const char *name);
// Reads a whole file (malloc'd, NUL-terminated); *len gets its size. NULL if unreadable.
char *test_read_file(const char *path, size_t *len);

#endif
