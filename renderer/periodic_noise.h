// Periodic noise for tileable textures: gradient noise, its fractal sum and cellular
// (Worley) noise whose lattices wrap after a whole number of cells, so a texture that
// samples them over one period repeats with no seam. Float math and integer hashing
// only (no libm beyond sqrtf, which is exact), so results are the same bytes on every
// machine.
//
// The point functions are the reference; the row functions fill a whole texture row
// at once, bit-identical to them, hashing each lattice cell once per row instead of at
// every texel (5-10 times faster).
#ifndef OROGEN_RENDERER_PERIODIC_NOISE_H
#define OROGEN_RENDERER_PERIODIC_NOISE_H

#include <stdint.h>

// Gradient noise at (x, y) in lattice units, repeating every px cells in x and py
// cells in y (both >= 1). About [-1, 1]; 0 at every lattice point.
float pnoise(uint32_t seed, float x, float y, int px, int py);

// Fractal sum of pnoise: octave i has frequency 2^i and amplitude gain^i, on a lattice
// of p * 2^i cells per period (so every octave wraps with the first). Normalised by
// the sum of amplitudes: about [-1, 1], rarely beyond +-0.7.
float pnoise_fbm(uint32_t seed, float x, float y, int p, int octaves, float gain);

// The nearest and second-nearest feature points of a periodic jittered grid.
typedef struct pnoise_cell {
    float f1, f2; // distances in lattice units to the nearest and second-nearest points
    float dx, dy; // from the nearest point to (x, y)
    uint32_t id;  // hash of the nearest point's cell (the same on every period)
} pnoise_cell;

// Cellular noise: one point per cell, jittered by up to jitter (0..1) of a cell,
// repeating every p cells in both directions.
pnoise_cell pnoise_cells(uint32_t seed, float x, float y, int p, float jitter);

// Rows of a texture n texels wide at height v in [0, 1): texel i samples u = i / n, so
// out[i] = pnoise(seed, u * px, v * py, px, py), and likewise for the others with
// (u * p, v * p). n is a power of two (u is then exact).
void pnoise_row(uint32_t seed, int px, int py, float v, int n, float *out);
void pnoise_fbm_row(uint32_t seed, int p, int octaves, float gain, float v, int n, float *out);
void pnoise_cells_row(uint32_t seed, int p, float jitter, float v, int n, pnoise_cell *out);

// Uniform in [0, 1) from a hash.
static inline float pnoise_unit(uint32_t h) {
    return (float)(h >> 8) * (1.0f / 16777216.0f);
}

#endif
