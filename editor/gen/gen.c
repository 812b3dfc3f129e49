// Generator dispatch and the fractal (fBm / ridged) generators.
#include "editor/gen/gen.h"

#include "editor/gen/gen_craters.h"
#include "editor/gen/gen_noise.h"
#include "editor/params/world_grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static gen_fractal fractal_for(const world_params *p, int level) {
    gen_fractal f = {
        .kind = p->generator == GEN_RIDGED ? GEN_FRACTAL_RIDGED : GEN_FRACTAL_FBM,
        .seed = (uint32_t)p->seed,
        .octaves = gen_octaves_at_level(p, level),
        .gain = p->w_factor,
        .lacunarity = p->exponent,
        .ridge_offset = p->ridge_offset,
    };
    return f;
}

// The low-frequency field that picks Kahoun 2010's "random exponents" for land.
static gen_fractal shaping_fractal(const world_params *p) {
    gen_fractal f = {.kind = GEN_FRACTAL_FBM,
                     .seed = gen_hash32((uint32_t)p->seed ^ 0x5eed0004U),
                     .octaves = 2.0,
                     .gain = 0.5,
                     .lacunarity = 2.0};
    return f;
}

// Seed 004's advanced post-processing of a normalised fBm value h, given the
// shaping noise value e in about [-1, 1]:
// - below the shore band the ocean floor drops with a square root and flattens;
// - land is raised to a varying exponent (1 to 2.5): lowlands flatten, highlands stay steep;
// - values above 1 fold back (2 - h) into valleys instead of clipping into mesas.
// On planets without a sea (rounded: airless presets), the fold's crease and the
// shore's cliff drew dark lines along two contours wherever the light fell across them:
// the fold is rounded over FOLD_ROUND either side of its top, and the shore is no cliff.
#define FOLD_ROUND 0.1f
static float advanced_shape(float h, float e, int rounded) {
    const float shore = 0.05f;
    if (h < -shore && !rounded) {
        h = -shore - 0.5f * sqrtf(-h - shore);
    } else if (h > 0.0f) {
        float expo = 1.0f + 0.75f * (e + 1.0f);
        h = powf(h, expo);
        const float x = h - (1.0f - FOLD_ROUND); // a parabola from 1 - W to 1 + W, C1
        if (rounded && x > 0.0f && x < 2.0f * FOLD_ROUND)
            h = 1.0f - FOLD_ROUND + x - x * x / (2.0f * FOLD_ROUND);
        else if (h > 1.0f)
            h = 2.0f - h;
    }
    return h;
}

static float finish_height(const world_params *p, float h) {
    if (h < -1.0f) h = -1.0f;
    if (h > 1.0f) h = 1.0f;
    return (float)(h * p->max_height + p->base_height);
}

void gen_fractal_tile(const world_params *p, tile_key key, float *out) {
    gen_fractal f = fractal_for(p, key.level);
    double scale = 1.0 / gen_feature_size(p);
    float *shape = NULL;
    int advanced = p->generator == GEN_FBM_ADVANCED || p->generator == GEN_CRATERS;
    if (advanced) shape = malloc(sizeof(float) * TILE_SAMPLES);
    gen_fractal sf = shaping_fractal(p);
    const int rounded =
        p->kind == WORLD_PLANET && world_params_ocean_height(p) < p->base_height - p->max_height;

    if (p->kind == WORLD_FLAT) {
        double xs[TILE_SIZE], zs[TILE_SIZE];
        for (int i = 0; i < TILE_SIZE; i++) {
            xs[i] = (double)world_grid_index(key.tx, i, key.level) * p->spacing * scale;
            zs[i] = (double)world_grid_index(key.ty, i, key.level) * p->spacing * scale;
        }
        gen_fractal_grid2(&f, xs, TILE_SIZE, zs, TILE_SIZE, out);
        if (shape) {
            for (int i = 0; i < TILE_SIZE; i++)
                xs[i] *= 0.5, zs[i] *= 0.5;
            gen_fractal_grid2(&sf, xs, TILE_SIZE, zs, TILE_SIZE, shape);
        }
    } else {
        double *xyz = malloc(sizeof(double) * 3 * TILE_SAMPLES);
        double radius_units = p->radius * scale;
        for (int j = 0; j < TILE_SIZE; j++) {
            double t = world_grid_face_coord(p, key.level, world_grid_index(key.ty, j, 0));
            for (int i = 0; i < TILE_SIZE; i++) {
                double s = world_grid_face_coord(p, key.level, world_grid_index(key.tx, i, 0));
                double *d = xyz + 3 * ((size_t)j * TILE_SIZE + i);
                world_grid_face_direction(key.face, s, t, d);
                d[0] *= radius_units, d[1] *= radius_units, d[2] *= radius_units;
            }
        }
        gen_fractal_points3(&f, xyz, TILE_SAMPLES, out);
        if (shape) {
            for (size_t k = 0; k < 3 * (size_t)TILE_SAMPLES; k++)
                xyz[k] *= 0.5;
            gen_fractal_points3(&sf, xyz, TILE_SAMPLES, shape);
        }
        free(xyz);
    }
    for (size_t k = 0; k < TILE_SAMPLES; k++) {
        float h = shape ? advanced_shape(out[k], shape[k], rounded) : out[k];
        out[k] = finish_height(p, h);
    }
    free(shape);
}

int gen_tile(const world_params *p, tile_key key, void *out) {
    int faces = p->kind == WORLD_PLANET ? 6 : 1;
    if (key.face < 0 || key.face >= faces ||
        (tile_key_has_mips(key) && (key.level < 0 || key.level > TILE_MAX_LEVEL)))
        return -1;
    switch (key.layer) {
    case TILE_LAYER_VOLUME: { // no volume edit yet: every voxel is far from both shapes
        int16_t *v = out;
        for (size_t k = 0; k < 2 * (size_t)TILE_SAMPLES; k++)
            v[k] = INT16_MAX;
        return 0;
    }
    case TILE_LAYER_DETAIL: // offsets and their slopes are zero until edited
    case TILE_LAYER_DETAIL_PD:
        memset(out, 0, tile_layer_bytes((tile_layer)key.layer));
        return 0;
    case TILE_LAYER_MATERIAL: {
        uint8_t *w = out;
        memset(w, 0, tile_layer_bytes(TILE_LAYER_MATERIAL));
        for (size_t k = 0; k < TILE_SAMPLES; k++)
            w[k * TILE_MATERIALS] = 255;
        return 0;
    }
    case TILE_LAYER_COARSE:
        break;
    default:
        return -1;
    }
    float *h = out;
    switch (p->generator) {
    case GEN_FBM:
    case GEN_FBM_ADVANCED:
    case GEN_RIDGED:
        gen_fractal_tile(p, key, h);
        break;
    case GEN_DIAMOND_SQUARE:
        gen_diamond_square_tile(p, key, h);
        break;
    case GEN_FAULTS:
        gen_faults_tile(p, key, h);
        break;
    case GEN_PLANET:
        gen_planet_tile(p, key, h);
        break;
    case GEN_CRATERS:
        gen_fractal_tile(p, key, h);
        gen_craters_add(p, key, h);
        break;
    default:
        for (size_t k = 0; k < TILE_SAMPLES; k++)
            h[k] = (float)p->base_height;
        break;
    }
    return 0;
}
