// 8-octave fBm throughput, single thread: Orogen's 2D grid path (flat worlds) and
// 3D points path (planets) against libnoise's Perlin module with 8 octaves, in the
// same run. Each figure is the median of 5 timed runs of a fixed workload.
#include "editor/gen/gen_noise.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

// Adapter in peer_libnoise.cpp.
void peer_libnoise_grid(const double *xs, int nx, const double *ys, int ny, double z, float *out);
void peer_libnoise_points(const double *xyz, size_t n, float *out);

enum { RUNS = 5, NX = 512, NY = 256, NPOINTS = 131072 };

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v) {
    qsort(v, RUNS, sizeof *v, cmp_double);
    return v[RUNS / 2];
}

// A sink for every output, so no run can be optimised away.
static volatile double sink;
static void consume(const float *out, size_t n) {
    double s = 0;
    for (size_t i = 0; i < n; i++)
        s += out[i];
    sink += s;
}

static const gen_fractal FBM = {
    .kind = GEN_FRACTAL_FBM, .seed = 1, .octaves = 8.0, .gain = 0.5, .lacunarity = 2.0};

typedef struct workload {
    const double *xs, *ys, *xyz;
    float *out;
} workload;

// Repeats of each tile per timed run: about 0.2-0.4 s per run on each side.
enum { OUR_GRID_REPS = 64, PEER_GRID_REPS = 4, OUR_POINT_REPS = 30, PEER_POINT_REPS = 5 };

static double run_ours_grid(const workload *w) {
    double t = now();
    for (int r = 0; r < OUR_GRID_REPS; r++) {
        gen_fractal_grid2(&FBM, w->xs, NX, w->ys + r, NY, w->out);
        consume(w->out, (size_t)NX * NY);
    }
    return (double)OUR_GRID_REPS * NX * NY / (now() - t);
}

static double run_peer_grid(const workload *w) {
    double t = now();
    for (int r = 0; r < PEER_GRID_REPS; r++) {
        peer_libnoise_grid(w->xs, NX, w->ys + r, NY, 0.37, w->out);
        consume(w->out, (size_t)NX * NY);
    }
    return (double)PEER_GRID_REPS * NX * NY / (now() - t);
}

static double run_ours_points(const workload *w) {
    double t = now();
    for (int r = 0; r < OUR_POINT_REPS; r++) {
        gen_fractal_points3(&FBM, w->xyz, NPOINTS, w->out);
        consume(w->out, NPOINTS);
    }
    return (double)OUR_POINT_REPS * NPOINTS / (now() - t);
}

static double run_peer_points(const workload *w) {
    double t = now();
    for (int r = 0; r < PEER_POINT_REPS; r++) {
        peer_libnoise_points(w->xyz, NPOINTS, w->out);
        consume(w->out, NPOINTS);
    }
    return (double)PEER_POINT_REPS * NPOINTS / (now() - t);
}

// Runs ours and the peer alternately so drift in clock speed hits both alike.
static void compare(const char *what, const workload *w, double (*ours)(const workload *),
                    double (*peer)(const workload *)) {
    double a[RUNS], b[RUNS];
    ours(w), peer(w); // warm up caches and page in the buffers
    for (int r = 0; r < RUNS; r++)
        a[r] = ours(w), b[r] = peer(w);
    double x = median(a) * 1e-6, y = median(b) * 1e-6;
    printf("%s 8 octaves: %.1f Msamples/s/core; libnoise Perlin 8 octaves: %.2f Msamples/s/core; "
           "ratio %.1f\n",
           what, x, y, x / y);
}

int main(void) {
    // Terrain-like sampling: 1/64 noise unit between samples, away from the origin;
    // planet points on a sphere of radius 100 noise units.
    double *xs = malloc(sizeof(double) * NX), *ys = malloc(sizeof(double) * (NY + 64));
    double *xyz = malloc(sizeof(double) * 3 * NPOINTS);
    float *out = malloc(sizeof(float) * (NX * NY > NPOINTS ? NX * NY : NPOINTS));
    if (!xs || !ys || !xyz || !out) return 1;
    for (int i = 0; i < NX; i++)
        xs[i] = 1000.25 + i / 64.0;
    for (int j = 0; j < NY + 64; j++)
        ys[j] = -733.5 + j / 64.0;
    uint64_t s = 12345;
    for (int i = 0; i < NPOINTS; i++) {
        double v[3], len = 0;
        for (int k = 0; k < 3; k++) {
            s = s * 6364136223846793005ull + 1442695040888963407ull;
            v[k] = (double)(s >> 11) * (1.0 / 9007199254740992.0) - 0.5;
            len += v[k] * v[k];
        }
        for (int k = 0; k < 3; k++)
            xyz[3 * i + k] = 100.0 * v[k] / sqrt(len);
    }
    workload w = {xs, ys, xyz, out};
    compare("fbm2 grid", &w, run_ours_grid, run_peer_grid);
    compare("fbm3 points", &w, run_ours_points, run_peer_points);
    free(xs), free(ys), free(xyz), free(out);
    return 0;
}
