#include "renderer/render_settings.h"

#include <string.h>

static const char *const view_names[VIEW_MODE_COUNT] = {"shaded", "wireframe", "levels", "height",
                                                        "slope"};

const char *view_mode_name(view_mode m) {
    return m >= 0 && m < VIEW_MODE_COUNT ? view_names[m] : "?";
}

int view_mode_parse(const char *text) {
    for (int i = 0; i < VIEW_MODE_COUNT; i++)
        if (strcmp(text, view_names[i]) == 0) return i;
    return -1;
}

void render_settings_default(render_settings *s) {
    *s = (render_settings){.levels = 8,
                           .parallax = 1,
                           .parallax_steps = 8,
                           .detail_distance = 150.0,
                           .view = VIEW_SHADED,
                           .sun_yaw = 135.0,
                           .sun_pitch = 35.0,
                           .fog_density = 0.0,
                           .culling = 1,
                           .morph = 1,
                           .auto_materials = 1,
                           .antialias = 1,
                           .lod_pixels = 6};
}

int render_settings_smooth_edges(const render_settings *s) {
    return s->antialias && s->view == VIEW_SHADED;
}
