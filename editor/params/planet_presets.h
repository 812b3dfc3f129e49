// Planet presets: bodies a person recognises (an Earth-, Mars- or Moon-like planet, a
// small asteroid), each a set of world parameters the World panel shows: radius,
// max_height, ocean_level (the sea's radius; 0 for no sea), omega, atmosphere, spacing.
#ifndef OROGEN_EDITOR_PARAMS_PLANET_PRESETS_H
#define OROGEN_EDITOR_PARAMS_PLANET_PRESETS_H

#include "editor/params/world_params.h"
#include "io/err.h"

#include <stddef.h>

size_t planet_preset_count(void);
const char *planet_preset_name(size_t i); // "earth", "mars", "moon", "asteroid"
// Sets the preset's parameters in p (the others unchanged); -1 when name is unknown.
int planet_preset_apply(world_params *p, const char *name, og_error *err);

#endif
