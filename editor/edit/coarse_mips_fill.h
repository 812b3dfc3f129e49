// Worlds saved before the coarse layer's mip levels followed edits past the level where
// one tile covers a bounded world hold the generator's heights there: the far clipmap
// levels drew a small sculpted or imported world flat from a few hundred metres away.
// On load those levels are made again from the saved level below, as an edit makes them.
#ifndef OROGEN_EDITOR_COARSE_MIPS_FILL_H
#define OROGEN_EDITOR_COARSE_MIPS_FILL_H

#include "editor/world/world.h"

// When w is a bounded flat world whose store holds coarse tiles of the composite at the
// level where one tile covers it (edit_mips_tile_cover_level) but none at the next,
// rebuilds the levels past it (part of the world's starting state: no undo step, no
// unsaved change; a save writes them). Returns 1 when it rebuilt them, 0 when nothing
// was missing, or -1 after a warning through world_warn naming the file (the world stays
// open: only its far view is stale).
int coarse_mips_fill_missing(world *w);

#endif
