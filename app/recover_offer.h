// The Recover unsaved edits dialog (like Blender's Recover Last Session): the crash
// journals the window offers, each with Recover and Discard. It comes up by itself for
// the journals that can be recovered now: the world's own, those an earlier session set
// aside, and the newest a never-saved world left when the editor started; File >
// Recover unsaved edits... lists every journal `recover list` knows, whatever its state.
// It acts only by running `recover` commands; it owns its state.
#ifndef OROGEN_APP_RECOVER_OFFER_H
#define OROGEN_APP_RECOVER_OFFER_H

#include "editor/world/world.h"
#include "ui/ui.h"

#include <stddef.h>
#include <stdint.h>

// Journals shown at most (more: the rest stay in `recover list`).
#define RECOVER_OFFER_MAX 12
#define RECOVER_OFFER_PATH 4400

typedef struct recover_offer_item {
    char path[RECOVER_OFFER_PATH];
    size_t steps;
    int64_t when;      // its last step (unix s)
    int recoverable;   // `recover PATH` would restore it now
    int unsaved;       // a never-saved world's
    char status[4600]; // as `recover list` says it
} recover_offer_item;

typedef struct recover_offer {
    recover_offer_item items[RECOVER_OFFER_MAX];
    size_t count;
    int all;   // opened from the menu: every journal, until closed
    int stale; // a recover command ran: look again
    // What the list was made for; a change of any means a new look.
    const world *seen_world;
    char seen_state[128];
    size_t seen_steps;
    int seen_modified, seen_journaled;
    // Offers put off with "Not now" (or Esc): not shown by themselves again.
    char dismissed[RECOVER_OFFER_MAX][RECOVER_OFFER_PATH];
    size_t dismissed_count;
    // The newest journal a never-saved world left, found when the editor started.
    char startup_unsaved[RECOVER_OFFER_PATH];
} recover_offer;

// At start: remembers the never-saved world's journal a crash left, if any.
void recover_offer_find_startup(recover_offer *o);
// Brings the list up to date for w; 1 when the dialog shows.
int recover_offer_update(recover_offer *o, const world *w);
// File > Recover unsaved edits...: every journal, recoverable or not.
void recover_offer_show_all(recover_offer *o);
// "Not now" or Esc: the shown offers wait until asked for.
void recover_offer_dismiss(recover_offer *o);
// Rows the dialog needs (for its height, in lines of the font).
float recover_offer_lines(const recover_offer *o);
// Draws the dialog in r; run runs a command (0: it succeeded).
void recover_offer_draw(recover_offer *o, ui_context *ui, const world *w, ui_rect r,
                        int (*run)(void *user, const char *text), void *user);

#endif
