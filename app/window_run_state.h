// The state of the window's life and loop (app/window.c): the session's text, the
// console on standard input, the turning light's clock, the close button pressed
// during long work, the window's pixel scale. Only window.c touches it; the window's
// other parts ask through its functions (window_internal.h).
#ifndef OROGEN_APP_WINDOW_RUN_STATE_H
#define OROGEN_APP_WINDOW_RUN_STATE_H

#include "editor/world/world_events.h"

#include <stddef.h>

typedef struct window_run_state {
    char *session_text; // the session's commands (`history script`): ctx->session's text
    size_t session_len;
    char stdin_buf[8192];
    size_t stdin_len;
    int stdin_open;
    double sun_turned_at;        // when the rotating light last turned (seconds)
    int close_after_work;        // the close button was pressed while work ran
    double px_scale;             // framebuffer pixels per window unit (HiDPI)
    world_subscription *changes; // the world's change notifications (another world: new camera)
    char cam_path[1024]; // the file of the world the camera looks at ("" unsaved): its camera
                         // is kept in the settings when the world is left
    char settings_path[4096];
} window_run_state;

#endif
