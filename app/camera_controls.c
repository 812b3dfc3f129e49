#include "app/camera_controls.h"

#include "renderer/planet_camera.h"

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

static double length3(const double v[3]) {
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

// Planets: the altitude above the ground below (the datum when it is unknown).
static double planet_altitude(const camera_controls *cc, const camera *c) {
    double ground = 0;
    if (cc->planet_ground && cc->planet_ground(cc->planet_user, c->pos, &ground) != 0) ground = 0;
    return length3(c->pos) - cc->planet_radius - ground;
}

// Puts the camera at distance r from the centre along its direction.
static void planet_set_distance(camera *c, double r) {
    double d = length3(c->pos);
    if (d > 0)
        for (int k = 0; k < 3; k++)
            c->pos[k] *= r / d;
}

// Keeps the eye eye_height over the ground (walking) or at least 0.5 m over it.
static void planet_keep_above(const camera_controls *cc, camera *c, double least) {
    double ground;
    if (!cc->planet_ground || cc->planet_ground(cc->planet_user, c->pos, &ground) != 0) return;
    double r = length3(c->pos), floor_r = cc->planet_radius + ground + least;
    if (cc->walk || r < floor_r) planet_set_distance(c, floor_r);
}

void camera_controls_orbit(const camera_controls *cc, camera *c, const double pivot[3], double dx,
                           double dy) {
    if (cc->planet_radius > 0) { // around the centre: the drag turns the globe
        double lat, lon, r = length3(c->pos);
        planet_lat_lon(c->pos, &lat, &lon);
        double alt = fmax(r - cc->planet_radius, 1.0);
        double k = cc->orbit_deg_per_px * fmin(1.0, alt / cc->planet_radius);
        lat = fmin(fmax(lat + dy * k, -89.9), 89.9);
        planet_position(lat, lon - dx * k, r, c->pos);
        return;
    }
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
    if (cc->planet_radius > 0) {
        if (fwd == 0 && side == 0 && up == 0) return 0;
        // Faster the higher: half the altitude a second at the default speed.
        double scale = fmax(1.0, planet_altitude(cc, c) / 100.0);
        double f[3], r[3], u[3], e[3], n[3], vertical[3];
        planet_camera_basis(c, f, r, u);
        planet_local_frame(c->pos, e, n, vertical);
        if (cc->walk) { // along the heading on the local level, then back onto the ground
            double d = f[0] * vertical[0] + f[1] * vertical[1] + f[2] * vertical[2];
            for (int k = 0; k < 3; k++)
                f[k] -= d * vertical[k];
            double len = length3(f);
            if (len > 0)
                for (int k = 0; k < 3; k++)
                    f[k] /= len;
            scale = 1.0, up = 0;
        }
        for (int k = 0; k < 3; k++)
            c->pos[k] += scale * (fwd * f[k] + side * r[k] + up * vertical[k]);
        planet_keep_above(cc, c, cc->walk ? cc->eye_height : 0.5);
        return 1;
    }
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
    if (cc->planet_radius > 0) { // toward the ground below, by the altitude
        double alt = fmax(planet_altitude(cc, c), 0.5);
        planet_set_distance(c, length3(c->pos) - alt + alt * pow(cc->dolly_per_notch, notches));
        planet_keep_above(cc, c, 0.5);
        return;
    }
    camera_dolly(c, pivot, pow(cc->dolly_per_notch, notches));
}

void camera_controls_focus(camera_controls *cc, camera *c, const double point[3],
                           double brush_radius) {
    cc->walk = 0;
    camera_focus(c, point, fmax(3.0 * brush_radius, 10.0));
}

int camera_controls_toggle_walk(camera_controls *cc, camera *c, pick_height_fn height, void *user) {
    cc->walk = !cc->walk;
    if (cc->planet_radius > 0) {
        if (cc->walk) planet_keep_above(cc, c, cc->eye_height);
        return cc->walk;
    }
    if (cc->walk) camera_walk(c, height, user, cc->eye_height);
    return cc->walk;
}
