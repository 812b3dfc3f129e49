#include "editor/tools/brush_dab.h"
#include "editor/tools/thermal_brush.h"

#include "editor/edit/edit_rows.h"
#include "editor/tools/box_blur.h"
#include "editor/tools/hot_loop.h"
#include "editor/tools/raise_row.h"
#include "editor/tools/smooth_row.h"
#include "editor/gen/gen_noise.h"
#include "editor/world/layer_rows.h"
#include "io/progress.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

// ---- shared per-sample pieces ---------------------------------------------------------

// Selects rather than branches, so loops using it vectorise.
static inline float keep_finite(float v, float old) {
    v = v == v ? v : old;
    v = v > (float)BRUSH_HEIGHT_LIMIT ? (float)BRUSH_HEIGHT_LIMIT : v;
    return v < (float)-BRUSH_HEIGHT_LIMIT ? (float)-BRUSH_HEIGHT_LIMIT : v;
}

// dx of sample k of a row is fdx0 + k, k counted from the dab's own first column:
// the same float whatever span (tile) the sample is computed in.
HOT_LOOP_WIDE static void smooth_weights(float fdx0, int k0, float dz2, float inv_r, float strength,
                                         int n, float *w) {
    for (int i = 0; i < n; i++) { // int: int64 to float conversion does not vectorise
        float dx = fdx0 + (float)(k0 + i);
        float t = sqrtf(dx * dx + dz2) * inv_r;
        t = t < 1.0f ? t : 1.0f;
        w[i] = (1.0f - t * t * (3.0f - 2.0f * t)) * strength;
    }
}

HOT_LOOP static void add_weighted(float *row, const float *w, float a, int64_t n) {
    for (int64_t i = 0; i < n; i++)
        row[i] = keep_finite(row[i] + w[i] * a, row[i]);
}

static int is_ramp(const brush_dab *d) {
    return d->brush->tool == BRUSH_RAMP;
}

static double angle_between(const double a[3], const double b[3]) {
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return 2.0 * asin(fmin(1.0, 0.5 * sqrt(dx * dx + dy * dy + dz * dz)));
}

// Planets: the ramp is the great-circle segment between its ends; the angle from it
// (and where along it, 0-1, the sample's direction projects) in samples on the sphere.
static double sphere_ramp_distance(const brush_dab *d, double x, double z, double *along) {
    double p[3];
    brush_dab_sample_direction(d, x, z, p);
    const double *a = d->ramp_a, *b = d->ramp_b;
    const double to_samples = d->planet_radius / d->spacing;
    double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double ab = atan2(len, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
    if (len > 1e-15 && ab > 0) {
        for (int k = 0; k < 3; k++)
            n[k] /= len;
        double off = p[0] * n[0] + p[1] * n[1] + p[2] * n[2];
        double q[3] = {p[0] - n[0] * off, p[1] - n[1] * off, p[2] - n[2] * off};
        double c[3] = {a[1] * q[2] - a[2] * q[1], a[2] * q[0] - a[0] * q[2],
                       a[0] * q[1] - a[1] * q[0]};
        double t =
            atan2(c[0] * n[0] + c[1] * n[1] + c[2] * n[2], a[0] * q[0] + a[1] * q[1] + a[2] * q[2]);
        if (t >= 0 && t <= ab) {
            *along = t / ab;
            return asin(fmin(1.0, fabs(off))) * to_samples;
        }
    }
    double da = angle_between(p, a), db = angle_between(p, b); // past an end
    *along = da <= db ? 0.0 : 1.0;
    return fmin(da, db) * to_samples;
}

// Distance (samples) from the ramp's segment, and where along it (0-1) x, z projects.
static double ramp_distance(const brush_dab *d, double x, double z, double *along) {
    if (d->sphere) return sphere_ramp_distance(d, x, z, along);
    double ux = d->bx - d->ax, uz = d->bz - d->az, len2 = ux * ux + uz * uz;
    double t = len2 > 0 ? ((x - d->ax) * ux + (z - d->az) * uz) / len2 : 0.0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    *along = t;
    double px = d->ax + t * ux - x, pz = d->az + t * uz - z;
    return sqrt(px * px + pz * pz);
}

static double face_coord(const brush_dab *d, double i) {
    return (i * d->index_scale + 0.5) / (double)d->face_samples * 2.0 - 1.0;
}

void brush_dab_sample_direction(const brush_dab *d, double x, double z, double dir[3]) {
    world_grid_face_direction_warped(d->face, tan(face_coord(d, x) * (M_PI / 4.0)),
                                     tan(face_coord(d, z) * (M_PI / 4.0)), dir);
}

// Planets: weights by great-circle distance (the chord turned into the angle).
static void sphere_weights(const brush_dab *d, int64_t z, int64_t x0, int64_t x1, float *w) {
    const double tb = tan(face_coord(d, (double)z) * (M_PI / 4.0));
    const double k = d->planet_radius / (d->radius * d->spacing); // radians to radii
    const double *c = d->centre_dir;
    for (int64_t x = x0; x < x1; x++) {
        double dir[3];
        world_grid_face_direction_warped(d->face, tan(face_coord(d, (double)x) * (M_PI / 4.0)), tb,
                                         dir);
        double dx = dir[0] - c[0], dy = dir[1] - c[1], dz = dir[2] - c[2];
        double chord = sqrt(dx * dx + dy * dy + dz * dz);
        double angle = 2.0 * asin(fmin(1.0, 0.5 * chord));
        w[x - x0] = brush_falloff_weight(d->brush, (float)(angle * k)) * d->strength;
    }
}

grid_rect brush_dab_rect(const brush_dab *d) {
    if (d->sphere) return d->rect;
    double r = d->radius;
    if (is_ramp(d)) {
        return (grid_rect){
            (int64_t)ceil(fmin(d->ax, d->bx) - r), (int64_t)ceil(fmin(d->az, d->bz) - r),
            (int64_t)floor(fmax(d->ax, d->bx) + r) + 1, (int64_t)floor(fmax(d->az, d->bz) + r) + 1};
    }
    return (grid_rect){(int64_t)ceil(d->cx - r), (int64_t)ceil(d->cz - r),
                       (int64_t)floor(d->cx + r) + 1, (int64_t)floor(d->cz + r) + 1};
}

// Weight of every sample of one row span [x0, x1) at row z: falloff x strength.
// The dab's first column (brush_dab_rect's x0) for a flat disc, without its four roundings.
static int64_t disc_first_column(const brush_dab *d) {
    return (int64_t)ceil(d->cx - d->radius);
}

static void row_weights(const brush_dab *d, int64_t z, int64_t x0, int64_t x1, float *w) {
    const brush *b = d->brush;
    float inv_r = (float)(1.0 / d->radius);
    if (d->sphere && !is_ramp(d)) {
        sphere_weights(d, z, x0, x1, w);
        return;
    }
    if (is_ramp(d)) {
        for (int64_t x = x0; x < x1; x++) {
            double along;
            float t = (float)ramp_distance(d, (double)x, (double)z, &along) * inv_r;
            w[x - x0] = brush_falloff_weight(b, t) * d->strength;
        }
        return;
    }
    float dz = (float)((double)z - d->cz), dz2 = dz * dz;
    int64_t first = disc_first_column(d);
    float fdx0 = (float)((double)first - d->cx);
    int k0 = (int)(x0 - first);
    if (b->falloff == FALLOFF_SMOOTH) { // the common case, vectorised
        smooth_weights(fdx0, k0, dz2, inv_r, d->strength, (int)(x1 - x0), w);
        return;
    }
    for (int64_t i = 0; i < x1 - x0; i++) {
        float dx = fdx0 + (float)(k0 + i);
        w[i] = brush_falloff_weight(b, sqrtf(dx * dx + dz2) * inv_r) * d->strength;
    }
}

static float terrace(const brush *b, float h) {
    double step = b->terrace_step, k = floor(h / step), f = h / step - k;
    // f^p: flat treads and steep risers as sharpness goes to 1.
    double p = 1.0 + 15.0 * b->terrace_sharpness * b->terrace_sharpness;
    return (float)((k + pow(f, p)) * step);
}

// Pointwise tools on one row span of heights.
static void height_row(const brush_dab *d, float *row, int64_t z, int64_t x0, int64_t x1,
                       float *w) {
    const brush *b = d->brush;
    float amount = (float)(b->invert ? -b->amount : b->amount);
    row_weights(d, z, x0, x1, w);
    int64_t n = x1 - x0;
    switch (b->tool) {
    case BRUSH_RAISE: {
        add_weighted(row, w, amount, n);
        break;
    }
    case BRUSH_FLATTEN:
    case BRUSH_SET: {
        float t = d->target;
        for (int64_t i = 0; i < n; i++) {
            float h = row[i];
            if (b->tool == BRUSH_FLATTEN && ((b->flatten == FLATTEN_RAISE && h >= t) ||
                                             (b->flatten == FLATTEN_LOWER && h <= t)))
                continue;
            row[i] = keep_finite(h + w[i] * (t - h), h);
        }
        break;
    }
    case BRUSH_RAMP:
        for (int64_t i = 0; i < n; i++) {
            if (w[i] <= 0.0f) continue;
            double along;
            ramp_distance(d, (double)(x0 + i), (double)z, &along);
            float t = (float)(d->ha + along * (d->hb - d->ha));
            row[i] = keep_finite(row[i] + w[i] * (t - row[i]), row[i]);
        }
        break;
    case BRUSH_NOISE: {
        gen_fractal f = {GEN_FRACTAL_FBM, b->seed, b->noise_octaves, 0.5, 2.0, 1.0};
        double k = d->spacing / b->noise_scale, zz = (double)z * k;
        float a = (float)(b->invert ? -b->amount : b->amount);
        for (int64_t i = 0; i < n; i++) {
            if (w[i] <= 0.0f) continue;
            float v;
            if (d->sphere) { // 3D on the sphere: the same pattern on every face
                double dir[3], m = d->planet_radius / b->noise_scale;
                brush_dab_sample_direction(d, (double)(x0 + i), (double)z, dir);
                v = gen_fractal3(&f, dir[0] * m, dir[1] * m, dir[2] * m);
            } else {
                v = gen_fractal2(&f, (double)(x0 + i) * k, zz);
            }
            row[i] = keep_finite(row[i] + w[i] * a * v, row[i]);
        }
        break;
    }
    case BRUSH_TERRACE:
        for (int64_t i = 0; i < n; i++) {
            if (w[i] <= 0.0f) continue;
            float h = row[i];
            row[i] = keep_finite(h + w[i] * (terrace(b, h) - h), h);
        }
        break;
    default:
        break;
    }
}

// Material weights of one sample: move toward (or away from) material m by w,
// keeping the 8 weights summing to exactly 255 (largest remainder rounding).
static void paint_sample(uint8_t *m8, int m, float w, int invert) {
    int sum = 0;
    for (int c = 0; c < TILE_MATERIALS; c++)
        sum += m8[c];
    double want[TILE_MATERIALS];
    double old_m = sum ? m8[m] * 255.0 / sum : 0.0;
    double new_m = invert ? old_m * (1.0 - w) : old_m + w * (255.0 - old_m);
    double rest_old = (sum ? 255.0 : 0.0) - old_m, rest_new = 255.0 - new_m;
    for (int c = 0; c < TILE_MATERIALS; c++) {
        if (c == m)
            want[c] = new_m;
        else if (rest_old > 0)
            want[c] = (sum ? m8[c] * 255.0 / sum : 0) * rest_new / rest_old;
        else
            want[c] = 0;
    }
    if (rest_old <= 0 && rest_new > 0)
        want[m == 0 ? 1 : 0] += rest_new; // removed from a pure sample
    int total = 0;
    double frac[TILE_MATERIALS];
    int out[TILE_MATERIALS];
    for (int c = 0; c < TILE_MATERIALS; c++) {
        out[c] = (int)floor(want[c]);
        frac[c] = want[c] - out[c];
        total += out[c];
    }
    while (total < 255) { // hand out the remaining units by largest remainder
        int best = 0;
        for (int c = 1; c < TILE_MATERIALS; c++)
            if (frac[c] > frac[best]) best = c;
        out[best]++;
        frac[best] = -1;
        total++;
    }
    for (int c = 0; c < TILE_MATERIALS; c++)
        m8[c] = (uint8_t)out[c];
}

// Paint works as a painting program's brush: a stroke (one edit) has a coverage per
// sample, 0 to 1, that each dab moves toward its falloff by the strength and never
// past it, and the sample shows the weights from before the stroke with the material
// laid over them at that coverage. So however many dabs a stroke lays (or a brush held
// still), its edge keeps the falloff's profile instead of hardening as dabs pile up;
// a new stroke lays its paint over the last. The coverage is read back from the weights
// (before -> now), so it needs no store of its own. before: the sample's weights when
// the stroke began.
static float paint_coverage(const uint8_t *before, const uint8_t *now, int m, int invert) {
    float b = (float)before[m], n = (float)now[m];
    float c =
        invert ? (b > 0.0f ? (b - n) / b : 1.0f) : (b < 255.0f ? (n - b) / (255.0f - b) : 1.0f);
    return c < 0.0f ? 0.0f : c > 1.0f ? 1.0f : c;
}

static void paint_row(const brush_dab *d, uint8_t *row, const uint8_t *before, int64_t z,
                      int64_t x0, int64_t x1, float *w) {
    brush_dab shape = *d; // the falloff alone: the strength is the rate toward it
    shape.strength = 1.0f;
    row_weights(&shape, z, x0, x1, w);
    const int m = d->brush->material, invert = d->brush->invert;
    for (int64_t i = 0; i < x1 - x0; i++) {
        uint8_t *now = row + i * TILE_MATERIALS;
        const uint8_t *was = before ? before + i * TILE_MATERIALS : now;
        float c = paint_coverage(was, now, m, invert);
        if (!(w[i] > c)) continue;
        c += d->strength * (w[i] - c);
        uint8_t out[TILE_MATERIALS];
        memcpy(out, was, sizeof out);
        paint_sample(out, m, c, invert);
        memcpy(now, out, sizeof out);
    }
}

static int is_pointwise(const brush *b) {
    return b->tool != BRUSH_SMOOTH && b->tool != BRUSH_THERMAL && b->tool != BRUSH_HYDRAULIC;
}

// ---- neighbourhood tools on a gathered area ---------------------------------------

static int halo_of(const brush_dab *d) {
    switch (d->brush->tool) {
    case BRUSH_SMOOTH:
        return 2 * (int)fmax(1.0, floor(d->radius / 8.0)); // two box passes
    case BRUSH_THERMAL:
        return 1;
    case BRUSH_HYDRAULIC:
        return (int)ceil(d->brush->hydraulic.radius_cells) + 2;
    default:
        return 0;
    }
}

// Moves each sample of a row with weight > 0 toward its smoothed value by its weight
// (away when inverting); the others keep their bits. Branch-free, so it vectorises.
HOT_LOOP_WIDE static void blend_smoothed(float *row, const float *smoothed, const float *weight,
                                         int invert, int64_t n) {
    for (int64_t i = 0; i < n; i++) {
        float old = row[i], w = weight[i];
        float v = keep_finite(old + (invert ? -w : w) * (smoothed[i] - old), old);
        row[i] = w > 0.0f ? v : old;
    }
}

// ---- row functions shared by both paths ------------------------------------------------

typedef struct dab_rows {
    const brush_dab *d;
    // paint: where the weights as the stroke began are (paint_row): the edit's snapshots
    // of the tiles (e, with the grid's layer and face), or an array over before_area
    edit *e;
    tile_layer layer;
    int face;
    const uint8_t *before;
    grid_rect before_area;
    // pointwise tools on a flat disc: per row of the dab's rect, the columns [a, b) its
    // falloff can reach (NULL: the whole rect)
    int64_t (*span)[2];
    int64_t span_z0, span_rows;
    // neighbourhood tools: the computed area and its weights; smooth: the heights are
    // the smoothed ones, which dab_row lays over the rows by the weights
    const float *heights, *weight;
    grid_rect area;
    int smoothed;
    // smooth with the smooth falloff on a flat disc: no weight array, each row's
    // weights computed as it is blended (smooth_row.c), from dx2: the squares of the
    // columns' distances from the centre, from the rect's first column (the same for
    // every row)
    int row_weighted;
    float *dx2;
    // raise with the smooth falloff on a flat disc: dx2 as above, and the row kernel's
    // path and amount (raise_row.c), chosen once per dab
    int raise_rows, raise_path;
    float raise_amount;
    // NULL, or the smoothed heights left packed as the blur wrote them: area row z's
    // column x (area columns) at heights[row_at[z] + x]
    int64_t *row_at;
} dab_rows;

// Narrows [x0, x1) of row z to the samples a flat disc's falloff can reach (every
// falloff is 0 from t = 1 on), with a sample of margin for float rounding: the others
// keep their bits, so skipping them changes nothing and saves a quarter of the work.
// Computed once per dab (the roundings and the square root cost as much per row as a
// few dozen samples).
// disc_spans' bounds of rows z0 + i, i < n, as whole numbers in double (vectorised: one
// row at a time, the square root and the roundings took as long as the blend of a few
// rows).
HOT_LOOP static void span_bounds(double cx, double cz, double reach, double z0, int n, double *lo,
                                 double *hi) {
    for (int i = 0; i < n; i++) {
        double a = fabs(z0 + (double)i - cz) - 1.0, dz = a > 0.0 ? a : 0.0;
        double q = reach * reach - dz * dz, root = sqrt(q > 0.0 ? q : 0.0); // no branch
        double half = dz < reach ? root + 1.0 : 0.0;
        lo[i] = floor(cx - half);
        hi[i] = ceil(cx + half);
    }
}

static void disc_spans(dab_rows *j) {
    const brush_dab *d = j->d;
    if (d->sphere || is_ramp(d)) return;
    grid_rect r = brush_dab_rect(d);
    j->span = malloc((size_t)(r.z1 - r.z0) * sizeof *j->span);
    if (!j->span) return; // the whole rect then: the same result, slower
    j->span_z0 = r.z0, j->span_rows = r.z1 - r.z0;
    enum { ROWS = 256 };
    double lo[ROWS], hi[ROWS];
    for (int64_t z = r.z0; z < r.z1; z += ROWS) {
        int n = r.z1 - z < ROWS ? (int)(r.z1 - z) : ROWS;
        span_bounds(d->cx, d->cz, d->radius + 1.0, (double)z, n, lo, hi);
        for (int i = 0; i < n; i++) {
            j->span[z - r.z0 + i][0] = (int64_t)lo[i];
            j->span[z - r.z0 + i][1] = (int64_t)hi[i] + 1;
        }
    }
}

static void disc_span(const dab_rows *j, int64_t z, int64_t *x0, int64_t *x1) {
    if (!j->span || z < j->span_z0 || z >= j->span_z0 + j->span_rows) return;
    int64_t a = j->span[z - j->span_z0][0], b = j->span[z - j->span_z0][1];
    if (a > *x0) *x0 = a < *x1 ? a : *x1;
    if (b < *x1) *x1 = b > *x0 ? b : *x0;
}

// Runs a neighbourhood tool on heights (w x h, covering `area`), changing only
// samples whose weight > 0. weight gets the per-sample weights (smooth: NULL when
// dab_row computes them itself). blurred: smooth's blur is done already.
static int neighbourhood(const brush_dab *d, const dab_rows *spans, float *heights, float *weight,
                         grid_rect area, int blurred, og_error *err) {
    int64_t w = area.x1 - area.x0, h = area.z1 - area.z0;
    int halo = halo_of(d);
    grid_rect inner = {area.x0 + halo, area.z0 + halo, area.x1 - halo, area.z1 - halo};
    if (weight) { // 0 in the halo; row_weights writes every inner sample.
        memset(weight, 0, (size_t)(halo * w) * sizeof *weight);
        memset(weight + (h - halo) * w, 0, (size_t)(halo * w) * sizeof *weight);
        for (int64_t z = inner.z0; z < inner.z1; z++) {
            float *row = weight + (z - area.z0) * w;
            int64_t x0 = inner.x0, x1 = inner.x1; // a flat disc: its span (0 past it)
            disc_span(spans, z, &x0, &x1);
            memset(row, 0, (size_t)(x0 - area.x0) * sizeof *row);
            memset(row + (x1 - area.x0), 0, (size_t)(area.x1 - x1) * sizeof *row);
            row_weights(d, z, x0, x1, row + (x0 - area.x0));
        }
    }
    const brush *b = d->brush;
    if (b->tool == BRUSH_SMOOTH) { // the blend comes as the rows are written (dab_row)
        if (!blurred && box_blur_twice(heights, heights, w, h, halo / 2) != 0) {
            return og_error_set(err, "out of memory smoothing (%lld x %lld samples)", (long long)w,
                                (long long)h);
        }
        return 0;
    }
    if (w > INT32_MAX / (h ? h : 1)) return og_error_set(err, "brush area too large");
    erosion_grid g = {heights, weight, (int)w, (int)h, (float)d->spacing, og_progress_current()};
    if (b->tool == BRUSH_THERMAL) {
        thermal_brush_erode(&g, &b->thermal, thermal_brush_block(d->radius));
    } else {
        hydraulic_params p = b->hydraulic;
        p.seed = d->seed;
        erosion_hydraulic(&g, &p, NULL);
    }
    if (og_progress_cancelled(g.progress)) return og_error_set(err, "cancelled");
    for (int64_t i = 0; i < w * h; i++)
        heights[i] = keep_finite(heights[i], 0.0f);
    return 0;
}

// A neighbourhood tool's result where its weight is > 0 (selects: vectorises).
HOT_LOOP static void copy_weighted(float *dst, const float *src, const float *weight, int64_t n) {
    for (int64_t i = 0; i < n; i++)
        dst[i] = weight[i] > 0.0f ? src[i] : dst[i];
}

// The weights of samples [x, ...) of row z as the stroke began (within one tile), or
// NULL: as they are now (the dab is the stroke).
static const uint8_t *stroke_start(const dab_rows *j, int64_t z, int64_t x) {
    if (j->before) {
        grid_rect a = j->before_area;
        return j->before + ((z - a.z0) * (a.x1 - a.x0) + (x - a.x0)) * TILE_MATERIALS;
    }
    if (!j->e) return NULL;
    int64_t tx = world_grid_floor_div(x, TILE_SIZE), tz = world_grid_floor_div(z, TILE_SIZE);
    // The row's span lies in the part this dab acquired, so the snapshot holds it.
    const uint8_t *t =
        edit_snapshot(j->e, (tile_key){j->layer, j->face, 0, (int32_t)tx, (int32_t)tz}, NULL);
    return t ? t + ((z - tz * TILE_SIZE) * TILE_SIZE + (x - tx * TILE_SIZE)) * TILE_MATERIALS
             : NULL;
}

// The smooth falloff's weights of samples [x0, x0 + n) of row z (row_weights' floats)
// and the blend (blend_smoothed's) in one pass.
static void blend_row_weighted(const dab_rows *j, float *row, const float *smoothed, int64_t z,
                               int64_t x0, int64_t n) {
    const brush_dab *d = j->d;
    float dz = (float)((double)z - d->cz);
    smooth_row_blend(row, smoothed, j->dx2 + (x0 - disc_first_column(d)), dz * dz,
                     (float)(1.0 / d->radius), d->strength, d->brush->invert,
                     (float)BRUSH_HEIGHT_LIMIT, (int)n);
}

static void dab_row(void *user, void *row, int64_t z, int64_t x0, int64_t x1) {
    dab_rows *j = user;
    { // only the disc's part of the row (every weight past it is 0)
        int64_t a = x0, b = x1;
        disc_span(j, z, &a, &b);
        size_t bytes = j->d->brush->tool == BRUSH_PAINT ? TILE_MATERIALS : sizeof(float);
        row = (uint8_t *)row + (a - x0) * (int64_t)bytes;
        x0 = a, x1 = b;
    }
    if (j->raise_rows) { // the common dab: one kernel call a row, whatever its length
        const brush_dab *d = j->d;
        float dz = (float)((double)z - d->cz);
        raise_row_smooth_path(j->raise_path, row, j->dx2 + (x0 - disc_first_column(d)), dz * dz,
                              (float)(1.0 / d->radius), d->strength, j->raise_amount,
                              (float)BRUSH_HEIGHT_LIMIT, (int)(x1 - x0));
        return;
    }
    float w[TILE_SIZE];
    for (int64_t s = x0; s < x1; s += TILE_SIZE) { // array rows can be longer than a tile
        int64_t e = s + TILE_SIZE < x1 ? s + TILE_SIZE : x1;
        if (!j->heights && j->d->brush->tool == BRUSH_PAINT) {
            paint_row(j->d, (uint8_t *)row + (s - x0) * TILE_MATERIALS, stroke_start(j, z, s), z, s,
                      e, w);
        } else if (!j->heights) {
            height_row(j->d, (float *)row + (s - x0), z, s, e, w);
        } else {
            int64_t aw = j->area.x1 - j->area.x0, at = (z - j->area.z0) * aw + (s - j->area.x0);
            if (j->row_at) at = j->row_at[z - j->area.z0] + (s - j->area.x0);
            float *out = (float *)row + (s - x0);
            if (j->row_weighted)
                blend_row_weighted(j, out, j->heights + at, z, s, e - s);
            else if (j->smoothed)
                blend_smoothed(out, j->heights + at, j->weight + at, j->d->brush->invert, e - s);
            else
                copy_weighted(out, j->heights + at, j->weight + at, e - s);
        }
    }
}

// Neighbourhood tools only write where the weight is > 0: skip tiles a disc grazes.

static int dab_wanted(void *user, grid_rect part) {
    dab_rows *j = user;
    if (!j->heights) return 1;
    if (j->row_weighted) { // the weights row by row, as dab_row computes them
        float w[TILE_SIZE];
        for (int64_t z = part.z0; z < part.z1; z++) {
            int64_t x0 = part.x0, x1 = part.x1;
            disc_span(j, z, &x0, &x1);
            for (int64_t s = x0; s < x1; s += TILE_SIZE) {
                int64_t e = s + TILE_SIZE < x1 ? s + TILE_SIZE : x1;
                row_weights(j->d, z, s, e, w);
                for (int64_t i = 0; i < e - s; i++)
                    if (w[i] > 0.0f) return 1;
            }
        }
        return 0;
    }
    int64_t aw = j->area.x1 - j->area.x0;
    for (int64_t z = part.z0; z < part.z1; z++)
        for (int64_t x = part.x0; x < part.x1; x++)
            if (j->weight[(z - j->area.z0) * aw + (x - j->area.x0)] > 0.0f) return 1;
    return 0;
}

// Gathers the area around r (r + halo) and runs the neighbourhood tool on it.
typedef int (*area_reader)(void *src, grid_rect area, float *out, og_error *err);
// Smooth's blur (radius k) of the area read straight from the source's rows into out,
// with need as box_blur_twice_rows takes it (row_at: NULL, or left packed as
// box_blur_twice_packed leaves them): 0, 1 when the source cannot (then it is read
// whole and blurred), -1 on error.
typedef int (*area_blur)(void *src, grid_rect area, const int64_t (*need)[2], float *out,
                         int64_t *row_at, int k, og_error *err);

// The columns of each row of area whose smoothed heights dab_row reads (those of the
// disc's span within r; none outside r), in area columns; NULL: every column (not a
// flat disc, or out of memory).
static int64_t (*wanted_columns(const dab_rows *rows, grid_rect area, grid_rect r))[2] {
    if (!rows->span) return NULL;
    int64_t h = area.z1 - area.z0, (*need)[2] = malloc((size_t)h * sizeof *need);
    if (!need) return NULL;
    for (int64_t z = area.z0; z < area.z1; z++) {
        int64_t x0 = r.x0, x1 = r.x1;
        if (z < r.z0 || z >= r.z1) x1 = x0;
        disc_span(rows, z, &x0, &x1);
        need[z - area.z0][0] = x0 - area.x0, need[z - area.z0][1] = x1 - area.x0;
    }
    return need;
}

// The raise dab's table of squared column distances (smooth_row_squares: the floats
// raise_row_smooth takes) and its kernel's path; without the table (out of memory)
// height_row computes the same bits in two passes.
static void raise_rows(dab_rows *rows) {
    const brush_dab *d = rows->d;
    int64_t first = disc_first_column(d), columns = brush_dab_rect(d).x1 - first;
    if (!(rows->dx2 = malloc((size_t)columns * sizeof *rows->dx2))) return;
    smooth_row_squares(rows->dx2, (float)((double)first - d->cx), (int)columns);
    rows->raise_rows = 1;
    rows->raise_path = raise_row_paths() - 1;
    rows->raise_amount = (float)(d->brush->invert ? -d->brush->amount : d->brush->amount);
}

// before (may be NULL): also a copy of the heights as read, before the tool ran.
static int prepare(const brush_dab *d, tile_layer layer, grid_rect r, area_reader read,
                   area_blur blur, void *src, dab_rows *rows, float **before, og_error *err) {
    *rows = (dab_rows){.d = d};
    disc_spans(rows);
    if (layer != TILE_LAYER_MATERIAL && d->brush->tool == BRUSH_RAISE &&
        d->brush->falloff == FALLOFF_SMOOTH && !d->sphere && !is_ramp(d))
        raise_rows(rows);
    if (layer == TILE_LAYER_MATERIAL || is_pointwise(d->brush)) return 0;
    int halo = halo_of(d);
    grid_rect area = {r.x0 - halo, r.z0 - halo, r.x1 + halo, r.z1 + halo};
    size_t n = (size_t)((area.x1 - area.x0) * (area.z1 - area.z0));
    // A flat disc's smooth falloff: dab_row computes the weights (an area wants them all).
    rows->row_weighted = d->brush->tool == BRUSH_SMOOTH && d->brush->falloff == FALLOFF_SMOOTH &&
                         !d->sphere && !before;
    float *heights = malloc(n * sizeof *heights);
    float *weight = rows->row_weighted ? NULL : malloc(n * sizeof *weight);
    float *copy = before ? malloc(n * sizeof *copy) : NULL;
    if (rows->row_weighted) {
        int64_t first = disc_first_column(d), columns = brush_dab_rect(d).x1 - first;
        if ((rows->dx2 = malloc((size_t)columns * sizeof *rows->dx2)))
            smooth_row_squares(rows->dx2, (float)((double)first - d->cx), (int)columns);
    }
    int ok = heights && (weight || rows->row_weighted) && (!rows->row_weighted || rows->dx2) &&
             (!before || copy);
    if (!ok) og_error_set(err, "out of memory for a brush of %zu samples", n);
    int blurred = 0; // smooth on tiles: its rows read as the blur takes them
    if (ok && d->brush->tool == BRUSH_SMOOTH && blur && !before) {
        int64_t(*need)[2] = wanted_columns(rows, area, r);
        // Only dab_row's own weights read the heights; it reads them where they lie.
        int64_t *row_at = need && rows->row_weighted
                              ? malloc((size_t)(area.z1 - area.z0) * sizeof *row_at)
                              : NULL;
        int rc = blur(src, area, (const int64_t(*)[2])need, heights, row_at, halo / 2, err);
        free(need);
        ok = rc >= 0, blurred = rc == 0;
        if (blurred)
            rows->row_at = row_at;
        else
            free(row_at);
    }
    if (ok && !blurred && (ok = read(src, area, heights, err) == 0) && copy)
        memcpy(copy, heights, n * sizeof *copy);
    if (!ok || neighbourhood(d, rows, heights, weight, area, blurred, err) != 0) {
        free(heights);
        free(weight);
        free(copy);
        free(rows->span);
        free(rows->row_at);
        free(rows->dx2);
        return -1;
    }
    rows->smoothed = d->brush->tool == BRUSH_SMOOTH;
    if (before) *before = copy;
    rows->heights = heights;
    rows->weight = weight;
    rows->area = area;
    return 0;
}

static void release(dab_rows *rows) {
    free(rows->span);
    free(rows->row_at);
    free(rows->dx2);
    free((void *)rows->heights);
    free((void *)rows->weight);
}

// ---- the plain-array path ---------------------------------------------------------------

typedef struct array_source {
    const float *data;
    grid_rect area;
} array_source;

static int read_array(void *src, grid_rect r, float *out, og_error *err) {
    (void)err;
    array_source *a = src;
    int64_t aw = a->area.x1 - a->area.x0, w = r.x1 - r.x0;
    for (int64_t z = r.z0; z < r.z1; z++) {
        int64_t cz = z < a->area.z0 ? a->area.z0 : z >= a->area.z1 ? a->area.z1 - 1 : z;
        for (int64_t x = r.x0; x < r.x1; x++) {
            int64_t cx = x < a->area.x0 ? a->area.x0 : x >= a->area.x1 ? a->area.x1 - 1 : x;
            out[(z - r.z0) * w + (x - r.x0)] = a->data[(cz - a->area.z0) * aw + (cx - a->area.x0)];
        }
    }
    return 0;
}

int brush_dab_apply_array(const brush_dab *d, tile_layer layer, void *data, grid_rect area,
                          og_error *err) {
    return brush_dab_apply_array_since(d, layer, data, NULL, area, err);
}

int brush_dab_apply_array_since(const brush_dab *d, tile_layer layer, void *data,
                                const void *stroke_start, grid_rect area, og_error *err) {
    grid_rect r = grid_rect_intersect(brush_dab_rect(d), area);
    if (grid_rect_empty(r)) return 0;
    array_source src = {data, area};
    dab_rows rows;
    if (prepare(d, layer, r, read_array, NULL, &src, &rows, NULL, err) != 0) return -1;
    if (layer == TILE_LAYER_MATERIAL) rows.before = stroke_start, rows.before_area = area;
    edit_rows_apply_array(layer, data, area, r, dab_row, &rows);
    release(&rows);
    return 0;
}

// ---- the tiled path ---------------------------------------------------------------------

typedef struct world_source {
    world *w;
    const layer_grid *g;
    const brush_dab *d;
} world_source;

int brush_dab_read_sphere(world *w, const layer_grid *grid, const brush_dab *d, double x, double z,
                          float *out, og_error *err) {
    double dir[3], fs, ft;
    int face;
    brush_dab_sample_direction(d, x, z, dir);
    world_grid_direction_face(dir, &face, &fs, &ft);
    layer_grid g = *grid;
    g.face = face;
    const double n = (double)d->face_samples, k = d->index_scale;
    double u = ((fs + 1.0) * 0.5 * n - 0.5) / k, v = ((ft + 1.0) * 0.5 * n - 0.5) / k;
    int64_t i = (int64_t)floor(u), j = (int64_t)floor(v);
    float q[4];
    if (layer_grid_read(w, &g, (grid_rect){i, j, i + 2, j + 2}, q, err) != 0) return -1;
    double a = u - (double)i, b = v - (double)j;
    *out = (float)((q[0] * (1 - a) + q[1] * a) * (1 - b) + (q[2] * (1 - a) + q[3] * a) * b);
    return 0;
}

// Planets: a sample past the face's edge reads the neighbouring face where its
// direction lands (bilinear there), so neighbourhood tools see the surface go on.
static int read_ghost(world_source *s, double x, double z, float *out, og_error *err) {
    return brush_dab_read_sphere(s->w, s->g, s->d, x, z, out, err);
}

static int read_world(void *src, grid_rect r, float *out, og_error *err) {
    world_source *s = src;
    if (layer_grid_read(s->w, s->g, r, out, err) != 0) return -1;
    if (!s->d->sphere || s->g->extent <= 0) return 0;
    const int64_t n = s->g->extent, w = r.x1 - r.x0;
    for (int64_t z = r.z0; z < r.z1; z++)
        for (int64_t x = r.x0; x < r.x1; x++)
            if ((x < 0 || z < 0 || x >= n || z >= n) &&
                read_ghost(s, (double)x, (double)z, &out[(z - r.z0) * w + (x - r.x0)], err) != 0)
                return -1;
    return 0;
}

static const float *world_row(void *user, int64_t y, int64_t x, int64_t *end) {
    const layer_rows *rows = user;
    const float *p = layer_rows_at(rows, rows->r.z0 + y, rows->r.x0 + x, end);
    *end -= rows->r.x0;
    return p;
}

static int blur_world(void *src, grid_rect area, const int64_t (*need)[2], float *out,
                      int64_t *row_at, int k, og_error *err) {
    world_source *s = src;
    layer_rows rows;
    int rc = layer_rows_open(s->w, s->g, area, &rows, err);
    if (rc != 0) return rc; // 1: past the grid's edge (or huge): read whole
    int64_t w = area.x1 - area.x0, h = area.z1 - area.z0;
    rc = row_at ? box_blur_twice_packed(world_row, &rows, need, out, row_at, w, h, k)
                : box_blur_twice_rows(world_row, &rows, need, out, w, h, k);
    layer_rows_close(&rows);
    if (rc != 0)
        return og_error_set(err, "out of memory smoothing (%lld x %lld samples)", (long long)w,
                            (long long)h);
    return 0;
}

struct brush_dab_job {
    edit *e;
    layer_grid g;
    brush_dab d;
    grid_rect r;
    dab_rows rows;
};

int brush_dab_begin(edit *e, const layer_grid *g, const brush_dab *d, brush_dab_job **out,
                    og_error *err) {
    *out = NULL;
    grid_rect r = layer_grid_clip(g, brush_dab_rect(d));
    if (grid_rect_empty(r)) return 0;
    brush_dab_job *j = calloc(1, sizeof *j);
    if (!j) return og_error_set(err, "out of memory");
    *j = (brush_dab_job){.e = e, .g = *g, .d = *d, .r = r};
    world_source src = {edit_world(e), &j->g, &j->d};
    if (prepare(&j->d, g->layer, r, read_world, blur_world, &src, &j->rows, NULL, err) != 0) {
        free(j);
        return -1;
    }
    j->rows.d = &j->d;
    j->rows.e = e, j->rows.layer = g->layer, j->rows.face = g->face;
    *out = j;
    return 0;
}

int brush_dab_finish(brush_dab_job *j, og_error *err) {
    if (!j) return 0;
    int rc = edit_rows_apply(j->e, &j->g, j->r, dab_row, dab_wanted, &j->rows, err);
    brush_dab_discard(j);
    return rc;
}

void brush_dab_discard(brush_dab_job *j) {
    if (!j) return;
    release(&j->rows);
    free(j);
}

int brush_dab_compute_area(edit *e, const layer_grid *g, const brush_dab *d, grid_rect r,
                           brush_dab_area *out, og_error *err) {
    *out = (brush_dab_area){0};
    world_source src = {edit_world(e), g, d};
    dab_rows rows;
    float *before = NULL;
    if (prepare(d, g->layer, r, read_world, blur_world, &src, &rows, &before, err) != 0) return -1;
    float *after = (float *)rows.heights;
    size_t n = (size_t)((rows.area.x1 - rows.area.x0) * (rows.area.z1 - rows.area.z0));
    if (rows.smoothed) { // the smoothed heights laid over those from before
        for (size_t i = 0; i < n; i++) {
            float s = after[i];
            after[i] = before[i];
            blend_smoothed(after + i, &s, rows.weight + i, d->brush->invert, 1);
        }
    }
    free(rows.span);
    free(rows.dx2);
    *out = (brush_dab_area){rows.area, before, after, (float *)rows.weight};
    return 0;
}

void brush_dab_area_free(brush_dab_area *a) {
    free(a->before);
    free(a->after);
    free(a->weight);
    *a = (brush_dab_area){0};
}

int brush_dab_apply(edit *e, const layer_grid *g, const brush_dab *d, og_error *err) {
    brush_dab_job *j;
    if (brush_dab_begin(e, g, d, &j, err) != 0) return -1;
    return brush_dab_finish(j, err);
}
