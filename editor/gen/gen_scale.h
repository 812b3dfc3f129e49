// Band limiting shared by the generators: feature size and octaves per mip level.
#ifndef OROGEN_EDITOR_GEN_SCALE_H
#define OROGEN_EDITOR_GEN_SCALE_H

#include "editor/params/world_params.h"

// The wavelength in metres of the generator's lowest octave (resolves feature_size = 0).
double gen_feature_size(const world_params *p);

// Octaves actually summed at a mip level: the parameter's count, minus the octaves
// whose wavelength is shorter than two samples at that level (band limiting).
double gen_octaves_at_level(const world_params *p, int level);

#endif
