// Failures shown where the user acted: a command started from a menu, shortcut, drop or
// dialog that failed puts its whole message here, and it stays over the viewport until
// the user dismisses it (never only in the console). Commands typed in the console
// report there, as a terminal does.
#ifndef OROGEN_APP_NOTICES_H
#define OROGEN_APP_NOTICES_H

#include "ui/ui.h"

#define NOTICES_MAX 6

typedef struct notices {
    char text[NOTICES_MAX][1024];
    int count; // oldest first
} notices;

// Adds a notice (the oldest goes when full; the same text twice in a row shows once).
void notices_add(notices *n, const char *text);
void notices_dismiss(notices *n, int i);
// Draws them across the top of area (the viewport), each with a Dismiss button
// (panel "Notices", buttons "Dismiss##I"); their text is listed by ui_messages.
void notices_draw(notices *n, ui_context *ui, ui_rect area);

#endif
