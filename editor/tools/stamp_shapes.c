// Radial profiles are cubic Hermite splines through hand-placed knots (value and
// slope), so C1 holds by construction and slope 0 at r = 1 gives the seamless edge.
#include "editor/tools/stamp_shapes.h"

#include <math.h>
#include <string.h>

static const char *const NAMES[STAMP_SHAPE_COUNT] = {"gaussian", "crater", "cone",
                                                     "volcano",  "mesa",   "ridge"};

const char *stamp_shape_name(stamp_shape s) {
    return (unsigned)s < STAMP_SHAPE_COUNT ? NAMES[s] : NULL;
}

int stamp_shape_from_name(const char *name) {
    if (!name) return -1;
    for (int i = 0; i < STAMP_SHAPE_COUNT; i++)
        if (strcmp(name, NAMES[i]) == 0) return i;
    return -1;
}

typedef struct knot {
    float r, h, slope;
} knot;

// Knots ascend in r from 0 to 1; r must lie in [0, 1).
static float hermite(const knot *k, int n, float r) {
    int i = 0;
    while (i < n - 2 && r >= k[i + 1].r)
        i++;
    float dr = k[i + 1].r - k[i].r, t = (r - k[i].r) / dr;
    float t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * k[i].h + (t3 - 2 * t2 + t) * dr * k[i].slope +
           (3 * t2 - 2 * t3) * k[i + 1].h + (t3 - t2) * dr * k[i + 1].slope;
}

// Real craters: floor below the surroundings, a rim raised a fraction of the
// depth, and an ejecta blanket thinning outwards.
static const knot CRATER[] = {
    {0.0f, -0.7f, 0.0f},  {0.4f, -0.35f, 1.9f}, {0.65f, 0.3f, 0.0f},
    {0.78f, 0.1f, -0.8f}, {1.0f, 0.0f, 0.0f},
};
// A stratovolcano: steep caldera wall, then flanks that flatten towards the foot.
static const knot VOLCANO[] = {
    {0.0f, 0.6f, 0.0f},   {0.16f, 1.0f, 0.0f}, {0.3f, 0.82f, -1.6f},
    {0.6f, 0.32f, -1.3f}, {1.0f, 0.0f, 0.0f},
};

// A cone of height 1 with straight flanks, a parabolic tip of radius tip and a
// parabolic foot of width foot matching the flank's slope: C1, value and slope 0 at x = 1.
static float cone_profile(float x, float tip, float foot) {
    float m = 1.0f / (1.0f - 0.5f * (tip + foot));
    if (x < tip) return 1.0f - m * x * x / (2.0f * tip);
    if (x < 1.0f - foot) return 1.0f - m * (0.5f * tip + (x - tip));
    if (x < 1.0f) return m * (1.0f - x) * (1.0f - x) / (2.0f * foot);
    return 0.0f;
}

static float smoothstep(float e0, float e1, float x) {
    float t = (x - e0) / (e1 - e0);
    t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
    return t * t * (3.0f - 2.0f * t);
}

// exp(-k s) minus its first-order Taylor expansion at s = 1 (s = r^2), scaled to 1
// at the centre: Crause 2010's Gaussian with value and slope 0 at the footprint edge.
static float gaussian(float s) {
    const float k = 4.0f, e = expf(-k);
    float g = (expf(-k * s) - e * (1.0f + k * (1.0f - s))) / (1.0f - e * (1.0f + k));
    return g > 0.0f ? g : 0.0f; // exact arithmetic never dips below 0; rounding might
}

static float ridge(float u, float v) {
    float au = fabsf(u);
    float along = 1.0f - smoothstep(0.4f, 1.0f, au);
    float half_width = 0.45f * (1.0f - 0.4f * smoothstep(0.0f, 1.0f, au));
    return along * cone_profile(fabsf(v) / half_width, 0.1f, 0.35f);
}

float stamp_shape_value(stamp_shape s, float u, float v) {
    if (s == STAMP_SHAPE_RIDGE) return fabsf(u) < 1.0f && fabsf(v) < 1.0f ? ridge(u, v) : 0.0f;
    float s2 = u * u + v * v;
    if (!(s2 < 1.0f)) return 0.0f; // also NaN and overflow to infinity
    float r = sqrtf(s2);
    switch (s) {
    case STAMP_SHAPE_GAUSSIAN:
        return gaussian(s2);
    case STAMP_SHAPE_CRATER:
        return hermite(CRATER, (int)(sizeof CRATER / sizeof CRATER[0]), r);
    case STAMP_SHAPE_CONE:
        return cone_profile(r, 0.15f, 0.25f);
    case STAMP_SHAPE_VOLCANO: // >= 0 exactly; rounding near the foot can give -4e-8
        return fmaxf(0.0f, hermite(VOLCANO, (int)(sizeof VOLCANO / sizeof VOLCANO[0]), r));
    case STAMP_SHAPE_MESA:
        return 0.85f * (1.0f - smoothstep(0.5f, 0.7f, r)) +
               0.15f * (1.0f - smoothstep(0.5f, 1.0f, r));
    default:
        return 0.0f;
    }
}
