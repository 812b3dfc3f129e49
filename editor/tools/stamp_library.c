// Each stamp is a function of footprint coordinates in [-1, 1]^2 (edge samples at
// exactly +-1), built from gen_noise fractals and stamp_shapes, then scaled so its
// peak is 1. Radial stamps end in disc_window, square ones in square_window: both are
// exactly 0 on the edge, which is what makes the border ring exactly 0.
#include "editor/tools/stamp_library.h"

#include "editor/gen/gen_hash.h"
#include "editor/gen/gen_noise.h"
#include "editor/tools/stamp_shapes.h"
#include "io/image_read.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct field {
    int n;           // samples per side
    const double *c; // c[i]: footprint coordinate of column (and row) i
    float *h;        // h[j * n + i]
} field;

static float smoothstep(float e0, float e1, float x) {
    float t = (x - e0) / (e1 - e0);
    t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
    return t * t * (3.0f - 2.0f * t);
}
static float clamp01(float x) {
    return x < 0.0f ? 0.0f : x > 1.0f ? 1.0f : x;
}

// 1 inside r = 0.6, 0 from r = 1 on.
static float disc_window(float r) {
    return 1.0f - smoothstep(0.6f, 1.0f, r);
}
// 1 inside |u|, |v| < 0.7, 0 on the square's edge.
static float square_window(float u, float v) {
    return (1.0f - smoothstep(0.7f, 1.0f, fabsf(u))) * (1.0f - smoothstep(0.7f, 1.0f, fabsf(v)));
}

static float fbm2(uint32_t seed, double octaves, double x, double y) {
    gen_fractal f = {GEN_FRACTAL_FBM, seed, octaves, 0.5, 2.0, 1.0};
    return gen_fractal2(&f, x, y);
}
static float fbm3(uint32_t seed, double octaves, double x, double y, double z) {
    gen_fractal f = {GEN_FRACTAL_FBM, seed, octaves, 0.5, 2.0, 1.0};
    return gen_fractal3(&f, x, y, z);
}

// A fractal sampled on the field's grid at frequency freq (cycles per footprint unit).
static float *fractal_grid(const field *f, const gen_fractal *fr, double freq) {
    size_t n = (size_t)f->n;
    double *xs = malloc(sizeof(double) * n);
    float *out = malloc(sizeof(float) * n * n);
    if (!xs || !out) {
        free(xs), free(out);
        return NULL;
    }
    for (size_t i = 0; i < n; i++)
        xs[i] = f->c[i] * freq;
    gen_fractal_grid2(fr, xs, f->n, xs, f->n, out);
    free(xs);
    return out;
}

#define FOR_EACH_SAMPLE(f)                                                                         \
    for (int j = 0; j < (f)->n; j++)                                                               \
        for (int i = 0; i < (f)->n; i++)

// Ridged multifractal over a cone: sharp crests running down the flanks.
static int mountain(field *f) {
    gen_fractal ridged = {GEN_FRACTAL_RIDGED, 101, 8.0, 0.5, 2.0, 1.0};
    float *rn = fractal_grid(f, &ridged, 1.6);
    if (!rn) return -1;
    FOR_EACH_SAMPLE(f) {
        float u = (float)f->c[i], v = (float)f->c[j], r = sqrtf(u * u + v * v);
        float base = stamp_shape_value(STAMP_SHAPE_CONE, u, v);
        float detail = 0.5f + 0.5f * rn[(size_t)j * f->n + i];
        f->h[(size_t)j * f->n + i] =
            base * (0.55f * base + 0.45f * detail * detail) * disc_window(r);
    }
    free(rn);
    return 0;
}

// A peak cut by gullies radiating from the summit: zero crossings of 3D noise on a
// cylinder that is long around the peak and short along the radius.
static int eroded_peak(field *f) {
    FOR_EACH_SAMPLE(f) {
        float u = (float)f->c[i], v = (float)f->c[j], r = sqrtf(u * u + v * v);
        float cu = r > 0.0f ? u / r : 1.0f, cv = r > 0.0f ? v / r : 0.0f;
        float peak = 0.5f * stamp_shape_value(STAMP_SHAPE_CONE, u, v) +
                     0.5f * stamp_shape_value(STAMP_SHAPE_GAUSSIAN, u, v);
        float n = fbm3(202, 3.0, cu * 3.0, cv * 3.0, r * 1.5);
        float gully = (1.0f - smoothstep(0.0f, 0.2f, fabsf(n))) * smoothstep(0.05f, 0.35f, r);
        float rough = fbm2(203, 6.0, u * 6.0, v * 6.0);
        f->h[(size_t)j * f->n + i] =
            peak * (1.0f - 0.3f * gully) * (1.0f + 0.06f * rough) * disc_window(r);
    }
    return 0;
}

// stamp_shapes' volcano with a ragged outline and lava-channel roughness.
static int volcano(field *f) {
    FOR_EACH_SAMPLE(f) {
        float u = (float)f->c[i], v = (float)f->c[j], r = sqrtf(u * u + v * v);
        float k = 1.0f + 0.12f * fbm2(301, 4.0, u * 3.0, v * 3.0);
        float cone = stamp_shape_value(STAMP_SHAPE_VOLCANO, u * k, v * k);
        float rough = fbm2(302, 6.0, u * 10.0, v * 10.0);
        f->h[(size_t)j * f->n + i] = cone * (1.0f + 0.04f * rough) * disc_window(r);
    }
    return 0;
}

// Non-overlapping craters of assorted sizes (placed by hash, rejecting overlaps) on a
// low dome, so that their bowls stay above 0.
static int crater_field(field *f) {
    enum { MAX_CRATERS = 16, TRIES = 400 };
    float cx[MAX_CRATERS], cy[MAX_CRATERS], cr[MAX_CRATERS];
    int nc = 0;
    for (uint32_t t = 0; t < TRIES && nc < MAX_CRATERS; t++) {
        float x = 0.7f * gen_hash_unit(gen_hash_3(401, t, 0));
        float y = 0.7f * gen_hash_unit(gen_hash_3(401, t, 1));
        float s = 0.5f + 0.5f * gen_hash_unit(gen_hash_3(401, t, 2)); // [0, 1)
        float rad = 0.06f + 0.22f * s * s;
        if (sqrtf(x * x + y * y) + rad > 0.85f) continue;
        int clear = 1;
        for (int k = 0; k < nc && clear; k++)
            clear = hypotf(x - cx[k], y - cy[k]) > rad + cr[k];
        if (!clear) continue;
        cx[nc] = x, cy[nc] = y, cr[nc] = rad, nc++;
    }
    FOR_EACH_SAMPLE(f) {
        float u = (float)f->c[i], v = (float)f->c[j], r = sqrtf(u * u + v * v);
        float sum = 0.0f; // disjoint footprints: within [-0.7, 0.3]
        for (int k = 0; k < nc; k++)
            sum += stamp_shape_value(STAMP_SHAPE_CRATER, (u - cx[k]) / cr[k], (v - cy[k]) / cr[k]);
        float rough = fbm2(402, 6.0, u * 8.0, v * 8.0);
        f->h[(size_t)j * f->n + i] =
            (0.6f + 0.5f * sum + 0.05f * rough) * (1.0f - smoothstep(0.5f, 1.0f, r));
    }
    return 0;
}

// Transverse dunes: gentle windward slopes and steep lee faces (an asymmetric
// smoothstep sawtooth), crests bent by noise, heights varying along them.
static int dunes(field *f) {
    FOR_EACH_SAMPLE(f) {
        float u = (float)f->c[i], v = (float)f->c[j];
        float warp = 0.35f * fbm2(501, 4.0, u * 1.5, v * 1.5);
        float p = u * 4.0f + warp + 8.0f; // positive, so the fraction is the phase
        p -= floorf(p);
        float profile = p < 0.8f ? smoothstep(0.0f, 0.8f, p) : 1.0f - smoothstep(0.8f, 1.0f, p);
        float amp = 0.65f + 0.35f * fbm2(502, 3.0, u * 2.0 + 7.0, v * 2.0);
        f->h[(size_t)j * f->n + i] = profile * amp * square_window(u, v);
    }
    return 0;
}

// A meandering canyon along u with a narrow inner gorge and a wider upper bench.
// Carve: the engine subtracts it.
static int canyon(field *f) {
    for (int i = 0; i < f->n; i++) {
        float u = (float)f->c[i];
        float centre = 0.3f * sinf(2.2f * u + 0.4f) + 0.12f * fbm2(601, 4.0, u * 2.0, 0.5);
        float along = 1.0f - smoothstep(0.6f, 1.0f, fabsf(u));
        for (int j = 0; j < f->n; j++) {
            float v = (float)f->c[j];
            float d = fabsf(v - centre) + 0.025f * fbm2(602, 5.0, u * 12.0, v * 12.0);
            float depth = 0.6f * (1.0f - smoothstep(0.05f, 0.12f, d)) +
                          0.4f * (1.0f - smoothstep(0.15f, 0.3f, d));
            f->h[(size_t)j * f->n + i] = depth * along * square_window(u, v);
        }
    }
    return 0;
}

// A mesa with a ragged, noise-displaced rim and a faintly rough top.
static int plateau(field *f) {
    FOR_EACH_SAMPLE(f) {
        float u = (float)f->c[i], v = (float)f->c[j], r = sqrtf(u * u + v * v);
        float k = 1.0f + 0.18f * fbm2(701, 5.0, u * 2.5, v * 2.5);
        float mesa = stamp_shape_value(STAMP_SHAPE_MESA, u * k * 1.15f, v * k * 1.15f);
        float rough = fbm2(702, 6.0, u * 9.0, v * 9.0);
        f->h[(size_t)j * f->n + i] = mesa * (1.0f + 0.04f * rough) * disc_window(r);
    }
    return 0;
}

// Boulders (noisy half-ellipsoids, biggest near the middle) heaped on a low mound;
// the surface is the highest of them.
static int rock_pile(field *f) {
    enum { ROCKS = 40 };
    float rx[ROCKS], ry[ROCKS], ra[ROCKS], rb[ROCKS], rc[ROCKS], rs[ROCKS], rh[ROCKS], rz[ROCKS];
    for (uint32_t k = 0; k < ROCKS; k++) {
        float d = 0.62f * sqrtf(0.5f + 0.5f * gen_hash_unit(gen_hash_3(801, k, 0)));
        float a = 3.14159265f * gen_hash_unit(gen_hash_3(801, k, 1));
        float size = (0.11f + 0.06f * gen_hash_unit(gen_hash_3(801, k, 2))) * (1.2f - 0.6f * d);
        float turn = 3.14159265f * gen_hash_unit(gen_hash_3(801, k, 3));
        rx[k] = d * cosf(a), ry[k] = d * sinf(a);
        ra[k] = size * (1.15f + 0.25f * gen_hash_unit(gen_hash_3(801, k, 4)));
        rb[k] = size * (0.85f + 0.15f * gen_hash_unit(gen_hash_3(801, k, 5)));
        rc[k] = cosf(turn), rs[k] = sinf(turn);
        rh[k] = size * 2.2f;
        rz[k] = 0.55f * stamp_shape_value(STAMP_SHAPE_GAUSSIAN, rx[k] / 0.8f, ry[k] / 0.8f);
    }
    FOR_EACH_SAMPLE(f) {
        float u = (float)f->c[i], v = (float)f->c[j], r = sqrtf(u * u + v * v);
        float top = 0.5f * stamp_shape_value(STAMP_SHAPE_GAUSSIAN, u / 0.8f, v / 0.8f);
        float bump = fbm2(802, 4.0, u * 7.0, v * 7.0);
        for (int k = 0; k < ROCKS; k++) {
            float x = u - rx[k], y = v - ry[k];
            float p = (rc[k] * x + rs[k] * y) / ra[k], q = (rc[k] * y - rs[k] * x) / rb[k];
            float e = p * p + q * q + 0.2f * bump;
            if (e < 1.0f) {
                float z = rz[k] + rh[k] * sqrtf(1.0f - e);
                top = z > top ? z : top;
            }
        }
        f->h[(size_t)j * f->n + i] = top * disc_window(r);
    }
    return 0;
}

// A hill cut into flat steps with smooth risers; the noise that bends the contours
// fades out with the window so the border stays at 0.
static int terraces(field *f) {
    const float steps = 7.0f;
    FOR_EACH_SAMPLE(f) {
        float u = (float)f->c[i], v = (float)f->c[j], r = sqrtf(u * u + v * v);
        float w = disc_window(r);
        float wu = u + 0.15f * w * fbm2(901, 4.0, u * 2.0, v * 2.0);
        float wv = v + 0.15f * w * fbm2(902, 4.0, u * 2.0, v * 2.0);
        float base = stamp_shape_value(STAMP_SHAPE_GAUSSIAN, wu, wv) * w;
        float t = base * steps, fl = floorf(t);
        f->h[(size_t)j * f->n + i] = (fl + smoothstep(0.6f, 1.0f, t - fl)) / steps;
    }
    return 0;
}

// Rolling fBm hills.
static int hills(field *f) {
    gen_fractal fbm = {GEN_FRACTAL_FBM, 1001, 4.0, 0.45, 2.0, 1.0};
    float *nz = fractal_grid(f, &fbm, 2.0);
    if (!nz) return -1;
    FOR_EACH_SAMPLE(f) {
        float u = (float)f->c[i], v = (float)f->c[j], r = sqrtf(u * u + v * v);
        float x = clamp01(0.5f + 0.6f * nz[(size_t)j * f->n + i]);
        f->h[(size_t)j * f->n + i] = (0.2f + 0.8f * x * x) * disc_window(r);
    }
    free(nz);
    return 0;
}

typedef struct stamp_def {
    stamp_library_entry entry;
    int (*make)(field *f);
} stamp_def;

static const stamp_def STAMPS[] = {
    {{"mountain", 0, "ridged multifractal (8 octaves) over a cone"}, mountain},
    {{"eroded_peak", 0, "cone + gaussian peak cut by radial gullies (zero crossings of 3D fBm)"},
     eroded_peak},
    {{"stratovolcano", 0, "the volcano shape with an fBm-ragged outline and rough flanks"},
     volcano},
    {{"crater_field", 0, "disjoint crater shapes of assorted sizes on a low dome"}, crater_field},
    {{"dunes", 0, "asymmetric transverse dunes along u, crests bent by fBm"}, dunes},
    {{"canyon", 1, "a meandering gorge with a bench along u; subtract it"}, canyon},
    {{"plateau", 0, "the mesa shape with an fBm-displaced rim"}, plateau},
    {{"rock_pile", 0, "noisy half-ellipsoid boulders heaped on a gaussian mound"}, rock_pile},
    {{"terraces", 0, "a warped gaussian hill quantised into 7 smooth steps"}, terraces},
    {{"hills", 0, "rolling fBm hills (6 octaves)"}, hills},
};
#define NSTAMPS ((int)(sizeof STAMPS / sizeof STAMPS[0]))

int stamp_library_count(void) {
    return NSTAMPS;
}

const stamp_library_entry *stamp_library_entry_at(int i) {
    return i >= 0 && i < NSTAMPS ? &STAMPS[i].entry : NULL;
}

int stamp_library_render(int i, int size, float *out) {
    if (i < 0 || i >= NSTAMPS || size < 3 || size > IMAGE_MAX_SIZE || !out) return -1;
    double *c = malloc(sizeof(double) * (size_t)size);
    if (!c) return -1;
    for (int k = 0; k < size; k++)
        c[k] = -1.0 + 2.0 * k / (size - 1);
    c[size - 1] = 1.0;
    field f = {size, c, out};
    int rc = STAMPS[i].make(&f);
    free(c);
    if (rc != 0) return -1;
    size_t n = (size_t)size * (size_t)size;
    float peak = 0.0f;
    for (size_t k = 0; k < n; k++)
        peak = out[k] > peak ? out[k] : peak;
    if (!(peak > 0.0f)) return -1; // every stamp has a positive peak; this would be a bug
    for (size_t k = 0; k < n; k++) // also turns -0 into 0
        out[k] = out[k] > 0.0f ? out[k] / peak : 0.0f;
    return 0;
}

int stamp_library_generate(const char *dir, og_error *err) {
    size_t n = (size_t)STAMP_LIBRARY_SIZE * STAMP_LIBRARY_SIZE;
    float *px = malloc(sizeof(float) * n);
    if (!px) return og_error_set(err, "%s: out of memory for the stamp library", dir);
    for (int i = 0; i < NSTAMPS; i++) {
        char path[4096];
        int len = snprintf(path, sizeof path, "%s/%s.png", dir, STAMPS[i].entry.name);
        if (len < 0 || (size_t)len >= sizeof path) {
            free(px);
            return og_error_set(err, "%s: folder name too long", dir);
        }
        if (stamp_library_render(i, STAMP_LIBRARY_SIZE, px) != 0) {
            free(px);
            return og_error_set(err, "%s: cannot render the stamp (out of memory?)", path);
        }
        if (image_write_gray16(path, px, STAMP_LIBRARY_SIZE, STAMP_LIBRARY_SIZE, err) != 0) {
            free(px);
            return -1;
        }
    }
    free(px);
    return 0;
}
