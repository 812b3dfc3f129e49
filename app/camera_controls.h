// The viewport's navigation: what mouse drags, the wheel and held keys do to the camera
// (renderer/camera.h). Pure functions of input deltas (pixels, wheel notches, seconds)
// and a ground-height callback, so the mapping is unit-tested without a window; the
// window only turns GLFW events into these calls.
#ifndef OROGEN_APP_CAMERA_CONTROLS_H
#define OROGEN_APP_CAMERA_CONTROLS_H

#include "renderer/camera.h"
#include "renderer/pick.h"

typedef struct camera_controls {
    double fly_speed;        // m/s while flying (50)
    double walk_speed;       // m/s while walking (6)
    double fast_factor;      // Shift multiplies the speed (4)
    double speed_per_notch;  // wheel with the right button held: speed factor (1.25)
    double look_deg_per_px;  // mouse look (0.2)
    double orbit_deg_per_px; // orbit drag (0.3)
    double dolly_per_notch;  // wheel: distance to the point under the cursor x this (0.8)
    double eye_height;       // walk mode: metres above the ground (1.8)
    int walk;                // walk mode: the eye follows the ground
    // Planets: the radius (0 on flat worlds) and the ground's height above the datum
    // below a position (planet coordinates; 0 and *h, or -1). On a planet the camera
    // orbits its centre, flies at a speed that grows with the altitude, dollies by
    // altitude and walks with "up" on the local vertical.
    double planet_radius;
    int (*planet_ground)(void *user, const double pos[3], double *h);
    void *planet_user;
} camera_controls;

// Movement keys: how many seconds each was held since the last step (the window
// measures press and release times, so a slow frame loses no movement), and Shift.
typedef struct move_keys {
    double forward, back, left, right, up, down;
    int fast;
} move_keys;

void camera_controls_init(camera_controls *cc);

// The speed WASD moves at now (walk or fly speed, without Shift).
double camera_controls_speed(const camera_controls *cc);

// Mouse look (right button held): dx, dy in pixels, right and down positive.
// Moving the mouse right turns right, moving it down looks down.
void camera_controls_look(const camera_controls *cc, camera *c, double dx, double dy);

// Orbit drag around pivot: dragging right turns the terrain with the mouse (the camera
// goes left around the pivot), dragging up takes the camera up over the pivot.
void camera_controls_orbit(const camera_controls *cc, camera *c, const double pivot[3], double dx,
                           double dy);

// Moves for held keys. Flying: along the view (forward/back), sideways, and world
// up/down. Walking: horizontally along the view's heading, then the eye is put
// eye_height above the ground; a step onto ground of unknown height is not taken.
// Walking also re-seats the eye when no key is held (the ground may have changed).
// Returns 1 if the camera moved.
int camera_controls_move(const camera_controls *cc, camera *c, const move_keys *keys,
                         pick_height_fn height, void *user);

// Wheel with the right button held: the current mode's speed x speed_per_notch^notches
// (kept within 0.01 .. 100000 m/s).
void camera_controls_speed_wheel(camera_controls *cc, double notches);

// Wheel: notches > 0 (away from the user) move toward pivot, the distance times
// dolly_per_notch^notches.
void camera_controls_dolly(const camera_controls *cc, camera *c, const double pivot[3],
                           double notches);

// Focus on a point: the view keeps its direction and backs off 3 brush radii (at least
// 10 m) from point. Leaves walk mode.
void camera_controls_focus(camera_controls *cc, camera *c, const double point[3],
                           double brush_radius);

// Toggles walk mode; switching it on seats the eye on the ground at once when the
// height there is known. Returns the new mode (1 walking).
int camera_controls_toggle_walk(camera_controls *cc, camera *c, pick_height_fn height, void *user);

#endif
