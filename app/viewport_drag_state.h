// The state of the viewport's mouse interaction (app/viewport_drag.c): a small state
// machine of drags (none, sculpt, orbit, brush resize), mouse look, and the camera mode
// the right button follows. Only viewport_drag.c touches it; the window's other parts
// ask through its functions (window_internal.h).
#ifndef OROGEN_APP_VIEWPORT_DRAG_STATE_H
#define OROGEN_APP_VIEWPORT_DRAG_STATE_H

#include "app/sculpt_drag.h"

// Left: sculpt; middle or Alt+left: orbit; Alt+right: resize the brush on screen.
typedef enum drag_kind { DRAG_NONE, DRAG_SCULPT, DRAG_ORBIT, DRAG_RESIZE } drag_kind;

typedef struct viewport_drag_state {
    drag_kind kind;  // left or middle button
    int looking;     // right button held: mouse look, WASD, wheel sets the speed
    int orbit_mode;  // the orbit camera (C): the right button orbits the view's centre
    double pivot[3]; // orbit pivot of the current drag
    // Alt+right drag: right/left sizes the brush, up/down its strength; the cursor stays
    // where the drag began and one `tool` command applies the result on release.
    double resize_x0, resize_y0, resize_r0, resize_s0, resize_radius, resize_strength;
    double resize_at[3];
    sculpt_drag sculpt; // the left button's sculpting drag
} viewport_drag_state;

#endif
