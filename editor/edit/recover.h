// Crash recovery: replays the journal a session that did not save left beside the
// world (editor/world/recovery_journal.h) onto the saved state it builds on. The world
// ends as it was when that session last committed a step; the steps are in the
// history (undoable) and the world is unsaved. The journal then goes on with this
// session's steps.
#ifndef OROGEN_EDITOR_RECOVER_H
#define OROGEN_EDITOR_RECOVER_H

#include "editor/world/world.h"
#include "io/err.h"

#include <stddef.h>
#include <stdint.h>

typedef struct recover_report {
    size_t records;       // journal records replayed
    size_t steps;         // undo steps added to the history
    size_t dropped_bytes; // a torn or damaged tail left out
    int64_t when;         // when the last replayed step was made (unix s)
} recover_report;

// Replays journal (NULL: the world's own, when it has unrecovered steps) onto w: one
// of w's journal files, its own or one set aside, on the saved state w is in, not in use,
// with w not edited since it was opened. The journal is then this session's (it grows
// with its edits; save removes it). Fails, nothing changed, otherwise.
int edit_recover(world *w, const char *journal, recover_report *report, og_error *err);
// Remakes a never-saved world's base from what it was made from (the journal's
// base_source, world_set_base_source): the command layer's, which knows the text.
typedef int (*recover_base_fn)(world *w, const char *base_source, og_error *err);

// A never-saved world's journal (world_recovery_dir): a new world of its base
// parameters (made again from its source by remake, when it was made from a file) with
// its steps replayed, the journal now its own. NULL with err when the journal is not
// one, its Orogen still runs, or its source cannot be read again as it was.
world *edit_recover_unsaved(const char *journal, const world_settings *settings,
                            recover_base_fn remake, recover_report *report, og_error *err);
// `recover discard JOURNAL`: removes a journal (w's own, or any other one a running
// Orogen does not write; a file that is not a journal is left alone).
int edit_discard_journal(world *w, const char *journal, og_error *err);

// One journal `recover list` shows.
typedef struct recover_entry {
    char path[4400];
    recovery_scan scan;
    int recoverable; // 'recover PATH' would restore it now
    char status[4600];
} recover_entry;
// Every journal of w (its own, those set aside, this session's) and the never-saved
// worlds' journals of the recovery folder; returns how many.
size_t edit_recover_list(const world *w, void (*fn)(void *user, const recover_entry *e),
                         void *user);
// The newest journal a never-saved world left in the recovery folder when its Orogen
// stopped without saving (a crash, a kill): 1 with its path and scan, or 0.
int edit_find_unsaved_journal(char *path, size_t len, recovery_scan *scan);

#endif
