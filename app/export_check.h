// An export the dialog built, checked before it is queued (the export itself runs as a
// job and reports to the console): what would refuse it at once is said in the dialog,
// which stays open with the user's choices.
#ifndef OROGEN_APP_EXPORT_CHECK_H
#define OROGEN_APP_EXPORT_CHECK_H

#include "app/interchange_dialog.h"
#include "editor/world/world.h"

// The export command's own checks on d's choices: the region's numbers, the file's
// folder (there and writable), a heightmap format for one layer's change or the stack up
// to it, and that layer in w's stack. 0, or -1 with err naming the field or the file.
int export_check(world *w, const interchange_dialog *d, og_error *err);
// After the dialog's Export: 1 to run its command; 0 with the dialog open again and the
// reason shown in it. Imports and planets' exports pass (their commands check).
int export_check_accept(interchange_dialog *d, world *w);

#endif
