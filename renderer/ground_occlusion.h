// Occlusion by the ground itself, for a heightfield drawn nearest first from a camera
// above it: a few metres up, most of what lies past the horizon the nearby ground makes
// passes the frustum and horizon tests (a sphere under the ground cannot be tighter than
// the lowest valley in reach), and a software renderer pays for every triangle.
//
// Why ground occludes: take a point q at or below the drawn surface, and the ray from the
// camera (above the surface) to q. Along it the height above the surface goes from
// positive to at most zero, so the ray meets the surface no farther than q. So every
// pixel whose ray passes through a solid lying under the drawn ground (a chunk's
// footprint below its lowest point) shows ground no farther than the solid's farthest
// corner, and anything beyond that in the pixel is hidden. (Distances here are depths
// along the view direction: on one pixel's ray they order points as distances do.)
//
// The screen is cut into columns; per column and per depth band (quarter octaves of
// metres) it keeps one covered interval of heights on the screen, grown as solids are
// added (nearest first, the covered part of a column is one run from the nearby ground
// up to the horizon). Every answer is conservative: a chunk is hidden only if the box of
// its projection lies, in every column, inside an interval covered nearer than it.
#ifndef OROGEN_RENDERER_GROUND_OCCLUSION_H
#define OROGEN_RENDERER_GROUND_OCCLUSION_H

#define GROUND_OCCLUSION_COLUMNS 160
#define GROUND_OCCLUSION_BANDS_PER_OCTAVE 4
#define GROUND_OCCLUSION_BANDS 104 // band b: covered no deeper than 2^(b/4) metres (to 2^26)

typedef struct ground_occlusion {
    double eye[3], forward[3], right[3], up[3]; // the camera, any frame (planet coordinates)
    double tan_half_x, tan_half_y;
    // Covered heights on the screen (-1 bottom, 1 top) per column and band; lo > hi: none.
    // A solid changes every band from its depth on, so the bands from a column's top[i]
    // on (past the farthest solid's first band) are all alike: only band top[i] holds
    // them, and a column's bands lie side by side.
    float lo[GROUND_OCCLUSION_COLUMNS][GROUND_OCCLUSION_BANDS];
    float hi[GROUND_OCCLUSION_COLUMNS][GROUND_OCCLUSION_BANDS];
    unsigned char top[GROUND_OCCLUSION_COLUMNS];
} ground_occlusion;

// Starts a frame: nothing covered. forward, right, up: the camera's unit basis;
// tan_half_x, tan_half_y: tangents of half the horizontal and vertical fields of view.
void ground_occlusion_begin(ground_occlusion *o, const double eye[3], const double forward[3],
                            const double right[3], const double up[3], double tan_half_x,
                            double tan_half_y);

// Adds the convex hull of n points (n <= 8) lying under the ground, inside the footprint
// of ground that is drawn or was found hidden (a ray meeting hidden ground has met drawn
// ground before it). Ignored when a point is not in front of the camera.
void ground_occlusion_add_solid(ground_occlusion *o, const double (*pts)[3], int n);

// Whether everything inside the convex hull of n points (n <= 8) is hidden by the solids
// added so far. Never when a point is not in front of the camera or the hull is off the
// screen.
int ground_occlusion_hidden(const ground_occlusion *o, const double (*pts)[3], int n);

#endif
