#include "app/new_planet_dialog.h"

#include "editor/params/planet_presets.h"
#include "editor/params/world_params.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// The presets as the menu names them, in planet_preset_name's order.
static const char *const PRESET_LABELS[] = {"Earth-like", "Mars-like", "Moon", "Small asteroid"};
#define PRESETS ((int)(sizeof PRESET_LABELS / sizeof PRESET_LABELS[0]))

void new_planet_dialog_preset(new_planet_dialog *d, int i) {
    if (i < 0 || i >= PRESETS || (size_t)i >= planet_preset_count()) i = 0;
    world_params p;
    world_params_default(&p, WORLD_PLANET);
    og_error err;
    planet_preset_apply(&p, planet_preset_name((size_t)i), &err);
    d->preset = i;
    snprintf(d->radius_km, sizeof d->radius_km, "%.6g", p.radius / 1000.0);
    snprintf(d->max_height, sizeof d->max_height, "%.6g", p.max_height);
    d->sea = p.ocean_level > 0;
    snprintf(d->sea_level, sizeof d->sea_level, "%.6g", d->sea ? p.ocean_level - p.radius : 0.0);
    snprintf(d->atmosphere, sizeof d->atmosphere, "%.6g", p.atmosphere);
    // A day: one turn at omega (0: the planet does not turn).
    snprintf(d->day_hours, sizeof d->day_hours, "%.6g",
             p.omega > 0 ? 2.0 * M_PI / p.omega / 3600.0 : 0.0);
    snprintf(d->spacing, sizeof d->spacing, "%.6g", p.spacing);
    snprintf(d->seed, sizeof d->seed, "%lld", (long long)p.seed);
    d->error[0] = 0;
}

void new_planet_dialog_show(new_planet_dialog *d) {
    if (!d->radius_km[0]) new_planet_dialog_preset(d, 0);
    d->error[0] = 0;
    d->open = 1;
}

int new_planet_dialog_rows(const new_planet_dialog *d) {
    // preset, 6 fields, the sea's box and its level, the error line, the buttons
    return 9 + (d->sea != 0) + (d->error[0] != 0);
}

// A field's number, or an error naming the field.
static int number(const char *label, const char *text, double *out, char *error, size_t len) {
    char *end;
    *out = strtod(text, &end);
    while (*end == ' ')
        end++;
    if (end == text || *end || !isfinite(*out)) {
        snprintf(error, len, "%s: expected a number, got '%s'", label, text);
        return -1;
    }
    return 0;
}

// The command for the fields, checked as the world's parameters: 0, or -1 with the
// reason in d->error.
static int build_command(new_planet_dialog *d, char *cmd, size_t cmd_len) {
    double radius_km, max_height, sea_level = 0, atmosphere, day_hours, spacing;
    char *e = d->error;
    size_t el = sizeof d->error;
    if (number("Radius", d->radius_km, &radius_km, e, el) ||
        number("Highest relief", d->max_height, &max_height, e, el) ||
        (d->sea && number("Sea level", d->sea_level, &sea_level, e, el)) ||
        number("Atmosphere", d->atmosphere, &atmosphere, e, el) ||
        number("Day", d->day_hours, &day_hours, e, el) ||
        number("Spacing", d->spacing, &spacing, e, el))
        return -1;
    if (day_hours < 0) {
        snprintf(e, el, "Day: hours per turn must be 0 (not turning) or more, got %g", day_hours);
        return -1;
    }
    const double radius = radius_km * 1000.0;
    const double omega = day_hours > 0 ? 2.0 * M_PI / (day_hours * 3600.0) : 0.0;
    const double ocean = d->sea ? radius + sea_level : 0.0;
    char values[7][40];
    snprintf(values[0], sizeof values[0], "%.17g", radius);
    snprintf(values[1], sizeof values[1], "%.17g", max_height);
    snprintf(values[2], sizeof values[2], "%.17g", ocean);
    snprintf(values[3], sizeof values[3], "%.17g", atmosphere);
    snprintf(values[4], sizeof values[4], "%.17g", omega);
    snprintf(values[5], sizeof values[5], "%.17g", spacing);
    snprintf(values[6], sizeof values[6], "%s", d->seed);
    static const char *const keys[7] = {"radius", "max_height", "ocean_level", "atmosphere",
                                        "omega",  "spacing",    "seed"};
    // The same checks the command makes, so a mistake keeps the dialog open.
    world_params p;
    world_params_default(&p, WORLD_PLANET);
    og_error err = {{0}};
    for (int i = 0; i < 7; i++)
        if (world_params_set(&p, keys[i], values[i], &err) != 0) break;
    if (err.msg[0] || world_params_validate(&p, &err) != 0) {
        snprintf(e, el, "%s", err.msg);
        return -1;
    }
    int n = snprintf(cmd, cmd_len, "new planet preset=%s", planet_preset_name((size_t)d->preset));
    for (int i = 0; i < 7 && n > 0 && (size_t)n < cmd_len; i++)
        n += snprintf(cmd + n, cmd_len - (size_t)n, " %s=%s", keys[i], values[i]);
    e[0] = 0;
    return 0;
}

int new_planet_dialog_draw(new_planet_dialog *d, ui_context *ui, ui_rect r, char *cmd,
                           size_t cmd_len) {
    ui_panel_begin(ui, "New planet", r);
    ui_row(ui, 1, NULL, 0);
    int preset = d->preset;
    if (ui_combo(ui, "Preset", &preset, PRESET_LABELS, PRESETS))
        new_planet_dialog_preset(d, preset);
    ui_tooltip(ui, "A body to start from: its values fill the fields below");
    ui_form_field(ui, "Radius (km)", "radius", d->radius_km, sizeof d->radius_km,
                  "From the centre to the datum (Earth 6371, the Moon 1737.4)");
    ui_form_field(ui, "Relief (m)", "relief", d->max_height, sizeof d->max_height,
                  "The highest mountains and deepest basins, metres from the datum");
    ui_row(ui, 1, NULL, 0);
    ui_checkbox(ui, "A sea##sea", &d->sea);
    ui_tooltip(ui, "Water up to the sea level below (saved as its radius, seed 004's way)");
    if (d->sea)
        ui_form_field(ui, "Sea level (m)", "sea_level", d->sea_level, sizeof d->sea_level,
                      "The sea's surface, metres above the datum");
    ui_form_field(ui, "Atmosphere", "atmosphere", d->atmosphere, sizeof d->atmosphere,
                  "Air relative to Earth's: 1 Earth, 0.3 a thin haze, 0 none");
    ui_form_field(ui, "Day (hours)", "day", d->day_hours, sizeof d->day_hours,
                  "Hours per turn (the light's rotation, R in the view); 0: it does not turn");
    ui_form_field(ui, "Spacing (m)", "spacing", d->spacing, sizeof d->spacing,
                  "Metres between samples on the ground (1 m: an Earth of 10 million per face "
                  "side)");
    ui_form_field(ui, "Seed", "seed", d->seed, sizeof d->seed,
                  "Any integer: another seed, other continents");
    if (d->error[0]) {
        ui_row(ui, 1, NULL, 0);
        ui_label_wrapped(ui, d->error, ui_get_theme(ui)->text_error);
    }
    float bottom[2] = {-0.5f, 0};
    ui_row(ui, 2, bottom, 0);
    int go = ui_button(ui, "Create");
    ui_tooltip(ui, "Replace the current world with this planet");
    if (ui_button(ui, "Cancel")) d->open = 0;
    ui_tooltip(ui, "Close without doing anything (Esc)");
    ui_panel_end(ui);
    if (!go || build_command(d, cmd, cmd_len) != 0) return 0;
    d->open = 0;
    return 1;
}
