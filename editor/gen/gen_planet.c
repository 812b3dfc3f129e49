// The "planet" generator. Plain fBm at Earth's proportions gave rolling ground of one
// character everywhere: blobs for continents, no ranges from orbit, a plateau from
// 10 km. This one builds a planet from parts a geographer would name, all in noise
// units of the feature size (a radius on planets), each band-limited by the level's
// octaves (gen_octaves_at_level) so coarse mips hold what they can show:
//  - continents: fBm over a domain warped by a lower fBm (coastlines turn and bays cut
//    in rather than blobs), shaped into shelves, deep ocean floor and lowland plains;
//  - mountain ranges: Musgrave's ridged multifractal over the same warped domain, from
//    a few hundred kilometres on Earth down to the samples, in belts (a low fBm) that
//    lie mostly on land: long sinuous ranges with sharp crests that read from orbit;
//  - hills and valleys: ridged noise from tens of kilometres down, everywhere on land
//    (stronger in the belts), so valleys and ridges show from 10 km.
// Keys used: seed, octaves (the finest octave), exponent (the lacunarity of ranges and
// hills), ridge_offset, max_height (heights are shares of it), base_height, feature_size.
#include "editor/gen/gen_planet.h"

#include "editor/gen/gen_hash.h"
#include "editor/gen/gen_noise.h"
#include "editor/gen/gen_scale.h"
#include "editor/params/world_grid.h"

#include <math.h>
#include <stdlib.h>

#define WARP 0.25      // how far the warp moves the continents' domain (noise units)
#define SEA_SHARE 0.05 // continent values under this are sea: about 60% of the surface
#define RANGES 0.8     // a range's crest, as a share of max_height
#define RANGE_OCTAVE 5 // ranges' first octave: a 32nd of the feature size (200 km on Earth)
#define HILL_OCTAVE 9  // hills' first octave (12 km on Earth)

static double smooth(double e0, double e1, double x) {
    double t = (x - e0) / (e1 - e0);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return t * t * (3.0 - 2.0 * t);
}

// A fractal of `octaves` (at most what the level allows past `first`), or none.
static int component(const world_params *p, int level, gen_fractal_kind kind, uint32_t salt,
                     int first, double octaves, double gain, gen_fractal *f) {
    const double room = gen_octaves_at_level(p, level) - first;
    if (room <= 0.0) return 0;
    *f = (gen_fractal){.kind = kind,
                       .seed = gen_hash32((uint32_t)p->seed ^ salt),
                       .octaves = octaves < room ? octaves : room,
                       .gain = gain,
                       .lacunarity = kind == GEN_FRACTAL_RIDGED ? p->exponent : 2.0,
                       .ridge_offset = p->ridge_offset};
    return 1;
}

// Evaluates f at xyz scaled by `scale` (xyz kept), into out.
static void at_scale(const gen_fractal *f, const double *xyz, double scale, double *tmp,
                     float *out) {
    for (size_t k = 0; k < 3 * (size_t)TILE_SAMPLES; k++)
        tmp[k] = xyz[k] * scale;
    gen_fractal_points3(f, tmp, TILE_SAMPLES, out);
}

// The tile's sample positions in noise units: on the unit sphere times radius /
// feature size on planets, on a plane at y = 0.5 on flat worlds.
static void sample_points(const world_params *p, tile_key key, double *xyz) {
    const double scale = 1.0 / gen_feature_size(p);
    for (int j = 0; j < TILE_SIZE; j++)
        for (int i = 0; i < TILE_SIZE; i++) {
            double *d = xyz + 3 * ((size_t)j * TILE_SIZE + i);
            if (p->kind == WORLD_PLANET) {
                const double s =
                    world_grid_face_coord(p, key.level, world_grid_index(key.tx, i, 0));
                const double t =
                    world_grid_face_coord(p, key.level, world_grid_index(key.ty, j, 0));
                world_grid_face_direction(key.face, s, t, d);
                for (int a = 0; a < 3; a++)
                    d[a] *= p->radius * scale;
            } else {
                d[0] = (double)world_grid_index(key.tx, i, key.level) * p->spacing * scale;
                d[1] = 0.5;
                d[2] = (double)world_grid_index(key.ty, j, key.level) * p->spacing * scale;
            }
        }
}

void gen_planet_tile(const world_params *p, tile_key key, float *out) {
    double *xyz = malloc(sizeof(double) * 3 * TILE_SAMPLES);
    double *warped = malloc(sizeof(double) * 3 * TILE_SAMPLES);
    double *tmp = malloc(sizeof(double) * 3 * TILE_SAMPLES);
    float *field = malloc(sizeof(float) * 4 * TILE_SAMPLES);
    float *cont = field, *belt = field + TILE_SAMPLES, *ranges = field + 2 * TILE_SAMPLES,
          *hills = field + 3 * TILE_SAMPLES;
    sample_points(p, key, xyz);
    // The warp: three low fBm fields displace the domain.
    gen_fractal f;
    for (size_t k = 0; k < 3 * (size_t)TILE_SAMPLES; k++)
        warped[k] = xyz[k];
    for (int a = 0; a < 3; a++)
        if (component(p, key.level, GEN_FRACTAL_FBM, 0x3a9d0000U + (uint32_t)a, 1, 3.0, 0.5, &f)) {
            at_scale(&f, xyz, 2.0, tmp, cont);
            for (size_t k = 0; k < TILE_SAMPLES; k++)
                warped[3 * k + a] += WARP * cont[k];
        }
    for (size_t k = 0; k < TILE_SAMPLES; k++)
        cont[k] = belt[k] = ranges[k] = hills[k] = 0.0f;
    if (component(p, key.level, GEN_FRACTAL_FBM, 0xc0a71000U, 0, 6.0, 0.55, &f))
        at_scale(&f, warped, 1.3, tmp, cont);
    if (component(p, key.level, GEN_FRACTAL_FBM, 0xbe170000U, 1, 2.0, 0.5, &f))
        at_scale(&f, warped, 2.0, tmp, belt);
    if (component(p, key.level, GEN_FRACTAL_RIDGED, 0x7a9e0000U, RANGE_OCTAVE, 64.0, 0.55, &f))
        at_scale(&f, warped, ldexp(1.0, RANGE_OCTAVE), tmp, ranges);
    if (component(p, key.level, GEN_FRACTAL_RIDGED, 0x4111c000U, HILL_OCTAVE, 64.0, 0.6, &f))
        at_scale(&f, warped, ldexp(1.0, HILL_OCTAVE), tmp, hills);
    for (size_t k = 0; k < TILE_SAMPLES; k++) {
        const double c = cont[k] - SEA_SHARE;
        // Lowlands rising inland to low plateaus; under the sea a shelf, then the
        // ocean floor at half the relief below the sea.
        double h = c >= 0 ? 0.01 + 0.3 * c : fmax(0.01 + 2.0 * c, -0.5);
        const double land = smooth(-0.02, 0.04, c);
        const double mountain = smooth(0.05, 0.35, belt[k]) * (0.25 + 0.75 * land);
        // Ridged values gather between 0.5 and 0.8 of their range: stretched, the
        // crests stand out of broad valleys instead of a plateau.
        const double crest = smooth(0.4, 0.92, 0.5 * (ranges[k] + 1.0)),
                     hill = smooth(0.3, 0.9, 0.5 * (hills[k] + 1.0));
        h += RANGES * mountain * crest * sqrt(crest);
        h += (0.06 + 0.15 * mountain) * (0.3 + 0.7 * land) * hill;
        h = h < -1.0 ? -1.0 : h > 1.0 ? 1.0 : h;
        out[k] = (float)(h * p->max_height + p->base_height);
    }
    free(field);
    free(tmp);
    free(warped);
    free(xyz);
}
