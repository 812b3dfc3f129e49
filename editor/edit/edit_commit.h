// Finishing an edit: the active edit layer takes the change (layer_composite.h), the coarse mip
// levels and the detail layer's PD map follow the changed area, then the edit becomes one undo
// step. What tools call at the end of a stroke, dab or stamp.
#ifndef OROGEN_EDITOR_EDIT_COMMIT_H
#define OROGEN_EDITOR_EDIT_COMMIT_H

#include "editor/edit/edit.h"

// Updates mips and PD maps over the edit's changed areas and records it as one undo
// step. On failure the world is restored to its state before the edit. Frees e
// either way.
int edit_commit(edit *e, og_error *err);

#endif
