// Periodic gradient and cellular noise (see the header). Lattice corners are wrapped
// to [0, period) before hashing, which is all it takes to make the noise tile. The
// row functions repeat the point functions' arithmetic exactly, only caching hashes.
#include "renderer/periodic_noise.h"

#include "editor/gen/gen_hash.h"

#include <math.h>

// The largest cellular period the row function takes (its hash cache is on the stack).
#define CELLS_MAX_PERIOD 256

// Texture coordinates are almost always within one period already: skip the division.
static inline int wrap(int i, int p) {
    if ((unsigned)i < (unsigned)p) return i;
    i %= p;
    return i < 0 ? i + p : i;
}

// floor() for |x| < 2^31, exact; floorf is a libm call on baseline x86-64 (no SSE4.1).
static inline int ifloor(float x) {
    const int i = (int)x;
    return (float)i > x ? i - 1 : i;
}

static inline uint32_t corner_hash(uint32_t seed, int ix, int iy) {
    return gen_hash32(((uint32_t)ix * 0x8da6b343u) ^ ((uint32_t)iy * 0xd8163841u) ^ seed);
}

// Quintic fade: zero first and second derivative at the lattice, so no creases.
static inline float fade(float t) {
    return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

// Eight gradients: the axes and the diagonals, all of length 1.
static inline float grad(uint32_t h, float x, float y) {
    static const float g[8][2] = {{1.0f, 0.0f},
                                  {-1.0f, 0.0f},
                                  {0.0f, 1.0f},
                                  {0.0f, -1.0f},
                                  {0.7071068f, 0.7071068f},
                                  {-0.7071068f, 0.7071068f},
                                  {0.7071068f, -0.7071068f},
                                  {-0.7071068f, -0.7071068f}};
    const float *v = g[h >> 29];
    return v[0] * x + v[1] * y;
}

// The four corner hashes of a lattice cell.
typedef struct corners {
    uint32_t h00, h10, h01, h11;
} corners;

static inline corners cell_corners(uint32_t seed, int x0, int y0, int px, int py) {
    const int ix = wrap(x0, px), iy = wrap(y0, py);
    const int ix1 = ix + 1 == px ? 0 : ix + 1, iy1 = iy + 1 == py ? 0 : iy + 1;
    return (corners){corner_hash(seed, ix, iy), corner_hash(seed, ix1, iy),
                     corner_hash(seed, ix, iy1), corner_hash(seed, ix1, iy1)};
}

static inline float blend(const corners *c, float fx, float fy, float uy) {
    const float n00 = grad(c->h00, fx, fy);
    const float n10 = grad(c->h10, fx - 1.0f, fy);
    const float n01 = grad(c->h01, fx, fy - 1.0f);
    const float n11 = grad(c->h11, fx - 1.0f, fy - 1.0f);
    const float ux = fade(fx);
    const float a = n00 + (n10 - n00) * ux, b = n01 + (n11 - n01) * ux;
    // Unit gradients peak near 0.7: scale to about [-1, 1].
    return 1.4142136f * (a + (b - a) * uy);
}

float pnoise(uint32_t seed, float x, float y, int px, int py) {
    const int x0 = ifloor(x), y0 = ifloor(y);
    const corners c = cell_corners(seed, x0, y0, px, py);
    const float fy = y - (float)y0;
    return blend(&c, x - (float)x0, fy, fade(fy));
}

static inline uint32_t octave_seed(uint32_t seed, int i) {
    return seed + (uint32_t)i * 0x9e3779b9u;
}

float pnoise_fbm(uint32_t seed, float x, float y, int p, int octaves, float gain) {
    float sum = 0.0f, amp = 1.0f, norm = 0.0f;
    for (int i = 0; i < octaves; i++) {
        sum += amp * pnoise(octave_seed(seed, i), x, y, p, p);
        norm += amp;
        amp *= gain;
        x *= 2.0f;
        y *= 2.0f;
        p *= 2;
    }
    return sum / norm;
}

pnoise_cell pnoise_cells(uint32_t seed, float x, float y, int p, float jitter) {
    const int cx = ifloor(x), cy = ifloor(y);
    pnoise_cell c = {0.0f, 0.0f, 0.0f, 0.0f, 0u};
    float d1 = 1e30f, d2 = 1e30f; // squared, rooted at the end
    for (int j = -1; j <= 1; j++)
        for (int i = -1; i <= 1; i++) {
            const uint32_t h = corner_hash(seed, wrap(cx + i, p), wrap(cy + j, p));
            // The point lives in the unwrapped cell so distances stay continuous; its
            // offsets are the two halves of the hash.
            const float ox = (float)(h & 0xffffu) * (1.0f / 65536.0f) - 0.5f;
            const float oy = (float)(h >> 16) * (1.0f / 65536.0f) - 0.5f;
            const float dx = x - ((float)(cx + i) + 0.5f + jitter * ox);
            const float dy = y - ((float)(cy + j) + 0.5f + jitter * oy);
            const float d = dx * dx + dy * dy;
            if (d < d1) {
                d2 = d1;
                d1 = d;
                c.dx = dx;
                c.dy = dy;
                c.id = h;
            } else if (d < d2) {
                d2 = d;
            }
        }
    c.f1 = sqrtf(d1);
    c.f2 = sqrtf(d2);
    return c;
}

// Adds amp * pnoise over a row at x = u * px. For the fBm's octaves this is the same
// float as the point function's (u * p) * 2^i: scaling by a power of two is exact. It
// walks the row cell by cell: u * px = i * px / n is exact in float, so the texels of
// lattice cell cx are exactly those with cx * n <= i * px < (cx + 1) * n, and the inner
// loop has no branches. The gradient terms repeat blend()'s arithmetic in its order, so
// the result is bit-identical to pnoise.
static void add_row(uint32_t seed, int px, int py, float y, float amp, int n, float *out) {
    static const float g[8][2] = {{1.0f, 0.0f},
                                  {-1.0f, 0.0f},
                                  {0.0f, 1.0f},
                                  {0.0f, -1.0f},
                                  {0.7071068f, 0.7071068f},
                                  {-0.7071068f, 0.7071068f},
                                  {0.7071068f, -0.7071068f},
                                  {-0.7071068f, -0.7071068f}};
    const int y0 = ifloor(y);
    const float fy = y - (float)y0, uy = fade(fy), fy1 = fy - 1.0f;
    const float inv_n = 1.0f / (float)n; // exact: n is a power of two
    for (int cx = 0, i = 0; cx < px && i < n; cx++) {
        // First texel past this cell: ceil((cx + 1) * n / px), in integers.
        const long long end_ll = ((long long)(cx + 1) * n + px - 1) / px;
        const int end = end_ll < n ? (int)end_ll : n;
        const corners c = cell_corners(seed, cx, y0, px, py);
        const float *g00 = g[c.h00 >> 29], *g10 = g[c.h10 >> 29];
        const float *g01 = g[c.h01 >> 29], *g11 = g[c.h11 >> 29];
        const float a00 = g00[0], b00 = g00[1] * fy, a10 = g10[0], b10 = g10[1] * fy;
        const float a01 = g01[0], b01 = g01[1] * fy1, a11 = g11[0], b11 = g11[1] * fy1;
        const float fcx = (float)cx;
        for (; i < end; i++) {
            const float fx = (float)i * inv_n * (float)px - fcx, fx1 = fx - 1.0f;
            const float n00 = a00 * fx + b00, n10 = a10 * fx1 + b10;
            const float n01 = a01 * fx + b01, n11 = a11 * fx1 + b11;
            const float ux = fade(fx);
            const float lo = n00 + (n10 - n00) * ux, hi = n01 + (n11 - n01) * ux;
            out[i] += amp * (1.4142136f * (lo + (hi - lo) * uy));
        }
    }
}

void pnoise_row(uint32_t seed, int px, int py, float v, int n, float *out) {
    for (int i = 0; i < n; i++)
        out[i] = 0.0f; // 0 + 1 * v is v exactly
    add_row(seed, px, py, v * (float)py, 1.0f, n, out);
}

void pnoise_fbm_row(uint32_t seed, int p, int octaves, float gain, float v, int n, float *out) {
    for (int i = 0; i < n; i++)
        out[i] = 0.0f;
    float amp = 1.0f, norm = 0.0f, y = v * (float)p;
    int pi = p;
    for (int o = 0; o < octaves; o++) {
        add_row(octave_seed(seed, o), pi, pi, y, amp, n, out);
        norm += amp;
        amp *= gain;
        y *= 2.0f;
        pi *= 2;
    }
    for (int i = 0; i < n; i++)
        out[i] /= norm;
}

void pnoise_cells_row(uint32_t seed, int p, float jitter, float v, int n, pnoise_cell *out) {
    const float y = v * (float)p;
    const int cy = ifloor(y);
    const float inv_n = 1.0f / (float)n;
    if (p > CELLS_MAX_PERIOD) { // beyond the cache: the reference
        for (int k = 0; k < n; k++)
            out[k] = pnoise_cells(seed, (float)k * inv_n * (float)p, y, p, jitter);
        return;
    }
    // The points of the three cell rows around y, for cell columns -1 .. p (texels
    // sample x in [0, p), so their 3 x 3 neighbourhoods stay inside), placed exactly as
    // pnoise_cells places them.
    float ptx[3][CELLS_MAX_PERIOD + 2], pty[3][CELLS_MAX_PERIOD + 2];
    uint32_t hash[3][CELLS_MAX_PERIOD + 2];
    for (int j = 0; j < 3; j++)
        for (int i = -1; i <= p; i++) {
            const uint32_t h = corner_hash(seed, wrap(i, p), wrap(cy + j - 1, p));
            const float ox = (float)(h & 0xffffu) * (1.0f / 65536.0f) - 0.5f;
            const float oy = (float)(h >> 16) * (1.0f / 65536.0f) - 0.5f;
            hash[j][i + 1] = h;
            ptx[j][i + 1] = (float)i + 0.5f + jitter * ox;
            pty[j][i + 1] = (float)(cy + j - 1) + 0.5f + jitter * oy;
        }
    for (int k = 0; k < n; k++) {
        const float x = (float)k * inv_n * (float)p;
        const int cx = ifloor(x);
        pnoise_cell c = {0.0f, 0.0f, 0.0f, 0.0f, 0u};
        float d1 = 1e30f, d2 = 1e30f;
        for (int j = 0; j < 3; j++)
            for (int i = cx; i <= cx + 2; i++) {
                const float dx = x - ptx[j][i], dy = y - pty[j][i];
                const float d = dx * dx + dy * dy;
                if (d < d1) {
                    d2 = d1;
                    d1 = d;
                    c.dx = dx;
                    c.dy = dy;
                    c.id = hash[j][i];
                } else if (d < d2) {
                    d2 = d;
                }
            }
        c.f1 = sqrtf(d1);
        c.f2 = sqrtf(d2);
        out[k] = c;
    }
}
