#include "renderer/ground_horizon.h"

#include <math.h>

enum { BINS = GROUND_HORIZON_BINS, BANDS = GROUND_HORIZON_BANDS, BANDS_PER_OCTAVE = 8 };

static double dot(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void ground_horizon_begin(ground_horizon *h, const double eye[3]) {
    h->eye_r = sqrt(dot(eye, eye));
    for (int k = 0; k < 3; k++)
        h->eye[k] = eye[k], h->up[k] = h->eye_r > 0 ? eye[k] / h->eye_r : k == 1;
    // Any east and north around up.
    const double ref[3] = {fabs(h->up[1]) < 0.9 ? 0 : 1, fabs(h->up[1]) < 0.9 ? 1 : 0, 0};
    h->east[0] = ref[1] * h->up[2] - ref[2] * h->up[1];
    h->east[1] = ref[2] * h->up[0] - ref[0] * h->up[2];
    h->east[2] = ref[0] * h->up[1] - ref[1] * h->up[0];
    const double e = sqrt(dot(h->east, h->east));
    for (int k = 0; k < 3; k++)
        h->east[k] /= e;
    h->north[0] = h->up[1] * h->east[2] - h->up[2] * h->east[1];
    h->north[1] = h->up[2] * h->east[0] - h->up[0] * h->east[2];
    h->north[2] = h->up[0] * h->east[1] - h->up[1] * h->east[0];
    h->frame++;
}

// A monotone stand-in for the angle of (x, y) in [0, 4): a quarter turn is 1.
static double pseudo_angle(double x, double y) {
    const double s = fabs(x) + fabs(y);
    if (!(s > 0)) return 0;
    if (y >= 0) return x >= 0 ? y / s : 1.0 - x / s;
    return x < 0 ? 2.0 - y / s : 3.0 + x / s;
}

// A patch as the camera's vertical sees it: its azimuths [a0, a1] (pseudo-angles, a1 -
// a0 < 2, a0 in [-2, 4)) and the tangents of its angles from the vertical [near, far].
// In the gnomonic projection onto the plane tangent at the vertical, great circles are
// straight lines and azimuths and the order of angles are kept: the patch is a convex
// quadrilateral there, its azimuths spanned by its corners, its nearest point the
// quadrilateral's nearest to the origin, its farthest a corner (and the distance from
// the origin is the angle's tangent). 0 when it cannot be judged.
typedef struct patch_view {
    double a0, a1, near, far;
} patch_view;

static int view_patch(const ground_horizon *h, const double (*dir)[3], patch_view *v) {
    static const int ring[4] = {0, 1, 3, 2}; // the grid's corners around the quadrilateral
    double g[4][2], far2 = 0, cx = 0, cy = 0;
    for (int k = 0; k < 4; k++) {
        const double *d = dir[ring[k]];
        const double z = dot(d, h->up);
        if (!(z > 1e-3)) return 0; // a right angle away, or beyond
        g[k][0] = dot(d, h->east) / z, g[k][1] = dot(d, h->north) / z;
        far2 = fmax(far2, g[k][0] * g[k][0] + g[k][1] * g[k][1]);
        cx += g[k][0], cy += g[k][1];
    }
    // The nearest point: none inside (the origin on the inner side of every edge), else
    // the nearest of the edges'.
    double turn = 0, near2 = INFINITY;
    for (int k = 0; k < 4; k++)
        turn += g[k][0] * g[(k + 1) & 3][1] - g[k][1] * g[(k + 1) & 3][0];
    int inside = 1;
    for (int k = 0; k < 4; k++) {
        const double *a = g[k], *b = g[(k + 1) & 3];
        const double ex = b[0] - a[0], ey = b[1] - a[1];
        if ((ey * a[0] - ex * a[1]) * turn <= 0) inside = 0; // origin not left of a -> b
        const double len2 = ex * ex + ey * ey;
        double t = len2 > 0 ? -(a[0] * ex + a[1] * ey) / len2 : 0;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        const double px = a[0] + t * ex, py = a[1] + t * ey;
        near2 = fmin(near2, px * px + py * py);
    }
    if (inside || !(near2 > 0)) return 0;
    v->near = sqrt(near2), v->far = sqrt(far2);
    const double mid = pseudo_angle(cx, cy);
    double lo = 0, hi = 0;
    for (int k = 0; k < 4; k++) {
        double d = pseudo_angle(g[k][0], g[k][1]) - mid;
        d -= 4.0 * floor((d + 2.0) / 4.0); // into [-2, 2)
        lo = fmin(lo, d), hi = fmax(hi, d);
    }
    v->a0 = mid + lo, v->a1 = mid + hi;
    return v->a1 - v->a0 < 2.0;
}

// The tangent of the elevation of a point at radius r whose angle from the camera's
// vertical has tangent t: (r cos - eye_r) / (r sin), the difference of radii first (the
// camera is metres above points millions of metres out).
static double slope(const ground_horizon *h, double r, double t) {
    const double root = sqrt(1.0 + t * t);
    return ((r - h->eye_r) - h->eye_r * t * t / (root + 1.0)) / (r * t);
}

static double bin_position(double a) {
    return (a / 4.0 + 1.0) * BINS; // a from -4 on: never negative
}

// The first band whose upper edge, a tangent of 2^(k / 8 - 28), is at least t.
static int band_of(double t) {
    const double k = ceil((log2(fmax(t, 1e-30)) + 28.0) * BANDS_PER_OCTAVE);
    return k < 0 ? 0 : k >= BANDS ? BANDS - 1 : (int)k;
}

static float *tree_of(ground_horizon *h, int bin) {
    float *tree = h->promised[bin];
    if (h->touched[bin] != h->frame) { // first use this frame: empty
        for (int i = 0; i <= BANDS; i++)
            tree[i] = -INFINITY;
        h->touched[bin] = h->frame;
    }
    return tree;
}

void ground_horizon_add_floor(ground_horizon *h, const double (*dir)[3], double floor_r) {
    patch_view v;
    if (!view_patch(h, dir, &v)) return;
    // In each half-plane through the patch, a stretch of the floor between the angles
    // near and far; the elevation along it is lowest at one end (it rises to the
    // horizon's tangent point, then falls).
    const double promise = fmin(slope(h, floor_r, v.near), slope(h, floor_r, v.far));
    float kept = (float)promise; // rounded down, never promising more
    if (kept > promise) kept = nextafterf(kept, -INFINITY);
    const int band = band_of(v.far);
    // The bins wholly inside the patch's azimuths.
    const long first = (long)ceil(bin_position(v.a0)), end = (long)floor(bin_position(v.a1));
    for (long i = first; i < end; i++) {
        float *tree = tree_of(h, (int)(i % BINS));
        for (int k = band + 1; k <= BANDS; k += k & -k)
            if (tree[k] < kept) tree[k] = kept;
    }
}

int ground_horizon_hidden(const ground_horizon *h, const double (*dir)[3], double top_r) {
    patch_view v;
    if (!view_patch(h, dir, &v)) return 0;
    // The highest it can be seen: at radius top_r, at the angle nearest the tangent
    // point from the camera to that sphere (at the nearest angle when above the camera).
    const double tangent =
        top_r < h->eye_r ? sqrt((h->eye_r - top_r) * (h->eye_r + top_r)) / top_r : 0.0;
    const double highest = slope(h, top_r, fmin(fmax(tangent, v.near), v.far));
    const int band = band_of(v.near) - 1; // the bands wholly short of its nearest point
    if (band < 0) return 0;
    const long first = (long)floor(bin_position(v.a0)), last = (long)floor(bin_position(v.a1));
    for (long i = first; i <= last; i++) {
        const int bin = (int)(i % BINS);
        if (h->touched[bin] != h->frame) return 0;
        float best = -INFINITY;
        for (int k = band + 1; k > 0; k -= k & -k)
            if (h->promised[bin][k] > best) best = h->promised[bin][k];
        if (!(best > highest + 1e-9 * (1.0 + fabs(highest)))) return 0;
    }
    return 1;
}
