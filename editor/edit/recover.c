#include "editor/edit/recover.h"

#include "editor/edit/edit.h"

#include <dirent.h>
#include <errno.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// Journal step ids of the steps replayed so far, and the ids the history gave them.
typedef struct id_pair {
    uint64_t journal, history;
} id_pair;

typedef struct recovery {
    world *w;
    id_pair *ids;
    size_t id_count, id_cap;
    recover_report *report;
} recovery;

static uint64_t history_id_of(const recovery *r, uint64_t journal_id) {
    for (size_t i = r->id_count; i-- > 0;)
        if (r->ids[i].journal == journal_id) return r->ids[i].history;
    return 0;
}

// An undo or redo of a step that is not where the history has it (it predates the
// journal): the same change as a step of its own, undoable like any other.
static void as_own_step(history_step *s, recovery_kind kind) {
    char label[sizeof s->label];
    snprintf(label, sizeof label, "%s %.120s", kind == RECOVERY_UNDO ? "undo" : "redo", s->label);
    memcpy(s->label, label, sizeof label);
    for (size_t i = 0; i < s->tile_count; i++)
        s->tiles[i].was_pristine = 0;
    if (kind == RECOVERY_UNDO && s->has_params) { // forwards, it goes to the old parameters
        world_params p = s->params_before;
        s->params_before = s->params_after;
        s->params_after = p;
    }
}

static int replay_record(void *user, recovery_kind kind, uint64_t journal_id, history_step *s,
                         og_error *err) {
    recovery *r = user;
    history *h = world_history(r->w);
    r->report->records++;
    uint64_t known = history_id_of(r, journal_id);
    const history_step *at = kind == RECOVERY_UNDO   ? history_undo_peek(h)
                             : kind == RECOVERY_REDO ? history_redo_peek(h)
                                                     : NULL;
    if (at && known && at->id == known) { // the history holds it where it was
        history_step_free(s);
        return (kind == RECOVERY_UNDO ? edit_undo(r->w, err) : edit_redo(r->w, err)) < 0 ? -1 : 0;
    }
    if (kind != RECOVERY_STEP) as_own_step(s, kind);
    if (edit_apply_step(r->w, s, 0, err) != 0) {
        history_step_free(s);
        return -1;
    }
    history_push(h, s);
    r->report->steps++;
    if (kind == RECOVERY_STEP) {
        if (r->id_count == r->id_cap) {
            size_t cap = r->id_cap ? r->id_cap * 2 : 64;
            id_pair *grown = realloc(r->ids, cap * sizeof *grown);
            if (!grown) return og_error_set(err, "recover: out of memory");
            r->ids = grown, r->id_cap = cap;
        }
        r->ids[r->id_count++] = (id_pair){journal_id, s->id};
    }
    return 0;
}

// Replays the journal at path onto w (its records are not journaled again).
static int replay_journal(world *w, const char *path, recover_report *report, recovery_scan *scan,
                          og_error *err) {
    memset(report, 0, sizeof *report);
    recovery r = {.w = w, .report = report};
    world_journal_pause(w, 1);
    int rc = recovery_journal_read(path, scan, replay_record, &r, err);
    world_journal_pause(w, 0);
    free(r.ids);
    report->dropped_bytes = scan->dropped_bytes;
    report->when = scan->last;
    world_publish(w, &(world_event){.kind = WORLD_EVENT_HISTORY});
    return rc;
}

int edit_recover(world *w, recover_report *report, og_error *err) {
    memset(report, 0, sizeof *report);
    if (!world_recoverable(w, NULL))
        return og_error_set(err, "recover: %s has no unsaved edits to recover",
                            world_path(w)[0] ? world_path(w) : "this world");
    recovery_scan scan;
    if (replay_journal(w, world_recovery_path(w), report, &scan, err) != 0) return -1;
    return world_journal_continue(w, scan.valid_bytes, err);
}

// Whether journal is a never-saved world's that no running Orogen writes.
static int check_unsaved(const char *journal, recovery_scan *scan, og_error *err) {
    if (recovery_journal_read(journal, scan, NULL, NULL, err) != 0) return -1;
    if (!scan->has_base)
        return og_error_set(err,
                            "recover: %s is the journal of a saved world: open that world and "
                            "run 'recover' or 'recover discard'",
                            journal);
    if (recovery_journal_in_use(journal))
        return og_error_set(err, "recover: %s belongs to an Orogen that is still running", journal);
    return 0;
}

int edit_discard_unsaved(const char *journal, og_error *err) {
    recovery_scan scan;
    if (check_unsaved(journal, &scan, err) != 0) return -1;
    if (remove(journal) != 0)
        return og_error_set(err, "recover: cannot remove %s: %s", journal, strerror(errno));
    return 0;
}

world *edit_recover_unsaved(const char *journal, const world_settings *settings,
                            recover_report *report, og_error *err) {
    memset(report, 0, sizeof *report);
    recovery_scan scan;
    if (check_unsaved(journal, &scan, err) != 0) return NULL;
    world *w = world_create(&scan.base, settings, err);
    if (!w) return NULL;
    if (replay_journal(w, journal, report, &scan, err) != 0 ||
        world_adopt_journal(w, journal, scan.valid_bytes, err) != 0) {
        world_close(w);
        return NULL;
    }
    return w;
}

int edit_find_unsaved_journal(char *path, size_t len, recovery_scan *scan) {
    char dir[4096];
    og_error err;
    if (world_recovery_dir(dir, sizeof dir, &err) != 0) return 0;
    DIR *d = opendir(dir);
    if (!d) return 0;
    int found = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t n = strlen(e->d_name);
        if (strncmp(e->d_name, "unsaved-", 8) != 0 || n < 9 ||
            strcmp(e->d_name + n - 8, ".recover") != 0)
            continue;
        char candidate[4400];
        snprintf(candidate, sizeof candidate, "%s/%s", dir, e->d_name);
        recovery_scan s;
        if (recovery_journal_in_use(candidate) ||
            recovery_journal_read(candidate, &s, NULL, NULL, &err) != 0 || !s.records ||
            !s.has_base)
            continue;
        if (!found || s.last > scan->last) {
            snprintf(path, len, "%s", candidate);
            *scan = s;
            found = 1;
        }
    }
    closedir(d);
    return found;
}
