#include "editor/edit/recover.h"

#include "editor/edit/edit.h"
#include "editor/world/journal_files.h"

#include <dirent.h>
#include <errno.h>
#include <libgen.h>
#include <limits.h>

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
        world_params p = s->params->before;
        s->params->before = s->params->after;
        s->params->after = p;
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

// Whether journal is one of w's journal files (its own or one set aside): beside w's
// parameter file, named after it.
static int journal_of(const world *w, const char *journal) {
    if (!world_path(w)[0]) return 0;
    char own[4400], dir_a[4400], dir_b[4400], real_a[PATH_MAX], real_b[PATH_MAX];
    snprintf(own, sizeof own, "%s.recover", world_path(w));
    snprintf(dir_a, sizeof dir_a, "%s", own);
    snprintf(dir_b, sizeof dir_b, "%s", journal);
    const char *slash_a = strrchr(own, '/'), *slash_b = strrchr(journal, '/');
    const char *base_a = slash_a ? slash_a + 1 : own, *base_b = slash_b ? slash_b + 1 : journal;
    if (strncmp(base_b, base_a, strlen(base_a)) != 0) return 0;
    const char *rest = base_b + strlen(base_a);
    if (*rest && strncmp(rest, ".old", 4) != 0) return 0;
    return realpath(dirname(dir_a), real_a) && realpath(dirname(dir_b), real_b) &&
           strcmp(real_a, real_b) == 0;
}

int edit_recover(world *w, const char *journal, recover_report *report, og_error *err) {
    memset(report, 0, sizeof *report);
    const char *own = world_recovery_path(w);
    if (!journal) {
        if (!world_recoverable(w, NULL))
            return og_error_set(err, "recover: %s has no unsaved edits to recover%s",
                                world_path(w)[0] ? world_path(w) : "this world",
                                world_path(w)[0] ? " ('recover list' lists its journals)" : "");
        journal = own;
    }
    world_journal_wait(w); // this session's journal may be the one named
    recovery_scan scan;
    if (recovery_journal_read(journal, &scan, NULL, NULL, err) != 0) return -1;
    if (scan.has_base)
        return og_error_set(err, "recover: %s is a never-saved world's journal", journal);
    if (!journal_of(w, journal))
        return og_error_set(err, "recover: %s is not a journal of %s", journal,
                            world_path(w)[0] ? world_path(w) : "this (never saved) world");
    if (recovery_journal_in_use(journal))
        return og_error_set(err, "recover: %s belongs to an Orogen that is still running", journal);
    if (world_session_journaled(w))
        return og_error_set(err,
                            "recover: this session has edits of its own since %s was opened or "
                            "saved; %s builds on the world as it was: load the world again, "
                            "then 'recover %s' (this session's edits stay journaled)",
                            world_path(w), journal, journal);
    if (strcmp(scan.state_id, world_state_id(w)) != 0)
        return og_error_set(err,
                            "recover: %s builds on another saved state of %s (its tile store was "
                            "saved since), so its steps cannot be replayed on this one; it is "
                            "kept until 'recover discard %s'",
                            journal, world_path(w), journal);
    if (!scan.records) return og_error_set(err, "recover: %s holds no steps", journal);
    if (replay_journal(w, journal, report, &scan, err) != 0) return -1;
    return world_journal_continue(w, journal, scan.valid_bytes, err);
}

// Whether journal is a never-saved world's that no running Orogen writes.
static int check_unsaved(const char *journal, recovery_scan *scan, og_error *err) {
    if (recovery_journal_read(journal, scan, NULL, NULL, err) != 0) return -1;
    if (!scan->has_base)
        return og_error_set(err, "recover: %s is the journal of a saved world", journal);
    if (recovery_journal_in_use(journal))
        return og_error_set(err, "recover: %s belongs to an Orogen that is still running", journal);
    return 0;
}

int edit_discard_journal(world *w, const char *journal, og_error *err) {
    if (!strcmp(journal, world_recovery_path(w))) return world_recover_discard(w, err);
    recovery_scan scan;
    og_error why;
    if (recovery_journal_read(journal, &scan, NULL, NULL, &why) != 0)
        return og_error_set(err, "recover: will not remove %s: %s", journal, why.msg);
    if (recovery_journal_in_use(journal))
        return og_error_set(err, "recover: %s belongs to an Orogen that is still running", journal);
    if (remove(journal) != 0)
        return og_error_set(err, "recover: cannot remove %s: %s", journal, strerror(errno));
    return 0;
}

world *edit_recover_unsaved(const char *journal, const world_settings *settings,
                            recover_base_fn remake, recover_report *report, og_error *err) {
    memset(report, 0, sizeof *report);
    recovery_scan scan;
    if (check_unsaved(journal, &scan, err) != 0) return NULL;
    world *w = world_create(&scan.base, settings, err);
    if (!w) return NULL;
    if (scan.base_source[0]) {
        // Made from a file: made again from it (checked to be what it was), not journaled.
        og_error why;
        world_journal_pause(w, 1);
        int rc = remake ? remake(w, scan.base_source, &why)
                        : og_error_set(&why, "nothing here remakes it");
        world_journal_pause(w, 0);
        if (rc != 0 || world_set_base_source(w, scan.base_source, &why) != 0) {
            og_error_set(
                err,
                "recover: %s: the world it holds was made from a file: %s; the journal is kept",
                journal, why.msg);
            world_close(w);
            return NULL;
        }
    }
    if (replay_journal(w, journal, report, &scan, err) != 0 ||
        world_adopt_journal(w, journal, scan.valid_bytes, err) != 0) {
        world_close(w);
        return NULL;
    }
    return w;
}

// ---- listing -----------------------------------------------------------------------

// Calls fn with the path of each never-saved world's journal in the recovery folder
// (unsaved-*.recover).
static void each_unsaved_journal(void (*fn)(void *user, const char *path), void *user) {
    char dir[4096];
    og_error err;
    if (world_recovery_dir(dir, sizeof dir, &err) != 0) return;
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t n = strlen(e->d_name);
        if (strncmp(e->d_name, "unsaved-", 8) != 0 || n < 9 ||
            strcmp(e->d_name + n - 8, ".recover") != 0)
            continue;
        char candidate[4400];
        snprintf(candidate, sizeof candidate, "%s/%s", dir, e->d_name);
        fn(user, candidate);
    }
    closedir(d);
}

typedef struct lister {
    const world *w;
    void (*fn)(void *user, const recover_entry *e);
    void *user;
    size_t count;
} lister;

static void list_one(void *user, const char *path) {
    lister *l = user;
    recover_entry e = {0};
    snprintf(e.path, sizeof e.path, "%s", path);
    og_error why;
    const char *own = world_recovery_path(l->w);
    if (recovery_journal_read(path, &e.scan, NULL, NULL, &why) != 0) {
        snprintf(e.status, sizeof e.status, "unreadable: %s", why.msg);
    } else if (world_session_journaled(l->w) && !strcmp(path, own)) {
        snprintf(e.status, sizeof e.status, "this session's (save keeps its edits)");
    } else if (recovery_journal_in_use(path)) {
        snprintf(e.status, sizeof e.status, "in use by a running Orogen");
    } else if (e.scan.has_base) {
        e.recoverable = e.scan.records > 0;
        snprintf(e.status, sizeof e.status, "a never-saved world's: 'recover %s' makes it again",
                 path);
    } else if (strcmp(e.scan.state_id, world_state_id(l->w)) != 0) {
        snprintf(e.status, sizeof e.status,
                 "builds on another saved state of the world: cannot be replayed");
    } else if (world_session_journaled(l->w)) {
        snprintf(e.status, sizeof e.status,
                 "recoverable once the world is loaded again (this session has edits)");
    } else {
        e.recoverable = e.scan.records > 0;
        snprintf(e.status, sizeof e.status, "recoverable: 'recover %s'", path);
    }
    l->fn(l->user, &e);
    l->count++;
}

static void list_other(void *user, const char *path) {
    lister *l = user;
    if (strcmp(path, world_recovery_path(l->w)) != 0) list_one(l, path);
}

size_t edit_recover_list(const world *w, void (*fn)(void *user, const recover_entry *e),
                         void *user) {
    lister l = {w, fn, user, 0};
    world_journal_wait(w); // this session's journal is listed with all its records
    char own[4400];
    if (world_path(w)[0]) {
        snprintf(own, sizeof own, "%s.recover", world_path(w));
        journal_files_each(own, list_one, &l); // a recovered set-aside one is among them
    } else if (world_session_journaled(w)) {
        list_one(&l, world_recovery_path(w));
    }
    // Never-saved worlds' journals in the recovery folder, not this session's.
    each_unsaved_journal(list_other, &l);
    return l.count;
}

typedef struct newest_finder {
    char *path;
    size_t len;
    recovery_scan *scan;
    int found;
} newest_finder;

static void consider_newest(void *user, const char *candidate) {
    newest_finder *f = user;
    recovery_scan s;
    og_error err;
    if (recovery_journal_in_use(candidate) ||
        recovery_journal_read(candidate, &s, NULL, NULL, &err) != 0 || !s.records || !s.has_base)
        return;
    if (!f->found || s.last > f->scan->last) {
        snprintf(f->path, f->len, "%s", candidate);
        *f->scan = s;
        f->found = 1;
    }
}

int edit_find_unsaved_journal(char *path, size_t len, recovery_scan *scan) {
    newest_finder f = {path, len, scan, 0};
    each_unsaved_journal(consider_newest, &f);
    return f.found;
}
