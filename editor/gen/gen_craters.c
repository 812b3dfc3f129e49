// The "craters" generator's craters: seed 004's advanced fBm (the moon's rolling ground)
// with impact craters laid over it, at every scale from a quarter of the feature size (a
// planet's radius) down to a few samples.
//
// Each scale is a 3D lattice of cells (in metres, over the planet's surface or a flat
// world's plane) whose edge halves from one scale to the next; a cell holds a crater with
// probability CRATER_CHANCE, centred anywhere in it, its radius a third of the cell or
// less. So there are four times as many craters per area at each halving of size (about
// the D^-2 cumulative count of real crater fields) and a crater reaches at most half a
// cell from its centre: a point needs only the 2 x 2 x 2 cells nearest it per scale.
// Distances are 3D, to centres off the surface too (such a crater shows smaller and
// shallower), so the field is continuous: a centre moved onto the surface reached past
// those cells, and craters appeared and vanished along the cells' mid-planes.
// A crater is a parabolic bowl (depth/diameter 0.2 for small ones, shallower for wide
// ones, as complex craters are) inside a raised rim whose ejecta fall off to nothing at
// 1.5 radii. Craters add up where they overlap. Band limited like the octaves: a scale
// whose craters would span fewer than four samples of the level is left out.
#include "editor/gen/gen_craters.h"

#include "editor/gen/gen_hash.h"
#include "editor/gen/gen_scale.h"
#include "editor/params/world_grid.h"

#include <math.h>
#include <string.h>

#define CRATER_CHANCE 0.85
#define CRATER_LARGEST 0.25 // the largest scale's cell, as a share of the feature size
#define RIM_SHARE 0.2       // the rim's height over the bowl's depth
#define WIDE_RADIUS 10000.0 // metres: wider craters are shallower for their size

// A crater's height (metres) at distance d from its centre.
static double crater_profile(double d, double radius) {
    const double depth = 0.4 * radius / (1.0 + radius / WIDE_RADIUS);
    const double rim = RIM_SHARE * depth, x = d / radius;
    if (x < 1.0) return rim - depth * (1.0 - x * x);
    if (x >= 1.5) return 0.0;
    const double f = 1.0 - (x - 1.0) / 0.5;
    return rim * f * f;
}

// One scale's 2 x 2 x 2 cells nearest a point, with their craters: neighbouring samples
// mostly share them, and the hashes were most of the generator's time.
typedef struct crater_cells {
    int valid;
    double base[3];
    int step[3];
    int n;
    double centre[8][3], radius[8], reach2[8]; // reach2: (1.5 radius)^2
} crater_cells;

static void find_cells(uint32_t scale_seed, double cell, const double base[3], const int step[3],
                       crater_cells *out) {
    out->valid = 1, out->n = 0;
    for (int a = 0; a < 3; a++)
        out->base[a] = base[a], out->step[a] = step[a];
    for (int c = 0; c < 8; c++) {
        const double cx = base[0] + ((c & 1) ? step[0] : 0), cy = base[1] + ((c & 2) ? step[1] : 0),
                     cz = base[2] + ((c & 4) ? step[2] : 0);
        const uint32_t h = gen_hash_3((uint32_t)(int64_t)cx ^ scale_seed, (uint32_t)(int64_t)cy,
                                      (uint32_t)(int64_t)cz);
        if ((h & 0xffff) >= (uint32_t)(CRATER_CHANCE * 65536.0)) continue;
        const uint32_t h1 = gen_hash32(h), h2 = gen_hash32(h1), h3 = gen_hash32(h2);
        double *centre = out->centre[out->n];
        centre[0] = (cx + 0.5 + 0.5 * gen_hash_unit(h1)) * cell;
        centre[1] = (cy + 0.5 + 0.5 * gen_hash_unit(h2)) * cell;
        centre[2] = (cz + 0.5 + 0.5 * gen_hash_unit(h3)) * cell;
        const double radius = cell * (0.12 + 0.21 * (double)(gen_hash32(h3) >> 8) / 16777216.0);
        out->radius[out->n] = radius;
        out->reach2[out->n] = 2.25 * radius * radius * (1.0 + 1e-9);
        out->n++;
    }
}

// The craters at point p (metres; on a planet, on the sphere of its radius). cells: one
// per scale, the last point's (kept when this point's cells are the same).
static double craters_at(uint32_t seed, double largest, int scales, const double point[3],
                         crater_cells *cells) {
    double sum = 0.0, cell = largest;
    for (int k = 0; k < scales; k++, cell *= 0.5) {
        double base[3];
        int step[3];
        for (int a = 0; a < 3; a++) {
            const double u = point[a] / cell, f = floor(u);
            base[a] = f;
            step[a] = u - f < 0.5 ? -1 : 1; // the nearer neighbour along this axis
        }
        crater_cells *cc = &cells[k];
        if (!cc->valid || memcmp(cc->base, base, sizeof base) != 0 ||
            memcmp(cc->step, step, sizeof step) != 0)
            find_cells(gen_hash32(seed + 0x51ed27u * (uint32_t)(k + 1)), cell, base, step, cc);
        for (int c = 0; c < cc->n; c++) {
            const double dx = point[0] - cc->centre[c][0], dy = point[1] - cc->centre[c][1],
                         dz = point[2] - cc->centre[c][2];
            const double d2 = dx * dx + dy * dy + dz * dz;
            if (d2 > cc->reach2[c]) continue; // (the square's rounding: the test below decides)
            const double d = sqrt(d2);
            if (d < 1.5 * cc->radius[c]) sum += crater_profile(d, cc->radius[c]);
        }
    }
    return sum;
}

void gen_craters_add(const world_params *p, tile_key key, float *out) {
    const double largest = CRATER_LARGEST * gen_feature_size(p);
    const double sample = p->spacing * ldexp(1.0, key.level);
    // Scales whose smallest craters (0.12 of a cell across a radius) span 4 samples.
    int scales = 0;
    for (double cell = largest; 2.0 * 0.12 * cell >= 4.0 * sample && scales < 24; cell *= 0.5)
        scales++;
    if (scales == 0) return;
    const uint32_t seed = gen_hash32((uint32_t)p->seed ^ 0xc7a7e500u);
    crater_cells cells[24] = {{0}};
    for (int j = 0; j < TILE_SIZE; j++)
        for (int i = 0; i < TILE_SIZE; i++) {
            double point[3];
            if (p->kind == WORLD_PLANET) {
                const double s =
                    world_grid_face_coord(p, key.level, world_grid_index(key.tx, i, 0));
                const double t =
                    world_grid_face_coord(p, key.level, world_grid_index(key.ty, j, 0));
                world_grid_face_direction(key.face, s, t, point);
                for (int a = 0; a < 3; a++)
                    point[a] *= p->radius;
            } else {
                point[0] = (double)world_grid_index(key.tx, i, key.level) * p->spacing;
                point[1] = 0.0;
                point[2] = (double)world_grid_index(key.ty, j, key.level) * p->spacing;
            }
            float *h = &out[(size_t)j * TILE_SIZE + i];
            double v = *h + craters_at(seed, largest, scales, point, cells);
            const double lo = p->base_height - p->max_height, hi = p->base_height + p->max_height;
            *h = (float)(v < lo ? lo : v > hi ? hi : v);
        }
}
