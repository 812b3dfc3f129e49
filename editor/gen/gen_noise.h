// Gradient (Perlin) noise and its fractal sums: fBm with fractional octaves
// (Kahoun 2010) and Musgrave's ridged multifractal. The grid and point entry points
// are the fast paths the generators use; the single-sample functions are the
// reference they must match bit for bit.
//
// Inputs are in noise units: octave 0 has one lattice cell per unit. Positions are
// doubles so that coordinates far from the origin (int32 tiles) keep their
// fractional precision; the lattice wraps at 2^32 cells.
//
// Deterministic: the result depends only on the inputs, never on the thread, the
// batch a sample is computed in, or the SIMD width (the build forbids FMA contraction).
#ifndef OROGEN_EDITOR_GEN_NOISE_H
#define OROGEN_EDITOR_GEN_NOISE_H

#include <stddef.h>
#include <stdint.h>

typedef enum gen_fractal_kind { GEN_FRACTAL_FBM = 0, GEN_FRACTAL_RIDGED = 1 } gen_fractal_kind;

typedef struct gen_fractal {
    gen_fractal_kind kind;
    uint32_t seed;
    double octaves;      // > 0; a fractional part weights the last octave (Kahoun 2010)
    double gain;         // w_factor: amplitude multiplier per octave
    double lacunarity;   // exponent: frequency multiplier per octave
    double ridge_offset; // ridged only (Musgrave's "offset", typically 1.0)
} gen_fractal;

// Single samples (reference implementation).
float gen_noise2(uint32_t seed, double x, double y);           // about [-1, 1]
float gen_noise3(uint32_t seed, double x, double y, double z); // about [-1, 1]
float gen_fractal2(const gen_fractal *f, double x, double y);
float gen_fractal3(const gen_fractal *f, double x, double y, double z);

// Fills out[j * nx + i] = gen_fractal2(f, xs[i], ys[j]) for i < nx, j < ny, bit-identical
// to the reference. The separable grid lets the lattice split be done once per column.
void gen_fractal_grid2(const gen_fractal *f, const double *xs, int nx, const double *ys, int ny,
                       float *out);
// out[i] = gen_fractal3(f, xyz[3i], xyz[3i+1], xyz[3i+2]), bit-identical to the reference.
void gen_fractal_points3(const gen_fractal *f, const double *xyz, size_t n, float *out);

#endif
