// Seed 003's diamond-square, made seamless and order-independent over an
// unbounded int32 tile world.
//
// Seed 003 seeds each block from whichever neighbours happen to exist, so the
// terrain depends on the order blocks were generated in. Here every point of the
// infinite grid has one value, fixed by its own coordinates: a point born at
// subdivision level k (spacing 2^k) is the average of its four parents plus a
// displacement hashed from its global coordinates and the seed, scaled by
// roughness * smoothing^(levels below the top). The top grid (spacing 2^K, seed
// 003's super blocks) comes from a low-frequency fBm so mountains and valleys span
// many tiles. A tile is computed by walking down from the top grid over just the
// region its points depend on (a margin of two parent cells per level), so
// neighbouring tiles agree exactly on every shared parent and there are no seams.
// Mip level L is the same field stopped at spacing 2^L: coarser levels are exact
// subsamples of finer ones.
#include "editor/gen/gen_diamond.h"

#include "editor/gen/gen_hash.h"
#include "editor/gen/gen_noise.h"
#include "editor/gen/gen_scale.h"
#include "editor/params/world_grid.h"

#include <math.h>
#include <stdlib.h>

typedef struct ds_range {
    int64_t lo, hi; // inclusive, in units of the level's spacing
} ds_range;

typedef struct ds_grid {
    int64_t x0, z0; // index of v[0] in units of the level's spacing
    int64_t nx, nz;
    float *v;
} ds_grid;

static int64_t ceil_div2(int64_t a) {
    return -world_grid_floor_div(-a, 2);
}

static int top_level(const world_params *p) {
    int k = (int)lround(log2(gen_feature_size(p) / p->spacing));
    return k < 1 ? 1 : (k > 30 ? 30 : k);
}

static uint32_t point_hash(uint32_t seed, int64_t x, int64_t z) {
    uint32_t hx = (uint32_t)x ^ gen_hash32((uint32_t)((uint64_t)x >> 32) + 0x68e31da4U);
    uint32_t hz = (uint32_t)z ^ gen_hash32((uint32_t)((uint64_t)z >> 32) + 0xb5297a4dU);
    return gen_hash_3(hx, hz, seed);
}

// Top-grid heights: Harris 2011's super blocks, as a smooth fBm over top cells.
static void fill_top(const world_params *p, ds_grid *g) {
    gen_fractal f = {.kind = GEN_FRACTAL_FBM,
                     .seed = gen_hash32((uint32_t)p->seed ^ 0xd1a3050dU),
                     .octaves = 3.0,
                     .gain = 0.5,
                     .lacunarity = 2.0};
    double *xs = malloc(sizeof(double) * (size_t)g->nx);
    double *zs = malloc(sizeof(double) * (size_t)g->nz);
    // One noise cell every four top cells: features larger than a single block.
    for (int64_t i = 0; i < g->nx; i++)
        xs[i] = (double)(g->x0 + i) * 0.25;
    for (int64_t j = 0; j < g->nz; j++)
        zs[j] = (double)(g->z0 + j) * 0.25;
    gen_fractal_grid2(&f, xs, (int)g->nx, zs, (int)g->nz, g->v);
    float amp = (float)(p->max_height * 0.8);
    for (int64_t k = 0; k < g->nx * g->nz; k++)
        g->v[k] *= amp;
    free(xs);
    free(zs);
}

static inline float *at(ds_grid *g, int64_t x, int64_t z) {
    return &g->v[(z - g->z0) * g->nx + (x - g->x0)];
}

// Builds level k (ranges r[k] plus a ring of one for diamond centres) from level k+1.
static void subdivide(const world_params *p, int K, int k, const ds_grid *parent, ds_range rx,
                      ds_range rz, ds_grid *g) {
    g->x0 = rx.lo - 1, g->z0 = rz.lo - 1;
    g->nx = rx.hi - rx.lo + 3, g->nz = rz.hi - rz.lo + 3;
    g->v = malloc(sizeof(float) * (size_t)(g->nx * g->nz));
    float amp = (float)(p->max_height * p->roughness * pow(p->smoothing, K - 1 - k));
    uint32_t seed = (uint32_t)p->seed;
    const int64_t cell = (int64_t)1 << k; // level-0 samples per level-k step
    ds_grid *par = (ds_grid *)parent;
    // Copy the parents and displace the diamond centres over the whole working grid.
    for (int64_t z = g->z0; z < g->z0 + g->nz; z++) {
        for (int64_t x = g->x0; x < g->x0 + g->nx; x++) {
            int ex = (x & 1) == 0, ez = (z & 1) == 0;
            if (ex && ez) {
                *at(g, x, z) = *at(par, x / 2, z / 2);
            } else if (!ex && !ez) {
                int64_t px = (x - 1) / 2, pz = (z - 1) / 2; // exact: x, z are odd
                float sum = *at(par, px, pz) + *at(par, px + 1, pz) + *at(par, px, pz + 1) +
                            *at(par, px + 1, pz + 1);
                uint32_t h = point_hash(seed, x * cell, z * cell);
                *at(g, x, z) = sum * 0.25f + amp * gen_hash_unit(h);
            }
        }
    }
    // Square step on the needed range: neighbours are parents or diamond centres.
    for (int64_t z = rz.lo; z <= rz.hi; z++) {
        for (int64_t x = rx.lo; x <= rx.hi; x++) {
            if (((x ^ z) & 1) == 0) continue;
            float sum = *at(g, x - 1, z) + *at(g, x + 1, z) + *at(g, x, z - 1) + *at(g, x, z + 1);
            uint32_t h = point_hash(seed, x * cell, z * cell);
            *at(g, x, z) = sum * 0.25f + amp * gen_hash_unit(h);
        }
    }
}

void gen_diamond_square_region(const world_params *p, int level, int64_t x0, int64_t z0, int nx,
                               int nz, float *out) {
    int K = top_level(p), L = level;
    ds_range rx = {x0, x0 + nx - 1}, rz = {z0, z0 + nz - 1};
    if (L >= K) {
        // Coarser than the top grid: the samples are top-grid points themselves.
        int64_t step = (int64_t)1 << (L - K);
        if (step == 1) {
            ds_grid top = {rx.lo, rz.lo, nx, nz, out};
            fill_top(p, &top);
        } else {
            for (int j = 0; j < nz; j++)
                for (int i = 0; i < nx; i++) {
                    ds_grid one = {(rx.lo + i) * step, (rz.lo + j) * step, 1, 1,
                                   &out[(size_t)j * nx + i]};
                    fill_top(p, &one);
                }
        }
    } else {
        ds_range xr[32], zr[32];
        xr[L] = rx, zr[L] = rz;
        for (int k = L; k < K; k++) {
            xr[k + 1] = (ds_range){world_grid_floor_div(xr[k].lo - 2, 2), ceil_div2(xr[k].hi + 2)};
            zr[k + 1] = (ds_range){world_grid_floor_div(zr[k].lo - 2, 2), ceil_div2(zr[k].hi + 2)};
        }
        ds_grid parent = {xr[K].lo, zr[K].lo, xr[K].hi - xr[K].lo + 1, zr[K].hi - zr[K].lo + 1,
                          NULL};
        parent.v = malloc(sizeof(float) * (size_t)(parent.nx * parent.nz));
        fill_top(p, &parent);
        for (int k = K - 1; k >= L; k--) {
            ds_grid g;
            subdivide(p, K, k, &parent, xr[k], zr[k], &g);
            free(parent.v);
            parent = g;
        }
        for (int j = 0; j < nz; j++)
            for (int i = 0; i < nx; i++)
                out[(size_t)j * nx + i] = *at(&parent, rx.lo + i, rz.lo + j);
        free(parent.v);
    }
    float m = (float)p->max_height;
    for (size_t k = 0; k < (size_t)nx * nz; k++) {
        float h = out[k] < -m ? -m : (out[k] > m ? m : out[k]);
        out[k] = (float)(h + p->base_height);
    }
}

void gen_diamond_square_tile(const world_params *p, tile_key key, float *out) {
    gen_diamond_square_region(p, key.level, (int64_t)key.tx * TILE_SIZE,
                              (int64_t)key.ty * TILE_SIZE, TILE_SIZE, TILE_SIZE, out);
}
