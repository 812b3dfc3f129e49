// The detail layer's partial-derivative (PD) map (Crause 2010): d/dx and d/dz of the
// detail offsets by 4th-order central differences,
//   f'(x) = (f(x-2) - 8 f(x-1) + 8 f(x+1) - f(x+2)) / (12 h),
// stored as int16 x DETAIL_PD_SCALE in TILE_LAYER_DETAIL_PD tiles for the renderer.
#ifndef OROGEN_EDITOR_DETAIL_PD_H
#define OROGEN_EDITOR_DETAIL_PD_H

#include "editor/world/history.h"
#include "editor/world/world.h"

// Recomputes the PD map wherever the detail areas among rects can have changed it
// (each rect grown by the 2-sample stencil). Other layers' rects are ignored.
int detail_pd_update(world *w, const dirty_rect *rects, size_t count, og_error *err);

// The PD pair of one sample from its 5-point neighbourhoods (heights in metres,
// spacing in metres), as stored.
void detail_pd_encode(const float row[5], const float column[5], double spacing, int16_t out[2]);

#endif
