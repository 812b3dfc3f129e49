#include "editor/params/planet_presets.h"

#include <string.h>

typedef struct planet_preset {
    const char *name;
    double radius, max_height, ocean_level, omega, atmosphere, spacing;
    double w_factor, octaves; // the generator's gain and octaves (seed 004: 0.5 and 12.5)
    gen_kind generator;
} planet_preset;

// All but earth have no sea (ocean_level 0 is a radius of 0).
//
// Seed 004's gain of 0.5 keeps every octave's slope the same, the mountains' height over
// the planet's radius: its planets had a radius of 10 and heights of 0.1, but at Earth's
// proportions (8.8 km over 6,371 km) that is ground sloping at 1% at every scale, a
// smooth ball from 10 km up and a plain from 2 m. A gain of 0.7 (amplitude growing with
// the square root of the wavelength, as Earth's relief roughly does from 1 to 100 km)
// and octaves down to the samples give hills and valleys at every altitude with the same
// continents from orbit. The asteroid, whose heights are large for its size, is rough
// already at 0.55.
//
// Earth and Mars take the planet generator (gen_planet.c): fBm of any gain still gave
// one kind of rolling ground everywhere, no ranges from orbit and a plateau from 10 km;
// warped continents, ridged ranges in belts and ridged hills read as a planet at every
// altitude. The moon and the asteroid keep rough fBm (no tectonic ranges there).
static const planet_preset PRESETS[] = {
    {"earth", 6371000, 8848, 6371000, 7.2921e-5, 1.0, 100, 0.7, 18, GEN_PLANET},
    {"mars", 3389500, 10000, 0, 7.088e-5, 0.3, 100, 0.7, 18, GEN_PLANET},
    {"moon", 1737400, 6000, 0, 2.6617e-6, 0.0, 100, 0.7, 18, GEN_CRATERS},
    {"asteroid", 50000, 4000, 0, 1e-3, 0.0, 10, 0.55, 18, GEN_FBM_ADVANCED},
};

size_t planet_preset_count(void) {
    return sizeof PRESETS / sizeof PRESETS[0];
}

const char *planet_preset_name(size_t i) {
    return i < planet_preset_count() ? PRESETS[i].name : NULL;
}

int planet_preset_apply(world_params *p, const char *name, og_error *err) {
    for (size_t i = 0; i < planet_preset_count(); i++)
        if (strcmp(PRESETS[i].name, name) == 0) {
            p->radius = PRESETS[i].radius, p->max_height = PRESETS[i].max_height;
            p->ocean_level = PRESETS[i].ocean_level, p->omega = PRESETS[i].omega;
            p->atmosphere = PRESETS[i].atmosphere, p->spacing = PRESETS[i].spacing;
            p->w_factor = PRESETS[i].w_factor, p->octaves = PRESETS[i].octaves;
            p->generator = PRESETS[i].generator;
            return 0;
        }
    return og_error_set(err, "preset: unknown planet '%s' (earth, mars, moon, asteroid)", name);
}
