// Erosion kernel benchmarks on a 1024^2 grid (weight 1 inside a 2-cell zero halo),
// each the best of several runs, beside a reference from the same run:
//  - hydraulic: 100k droplets (default parameters) and the time per droplet step,
//    against one dependent random read of the grid per droplet (the memory latency
//    of starting somewhere random);
//  - thermal: one iteration and the per-iteration cost of ten, against a 3x3 box
//    filter over the same grid (a stencil of the same shape that does no physics).
#include "editor/tools/erosion.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define N 1024

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static uint32_t hash2(uint32_t i, uint32_t j) {
    uint32_t x = i * 0x9E3779B1u ^ (j + 0x7F4A7C15u) * 0x85EBCA77u;
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

// A slope with hills and +-1.5 m noise at 1 m spacing.
static void terrain(float *h, float *w) {
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            float x = (float)i, y = (float)j;
            h[j * N + i] =
                0.3f * x + 20.0f * sinf(x * 0.05f) * cosf(y * 0.043f) +
                3.0f * ((float)(hash2((uint32_t)i, (uint32_t)j) >> 8) / 16777216.0f - 0.5f);
            w[j * N + i] = (i >= 2 && j >= 2 && i < N - 2 && j < N - 2) ? 1.0f : 0.0f;
        }
}

static void box3(const float *in, float *out) {
    for (int j = 1; j < N - 1; j++)
        for (int i = 1; i < N - 1; i++) {
            const float *p = in + j * N + i;
            out[j * N + i] = ((p[-N - 1] + p[-N] + p[-N + 1]) + (p[-1] + p[0] + p[1]) +
                              (p[N - 1] + p[N] + p[N + 1])) *
                             (1.0f / 9.0f);
        }
}

int main(void) {
    float *h0 = malloc(sizeof(float) * N * N), *h = malloc(sizeof(float) * N * N);
    float *w = malloc(sizeof(float) * N * N), *tmp = malloc(sizeof(float) * N * N);
    if (!h0 || !h || !w || !tmp) return 1;
    terrain(h0, w);
    erosion_grid g = {h, w, N, N, 1.0f, NULL};

    hydraulic_params hp;
    hydraulic_params_default(&hp);
    hp.droplets = 100000;
    double best = 1e30;
    hydraulic_report r = {0};
    for (int run = 0; run < 3; run++) {
        memcpy(h, h0, sizeof(float) * N * N);
        double t = now();
        erosion_hydraulic(&g, &hp, &r);
        t = now() - t;
        if (t < best) best = t;
    }
    // Reference: one dependent read at a random cell per droplet, the memory latency a
    // droplet starting at a random spot cannot avoid without prefetching.
    uint64_t state = 1, idx = 0;
    double ref = 1e30;
    for (int run = 0; run < 3; run++) {
        double t = now();
        for (int k = 0; k < hp.droplets; k++) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            idx = ((state >> 40) ^ (uint64_t)(h0[idx] != 0.0f)) % ((uint64_t)N * N);
        }
        t = now() - t;
        if (t < ref) ref = t;
    }
    printf("hydraulic: %d droplets on %dx%d: %.3f s, %lld steps, %.0f ns per step\n", hp.droplets,
           N, N, best, (long long)r.steps, best * 1e9 / (double)r.steps);
    printf("  moved: eroded %.0f, deposited %.0f, dropped %.0f m x cells\n", r.eroded, r.deposited,
           r.dropped);
    printf("  reference: %d dependent random reads of the grid: %.3f s (index %llu)\n", hp.droplets,
           ref, (unsigned long long)idx);

    thermal_params tp = {.talus_deg = 30.0f, .iterations = 1, .rate = 1.0f};
    double one = 1e30, ten = 1e30, box = 1e30;
    for (int run = 0; run < 5; run++) {
        memcpy(h, h0, sizeof(float) * N * N);
        double t = now();
        erosion_thermal(&g, &tp);
        t = now() - t;
        if (t < one) one = t;
    }
    tp.iterations = 10;
    for (int run = 0; run < 3; run++) {
        memcpy(h, h0, sizeof(float) * N * N);
        double t = now();
        erosion_thermal(&g, &tp);
        t = now() - t;
        if (t / 10 < ten) ten = t / 10;
    }
    for (int run = 0; run < 5; run++) {
        double t = now();
        box3(h0, tmp);
        t = now() - t;
        if (t < box) box = t;
    }
    printf("thermal: 1 iteration on %dx%d: %.2f ms (call), %.2f ms per iteration of 10\n", N, N,
           one * 1e3, ten * 1e3);
    printf("  reference: 3x3 box filter over the grid: %.2f ms\n", box * 1e3);
    free(h0), free(h), free(w), free(tmp);
    return 0;
}
