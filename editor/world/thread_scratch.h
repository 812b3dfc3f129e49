// Working memory kept per thread and per use between calls: grown as needed, freed
// with its thread. For hot paths that need a buffer per call (an undo encoding's
// planes, a mip update's window of changes): fresh from malloc, such a buffer came
// from the top of a heap the history keeps growing and was page-faulted in anew on
// every edit.
#ifndef OROGEN_EDITOR_THREAD_SCRATCH_H
#define OROGEN_EDITOR_THREAD_SCRATCH_H

#include <stddef.h>

typedef enum thread_scratch_use {
    SCRATCH_UNDO_ENCODE, // history.c: a delta's planes and the delta before it is cut
    SCRATCH_MIP_WINDOW,  // edit_mips.c: the changes under a parent tile's samples
    SCRATCH_TAKE_MISSES, // layer_composite.c: a layer take's samples left to solve
    SCRATCH_USES
} thread_scratch_use;

// At least `bytes` of the calling thread's buffer for `use` (contents unspecified),
// valid until the thread's next call for the same use; NULL when out of memory.
void *thread_scratch(thread_scratch_use use, size_t bytes);

#endif
