// Band limiting: how big the largest features are and how many octaves a mip level
// can show without aliasing.
#include "editor/gen/gen_scale.h"

#include <math.h>

double gen_feature_size(const world_params *p) {
    if (p->feature_size > 0) return p->feature_size;
    // Flat: features a couple of thousand samples across look like landscape at any
    // spacing. Planets: Kahoun 2010 samples noise on the unit sphere, i.e. one radius.
    return p->kind == WORLD_PLANET ? p->radius : 2048.0 * p->spacing;
}

double gen_octaves_at_level(const world_params *p, int level) {
    double sample = p->spacing * ldexp(1.0, level);
    double lac = p->exponent > 1.0 ? p->exponent : 2.0;
    // Octave o has wavelength feature / lac^o; keep those at least two samples long.
    double fit = log(gen_feature_size(p) / (2.0 * sample)) / log(lac) + 1.0;
    double oct = p->octaves < fit ? p->octaves : fit;
    return oct < 1.0 ? 1.0 : oct;
}
