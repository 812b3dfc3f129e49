// Keeps the material layer's mip levels in step with level-0 paint on flat worlds, so
// the viewport's far clipmap levels show what was painted (as the coarse layer's mips
// show sculpting). Each parent sample is the tent filter (1 2 1 by 1 2 1, as the
// coarse mips) of its children's eight weights, rounded to whole units that still sum
// to 255. Unlike heights, generated material is the same everywhere ("automatic"), so
// refiltering the children gives the edited mip exactly.
#ifndef OROGEN_EDITOR_MATERIAL_MIPS_H
#define OROGEN_EDITOR_MATERIAL_MIPS_H

#include "editor/edit/edit.h"

#include <stdint.h>

// Updates every mip level over the edit's material dirty areas from index first on; the
// parent tiles it changes become part of the edit (and so of its undo step). Planets
// keep paint at level 0 only (their renderer shows it on the finest chunks).
int material_mips_update_from(edit *e, size_t first, og_error *err);

// One parent sample from its 3 x 3 children (row-major, TILE_MATERIALS weights each,
// each summing to 255): the tent-filtered weights, largest remainder rounding.
void material_mips_filter(const uint8_t *const children[9], uint8_t out[]);

#endif
