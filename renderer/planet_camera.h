// The camera on a planet: the same camera struct (position in metres from the planet's
// centre, yaw/pitch, fov, near), but yaw and pitch turn in the local frame where the
// camera stands: up is away from the centre, yaw 0 looks north (toward the +Y pole),
// 90 east; pitch > 0 looks up. So walking, flying and orbiting keep "up" on the local
// vertical. Latitude and longitude: latitude from the equator toward +Y, longitude 0
// on +Z growing toward +X (east).
#ifndef OROGEN_RENDERER_PLANET_CAMERA_H
#define OROGEN_RENDERER_PLANET_CAMERA_H

#include "editor/world/world.h"
#include "io/err.h"
#include "renderer/camera.h"

// East, north and up unit vectors at position pos (any length > 0; at the poles north
// is taken toward -Z so the frame stays defined).
void planet_local_frame(const double pos[3], double east[3], double north[3], double up[3]);

// The camera's unit basis in planet coordinates.
void planet_camera_basis(const camera *c, double forward[3], double right[3], double up[3]);

// Rotation-only view and the reversed-Z projection times it (camera_projection_matrix).
void planet_camera_view_projection(const camera *c, double aspect, float m[16]);

// Pixel ray (sx, sy in [0, 1] from the top-left), unit, planet coordinates.
void planet_camera_ray(const camera *c, double aspect, double sx, double sy, double dir[3]);

// Position at latitude, longitude (degrees) and distance from the centre.
void planet_position(double lat, double lon, double distance, double pos[3]);
// Latitude and longitude (degrees) of a position.
void planet_lat_lon(const double pos[3], double *lat, double *lon);

// The ground's height above the datum straight below pos (metres) as the viewport draws
// it: the finest level's triangles, whose corners are bilinear between the face's
// samples.
int planet_ground_height(world *w, const double pos[3], double *height, og_error *err);
// The surface a person stands or floats on there: the ground, or the sea's surface where
// the ground lies under it (what the viewport draws, and where `ground` puts a camera).
int planet_surface_height(world *w, const double pos[3], double *height, og_error *err);

#endif
