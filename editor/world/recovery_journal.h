// The crash-recovery journal: every committed undo step, undo and redo since the last
// save, appended to a file beside the world as it happens, so a kill, a crash or a
// power cut loses nothing that was committed. Each record is checksummed (CRC32C) and
// written with one writev() by the journal's writer thread, the commit going on
// meanwhile (its ~90 KB write was a third of a one-dab step); an append waits for the
// record before it, so a kill loses at most the last step, and only during its write
// (tens of microseconds). The file is fsync'd within a second of each record by a
// flusher thread (a kill loses nothing written even before that: the bytes are the
// kernel's). A torn or damaged tail is cut off: reading gives the longest valid prefix.
//
// The journal names the saved state it builds on (the tile store's state_id, set in
// the same transaction as a save's tiles), so it is never replayed onto another one.
#ifndef OROGEN_EDITOR_RECOVERY_JOURNAL_H
#define OROGEN_EDITOR_RECOVERY_JOURNAL_H

#include "editor/world/history.h"
#include "io/err.h"

#include <stddef.h>
#include <stdint.h>

typedef enum recovery_kind {
    RECOVERY_STEP = 1, // a new undo step (applied)
    RECOVERY_UNDO = 2, // the step was undone
    RECOVERY_REDO = 3, // the step was redone
} recovery_kind;

#define RECOVERY_STATE_CHARS 32
#define RECOVERY_SOURCE_MAX 8192

typedef struct recovery_journal recovery_journal;

// Opens the journal at path for appending records onto the saved state state_id
// ("" when the world has no tile store yet), or, for a world never saved, onto a new
// world of the parameters base (NULL when the world has a file) and, for a world made
// from a file, base_source (world_set_base_source; NULL: none). keep_bytes > 0 keeps
// that much of an existing journal (its valid prefix, after a recovery); 0 starts a
// new one. The file stays locked (flock) while open.
recovery_journal *recovery_journal_open(const char *path, const char *state_id,
                                        const world_params *base, const char *base_source,
                                        size_t keep_bytes, og_error *err);
// Appends one record: the step's label, tile deltas, dirty areas and parameters, written
// on the writer thread. The record points into s's deltas (an import's step holds
// hundreds of megabytes; a copy of a dab's 90 KB cost more than its write): they must
// stay as they are until recovery_journal_wait returns (history_set_reader). -1 with
// err when out of memory or when the record before failed to write (a full disk).
int recovery_journal_append(recovery_journal *j, recovery_kind kind, const history_step *s,
                            og_error *err);
// Waits until every record appended is in the file (readers of the file: `recover list`,
// tests); -1 with err when one failed to write. NULL: nothing to wait for.
int recovery_journal_wait(recovery_journal *j, og_error *err);
// Writes what is left, flushes to disk and closes.
void recovery_journal_close(recovery_journal *j);

typedef struct recovery_scan {
    char state_id[RECOVERY_STATE_CHARS + 1]; // the saved state it builds on
    int64_t started;                         // when its first record was written (unix s)
    int has_base;                            // a never-saved world's: made from base
    world_params base;
    char base_source[RECOVERY_SOURCE_MAX]; // what the base was made from ("": parameters only)
    int64_t last;                          // when its last valid record was written
    size_t records;                        // valid records
    size_t valid_bytes;                    // the file's valid prefix
    size_t dropped_bytes;                  // a torn or damaged tail after it
} recovery_scan;

// Reads the journal at path: for each valid record, fn gets its kind, an id of the step
// unique across the sessions that wrote the journal and the step (fn owns it), unless
// fn is NULL. Stops at the first
// torn or damaged record (scan says how many bytes were dropped). Returns -1 with err
// when the file cannot be read or is not a recovery journal, or when fn fails.
int recovery_journal_read(const char *path, recovery_scan *scan,
                          int (*fn)(void *user, recovery_kind kind, uint64_t session_id,
                                    history_step *step, og_error *err),
                          void *user, og_error *err);

// 1 when a live process has the journal at path open (it is not a crash's).
int recovery_journal_in_use(const char *path);

#endif
