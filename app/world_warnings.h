// What the world warns about (a file changed after Orogen saved it, lines that do not
// read, damaged tiles, a lock file taken over, a full disk while writing) reaches the
// window, not only the terminal that started it: a user who opened a damaged file from
// File > Open saw only "(read-only)" in the title. Any thread may report a warning; it
// still goes to stderr at once, and the window takes it on its own thread to show it in
// the console and as a notice over the viewport.
#ifndef OROGEN_APP_WORLD_WARNINGS_H
#define OROGEN_APP_WORLD_WARNINGS_H

#include "editor/world/world.h"

#include <stddef.h>

#define WORLD_WARNINGS_KEPT 16 // waiting at most; more drop the oldest

// Routes the warnings of every world made with settings (and its copies) here.
void world_warnings_install(world_settings *settings);
// The oldest warning waiting, into out: 1, or 0 when none is.
int world_warnings_take(char *out, size_t size);

#endif
