// Terrain picking on the CPU: where a ray (a pixel under the mouse, a brush) first meets
// the height field, and walk mode's ground following. Heights come through a callback
// so this knows nothing of tiles or caches.
#ifndef OROGEN_RENDERER_PICK_H
#define OROGEN_RENDERER_PICK_H

#include "renderer/camera.h"

// Ground height at world x, z in metres; returns 0 and *h, or -1 when unknown (outside a
// bounded world or not loaded).
typedef int (*pick_height_fn)(void *user, double x, double z, double *h);

// Marches origin + t * dir (dir unit) from t = 0 to max_dist with steps of `step` metres
// growing with distance (step * max(1, t / (256 * step)), so far terrain costs few
// samples), finds the first sign change of (ray.y - height), then bisects to within
// step / 64 metres along the ray. Returns 0 and hit (hit[1] = the height there) or -1 if
// nothing was hit, every sample was unknown or the arguments are unusable (step or
// max_dist not > 0, dir zero). Unknown samples count as "no terrain" (ray above ground,
// as if the height were -infinity): the ray passes through them, and a ray that comes
// out of an unknown region below the known ground hits at that region's edge (the side
// of a bounded world), with hit[1] the ground height on the known side.
int pick_ray(pick_height_fn height, void *user, const double origin[3], const double dir[3],
             double max_dist, double step, double hit[3]);

// Walk mode: puts the eye `eye_height` metres above the ground under c->pos. Returns -1
// (camera unchanged) if the height is unknown there.
int camera_walk(camera *c, pick_height_fn height, void *user, double eye_height);

#endif
