// The crash journals of a world on disk: its own (NAME.recover beside the parameter
// file) and those set aside (NAME.recover.old, NAME.recover.old2, ...) when a session
// edited without recovering an earlier one. A journal is never overwritten or removed
// here: setting one aside picks a free name or fails, leaving it where it was.
#ifndef OROGEN_EDITOR_JOURNAL_FILES_H
#define OROGEN_EDITOR_JOURNAL_FILES_H

#include "io/err.h"

#include <stddef.h>

// Renames the journal at path to the first free NAME.old, NAME.old2, ... (never
// replacing anything, a folder included); aside gets the new name. -1 with err when no
// name could be taken: the journal stays at path.
int journal_files_set_aside(const char *path, char *aside, size_t len, og_error *err);

// Calls fn with each journal file of the world whose journal is own_path (own_path
// itself, if it exists, then those set aside, in name order). Returns the count.
size_t journal_files_each(const char *own_path, void (*fn)(void *user, const char *path),
                          void *user);

#endif
