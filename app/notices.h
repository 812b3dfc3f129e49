// Failures shown where the user acted: a command started from a menu, shortcut, drop or
// dialog that failed puts its whole message here, over the viewport (never only in the
// console). A file action's failure (open, save, import, export...) stays until the user
// dismisses it; any other refusal passes: it goes after NOTICES_PASS_SECONDS or at the
// next action that works. Commands typed in the console report there, as a terminal does.
#ifndef OROGEN_APP_NOTICES_H
#define OROGEN_APP_NOTICES_H

#include "ui/ui.h"

#define NOTICES_MAX 6
#define NOTICES_PASS_SECONDS 6.0

typedef struct notices {
    char text[NOTICES_MAX][1024];
    double passes_at[NOTICES_MAX]; // notices_now() seconds it goes at; 0: stays
    int count;                     // oldest first
} notices;

// Adds a notice that stays until dismissed (the oldest goes when full; the same text
// twice in a row shows once).
void notices_add(notices *n, const char *text);
// Adds a failure of the command named `command` (its first word): one that stays for
// the file commands, else one that passes NOTICES_PASS_SECONDS after now.
void notices_add_failure(notices *n, const char *command, const char *text, double now);
// Drops the passing notices due by now; 1 when any went. notices_due: whether one is.
int notices_expire(notices *n, double now);
int notices_due(const notices *n, double now);
// An action worked: the passing notices go.
void notices_clear_passing(notices *n);
// Whether commands run under this label are the user's own actions (not the console,
// nor the window's automatic ones: the brush radius following the view, a planet's tool).
int notices_user_action(const char *label);
void notices_dismiss(notices *n, int i);
double notices_now(void); // seconds, CLOCK_MONOTONIC
// Draws them across the top of area (the viewport), each with a Dismiss button
// (panel "Notices", buttons "Dismiss##I"); their text is listed by ui_messages.
void notices_draw(notices *n, ui_context *ui, ui_rect area);

#endif
