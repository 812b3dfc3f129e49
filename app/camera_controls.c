#include "app/camera_controls.h"

#include <math.h>

static const double DEG = 3.14159265358979323846 / 180.0;

void camera_controls_init(camera_controls *cc) {
    *cc = (camera_controls){
        .fly_speed = 50,
        .walk_speed = 6,
        .fast_factor = 4,
        .speed_per_notch = 1.25,
        .look_deg_per_px = 0.2,
        .orbit_deg_per_px = 0.3,
        .dolly_per_notch = 0.8,
        .eye_height = 1.8,
    };
}

double camera_controls_speed(const camera_controls *cc) {
    return cc->walk ? cc->walk_speed : cc->fly_speed;
}

void camera_controls_look(const camera_controls *cc, camera *c, double dx, double dy) {
    camera_look(c, dx * cc->look_deg_per_px, -dy * cc->look_deg_per_px);
}

void camera_controls_orbit(const camera_controls *cc, camera *c, const double pivot[3], double dx,
                           double dy) {
    // camera_orbit turns the view: a view turned down (negative dpitch) sees the pivot
    // from above, and dy < 0 is a drag up.
    camera_orbit(c, pivot, dx * cc->orbit_deg_per_px, dy * cc->orbit_deg_per_px);
}

int camera_controls_move(const camera_controls *cc, camera *c, const move_keys *k,
                         pick_height_fn height, void *user) {
    double speed = camera_controls_speed(cc) * (k->fast ? cc->fast_factor : 1.0);
    // Metres along each axis: opposite keys cancel for the time both were held.
    double fwd = speed * (k->forward - k->back), side = speed * (k->right - k->left);
    double up = speed * (k->up - k->down);
    if (!isfinite(fwd) || !isfinite(side) || !isfinite(up)) return 0;
    double before[3] = {c->pos[0], c->pos[1], c->pos[2]};
    if (!cc->walk) {
        if (fwd == 0 && side == 0 && up == 0) return 0;
        camera_move_local(c, fwd, side, up);
        return 1;
    }
    // Walking: along the heading only, so looking down does not slow the walk, and a
    // diagonal is no faster than the longest-held key alone.
    double len = sqrt(fwd * fwd + side * side);
    double longest = speed * fmax(fmax(k->forward, k->back), fmax(k->left, k->right));
    if (len > longest && len > 0) fwd *= longest / len, side *= longest / len;
    double yaw = c->yaw * DEG;
    c->pos[0] += sin(yaw) * fwd + cos(yaw) * side;
    c->pos[2] += -cos(yaw) * fwd + sin(yaw) * side;
    if (camera_walk(c, height, user, cc->eye_height) != 0) {
        c->pos[0] = before[0], c->pos[2] = before[2]; // unknown ground: stay
        if (camera_walk(c, height, user, cc->eye_height) != 0) c->pos[1] = before[1];
    }
    return c->pos[0] != before[0] || c->pos[1] != before[1] || c->pos[2] != before[2];
}

void camera_controls_speed_wheel(camera_controls *cc, double notches) {
    double *speed = cc->walk ? &cc->walk_speed : &cc->fly_speed;
    double s = *speed * pow(cc->speed_per_notch, notches);
    if (!isfinite(s)) return;
    *speed = fmin(fmax(s, 0.01), 100000.0);
}

void camera_controls_dolly(const camera_controls *cc, camera *c, const double pivot[3],
                           double notches) {
    camera_dolly(c, pivot, pow(cc->dolly_per_notch, notches));
}

void camera_controls_focus(camera_controls *cc, camera *c, const double point[3],
                           double brush_radius) {
    cc->walk = 0;
    camera_focus(c, point, fmax(3.0 * brush_radius, 10.0));
}

int camera_controls_toggle_walk(camera_controls *cc, camera *c, pick_height_fn height, void *user) {
    cc->walk = !cc->walk;
    if (cc->walk) camera_walk(c, height, user, cc->eye_height);
    return cc->walk;
}
