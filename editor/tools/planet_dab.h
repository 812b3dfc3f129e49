// A brush dab on a planet: given on one face (its centre in that face's samples,
// which may lie past the face's edges), applied to every face its cap touches, each
// sample weighted by its great-circle distance to the centre. So a dab, a stroke
// or the erosion tools go on across face edges and corners as over a continuous
// surface, in the same edit (one undo step, mips and change notifications per face).
#ifndef OROGEN_EDITOR_PLANET_DAB_H
#define OROGEN_EDITOR_PLANET_DAB_H

#include "editor/edit/edit.h"
#include "editor/params/world_params.h"
#include "editor/tools/brush_dab.h"
#include "editor/world/layer_grid.h"

// The largest dab on a planet: its cap may span this angle (radians) from its centre.
#define PLANET_DAB_MAX_ANGLE (3.14159265358979323846 / 8.0)

// d: the dab on `face` of `layer` (cx, cz, radius in that layer's samples).
int planet_dab_apply(edit *e, const world_params *p, tile_layer layer, int face, const brush_dab *d,
                     og_error *err);

// The samples of face `target` within the dab's cap (empty when it does not reach it).
grid_rect planet_dab_face_rect(const brush_dab *sphere_dab, int target, int64_t layer_samples);

// Positions on a planet face may lie past its edges (its coordinates go on onto the
// neighbours), up to half a face beyond: 0, or -1 with err naming the face.
int planet_dab_check_position(const layer_grid *g, double x, double z, og_error *err);

// Fills the planet fields of d (sphere, face, centre_dir...) for a dab given on face.
void planet_dab_prepare(brush_dab *d, const world_params *p, tile_layer layer, int face);

#endif
