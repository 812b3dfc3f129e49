// Occlusion by the ground's horizon around a camera above a planet's ground: a few
// metres up, the chunks past a hill's crest pass every other test (ground_occlusion.h's
// solids lie under each chunk's lowest point, below the crest's sight lines).
//
// Why it holds: seen from the planet's centre, every plane through the centre and the
// camera is a vertical half-plane around the camera's local vertical at some azimuth,
// and in it the drawn ground is a curve over the angle from the camera's vertical (the
// ground is a heightfield over directions). Take a point p at or under the ground in that
// half-plane, and a point q farther from the vertical (a larger angle) seen under a
// lower elevation than p. Along the ray from the camera to q, the ray's radius at p's
// angle is below p's (rays from the camera cross a radial line lower the lower their
// elevation), so below the ground there, while the camera is above the ground: the ray
// meets the ground before it reaches q, and q is hidden.
//
// So per azimuth bin and reach (the angle from the vertical, in bands of an eighth of
// an octave of its tangent) it keeps the highest elevation promised on or under the
// ground by the patches added so far, as a prefix maximum over the bands (a Fenwick
// tree: both adding and asking take a few steps). A patch is hidden when in every bin
// it touches its highest possible elevation is below what is promised short of its
// nearest point. Every answer is conservative; a patch the camera's vertical passes
// through, or reaching a right angle from it, is never used nor hidden. Angles are
// kept as tangents and azimuths as pseudo-angles (monotone, no trigonometry).
#ifndef OROGEN_RENDERER_GROUND_HORIZON_H
#define OROGEN_RENDERER_GROUND_HORIZON_H

#define GROUND_HORIZON_BINS 1024 // azimuth bins around the vertical
#define GROUND_HORIZON_BANDS 256 // reach bands: 8 an octave of tan(reach), 2^-28 to 16

typedef struct ground_horizon {
    double eye[3], eye_r;            // the camera (planet coordinates) and its radius
    double up[3], east[3], north[3]; // the camera's local frame
    unsigned frame;                  // bins last touched in another frame are empty
    unsigned touched[GROUND_HORIZON_BINS];
    // Per bin, a Fenwick tree over the bands of the tangent of the elevation (above the
    // camera's horizontal plane) promised by patches reaching no farther.
    float promised[GROUND_HORIZON_BINS][GROUND_HORIZON_BANDS + 1];
} ground_horizon;

// Starts a frame with nothing added; eye: the camera, planet coordinates (centre at 0).
// The first call needs h zeroed.
void ground_horizon_begin(ground_horizon *h, const double eye[3]);

// Patches: the cone of 4 unit directions from the planet's centre, the corners of a
// quadrilateral whose edges are great-circle arcs, in the order (s0,t0), (s1,t0),
// (s0,t1), (s1,t1) of a grid.

// Adds a patch whose drawn ground lies nowhere below radius floor_r.
void ground_horizon_add_floor(ground_horizon *h, const double (*dir)[3], double floor_r);

// Whether everything in the patch up to radius top_r is hidden by what was added.
int ground_horizon_hidden(const ground_horizon *h, const double (*dir)[3], double top_r);

#endif
