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

// Fails (nothing changed) when the world has no journal to recover.
int edit_recover(world *w, recover_report *report, og_error *err);

#endif
