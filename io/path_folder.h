// The folder a file lives in, for checks and syncs that concern the folder rather than
// the file: free space, write permission, making a new name durable.
#pragma once

#include <stddef.h>

// Writes the folder holding path into out: "/" for a file at the root, "." for a bare
// name. The result is cut at len - 1 characters.
void path_folder(const char *path, char *out, size_t len);

// Flushes the folder holding path, so a file created or renamed there keeps its name
// after a crash. Best effort: returns 0 on success, -1 (errno set) otherwise.
int path_sync_folder(const char *path);
