// Tile-sized buffers for edits' undo snapshots (edit.c), kept between edits: a one-dab
// edit snapshots 14 tiles (the level-0 composite, the active layer, 12 mip levels) of
// which it copies only a corner. Fresh 256 KiB buffers from malloc came from mmap or a
// heap glibc trimmed again at their free, so every edit page-faulted them in anew
// (a third of a one-dab edit's time); kept, their pages stay mapped.
#ifndef OROGEN_EDITOR_SNAPSHOT_POOL_H
#define OROGEN_EDITOR_SNAPSHOT_POOL_H

#include <stddef.h>

// A buffer of `bytes` (uninitialised), or NULL when out of memory. Thread-safe.
void *snapshot_pool_take(size_t bytes);
// Gives back a buffer of `bytes` from snapshot_pool_take (NULL: nothing). Kept for the
// next edit up to a bound (SNAPSHOT_POOL_BYTES), freed past it. Thread-safe.
void snapshot_pool_give(void *p, size_t bytes);

#endif
