// Keeps the coarse layer's mip levels in step with level-0 edits: each level's
// change is the previous level's change, filtered down (a tent on flat worlds, whose
// mip samples coincide with even samples; a 2x2 box on planets, whose mip samples
// are block centres). Adding the filtered change, rather than refiltering, keeps
// the generator's own band-limited detail where nothing was edited.
#ifndef OROGEN_EDITOR_EDIT_MIPS_H
#define OROGEN_EDITOR_EDIT_MIPS_H

#include "editor/edit/edit.h"

// Updates every mip level over the edit's coarse (and, on flat worlds, material:
// material_mips.h) dirty areas changed since the last call (a stroke calls it as it goes, so
// coarser levels show it before it ends; the commit then does only what is left) and publishes
// those areas; the parent tiles it changes become part of the edit (and so of its undo step).
int edit_mips_update(edit *e, og_error *err);
// The same over the dirty areas from index first on (edit_dirty_rects). Each parent sample is set
// to its value before the edit plus the filtered change so far, so running it again
// over an area gives the same result.
int edit_mips_update_from(edit *e, size_t first, og_error *err);

// The deepest mip level edits reach on a world.
int edit_mips_top_level(const world_params *p);
// The level where one tile covers a bounded world or a planet face.
int edit_mips_tile_cover_level(const world_params *p);

// Recomputes levels first..top of a bounded flat world whole, each as the generator's
// tile plus the filtered difference of the level below from its generated tile: what
// one edit of a fresh world writes there, whatever edits led to the level below. A
// world imported in parts (base_pending.h) calls it once the last part is in: its deep
// levels, summed part by part, differed from a whole import's in float rounding.
int edit_mips_refilter_bounded(edit *e, int first, og_error *err);

#endif
