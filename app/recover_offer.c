// The Recover unsaved edits dialog: which journals it shows, and its rows.
#include "app/recover_offer.h"

#include "editor/cmd/tokenize.h"
#include "editor/edit/recover.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

void recover_offer_find_startup(recover_offer *o) {
    recovery_scan scan;
    if (!edit_find_unsaved_journal(o->startup_unsaved, sizeof o->startup_unsaved, &scan))
        o->startup_unsaved[0] = 0;
}

static int is_dismissed(const recover_offer *o, const char *path) {
    for (size_t i = 0; i < o->dismissed_count; i++)
        if (!strcmp(o->dismissed[i], path)) return 1;
    return 0;
}

typedef struct collector {
    recover_offer *o;
    const world *w;
} collector;

// Whether a journal `recover list` knows is offered without being asked for: one that
// can be restored now and was not put off. Of the never-saved worlds' journals only the
// one found at start, while the world is a fresh, untouched one (recovering it replaces
// the world).
static int offered_by_itself(const collector *c, const recover_entry *e) {
    if (!e->recoverable || is_dismissed(c->o, e->path)) return 0;
    if (!e->scan.has_base) return 1;
    return !strcmp(e->path, c->o->startup_unsaved) && !world_path(c->w)[0] &&
           !world_is_modified(c->w);
}

static void collect_one(void *user, const recover_entry *e) {
    collector *c = user;
    recover_offer *o = c->o;
    if (o->count == RECOVER_OFFER_MAX || (!o->all && !offered_by_itself(c, e))) return;
    recover_offer_item *it = &o->items[o->count++];
    snprintf(it->path, sizeof it->path, "%s", e->path);
    it->steps = e->scan.records;
    it->when = e->scan.last;
    it->recoverable = e->recoverable;
    it->unsaved = e->scan.has_base;
    snprintf(it->status, sizeof it->status, "%s", e->status);
}

static void rescan(recover_offer *o, const world *w) {
    o->count = 0;
    collector c = {o, w};
    edit_recover_list(w, collect_one, &c);
    o->stale = 0;
}

int recover_offer_update(recover_offer *o, const world *w) {
    size_t steps = world_recoverable(w, NULL);
    int modified = world_is_modified(w), journaled = world_session_journaled(w);
    const char *state = world_state_id(w);
    if (o->stale || w != o->seen_world || steps != o->seen_steps || modified != o->seen_modified ||
        journaled != o->seen_journaled || strcmp(state, o->seen_state) != 0) {
        o->seen_world = w;
        o->seen_steps = steps;
        o->seen_modified = modified;
        o->seen_journaled = journaled;
        snprintf(o->seen_state, sizeof o->seen_state, "%s", state);
        rescan(o, w);
    }
    return o->all || o->count > 0;
}

void recover_offer_show_all(recover_offer *o) {
    o->all = 1;
    o->stale = 1;
}

void recover_offer_dismiss(recover_offer *o) {
    for (size_t i = 0; i < o->count; i++)
        if (!is_dismissed(o, o->items[i].path) && o->dismissed_count < RECOVER_OFFER_MAX)
            snprintf(o->dismissed[o->dismissed_count++], RECOVER_OFFER_PATH, "%s",
                     o->items[i].path);
    o->all = 0;
    o->stale = 1;
}

// Lines of one journal's rows: what it is, when, (why not, when it cannot be restored
// now), the buttons.
// (lines of 1.45 em with their gaps, the 1.5 em buttons, the separator).
static float item_lines(const recover_offer_item *it) {
    return it->recoverable ? 5.2f : 8.2f;
}

float recover_offer_lines(const recover_offer *o) {
    float lines = 3.5f; // the last row's buttons and the panel's padding
    if (!o->count) lines += 1.5f;
    for (size_t i = 0; i < o->count; i++)
        lines += item_lines(&o->items[i]);
    return lines;
}

static const char *base_name(const char *path) {
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

// The first line: what the journal is.
static void describe(const recover_offer_item *it, const world *w, char *out, size_t len) {
    if (it->unsaved)
        snprintf(out, len, "A world that was never saved was open when Orogen stopped.");
    else if (!strcmp(it->path, world_recovery_path(w)) && world_path(w)[0])
        snprintf(out, len, "%s was not saved when Orogen last stopped.", base_name(world_path(w)));
    else
        snprintf(out, len, "Edits an earlier session set aside (%s).", base_name(it->path));
}

static void item_rows(const recover_offer_item *it, ui_context *ui, const world *w,
                      int (*run)(void *user, const char *text), void *user, int *acted) {
    char text[4700], stamp[64], cmd[4600], arg[4400];
    ui_push_scope(ui, base_name(it->path));
    ui_row(ui, 1, NULL, 0);
    describe(it, w, text, sizeof text);
    ui_label(ui, text);
    time_t t = (time_t)it->when;
    struct tm tm;
    if (!localtime_r(&t, &tm) || !strftime(stamp, sizeof stamp, "%Y-%m-%d %H:%M", &tm))
        snprintf(stamp, sizeof stamp, "?");
    snprintf(text, sizeof text, "Its edits of %s (%zu step%s) %s", stamp, it->steps,
             it->steps == 1 ? "" : "s",
             it->recoverable ? "can be recovered." : "cannot be recovered now:");
    ui_label(ui, text);
    ui_tooltip(ui, it->path);
    if (!it->recoverable) ui_label_wrapped(ui, it->status, ui_get_theme(ui)->text_dim);
    cmd_quote_arg(arg, sizeof arg, it->path);
    float halves[2] = {-0.5f, 0};
    ui_row(ui, 2, halves, ui_em(ui, 1.5f));
    if (it->recoverable && ui_button(ui, "Recover")) {
        snprintf(cmd, sizeof cmd, "recover %s", arg);
        run(user, cmd);
        *acted = 1;
    }
    if (it->recoverable)
        ui_tooltip(ui, "Restore those edits: undoable, and unsaved until you save (recover)");
    snprintf(text, sizeof text, "Discard %zu step%s", it->steps, it->steps == 1 ? "" : "s");
    if (ui_button(ui, text)) {
        snprintf(cmd, sizeof cmd, "recover discard %s", arg);
        run(user, cmd);
        *acted = 1;
    }
    snprintf(text, sizeof text, "Drop the edits in %s for good (recover discard)", it->path);
    ui_tooltip(ui, text);
    ui_pop_scope(ui);
    ui_separator(ui);
}

void recover_offer_draw(recover_offer *o, ui_context *ui, const world *w, ui_rect r,
                        int (*run)(void *user, const char *text), void *user) {
    ui_panel_begin(ui, "Recover unsaved edits", r);
    ui_row(ui, 1, NULL, 0);
    if (!o->count)
        ui_label(ui, "No recovery journals: every session saved or discarded its edits.");
    int acted = 0;
    for (size_t i = 0; i < o->count && !acted; i++)
        item_rows(&o->items[i], ui, w, run, user, &acted);
    if (acted) o->stale = 1; // a journal went or became this session's
    ui_row(ui, 1, NULL, ui_em(ui, 1.5f));
    if (o->all) {
        if (ui_button(ui, "Close")) o->all = 0;
        ui_tooltip(ui, "The journals stay; the console's 'recover list' shows them too");
    } else {
        if (ui_button(ui, "Not now")) recover_offer_dismiss(o);
        ui_tooltip(ui, "Keep them for later: File > Recover unsaved edits... and the console's "
                       "'recover' restore them until the world is edited or saved");
    }
    ui_panel_end(ui);
}
