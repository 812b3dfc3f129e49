// Gradient noise and fractal sums. One set of always-inline kernels is shared by
// the single-sample reference and the batch paths, so every sample goes through
// the same IEEE operations in the same order whatever the batch or SIMD width.
// The batch paths are compiled twice (baseline x86-64 and AVX2) and picked at run time.
#include "editor/gen/gen_noise.h"

#include "editor/gen/gen_hash.h"

#include <math.h>
#include <stdatomic.h>
#include <string.h>

#define INLINE static inline __attribute__((always_inline))

// Octave counts are clamped to this: finer octaves are below what a double
// position far from the origin can resolve anyway.
#define MAX_OCTAVES 32
// Columns per grid chunk and points per block: small enough for stack scratch.
#define CHUNK 64

// Per-axis multipliers that spread lattice coordinates before mixing (odd, so a
// cell index maps to a distinct 32-bit value on each axis).
#define PX 0x9E3779B1u
#define PY 0x85EBCA77u
#define PZ 0xC2B2AE3Du

// Musgrave's feedback gain for the ridged multifractal: a ridge (signal >= 0.5)
// keeps full detail while valleys are smoothed. The amplitude per octave is the
// fractal's own gain, so the struct's one gain keeps its fBm meaning.
#define RIDGE_FEEDBACK 2.0f

// The 3D gradient set (12 cube edges) peaks at 1.0363 near (0.36, 0.48, 0.5) of a
// cell; scale so the output stays within [-1, 1]. The 2D set peaks at exactly 1.
#define NOISE3_SCALE 0.9649f

// Lattice hash: pre is the xor of the per-axis terms. The seed enters between two
// multiply rounds so that changing it scrambles every lattice point independently
// rather than permuting rows or columns. Callers use the top bits.
INLINE uint32_t lattice_hash(uint32_t pre, uint32_t seed) {
    uint32_t h = pre ^ (pre >> 16);
    h *= 0x7FEB352Du;
    h ^= seed ^ (h >> 15);
    h *= 0x846CA68Bu;
    return h;
}

// Branch-free selects on bit patterns. Plain ?: on floats lets GCC move the
// arithmetic into branches, which it then refuses to vectorise (it could trap).
INLINE uint32_t f2u(float f) {
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}
INLINE float u2f(uint32_t u) {
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}
// mask is all ones (take a) or zero (take b).
INLINE float select_f(uint32_t mask, float a, float b) {
    return u2f((f2u(a) & mask) | (f2u(b) & ~mask));
}
// sign is 0 or 0x80000000: the same value as a conditional negation.
INLINE float flip_sign(float x, uint32_t sign) {
    return u2f(f2u(x) ^ sign);
}

INLINE uint64_t d2u(double d) {
    uint64_t u;
    memcpy(&u, &d, sizeof u);
    return u;
}
INLINE double u2d(uint64_t u) {
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

// floor() by adding and removing 2^52 (exact, round-to-nearest), written so that
// GCC vectorises it: its own floor is only vectorised without trapping math.
// Returns the same value as floor() for every input, including -0, NaN and inf.
INLINE double floor_exact(double x) {
    const double big = 4503599627370496.0; // 2^52: from here on every double is an integer
    double ax = fabs(x);
    double r = copysign((ax + big) - big, x);
    uint64_t keep = 0 - (uint64_t)(ax >= big);
    r = u2d((d2u(x) & keep) | (d2u(r) & ~keep));
    uint64_t above = 0 - (uint64_t)(r > x);
    return r - u2d(d2u(1.0) & above);
}

// Splits a position into its lattice cell (wrapped to 32 bits) and the fraction.
// Every step is exact in double: w is the cell index modulo 2^32, and adding 2^52
// puts it in the low mantissa bits. NaN and infinities give a NaN fraction.
INLINE void lattice_split(double p, uint32_t *cell, float *frac) {
    double fl = floor_exact(p);
    double w = fl - 4294967296.0 * floor_exact(fl * (1.0 / 4294967296.0));
    *cell = (uint32_t)d2u(w + 4503599627370496.0);
    *frac = (float)(p - fl);
}

// Quintic fade 6t^5 - 15t^4 + 10t^3: zero first and second derivative at the lattice.
INLINE float fade(float t) {
    return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

INLINE float lerp(float a, float b, float t) {
    return a + t * (b - a);
}

// 2D gradients of length sqrt(2): the four diagonals (+-1, +-1) and the four axes
// (+-sqrt2, 0), (0, +-sqrt2), chosen by the top three hash bits.
INLINE float grad2(uint32_t h, float x, float y) {
    uint32_t g = h >> 29;
    float a = flip_sign(x, (g & 1) << 31);
    float b = flip_sign(y, (g & 1) << 31);
    float c = flip_sign(y, (g & 2) << 30);
    float diag = a + c;
    float axis = 1.41421356f * select_f(0u - ((g >> 1) & 1), a, b);
    return select_f(0u - (g >> 2), axis, diag);
}

// 3D gradients: the 12 cube edge midpoints (+-1, +-1, 0) etc., four of them
// repeated to fill 16 entries (Perlin's improved-noise set).
INLINE float grad3(uint32_t h, float x, float y, float z) {
    uint32_t g = h >> 28;
    float u = select_f((g >> 3) - 1u, x, y);                // g < 8
    float v = select_f(0u - ((g & 13) == 12), x, z);        // g == 12 or 14
    v = select_f(((g >> 2) == 0) ? 0xFFFFFFFFu : 0u, y, v); // g < 4
    return flip_sign(u, (g & 1) << 31) + flip_sign(v, (g & 2) << 30);
}

// One 2D noise value from the cell's hashed axis terms (hx = cell_x * PX, and so
// on), the fractions and their fades.
INLINE float noise2_cell(uint32_t hx, uint32_t hy, uint32_t seed, float fx, float fy, float ux,
                         float uy) {
    uint32_t hx1 = hx + PX, hy1 = hy + PY;
    float fx1 = fx - 1.0f, fy1 = fy - 1.0f;
    float n00 = grad2(lattice_hash(hx ^ hy, seed), fx, fy);
    float n10 = grad2(lattice_hash(hx1 ^ hy, seed), fx1, fy);
    float n01 = grad2(lattice_hash(hx ^ hy1, seed), fx, fy1);
    float n11 = grad2(lattice_hash(hx1 ^ hy1, seed), fx1, fy1);
    return lerp(lerp(n00, n10, ux), lerp(n01, n11, ux), uy);
}

INLINE float noise3_cell(uint32_t hx, uint32_t hy, uint32_t hz, uint32_t seed, float fx, float fy,
                         float fz) {
    uint32_t hx1 = hx + PX, hy1 = hy + PY, hz1 = hz + PZ;
    float fx1 = fx - 1.0f, fy1 = fy - 1.0f, fz1 = fz - 1.0f;
    float ux = fade(fx), uy = fade(fy), uz = fade(fz);
    uint32_t a0 = hy ^ hz, a1 = hy1 ^ hz, a2 = hy ^ hz1, a3 = hy1 ^ hz1;
    float n000 = grad3(lattice_hash(hx ^ a0, seed), fx, fy, fz);
    float n100 = grad3(lattice_hash(hx1 ^ a0, seed), fx1, fy, fz);
    float n010 = grad3(lattice_hash(hx ^ a1, seed), fx, fy1, fz);
    float n110 = grad3(lattice_hash(hx1 ^ a1, seed), fx1, fy1, fz);
    float n001 = grad3(lattice_hash(hx ^ a2, seed), fx, fy, fz1);
    float n101 = grad3(lattice_hash(hx1 ^ a2, seed), fx1, fy, fz1);
    float n011 = grad3(lattice_hash(hx ^ a3, seed), fx, fy1, fz1);
    float n111 = grad3(lattice_hash(hx1 ^ a3, seed), fx1, fy1, fz1);
    float y0 = lerp(lerp(n000, n100, ux), lerp(n010, n110, ux), uy);
    float y1 = lerp(lerp(n001, n101, ux), lerp(n011, n111, ux), uy);
    return NOISE3_SCALE * lerp(y0, y1, uz);
}

float gen_noise2(uint32_t seed, double x, double y) {
    uint32_t cx, cy;
    float fx, fy;
    lattice_split(x, &cx, &fx);
    lattice_split(y, &cy, &fy);
    return noise2_cell(cx * PX, cy * PY, gen_hash32(seed), fx, fy, fade(fx), fade(fy));
}

float gen_noise3(uint32_t seed, double x, double y, double z) {
    uint32_t cx, cy, cz;
    float fx, fy, fz;
    lattice_split(x, &cx, &fx);
    lattice_split(y, &cy, &fy);
    lattice_split(z, &cz, &fz);
    return noise3_cell(cx * PX, cy * PY, cz * PZ, gen_hash32(seed), fx, fy, fz);
}

// Everything a fractal evaluation needs per octave, derived once from the
// parameters so the reference and the batch paths read identical constants.
typedef struct octave_plan {
    int count;  // octaves evaluated, including a partial last one
    int ridged; // GEN_FRACTAL_RIDGED
    float ridge_offset;
    float ridge_scale; // ridged: maps [0, offset^2 * sum(amp)] onto [-1, 1]
    double freq[MAX_OCTAVES + 1];
    double off[MAX_OCTAVES + 1][3];
    float amp[MAX_OCTAVES + 1];
    uint32_t seed[MAX_OCTAVES + 1];
} octave_plan;

static void plan_octaves(const gen_fractal *f, octave_plan *pl) {
    double k = f->octaves;
    if (!(k > 0.0)) k = 0.0;
    if (k > MAX_OCTAVES) k = MAX_OCTAVES;
    int full = (int)k;
    double partial = k - full;
    pl->count = full + (partial > 0.0);
    pl->ridged = f->kind == GEN_FRACTAL_RIDGED;
    pl->ridge_offset = (float)f->ridge_offset;
    double w = 1.0, n = 1.0, sum = 0.0;
    for (int o = 0; o < pl->count; o++) {
        double a = o < full ? w : partial * w;
        pl->amp[o] = (float)a;
        sum += a;
        pl->freq[o] = n;
        // A distinct seed and a sub-cell offset per octave: octaves are not scaled
        // copies of each other and their lattices never line up at the origin.
        uint32_t s = gen_hash32(f->seed + 0x9E3779B9u * (uint32_t)(o + 1));
        pl->seed[o] = s;
        for (int axis = 0; axis < 3; axis++) {
            uint32_t h = gen_hash32(s + 0x632BE5ABu * (uint32_t)(axis + 1));
            pl->off[o][axis] = 0.125 + 0.75 * (double)(h >> 8) * (1.0 / 16777216.0);
        }
        w *= f->gain;
        n *= f->lacunarity;
    }
    double peak = f->ridge_offset * f->ridge_offset * sum;
    pl->ridge_scale = peak > 0.0 ? (float)(2.0 / peak) : 0.0f;
}

// Adds octave o's noise value v to the running sum; ridged also carries the
// previous octave's weighted signal in *prev (1 before the first octave).
INLINE float fbm_step(float acc, float amp, float v) {
    return acc + amp * v;
}

INLINE float ridged_step(float acc, float *prev, float amp, float offset, float v) {
    float s = offset - fabsf(v);
    s = s * s;
    float weight = *prev * RIDGE_FEEDBACK;
    weight = select_f(0u - (weight > 1.0f), 1.0f, weight);
    s = s * weight;
    *prev = s;
    return acc + s * amp;
}

INLINE float ridged_finish(const octave_plan *pl, float acc) {
    return acc * pl->ridge_scale - 1.0f;
}

float gen_fractal2(const gen_fractal *f, double x, double y) {
    octave_plan pl;
    plan_octaves(f, &pl);
    float acc = 0.0f, prev = 1.0f;
    for (int o = 0; o < pl.count; o++) {
        uint32_t cx, cy;
        float fx, fy;
        lattice_split(x * pl.freq[o] + pl.off[o][0], &cx, &fx);
        lattice_split(y * pl.freq[o] + pl.off[o][1], &cy, &fy);
        float v = noise2_cell(cx * PX, cy * PY, pl.seed[o], fx, fy, fade(fx), fade(fy));
        acc = pl.ridged ? ridged_step(acc, &prev, pl.amp[o], pl.ridge_offset, v)
                        : fbm_step(acc, pl.amp[o], v);
    }
    return pl.ridged ? ridged_finish(&pl, acc) : acc;
}

float gen_fractal3(const gen_fractal *f, double x, double y, double z) {
    octave_plan pl;
    plan_octaves(f, &pl);
    float acc = 0.0f, prev = 1.0f;
    for (int o = 0; o < pl.count; o++) {
        uint32_t cx, cy, cz;
        float fx, fy, fz;
        lattice_split(x * pl.freq[o] + pl.off[o][0], &cx, &fx);
        lattice_split(y * pl.freq[o] + pl.off[o][1], &cy, &fy);
        lattice_split(z * pl.freq[o] + pl.off[o][2], &cz, &fz);
        float v = noise3_cell(cx * PX, cy * PY, cz * PZ, pl.seed[o], fx, fy, fz);
        acc = pl.ridged ? ridged_step(acc, &prev, pl.amp[o], pl.ridge_offset, v)
                        : fbm_step(acc, pl.amp[o], v);
    }
    return pl.ridged ? ridged_finish(&pl, acc) : acc;
}

// Grid path: per chunk of columns, the column split (cell term, fraction, fade) is
// done once per octave; each row then splits its y once per octave and runs the
// branch-free inner loops over the chunk.
INLINE void grid2_body(const octave_plan *pl, const double *xs, int nx, const double *ys, int ny,
                       float *out) {
    uint32_t chx[MAX_OCTAVES + 1][CHUNK];
    float cfx[MAX_OCTAVES + 1][CHUNK], cux[MAX_OCTAVES + 1][CHUNK];
    for (int i0 = 0; i0 < nx; i0 += CHUNK) {
        int m = nx - i0 < CHUNK ? nx - i0 : CHUNK;
        for (int o = 0; o < pl->count; o++) {
            double fr = pl->freq[o], off = pl->off[o][0];
            for (int i = 0; i < m; i++) {
                uint32_t c;
                float fx;
                lattice_split(xs[i0 + i] * fr + off, &c, &fx);
                chx[o][i] = c * PX;
                cfx[o][i] = fx;
                cux[o][i] = fade(fx);
            }
        }
        for (int j = 0; j < ny; j++) {
            float acc[CHUNK], prev[CHUNK];
            for (int i = 0; i < m; i++)
                acc[i] = 0.0f, prev[i] = 1.0f;
            for (int o = 0; o < pl->count; o++) {
                uint32_t cy;
                float fy;
                lattice_split(ys[j] * pl->freq[o] + pl->off[o][1], &cy, &fy);
                uint32_t hy = cy * PY, seed = pl->seed[o];
                float uy = fade(fy), amp = pl->amp[o];
                const uint32_t *hx = chx[o];
                const float *fx = cfx[o], *ux = cux[o];
                if (pl->ridged) {
                    float offset = pl->ridge_offset;
                    for (int i = 0; i < m; i++) {
                        float v = noise2_cell(hx[i], hy, seed, fx[i], fy, ux[i], uy);
                        acc[i] = ridged_step(acc[i], &prev[i], amp, offset, v);
                    }
                } else {
                    for (int i = 0; i < m; i++) {
                        float v = noise2_cell(hx[i], hy, seed, fx[i], fy, ux[i], uy);
                        acc[i] = fbm_step(acc[i], amp, v);
                    }
                }
            }
            float *row = out + (size_t)j * (size_t)nx + (size_t)i0;
            if (pl->ridged) {
                for (int i = 0; i < m; i++)
                    row[i] = ridged_finish(pl, acc[i]);
            } else {
                for (int i = 0; i < m; i++)
                    row[i] = acc[i];
            }
        }
    }
}

// Points path: per block, the positions are deinterleaved once; each octave
// splits them (double, 4 lanes) and then evaluates the noise (float, 8 lanes).
INLINE void points3_body(const octave_plan *pl, const double *xyz, size_t n, float *out) {
    for (size_t b = 0; b < n; b += CHUNK) {
        int m = n - b < CHUNK ? (int)(n - b) : CHUNK;
        double px[CHUNK], py[CHUNK], pz[CHUNK];
        for (int i = 0; i < m; i++) {
            px[i] = xyz[3 * (b + i)];
            py[i] = xyz[3 * (b + i) + 1];
            pz[i] = xyz[3 * (b + i) + 2];
        }
        float acc[CHUNK], prev[CHUNK];
        for (int i = 0; i < m; i++)
            acc[i] = 0.0f, prev[i] = 1.0f;
        for (int o = 0; o < pl->count; o++) {
            uint32_t hx[CHUNK], hy[CHUNK], hz[CHUNK];
            float fx[CHUNK], fy[CHUNK], fz[CHUNK];
            double fr = pl->freq[o], ox = pl->off[o][0], oy = pl->off[o][1], oz = pl->off[o][2];
            for (int i = 0; i < m; i++) {
                uint32_t c;
                lattice_split(px[i] * fr + ox, &c, &fx[i]);
                hx[i] = c * PX;
                lattice_split(py[i] * fr + oy, &c, &fy[i]);
                hy[i] = c * PY;
                lattice_split(pz[i] * fr + oz, &c, &fz[i]);
                hz[i] = c * PZ;
            }
            uint32_t seed = pl->seed[o];
            float amp = pl->amp[o];
            if (pl->ridged) {
                float offset = pl->ridge_offset;
                for (int i = 0; i < m; i++) {
                    float v = noise3_cell(hx[i], hy[i], hz[i], seed, fx[i], fy[i], fz[i]);
                    acc[i] = ridged_step(acc[i], &prev[i], amp, offset, v);
                }
            } else {
                for (int i = 0; i < m; i++) {
                    float v = noise3_cell(hx[i], hy[i], hz[i], seed, fx[i], fy[i], fz[i]);
                    acc[i] = fbm_step(acc[i], amp, v);
                }
            }
        }
        if (pl->ridged) {
            for (int i = 0; i < m; i++)
                out[b + i] = ridged_finish(pl, acc[i]);
        } else {
            for (int i = 0; i < m; i++)
                out[b + i] = acc[i];
        }
    }
}

static void grid2_base(const octave_plan *pl, const double *xs, int nx, const double *ys, int ny,
                       float *out) {
    grid2_body(pl, xs, nx, ys, ny, out);
}

static void points3_base(const octave_plan *pl, const double *xyz, size_t n, float *out) {
    points3_body(pl, xyz, n, out);
}

#if defined(__x86_64__) || defined(__i386__)
#define HAVE_AVX2_PATH 1
__attribute__((target("avx2"))) static void
grid2_avx2(const octave_plan *pl, const double *xs, int nx, const double *ys, int ny, float *out) {
    grid2_body(pl, xs, nx, ys, ny, out);
}

__attribute__((target("avx2"))) static void points3_avx2(const octave_plan *pl, const double *xyz,
                                                         size_t n, float *out) {
    points3_body(pl, xyz, n, out);
}
#endif

// Test hook (not in the header): 0 forces the baseline kernels so tests can check
// that both builds of the batch paths agree with the reference.
void gen_noise_allow_avx2(int allow);
static atomic_int allow_avx2 = 1;
void gen_noise_allow_avx2(int allow) {
    atomic_store(&allow_avx2, allow);
}

static int use_avx2(void) {
#ifdef HAVE_AVX2_PATH
    return atomic_load_explicit(&allow_avx2, memory_order_relaxed) &&
           __builtin_cpu_supports("avx2");
#else
    return 0;
#endif
}

void gen_fractal_grid2(const gen_fractal *f, const double *xs, int nx, const double *ys, int ny,
                       float *out) {
    if (nx <= 0 || ny <= 0) return;
    octave_plan pl;
    plan_octaves(f, &pl);
#ifdef HAVE_AVX2_PATH
    if (use_avx2()) {
        grid2_avx2(&pl, xs, nx, ys, ny, out);
        return;
    }
#endif
    grid2_base(&pl, xs, nx, ys, ny, out);
}

void gen_fractal_points3(const gen_fractal *f, const double *xyz, size_t n, float *out) {
    if (n == 0) return;
    octave_plan pl;
    plan_octaves(f, &pl);
#ifdef HAVE_AVX2_PATH
    if (use_avx2()) {
        points3_avx2(&pl, xyz, n, out);
        return;
    }
#endif
    points3_base(&pl, xyz, n, out);
}
