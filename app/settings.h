// The editor's own settings, kept between runs in $XDG_CONFIG_HOME/orogen/settings
// (default ~/.config/orogen/settings) in the parameter-file syntax: window size and
// position, the UI scale, the frame-time goal while moving, recent files, each tool's
// settings, and Kahoun
// 2010's configuration keys (width, height, field_of_view, enable_fullscreen,
// enable_dynamic_LOD and, for its thresholds, lod_pixels). The
// console's history is kept beside it in console_history, one command a line.
// A broken file gives warnings naming its lines and the defaults, never a failure.
#ifndef OROGEN_APP_SETTINGS_H
#define OROGEN_APP_SETTINGS_H

#include "io/err.h"

#include <stddef.h>

#define SETTINGS_RECENT 8
#define SETTINGS_TOOLS 16
#define SETTINGS_CAMERAS 8

// Where the camera was when a world was last left (closed, replaced, the editor quit):
// X Y Z YAW PITCH, for the world at path (absolute). world_camera_N in the file.
typedef struct app_world_camera {
    char path[1024];
    double pose[5];
} app_world_camera;

typedef struct app_settings {
    int width, height;      // window size (1280 x 800)
    int x, y, has_position; // window position, when known
    int maximized, fullscreen;
    double ui_scale;        // the user's UI scale, times the monitor's (1)
    double field_of_view;   // degrees (60)
    double frame_target_ms; // dynamic resolution's goal while moving (50)
    double fly_speed;       // the camera's flying speed, m/s (50)
    // Kahoun 2010's level-of-detail keys, in this program's terms: enable_dynamic_LOD
    // (1) lowers the viewport's resolution while moving to hold frame_target_ms;
    // lod_pixels (6, 1 .. 64) is the planet's split threshold, the pixels a sample may
    // cover before its chunk splits (seed 004's default_threshold).
    int dynamic_lod;
    double lod_pixels;
    char recent[SETTINGS_RECENT][1024];
    int recent_count;
    // Each tool's settings as last used, "NAME key=value ..." (tool_NAME in the file),
    // and the tool in use (tool); see tool_settings.h.
    char tools[SETTINGS_TOOLS][768];
    int tool_count;
    char tool[32];
    app_world_camera cameras[SETTINGS_CAMERAS]; // most recently left first
    int camera_count;
} app_settings;

void app_settings_default(app_settings *s);
// The settings folder's file (or "" when neither XDG_CONFIG_HOME nor HOME is set).
void app_settings_path(char *buf, size_t size, const char *file);
// Reads path; a missing file keeps the defaults silently, bad lines are reported to
// stderr as path:line warnings and keep their defaults.
void app_settings_load(app_settings *s, const char *path);
// Creates every folder of path's parent (the settings folder on a first run).
int app_settings_make_folders(const char *path);
// Writes path atomically, creating its folder.
int app_settings_save(const app_settings *s, const char *path, og_error *err);
// Fits the window to the screen's work area (x, y, width, height): the default 1280 x 800
// window, or one kept from a larger screen, would reach past a small screen's edges,
// hiding the panels and the status line; such a window is made to fit, placed at the
// area's corner and maximised (so a window manager adds its frame inside the area). A
// kept position that would put part of the window off the area is forgotten. An empty
// area changes nothing.
void app_settings_fit_to_screen(app_settings *s, int ax, int ay, int aw, int ah);
// Puts path first in the recent files (once), made absolute.
void app_settings_add_recent(app_settings *s, const char *path);
// path as an absolute path (the file resolved when it exists, else joined to the
// working directory), so a recent file opens from wherever the editor starts next.
void app_absolute_path(const char *path, char *out, size_t size);
// Keeps pose as the camera of the world at path (made absolute), first.
void app_settings_put_camera(app_settings *s, const char *path, const double pose[5]);
// The camera kept for the world at path: 0 and pose, or -1 when none is.
int app_settings_find_camera(const app_settings *s, const char *path, double pose[5]);

#endif
