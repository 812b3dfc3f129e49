// The state of the window's frame (app/window_frame.c): the terrain image and what it
// shows, its resolution while moving (dynamic resolution), the edge smoothing of still
// frames, and whether tiles are still arriving. Only window_frame.c touches it; the
// window's other parts ask through its functions (window_internal.h).
#ifndef OROGEN_APP_WINDOW_FRAME_STATE_H
#define OROGEN_APP_WINDOW_FRAME_STATE_H

#include "renderer/gl_target.h"
#include "renderer/viewport.h"

typedef struct window_frame_state {
    // The terrain image, reused while only the UI changes; rendered at a lower
    // resolution while the camera moves or a stroke is drawn (dynamic resolution).
    gl_target terrain;
    gl_target terrain_smooth; // the terrain image with its edges smoothed (full-size frames)
    int smooth_shown;         // compose shows terrain_smooth
    int smooth_owed;          // the image wants smoothing once the view is still
    int smooth_failed;        // the pass failed once (reported): not tried again
    int terrain_valid;
    float res_scale;
    double terrain_ms; // wall time of the last terrain frame
    double target_ms;  // frame-time goal while moving
    camera drawn_cam;  // what the terrain image shows
    render_settings drawn_settings;
    brush_cursor drawn_cursor;
    float drawn_scale;
    int drawn_w, drawn_h;
    int world_changed;    // change notifications since the terrain image
    int settled;          // frames in a row with every level current
    int pending;          // levels (or layers) still waiting for tiles
    int render_failed;    // the renderer refused this world (a planet): said once
    char title[512];      // the window's title as last set
    double busy_drawn_ms; // when the progress of long work was last drawn
    int dynamic_res;      // lower the resolution while moving (L, dynamic_resolution)
} window_frame_state;

#endif
