// Ray marching against a height callback for picking, and walk mode's ground clamp.
// Everything is double so a camera 10,000 km from the origin picks as well as at it.
#include "renderer/pick.h"

#include <math.h>

// Height difference (ray above ground > 0) at t; returns 0 if the height is unknown.
static int sample(pick_height_fn height, void *user, const double o[3], const double d[3], double t,
                  double *diff, double *h) {
    double x = o[0] + t * d[0], z = o[2] + t * d[2];
    if (height(user, x, z, h) != 0 || !isfinite(*h)) return 0;
    *diff = o[1] + t * d[1] - *h;
    return 1;
}

int pick_ray(pick_height_fn height, void *user, const double origin[3], const double dir[3],
             double max_dist, double step, double hit[3]) {
    if (!height || !(step > 0) || !(max_dist > 0) || !isfinite(step) || !isfinite(max_dist))
        return -1;
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(len > 0) || !isfinite(len)) return -1;
    const double d[3] = {dir[0] / len, dir[1] / len, dir[2] / len};

    double t0 = 0, diff0 = 0, h;
    int known0 = sample(height, user, origin, d, 0, &diff0, &h);
    for (;;) {
        if (t0 >= max_dist) return -1;
        double dt = step * fmax(1.0, t0 / (256.0 * step));
        double t1 = fmin(t0 + dt, max_dist), diff1 = 0;
        int known1 = sample(height, user, origin, d, t1, &diff1, &h);
        // Unknown samples are "no terrain": above ground, as if the height were -infinity.
        int below0 = known0 && !(diff0 > 0), below1 = known1 && !(diff1 > 0);
        if (below0 != below1) {
            // Bisect [t0, t1] keeping the sign change inside.
            int lo_known = known0;
            double lo = t0, hi = t1;
            for (int i = 0; i < 200 && hi - lo > step / 128.0; i++) {
                double mid = 0.5 * (lo + hi), dm = 1.0;
                int known = sample(height, user, origin, d, mid, &dm, &h);
                int below = known && !(dm > 0);
                if (below == below0) {
                    lo = mid;
                    lo_known = known;
                } else {
                    hi = mid;
                }
            }
            // The midpoint is within step / 128 of the crossing; if its height is unknown
            // (the ray came out of an unknown region below the ground, or a hole) use the
            // end that is known (the one below ground always is; lo may be either).
            double t = 0.5 * (lo + hi);
            if (height(user, origin[0] + t * d[0], origin[2] + t * d[2], &h) != 0 || !isfinite(h)) {
                t = lo_known ? lo : hi;
                if (height(user, origin[0] + t * d[0], origin[2] + t * d[2], &h) != 0) return -1;
            }
            hit[0] = origin[0] + t * d[0];
            hit[1] = h;
            hit[2] = origin[2] + t * d[2];
            return 0;
        }
        t0 = t1;
        diff0 = diff1;
        known0 = known1;
    }
}

int camera_walk(camera *c, pick_height_fn height, void *user, double eye_height) {
    double h;
    if (!height || height(user, c->pos[0], c->pos[2], &h) != 0 || !isfinite(h)) return -1;
    c->pos[1] = h + eye_height;
    return 0;
}
