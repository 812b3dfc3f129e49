// `generate` over edit layers: the generated base under the layers changes, and the
// edits ride on the new terrain.
#ifndef OROGEN_EDITOR_LAYER_GENERATE_H
#define OROGEN_EDITOR_LAYER_GENERATE_H

#include "editor/world/world.h"
#include "io/err.h"

// The world switches to new parameters (keeping its layers) and the composite is
// recomposed wherever a visible layer has tiles; one undo step. What `generate` runs.
int layer_generate(world *w, const world_params *params, og_error *err);

#endif
