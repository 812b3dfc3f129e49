#include "editor/params/planet_presets.h"

#include <string.h>

typedef struct planet_preset {
    const char *name;
    double radius, max_height, ocean_level, omega, atmosphere, spacing;
} planet_preset;

// All but earth have no sea (ocean_level 0 is a radius of 0).
static const planet_preset PRESETS[] = {
    {"earth", 6371000, 8848, 6371000, 7.2921e-5, 1.0, 100},
    {"mars", 3389500, 10000, 0, 7.088e-5, 0.3, 100},
    {"moon", 1737400, 6000, 0, 2.6617e-6, 0.0, 100},
    {"asteroid", 50000, 4000, 0, 1e-3, 0.0, 10},
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
            return 0;
        }
    return og_error_set(err, "preset: unknown planet '%s' (earth, mars, moon, asteroid)", name);
}
