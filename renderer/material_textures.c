// The eight material recipes. Each fills one texture row from rows of periodic noise
// (renderer/periodic_noise.h): albedo in sRGB and a height in [0, 1]. Everything
// sampled is periodic over the unit square with whole-number periods, so the texture
// tiles. Shading that does not depend on the sun (gaps, creases and the undersides of
// stones darker) is baked into the albedo: it is what makes stones and blades read
// without a normal map.
#include "renderer/material_textures.h"

#include "editor/gen/gen_hash.h"
#include "renderer/periodic_noise.h"

#include <math.h>
#include <stddef.h>

#define N MATERIAL_TEXTURE_SIZE

typedef void (*recipe_fn)(int y, unsigned char *row);

typedef struct rgb {
    float r, g, b;
} rgb;

static inline float clamp01(float x) {
    return x < 0.0f ? 0.0f : x > 1.0f ? 1.0f : x;
}
static inline float absf(float x) {
    return x < 0.0f ? -x : x;
}
static inline float mixf(float a, float b, float t) {
    return a + (b - a) * t;
}
static inline float smooth(float e0, float e1, float x) {
    const float t = clamp01((x - e0) / (e1 - e0));
    return t * t * (3.0f - 2.0f * t);
}
// floor() for |x| < 2^31, exact, without a libm call (no SSE4.1 on baseline x86-64).
static inline int ifloor(float x) {
    const int i = (int)x;
    return (float)i > x ? i - 1 : i;
}
static inline float fract(float x) {
    return x - (float)ifloor(x);
}
static inline int wrap(int i, int p) {
    i %= p;
    return i < 0 ? i + p : i;
}
static inline float hash01(uint32_t h) {
    return pnoise_unit(gen_hash32(h));
}

static inline rgb mixc(rgb a, rgb b, float t) {
    return (rgb){mixf(a.r, b.r, t), mixf(a.g, b.g, t), mixf(a.b, b.b, t)};
}
static inline rgb scalec(rgb a, float s) {
    return (rgb){a.r * s, a.g * s, a.b * s};
}
static inline rgb byte_rgb(int r, int g, int b) {
    return (rgb){(float)r / 255.0f, (float)g / 255.0f, (float)b / 255.0f};
}

static inline unsigned char to_byte(float x) {
    return (unsigned char)(clamp01(x) * 255.0f + 0.5f);
}
static inline void put(unsigned char *row, int x, rgb c, float h) {
    unsigned char *p = row + 4 * x;
    p[0] = to_byte(c.r);
    p[1] = to_byte(c.g);
    p[2] = to_byte(c.b);
    p[3] = to_byte(h);
}

// Per-texel hash: periodic because it is indexed by the texel itself.
static inline uint32_t texel_hash(uint32_t seed, int x, int y) {
    return gen_hash32(seed ^ (uint32_t)(y * N + x) * 0x9e3779b1u);
}
// Per-texel grain in [-1, 1).
static inline float grain(uint32_t seed, int x, int y) {
    return gen_hash_unit(texel_hash(seed, x, y));
}

static inline float texel_u(int x) {
    return (float)x * (1.0f / (float)N);
}

// Sand: warm beige, wind ripples with a gentle stoss side and a steep lee, a finer
// cross set of ripples, dark mineral grains and bright quartz.
static void sand(int y, unsigned char *row) {
    const float v = texel_u(y);
    float warp[N], patches[N], fine[N];
    pnoise_fbm_row(101, 3, 3, 0.5f, v, N, warp);
    pnoise_fbm_row(103, 2, 4, 0.5f, v, N, patches);
    pnoise_fbm_row(107, 32, 2, 0.5f, v, N, fine);
    for (int x = 0; x < N; x++) {
        const float u = texel_u(x);
        // Crests run along 9u + 2v = const (whole numbers: periodic).
        const float f = fract(9.0f * u + 2.0f * v + 0.9f * warp[x]);
        const float ripple = f < 0.72f ? smooth(0.0f, 0.72f, f) : smooth(1.0f, 0.72f, f);
        const float f2 = fract(3.0f * u - 17.0f * v + 0.5f * warp[x]);
        const float small = f2 < 0.6f ? smooth(0.0f, 0.6f, f2) : smooth(1.0f, 0.6f, f2);
        const float lee = f >= 0.72f ? 1.0f : 0.0f;
        rgb c =
            mixc(byte_rgb(196, 164, 118), byte_rgb(222, 196, 152), smooth(-0.5f, 0.5f, patches[x]));
        c = scalec(c, 0.90f + 0.12f * ripple - 0.04f * lee + 0.02f * small + 0.03f * fine[x]);
        const uint32_t gh = texel_hash(0x51ed, x, y);
        if ((gh & 31u) == 0)
            c = scalec(c, 0.78f); // dark mineral grains
        else if ((gh & 63u) == 1)
            c = mixc(c, (rgb){1.0f, 0.97f, 0.92f}, 0.5f); // quartz
        c = scalec(c, 1.0f + 0.035f * gen_hash_unit(gen_hash32(gh)));
        put(row, x, c, 0.15f + 0.6f * ripple + 0.1f * small + 0.15f * fine[x]);
    }
}

// A grass blade: a tapered segment from its root, at most one cell long.
typedef struct blade {
    float ax, ay; // root, in cell units
    float dx, dy; // unit direction
    float len, width;
    float mx, my, r2; // midpoint and squared radius of a disc holding the whole blade
    float inv_len;
    float h; // height of the blade's tip
    uint32_t id;
} blade;

// The blades rooted in the three cell rows around cell row cy (columns -1 .. g) of a
// g x g grid; one per cell, so the 3 x 3 cells around a texel hold every blade that can
// cover it.
static void blade_rows(uint32_t seed, int g, int cy, blade out[3][34]) {
    const float wscale = (float)g / 24.0f; // widths are set for a 24-cell grid
    for (int j = 0; j < 3; j++)
        for (int i = -1; i <= g; i++) {
            const int cx = i, cyy = cy + j - 1;
            const uint32_t h = gen_hash_3(seed, (uint32_t)wrap(cx, g), (uint32_t)wrap(cyy, g));
            const uint32_t h2 = gen_hash32(h);
            blade *b = &out[j][i + 1];
            b->ax = (float)cx + (float)(h & 0xffffu) * (1.0f / 65536.0f);
            b->ay = (float)cyy + (float)(h >> 16) * (1.0f / 65536.0f);
            // Leaning one way, as if combed by the wind, with spread.
            float dx = (float)(h2 & 0xffu) * (1.0f / 128.0f) - 0.65f;
            float dy = (float)((h2 >> 8) & 0xffu) * (1.0f / 128.0f) - 1.55f;
            float len2 = dx * dx + dy * dy;
            if (len2 < 1e-4f) dx = 1.0f, dy = 0.0f, len2 = 1.0f;
            const float r = 1.0f / sqrtf(len2); // sqrtf is correctly rounded: deterministic
            b->dx = dx * r;
            b->dy = dy * r;
            b->len = 0.55f + 0.45f * (float)((h2 >> 16) & 0xffu) * (1.0f / 256.0f);
            b->width = (0.07f + 0.05f * (float)(h2 >> 24) * (1.0f / 256.0f)) * wscale;
            b->h = 0.45f + 0.3f * (float)(h & 0xffu) * (1.0f / 256.0f);
            b->id = h2;
            b->inv_len = 1.0f / b->len;
            b->mx = b->ax + 0.5f * b->len * b->dx;
            b->my = b->ay + 0.5f * b->len * b->dy;
            // Half the length, the widest width and the anti-aliasing half texel (at
            // most 32 / 256 / 2 cell for the finest grid; 0.1 is generous).
            const float reach = 0.5f * b->len + b->width + 0.1f;
            b->r2 = reach * reach;
        }
}

// The highest blade point covering (x, y) among the 3 x 3 cells around it: a tiny
// z-buffer. Returns its coverage (0: none) and fills the blade and the position t
// along it (0 root, 1 tip).
static float blade_at(const blade rows[3][34], float x, float y, float px_cell, const blade **hit,
                      float *t_hit) {
    const int cx = ifloor(x);
    float best = -1.0f, cover_best = 0.0f;
    for (int j = 0; j < 3; j++)
        for (int i = cx; i <= cx + 2; i++) {
            const blade *b = &rows[j][i];
            // Most blades are nowhere near: test their bounding disc first.
            const float mx = x - b->mx, my = y - b->my;
            if (mx * mx + my * my > b->r2) continue;
            const float qx = x - b->ax, qy = y - b->ay;
            const float t = clamp01((qx * b->dx + qy * b->dy) * b->inv_len);
            const float ex = qx - b->dx * t * b->len, ey = qy - b->dy * t * b->len;
            const float w = b->width * (1.0f - 0.8f * t) + 0.5f * px_cell;
            const float d2 = ex * ex + ey * ey;
            if (d2 >= w * w) continue;
            const float bh = b->h * (0.5f + 0.5f * t);
            if (bh <= best) continue;
            best = bh;
            cover_best = smooth(w, w - px_cell, sqrtf(d2));
            *hit = b;
            *t_hit = t;
        }
    return cover_best;
}

// Grass: a dark tangle of stems under three layers of blades in varied greens, in
// clumps that are lusher or drier.
static void grass(int y, unsigned char *row) {
    const float v = texel_u(y);
    float clump[N], dry[N], under[N];
    pnoise_fbm_row(201, 3, 4, 0.55f, v, N, clump);
    pnoise_fbm_row(203, 2, 3, 0.5f, v, N, dry);
    pnoise_fbm_row(205, 24, 2, 0.5f, v, N, under);
    enum { LAYERS = 3 };
    static const int grids[LAYERS] = {20, 26, 32};
    blade rows[LAYERS][3][34];
    for (int l = 0; l < LAYERS; l++)
        blade_rows(211 + (uint32_t)l * 7919u, grids[l], ifloor(v * (float)grids[l]), rows[l]);
    for (int x = 0; x < N; x++) {
        const float u = texel_u(x);
        rgb c = mixc(byte_rgb(38, 52, 16), byte_rgb(64, 78, 26), 0.5f + 0.5f * under[x]);
        float h = 0.1f + 0.1f * under[x];
        const float d = smooth(0.1f, 0.6f, dry[x]);
        for (int l = 0; l < LAYERS; l++) {
            const float g = (float)grids[l];
            const blade *b = NULL;
            float t = 0.0f;
            const float cover = blade_at(rows[l], u * g, v * g, g / (float)N, &b, &t);
            if (cover <= 0.0f) continue;
            const float hue = hash01(b->id ^ 0x6a55u);
            rgb bc = mixc(byte_rgb(64, 104, 30), byte_rgb(106, 142, 44), hue);
            bc = mixc(bc, byte_rgb(150, 150, 70), d * (0.3f + 0.5f * hue));
            bc = mixc(bc, byte_rgb(44, 78, 22), smooth(0.3f, -0.4f, clump[x]) * 0.7f);
            // Lighter towards the tip, and each layer up a little brighter (less shaded).
            bc = scalec(bc, (0.72f + 0.18f * (float)l) * (0.85f + 0.3f * t));
            const float bh = 0.2f + 0.25f * (float)l + 0.3f * b->h * (0.5f + 0.5f * t);
            if (bh > h) {
                c = mixc(c, bc, cover);
                h = mixf(h, bh, cover);
            }
        }
        c = scalec(c, 1.0f + 0.04f * grain(219, x, y));
        put(row, x, c, h * (0.75f + 0.25f * (0.5f + 0.5f * clump[x])));
    }
}

// Cracks from the edges of a cellular pattern: 0 on a crack, 1 away from any. The edge
// distance is wobbled by a noise so cracks wander, and a mask keeps only some of them
// so they never form a closed net.
static inline float crack(const pnoise_cell *cell, float wobble, float mask, float width) {
    const float edge = cell->f2 - cell->f1 + wobble;
    return 1.0f - (1.0f - smooth(0.0f, width, edge)) * (1.0f - mask);
}

// Rock: grey-brown, bedded in gently folded strata, with cracks and grain.
static void rock(int y, unsigned char *row) {
    const float v = texel_u(y);
    float big[N], fold[N], fine[N], wob1[N], wob2[N], mask1[N], mask2[N];
    pnoise_cell c1[N], c2[N];
    pnoise_fbm_row(301, 4, 5, 0.55f, v, N, big);
    pnoise_fbm_row(303, 2, 2, 0.5f, v, N, fold);
    pnoise_fbm_row(307, 32, 2, 0.6f, v, N, fine);
    pnoise_fbm_row(311, 16, 2, 0.5f, v, N, wob1);
    pnoise_fbm_row(312, 40, 2, 0.5f, v, N, wob2);
    pnoise_row(313, 3, 3, v, N, mask1);
    pnoise_row(314, 3, 3, v, N, mask2);
    pnoise_cells_row(315, 5, 0.9f, v, N, c1);
    pnoise_cells_row(316, 13, 0.9f, v, N, c2);
    for (int x = 0; x < N; x++) {
        // 11 layers per repeat; the layer index mod 11 so the colours repeat too.
        const float s = 11.0f * v + 1.2f * fold[x] + 0.25f * big[x];
        const int layer = ifloor(s);
        const float within = s - (float)layer;
        const float lh = hash01(gen_hash_3(305, (uint32_t)wrap(layer, 11), 0));
        const float k = crack(&c1[x], 0.12f * wob1[x], smooth(0.4f, 0.7f, 0.5f + mask1[x]), 0.06f) *
                        (0.6f + 0.4f * crack(&c2[x], 0.1f * wob2[x],
                                             smooth(0.3f, 0.6f, 0.5f + mask2[x]), 0.05f));
        rgb c = mixc(byte_rgb(116, 110, 102), byte_rgb(130, 114, 96), lh);
        c = mixc(c, byte_rgb(152, 148, 140), smooth(0.0f, 0.6f, big[x]) * 0.6f);
        c = mixc(c, byte_rgb(84, 78, 72), smooth(0.0f, -0.6f, big[x]) * 0.6f);
        // Bedding planes: a thin darker seam at the bottom of each layer.
        const float seam = smooth(0.0f, 0.08f, within);
        c = scalec(c, (0.8f + 0.2f * seam) * (0.9f + 0.1f * fine[x]) * (0.45f + 0.55f * k));
        c = scalec(c, 1.0f + 0.05f * grain(309, x, y));
        float h = 0.5f + 0.25f * big[x] + 0.12f * lh + 0.1f * fine[x];
        put(row, x, c, h * (0.6f + 0.4f * seam) * (0.4f + 0.6f * k));
    }
}

// Snow: bright and soft drifts; small hollows a little bluer, faint wind-packed
// streaks, rare glints.
static void snow(int y, unsigned char *row) {
    const float v = texel_u(y);
    float soft[N], bumps[N], wind1[N], wind2[N], crust[N];
    pnoise_fbm_row(401, 2, 3, 0.5f, v, N, soft);
    pnoise_fbm_row(402, 8, 3, 0.5f, v, N, bumps);
    pnoise_row(403, 2, 12, v, N, wind1);
    pnoise_row(404, 4, 28, v, N, wind2);
    pnoise_row(406, 48, 48, v, N, crust);
    for (int x = 0; x < N; x++) {
        const float wind = 0.6f * wind1[x] + 0.3f * wind2[x];
        const float h =
            clamp01(0.5f + 0.35f * soft[x] + 0.35f * bumps[x] + 0.08f * wind + 0.03f * crust[x]);
        const float shade = 0.5f + 0.8f * bumps[x] + 0.2f * soft[x] + 0.1f * wind;
        rgb c = mixc(byte_rgb(224, 233, 247), byte_rgb(248, 250, 253), smooth(0.0f, 0.8f, shade));
        c = scalec(c, 1.0f + 0.01f * crust[x] + 0.01f * grain(405, x, y));
        if ((texel_hash(0x5a0, x, y) & 1023u) == 0) c = (rgb){1.0f, 1.0f, 1.0f};
        put(row, x, c, h);
    }
}

// A scattered stone in a fraction of the cells of a cellular pattern: oval, with a
// wobbly outline.
typedef struct stone {
    float dome;  // 0 outside, rising to 1 at the centre
    float rim;   // 1 just outside the stone, for the soil's contact shadow
    float cover; // anti-aliased coverage
    uint32_t id;
} stone;

static stone pebble(const pnoise_cell *cell, float wobble, int p, float density, float rmin,
                    float rmax) {
    stone s = {0.0f, 0.0f, 0.0f, cell->id};
    if (hash01(cell->id ^ 0x77u) >= density) return s;
    const float r = mixf(rmin, rmax, hash01(cell->id)) * (1.0f + 0.18f * wobble);
    const float q = gen_hash_unit(gen_hash32(cell->id ^ 0x99u));
    const float ax = cell->dx + q * cell->dy * 0.6f, ay = cell->dy * (1.0f + 0.4f * q);
    const float d = sqrtf(ax * ax + ay * ay);
    const float px = (float)p / (float)N;
    s.cover = smooth(r, r - px, d);
    s.dome = s.cover * sqrtf(clamp01(1.0f - (d / r) * (d / r)));
    s.rim = smooth(r + 0.18f, r, d) * (1.0f - s.cover);
    return s;
}

static rgb stone_colour(uint32_t id, rgb a, rgb b) {
    return scalec(mixc(a, b, hash01(id ^ 0xc0104u)), 0.8f + 0.4f * hash01(id ^ 0x11u));
}

// Dirt: brown soil, damp and dry patches, crumbs, and scattered pebbles.
static void dirt(int y, unsigned char *row) {
    const float v = texel_u(y);
    float patches[N], crumbs[N], wob1[N], wob2[N];
    pnoise_cell c1[N], c2[N];
    pnoise_fbm_row(501, 3, 4, 0.55f, v, N, patches);
    pnoise_fbm_row(503, 24, 3, 0.6f, v, N, crumbs);
    pnoise_row(504, 36, 36, v, N, wob1);
    pnoise_row(506, 88, 88, v, N, wob2);
    pnoise_cells_row(505, 9, 0.7f, v, N, c1);
    pnoise_cells_row(507, 22, 0.7f, v, N, c2);
    for (int x = 0; x < N; x++) {
        rgb c = mixc(byte_rgb(82, 60, 42), byte_rgb(122, 94, 66), smooth(-0.4f, 0.5f, patches[x]));
        c = scalec(c, 0.88f + 0.22f * smooth(-0.5f, 0.6f, crumbs[x]));
        float h = 0.25f + 0.15f * patches[x] + 0.12f * crumbs[x];
        const stone big = pebble(&c1[x], wob1[x], 9, 0.45f, 0.18f, 0.32f);
        const stone small = pebble(&c2[x], wob2[x], 22, 0.5f, 0.14f, 0.28f);
        c = scalec(c, 1.0f - 0.3f * (big.rim > small.rim ? big.rim : small.rim));
        const stone *st[2] = {&small, &big};
        for (int k = 0; k < 2; k++) {
            if (st[k]->cover <= 0.0f) continue;
            const rgb sc =
                stone_colour(st[k]->id, byte_rgb(128, 116, 102), byte_rgb(150, 128, 100));
            c = mixc(c, scalec(sc, 0.7f + 0.35f * st[k]->dome), st[k]->cover);
            h = mixf(h, 0.55f + 0.4f * st[k]->dome * (k == 1 ? 1.0f : 0.7f), st[k]->cover);
        }
        c = scalec(c, 1.0f + 0.06f * grain(509, x, y));
        put(row, x, c, h);
    }
}

// Gravel: packed rounded stones in greys with warm and cool tints, dark fines in the
// gaps; a layer of small stones under a layer of larger ones.
static void gravel(int y, unsigned char *row) {
    const float v = texel_u(y);
    enum { LAYERS = 2 };
    static const int grids[LAYERS] = {30, 16};
    float fines[N], speck[N], wob[LAYERS][N];
    pnoise_cell cells[LAYERS][N];
    pnoise_fbm_row(601, 48, 2, 0.5f, v, N, fines);
    pnoise_row(617, 96, 96, v, N, speck);
    for (int l = 0; l < LAYERS; l++) {
        pnoise_row(611 + (uint32_t)l, 64, 64, v, N, wob[l]);
        pnoise_cells_row(613 + (uint32_t)l, grids[l], 0.85f, v, N, cells[l]);
    }
    for (int x = 0; x < N; x++) {
        rgb c = scalec(byte_rgb(52, 49, 46), 0.85f + 0.3f * (0.5f + 0.5f * fines[x]));
        float h = 0.08f + 0.08f * fines[x], best = 0.0f;
        for (int l = 0; l < LAYERS; l++) {
            const pnoise_cell *cell = &cells[l][x];
            const float edge = cell->f2 - cell->f1 + 0.06f * wob[l][x];
            const float px = (float)grids[l] / (float)N;
            const float gap = 0.08f + 0.06f * hash01(cell->id ^ 0x3u);
            const float cover = smooth(gap, gap + px, edge);
            if (cover <= 0.0f) continue;
            const float dome = smooth(gap, gap + 0.45f, edge);
            const float sh = (0.35f + 0.35f * (float)l) * (0.6f + 0.4f * dome);
            if (sh < best) continue;
            best = sh;
            rgb sc = (cell->id & 7u) == 0
                         ? stone_colour(cell->id, byte_rgb(90, 92, 96), byte_rgb(70, 72, 76))
                         : stone_colour(cell->id, byte_rgb(120, 118, 114), byte_rgb(146, 134, 118));
            sc = scalec(sc, (0.6f + 0.45f * dome) * (0.94f + 0.08f * speck[x]));
            c = mixc(c, sc, cover);
            h = mixf(h, 0.2f + sh, cover);
        }
        c = scalec(c, 1.0f + 0.04f * grain(619, x, y));
        put(row, x, c, h);
    }
}

// Moss: dark, soft cushions of tiny tuft heads, lighter yellow-green on the tops,
// dark meandering creases between cushions.
static void moss(int y, unsigned char *row) {
    const float v = texel_u(y);
    float cushion[N], edge[N], bend[N];
    pnoise_cell tufts[N];
    pnoise_fbm_row(703, 4, 3, 0.5f, v, N, cushion);
    pnoise_fbm_row(705, 5, 2, 0.4f, v, N, edge);
    pnoise_row(706, 3, 3, v, N, bend);
    pnoise_cells_row(707, 52, 0.8f, v, N, tufts);
    for (int x = 0; x < N; x++) {
        // The zero set of a noise: creases that wander instead of a cell net.
        const float crease = smooth(0.0f, 0.07f, absf(edge[x] + 0.3f * bend[x]));
        const pnoise_cell *t = &tufts[x];
        const float head = clamp01(1.0f - t->f1 * 1.3f);
        const float top = clamp01(0.55f + 0.6f * cushion[x]);
        rgb c = mixc(byte_rgb(38, 54, 16), byte_rgb(74, 94, 28), smooth(0.15f, 0.95f, top));
        const float tip = hash01(t->id ^ 0x1234u);
        c = mixc(c, byte_rgb(112, 122, 42), (tip > 0.7f ? 0.6f : 0.15f) * head * top);
        c = scalec(c, (0.7f + 0.3f * crease) * (0.72f + 0.38f * head));
        c = scalec(c, 1.0f + 0.03f * grain(709, x, y));
        put(row, x, c, (0.15f + 0.65f * top + 0.15f * head) * (0.6f + 0.4f * crease));
    }
}

// Cliff: dark layered rock with near-vertical strata, slabs with grooves between them,
// and fractures across them.
static void cliff(int y, unsigned char *row) {
    const float v = texel_u(y);
    float bend[N], big[N], stretch[N], frac[N], keep[N], fine[N];
    pnoise_fbm_row(801, 2, 3, 0.5f, v, N, bend);
    pnoise_fbm_row(803, 3, 4, 0.55f, v, N, big);
    pnoise_row(805, 4, 24, v, N, stretch);
    pnoise_row(811, 3, 14, v, N, frac);
    pnoise_row(812, 4, 4, v, N, keep);
    pnoise_fbm_row(813, 32, 2, 0.6f, v, N, fine);
    for (int x = 0; x < N; x++) {
        // 9 strata per repeat across u, bent by the noise; the index mod 9 so colours
        // repeat.
        const float s = 9.0f * texel_u(x) + bend[x] + 0.15f * stretch[x];
        const int layer = ifloor(s);
        const float within = s - (float)layer;
        const float lh = hash01(gen_hash_3(807, (uint32_t)wrap(layer, 9), 0));
        // Each stratum a slab: raised, eroded at one edge, a groove between slabs.
        const float slab = smooth(0.0f, 0.15f, within) * (1.0f - 0.5f * smooth(0.6f, 1.0f, within));
        // Fractures: the zero set of a noise stretched along u, kept in patches.
        const float across =
            1.0f - (1.0f - smooth(0.0f, 0.09f, absf(frac[x]))) * smooth(0.0f, 0.3f, keep[x]);
        rgb c = mixc(byte_rgb(72, 68, 64), byte_rgb(98, 90, 80), lh);
        c = mixc(c, byte_rgb(112, 108, 102), smooth(0.1f, 0.6f, big[x]) * 0.5f);
        c = scalec(c, (0.55f + 0.45f * slab) * (0.7f + 0.3f * across) * (0.9f + 0.12f * fine[x]));
        c = scalec(c, 1.0f + 0.05f * grain(809, x, y));
        const float h = 0.35f + 0.25f * big[x] + 0.2f * lh + 0.08f * fine[x];
        put(row, x, c, h * (0.45f + 0.55f * slab) * (0.7f + 0.3f * across));
    }
}

static const struct {
    const char *name;
    recipe_fn fn;
} recipes[MATERIAL_TEXTURE_COUNT] = {
    {"sand", sand}, {"grass", grass},   {"rock", rock}, {"snow", snow},
    {"dirt", dirt}, {"gravel", gravel}, {"moss", moss}, {"cliff", cliff},
};

const char *material_texture_name(int index) {
    if (index < 0 || index >= MATERIAL_TEXTURE_COUNT) return NULL;
    return recipes[index].name;
}

void material_texture_generate(int index, unsigned char *rgba) {
    if (index < 0 || index >= MATERIAL_TEXTURE_COUNT) {
        for (size_t i = 0; i < (size_t)N * N * 4; i++)
            rgba[i] = 128;
        return;
    }
    for (int y = 0; y < N; y++)
        recipes[index].fn(y, rgba + (size_t)y * N * 4);
}
