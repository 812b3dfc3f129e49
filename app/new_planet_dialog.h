// File > New planet...: a preset (Earth-like, Mars-like, moon, small asteroid) fills the
// fields, which the user may change before the planet is made: its radius, the highest
// relief, the sea (none, or its level above the datum), the air, the length of a day,
// the spacing of the samples and the seed. The dialog only builds the `new planet`
// command (every field as a world parameter); the editor runs it.
#ifndef OROGEN_APP_NEW_PLANET_DIALOG_H
#define OROGEN_APP_NEW_PLANET_DIALOG_H

#include "ui/ui.h"

#include <stddef.h>

typedef struct new_planet_dialog {
    int open;
    int preset; // index of planet_preset_name
    char radius_km[32], max_height[32], sea_level[32], atmosphere[32], day_hours[32], spacing[32],
        seed[32];
    int sea;          // a sea at sea_level metres above the datum
    char error[1024]; // why Create did nothing ("" when fine)
} new_planet_dialog;

// Opens it with the last preset's values (Earth-like the first time).
void new_planet_dialog_show(new_planet_dialog *d);
// Sets the fields from preset i.
void new_planet_dialog_preset(new_planet_dialog *d, int i);
// The rows of widgets it shows (to size its rectangle).
int new_planet_dialog_rows(const new_planet_dialog *d);
// Draws it over r; returns 1 when the user pressed Create with valid fields, with the
// command in cmd (the dialog closes). Bad fields keep it open with the reason shown.
int new_planet_dialog_draw(new_planet_dialog *d, ui_context *ui, ui_rect r, char *cmd,
                           size_t cmd_len);

#endif
