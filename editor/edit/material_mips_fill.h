// Worlds saved before the material layer had mip levels hold their paint at level 0
// only: the far clipmap levels then showed the automatic materials (painted snow
// turned grey a few hundred metres away) until the paint was touched again. On load
// the missing levels are built from the saved paint, as a stroke would have built them.
#ifndef OROGEN_EDITOR_MATERIAL_MIPS_FILL_H
#define OROGEN_EDITOR_MATERIAL_MIPS_FILL_H

#include "editor/world/world.h"

// When w is flat and its store holds painted level-0 material tiles but no material mip
// tile, builds the mip levels over every painted tile (part of the world's starting
// state: no undo step, no unsaved change; a save writes them). Returns the painted tiles
// it built them for (0: nothing was missing), or -1 after a warning through world_warn
// naming the file (the world stays open: only the far view of the paint is missing).
int64_t material_mips_fill_missing(world *w);

#endif
