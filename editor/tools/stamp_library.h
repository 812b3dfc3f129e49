// The built-in texture stamps (resources/stamps/<name>.png): heightmaps the project
// makes itself from its own noise and stamp shapes, deterministically, so the
// committed files can be checked against a fresh run (tools/make_stamps).
//
// Every stamp is positive with its peak at exactly 1 and exactly 0 on its outermost
// ring of samples, so the engine can place it without a step. Stamps marked carve
// are depressions stored positive: the engine subtracts them.
#ifndef OROGEN_EDITOR_STAMP_LIBRARY_H
#define OROGEN_EDITOR_STAMP_LIBRARY_H

#include "io/err.h"

// Width and height of the written stamp files.
#define STAMP_LIBRARY_SIZE 512

typedef struct stamp_library_entry {
    const char *name;  // the file is <name>.png
    int carve;         // 1: meant to be subtracted (a canyon, not a wall)
    const char *about; // what it is and how it is made, one line
} stamp_library_entry;

int stamp_library_count(void);
// Entry i in file order, NULL if i is out of range.
const stamp_library_entry *stamp_library_entry_at(int i);
// Renders stamp i into out[y * size + x] in [0, 1]. size >= 3; -1 if i or size is invalid.
int stamp_library_render(int i, int size, float *out);
// Writes every stamp as <dir>/<name>.png, 16-bit grey, STAMP_LIBRARY_SIZE square.
// The folder must exist.
int stamp_library_generate(const char *dir, og_error *err);

#endif
