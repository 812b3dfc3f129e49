// Fault-line terrain. Flat worlds: every 64 km x 64 km cell owns fault_count
// faults, each a smooth step (up on one side, down on the other) across a line
// through a random point, faded out within a random reach of at most one cell,
// so a sample only needs the faults of its own and the eight neighbouring cells:
// seamless and unbounded. Planets: the classic great-circle faults, each a random
// plane through the centre lifting one hemisphere and lowering the other.
// The step's width is never narrower than two samples of the mip level, which
// band-limits coarse levels.
#include "editor/gen/gen_faults.h"

#include "editor/gen/gen_hash.h"
#include "editor/params/world_grid.h"

#include <math.h>
#include <stdlib.h>

#define FAULT_CELL_METRES 65536.0

typedef struct fault {
    double cx, cz; // a point on the line, metres
    double nx, nz; // unit normal of the line
    double reach;  // metres: the fault fades out beyond this distance from (cx, cz)
    double amp;    // metres, signed
} fault;

static double unit(uint32_t h) {
    return (double)h * (1.0 / 4294967296.0);
} // [0, 1)

static double fault_amplitude(const world_params *p, uint32_t h) {
    int n = p->fault_count > 0 ? p->fault_count : 1;
    return p->max_height * 1.5 * (2.0 * unit(h) - 1.0) / sqrt((double)n);
}

static void cell_faults(const world_params *p, int64_t cx, int64_t cz, fault *out) {
    uint32_t seed = (uint32_t)p->seed;
    uint32_t base = gen_hash_3((uint32_t)cx ^ gen_hash32((uint32_t)((uint64_t)cx >> 32)),
                               (uint32_t)cz ^ gen_hash32((uint32_t)((uint64_t)cz >> 32)), seed);
    for (int i = 0; i < p->fault_count; i++) {
        uint32_t h0 = gen_hash_3(base, (uint32_t)i, 0x0fa1u);
        uint32_t h1 = gen_hash32(h0 + 1), h2 = gen_hash32(h0 + 2), h3 = gen_hash32(h0 + 3);
        uint32_t h4 = gen_hash32(h0 + 4);
        double angle = unit(h2) * 2.0 * M_PI;
        out[i] = (fault){
            .cx = ((double)cx + unit(h0)) * FAULT_CELL_METRES,
            .cz = ((double)cz + unit(h1)) * FAULT_CELL_METRES,
            .nx = cos(angle),
            .nz = sin(angle),
            .reach = FAULT_CELL_METRES * (0.25 + 0.75 * unit(h3)),
            .amp = fault_amplitude(p, h4),
        };
    }
}

// Odd smooth step in [-1, 1]: 0 on the line, +-1 beyond the width.
static double smooth_sign(double d, double width) {
    double x = d / width;
    if (x <= -1.0) return -1.0;
    if (x >= 1.0) return 1.0;
    return x * (1.5 - 0.5 * x * x);
}

// Index of the last sample at or before position v in a row starting at origin, clamped
// to [-1, TILE_SIZE] so far-away faults give empty ranges without overflow.
static int sample_floor(double v, double origin, double step) {
    double k = floor((v - origin) / step);
    return k < -1.0 ? -1 : (k > TILE_SIZE ? TILE_SIZE : (int)k);
}

static void flat_faults(const world_params *p, tile_key key, float *out) {
    double step = p->spacing * ldexp(1.0, key.level);
    // Faults are cell-sized features: they fade out as the sample step nears half a
    // cell (below Nyquist), which also keeps the coarsest levels cheap.
    double band =
        (FAULT_CELL_METRES / 2.0 - step) / (FAULT_CELL_METRES / 2.0 - FAULT_CELL_METRES / 8.0);
    band = band < 0.0 ? 0.0 : (band > 1.0 ? 1.0 : band);
    if (band == 0.0) {
        for (size_t k = 0; k < TILE_SAMPLES; k++)
            out[k] = 0.0f;
        return;
    }
    double width = fmax(FAULT_CELL_METRES / 1024.0, 2.0 * step);
    double x0 = (double)world_grid_index(key.tx, 0, key.level) * p->spacing;
    double z0 = (double)world_grid_index(key.ty, 0, key.level) * p->spacing;
    double extent = step * TILE_SIZE;
    int64_t c0x = (int64_t)floor(x0 / FAULT_CELL_METRES) - 1;
    int64_t c1x = (int64_t)floor((x0 + extent) / FAULT_CELL_METRES) + 1;
    int64_t c0z = (int64_t)floor(z0 / FAULT_CELL_METRES) - 1;
    int64_t c1z = (int64_t)floor((z0 + extent) / FAULT_CELL_METRES) + 1;
    double *acc = calloc(TILE_SAMPLES, sizeof(double));
    fault *faults = malloc(sizeof(fault) * (size_t)(p->fault_count > 0 ? p->fault_count : 1));
    // Cells in a fixed order, faults in a fixed order: the sum is the same for a
    // sample whichever tile it is computed in. Cells too far to matter are skipped
    // whole (they add exactly zero), so huge mip tiles stay cheap.
    for (int64_t cz = c0z; cz <= c1z; cz++) {
        for (int64_t cx = c0x; cx <= c1x; cx++) {
            cell_faults(p, cx, cz, faults);
            for (int f = 0; f < p->fault_count; f++) {
                const fault *ft = &faults[f];
                double amp = ft->amp * band;
                // Only the samples near the fault's reach (one extra each side: the
                // r2 test below, not this rounding, decides who is inside).
                int j0 = sample_floor(ft->cz - ft->reach, z0, step);
                int j1 = sample_floor(ft->cz + ft->reach, z0, step) + 1;
                int i0 = sample_floor(ft->cx - ft->reach, x0, step);
                int i1 = sample_floor(ft->cx + ft->reach, x0, step) + 1;
                for (int j = j0 < 0 ? 0 : j0; j <= j1 && j < TILE_SIZE; j++) {
                    double z = (double)world_grid_index(key.ty, j, key.level) * p->spacing;
                    double dz = z - ft->cz;
                    for (int i = i0 < 0 ? 0 : i0; i <= i1 && i < TILE_SIZE; i++) {
                        double x = (double)world_grid_index(key.tx, i, key.level) * p->spacing;
                        double dx = x - ft->cx;
                        double r2 = (dx * dx + dz * dz) / (ft->reach * ft->reach);
                        if (r2 >= 1.0) continue;
                        double fade = (1.0 - r2) * (1.0 - r2);
                        double d = dx * ft->nx + dz * ft->nz;
                        acc[j * TILE_SIZE + i] += amp * fade * smooth_sign(d, width);
                    }
                }
            }
        }
    }
    for (size_t k = 0; k < TILE_SAMPLES; k++)
        out[k] = (float)acc[k];
    free(faults);
    free(acc);
}

static void planet_faults(const world_params *p, tile_key key, float *out) {
    int n = p->fault_count;
    double *planes = malloc(sizeof(double) * 4 * (size_t)(n > 0 ? n : 1));
    for (int i = 0; i < n; i++) {
        uint32_t h = gen_hash_3((uint32_t)p->seed, (uint32_t)i, 0x91a7e7u);
        // A uniformly random plane normal: z uniform in [-1, 1], angle uniform.
        double z = 2.0 * unit(h) - 1.0, a = 2.0 * M_PI * unit(gen_hash32(h + 1));
        double r = sqrt(1.0 - z * z);
        planes[4 * i + 0] = r * cos(a), planes[4 * i + 1] = r * sin(a), planes[4 * i + 2] = z;
        planes[4 * i + 3] = fault_amplitude(p, gen_hash32(h + 2));
    }
    double step = p->spacing * ldexp(1.0, key.level);
    double width = fmax(0.002, 2.0 * step / p->radius); // in units of the radius
    for (int j = 0; j < TILE_SIZE; j++) {
        double t = world_grid_face_coord(p, key.level, world_grid_index(key.ty, j, 0));
        for (int i = 0; i < TILE_SIZE; i++) {
            double s = world_grid_face_coord(p, key.level, world_grid_index(key.tx, i, 0));
            double d[3];
            world_grid_face_direction(key.face, s, t, d);
            double h = 0.0;
            for (int f = 0; f < n; f++) {
                const double *pl = &planes[4 * f];
                h += pl[3] * smooth_sign(d[0] * pl[0] + d[1] * pl[1] + d[2] * pl[2], width);
            }
            out[j * TILE_SIZE + i] = (float)h;
        }
    }
    free(planes);
}

void gen_faults_tile(const world_params *p, tile_key key, float *out) {
    if (p->kind == WORLD_PLANET)
        planet_faults(p, key, out);
    else
        flat_faults(p, key, out);
    float m = (float)p->max_height;
    for (size_t k = 0; k < TILE_SAMPLES; k++) {
        float h = out[k] < -m ? -m : (out[k] > m ? m : out[k]);
        out[k] = (float)(h + p->base_height);
    }
}
