#include "editor/interchange/import.h"

#include "editor/edit/edit_commit.h"
#include "editor/edit/edit_rows.h"
#include "editor/interchange/sidecar.h"
#include "editor/params/world_georef.h"
#include "editor/world/layer_grid.h"
#include "io/parse.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

void import_options_defaults(import_options *o) {
    memset(o, 0, sizeof *o);
    o->layer = TILE_LAYER_COARSE;
    o->resample = IMPORT_BILINEAR;
    o->blend = IMPORT_REPLACE;
}

static int pick(const char *value, const char *what, const char *const *names, int count, int *out,
                og_error *err) {
    for (int i = 0; i < count; i++)
        if (strcmp(value, names[i]) == 0) return *out = i, 0;
    char list[200] = "";
    for (int i = 0; i < count; i++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? "|" : "", names[i]);
    return og_error_set(err, "%s: expected %s, got '%s'", what, list, value);
}

int import_options_set(import_options *o, const char *key, const char *value, og_error *err) {
    double v;
    int i = 0;
    if (!strcmp(key, "min") || !strcmp(key, "max")) {
        if (parse_number(value, key, &v, err) != 0) return -1;
        *(key[1] == 'i' ? &o->min : &o->max) = v;
        o->has_min_max |= key[1] == 'i' ? 1 : 2;
    } else if (!strcmp(key, "scale") || !strcmp(key, "offset")) {
        if (parse_number(value, key, &v, err) != 0) return -1;
        if (key[0] == 's') {
            o->scale = v;
            o->has_scale = 1;
        } else {
            o->offset = v;
            o->has_scale |= 2; // offset alone keeps scale 1
        }
    } else if (!strcmp(key, "spacing")) {
        if (parse_number_in(value, key, 1e-6, 1e7, &o->spacing, err) != 0) return -1;
    } else if (!strcmp(key, "x") || !strcmp(key, "z")) {
        if (parse_number_in(value, key, -1e15, 1e15, key[0] == 'x' ? &o->x : &o->z, err) != 0)
            return -1;
        o->has_position = 1;
    } else if (!strcmp(key, "anchor")) {
        static const char *const names[] = {"corner", "centre", "center"};
        if (pick(value, key, names, 3, &i, err) != 0) return -1;
        o->anchor_centre = i > 0;
    } else if (!strcmp(key, "layer")) {
        // The grid (coarse, detail) or an edit layer: new, or a layer's name.
        if (!strcmp(value, "coarse") || !strcmp(value, "detail")) {
            o->layer = !strcmp(value, "detail") ? TILE_LAYER_DETAIL : TILE_LAYER_COARSE;
        } else {
            og_error why;
            if (strcmp(value, "new") && layer_name_check(value, &why) != 0)
                return og_error_set(
                    err, "layer: expected coarse, detail, new or a layer's name; %s", why.msg);
            snprintf(o->edit_layer, sizeof o->edit_layer, "%s", value);
        }
    } else if (!strcmp(key, "resample")) {
        static const char *const names[] = {"nearest", "bilinear", "bicubic"};
        if (pick(value, key, names, 3, &i, err) != 0) return -1;
        o->resample = (import_resample)i;
    } else if (!strcmp(key, "blend")) {
        static const char *const names[] = {"replace", "add", "max", "min"};
        if (pick(value, key, names, 4, &i, err) != 0) return -1;
        o->blend = (import_blend)i;
    } else if (!strcmp(key, "falloff")) {
        if (parse_number_in(value, key, 0, 1e9, &o->falloff, err) != 0) return -1;
    } else if (!strcmp(key, "channel")) {
        if (strlen(value) >= sizeof o->read.channel)
            return og_error_set(err, "channel: name too long");
        snprintf(o->read.channel, sizeof o->read.channel, "%s", value);
    } else if (!strcmp(key, "endian")) {
        static const char *const names[] = {"little", "big"};
        if (pick(value, key, names, 2, &i, err) != 0) return -1;
        o->read.endian = (raster_endian)i;
    } else if (!strcmp(key, "format")) {
        static const char *const names[] = {"u16", "f32"};
        if (pick(value, key, names, 2, &i, err) != 0) return -1;
        o->read.raw_float = i;
    } else if (!strcmp(key, "width") || !strcmp(key, "height")) {
        if (parse_integer_in(value, key, 1, RASTER_MAX_SIZE, &v, err) != 0) return -1;
        *(key[0] == 'w' ? &o->read.width : &o->read.height) = (int)v;
    } else {
        return og_error_set(err,
                            "import: unknown option '%s' (min max scale offset spacing x z anchor "
                            "layer resample blend falloff channel endian format width height)",
                            key);
    }
    return 0;
}

// How stored values become metres (height = v x *scale + *offset): the options, else
// the sidecar sc (NULL: none), else by the kind of file.
static int height_mapping(const char *path, const raster *r, const import_options *o,
                          const sidecar *sc, double default_max, double *scale, double *offset,
                          char *how, size_t how_len, og_error *err) {
    if (o->has_scale && o->has_min_max)
        return og_error_set(err, "import: give min=/max= or scale=/offset=, not both");
    if (o->has_scale) {
        *scale = o->has_scale & 1 ? o->scale : 1.0;
        *offset = o->offset;
        snprintf(how, how_len, "height = stored x %.9g + %.9g m", *scale, *offset);
        return 0;
    }
    // The stored range a normalised format spans: integers 0 .. 2^bits - 1; float 0 .. 1.
    double top = r->kind == RASTER_FLOAT ? 1.0 : ldexp(1.0, r->bits) - 1.0;
    if (r->kind == RASTER_SIGNED) top = ldexp(1.0, r->bits - 1) - 1.0;
    if (o->has_min_max) {
        if (o->has_min_max != 3) return og_error_set(err, "import: min= and max= go together");
        *scale = (o->max - o->min) / top;
        *offset = o->min;
        snprintf(how, how_len, "stored 0..%.9g mapped to %.9g..%.9g m", top, o->min, o->max);
        return 0;
    }
    if (sc && r->georef.mapped) { // e.g. our 16-bit GeoTIFF: the band says what its sidecar says
        *scale = 1.0;
        *offset = 0.0;
        snprintf(how, how_len, "metres by the file's own scale and offset");
        return 0;
    }
    if (sc) {
        *scale = sc->scale;
        *offset = sc->offset;
        snprintf(how, how_len, "from %s.json: height = stored x %.9g + %.9g m", path, *scale,
                 *offset);
        return 0;
    }
    if (r->kind == RASTER_UNSIGNED && strcmp(r->reader, "gdal") != 0) {
        // A plain image or RAW carries no units: 0..top spans 0..default_max metres.
        *scale = default_max / top;
        *offset = 0.0;
        snprintf(how, how_len,
                 "stored 0..%.9g mapped to 0..%.9g m (the world's max_height; give min= max= "
                 "to choose)",
                 top, default_max);
        return 0;
    }
    *scale = 1.0;
    *offset = 0.0;
    snprintf(how, how_len, "metres as stored");
    return 0;
}

typedef struct import_op {
    const float *src; // mapped heights, width x height
    int width, height;
    double x0, z0;       // world position of the first sample
    double sx, sz;       // metres per source sample
    double grid_spacing; // metres per layer sample
    import_resample resample;
    import_blend blend;
    double falloff;
} import_op;

static float at(const import_op *o, int64_t i, int64_t j) {
    i = i < 0 ? 0 : i >= o->width ? o->width - 1 : i;
    j = j < 0 ? 0 : j >= o->height ? o->height - 1 : j;
    return o->src[j * o->width + i];
}

static double cubic(double a, double b, double c, double d, double t) { // Catmull-Rom
    return b + 0.5 * t * (c - a + t * (2 * a - 5 * b + 4 * c - d + t * (3 * (b - c) + d - a)));
}

// A source coordinate that lands within rounding of a sample is that sample: equal
// spacings then copy samples exactly (the round-trip guarantee).
static double snap(double u) {
    double r = round(u);
    return fabs(u - r) < 1e-6 ? r : u;
}

static double sample(const import_op *o, double u, double v) {
    u = snap(u);
    v = snap(v);
    if (o->resample == IMPORT_NEAREST) return at(o, (int64_t)llround(u), (int64_t)llround(v));
    int64_t i = (int64_t)floor(u), j = (int64_t)floor(v);
    double tu = u - (double)i, tv = v - (double)j;
    if (tu == 0 && tv == 0) return at(o, i, j);
    if (o->resample == IMPORT_BILINEAR) {
        double a = at(o, i, j) * (1 - tu) + at(o, i + 1, j) * tu;
        double b = at(o, i, j + 1) * (1 - tu) + at(o, i + 1, j + 1) * tu;
        return a * (1 - tv) + b * tv;
    }
    double rows[4];
    for (int k = 0; k < 4; k++)
        rows[k] = cubic(at(o, i - 1, j - 1 + k), at(o, i, j - 1 + k), at(o, i + 1, j - 1 + k),
                        at(o, i + 2, j - 1 + k), tu);
    return cubic(rows[0], rows[1], rows[2], rows[3], tv);
}

// Whether the row's samples all land on source samples (equal spacing, a whole-sample
// offset): then a replace is a copy, as sample() would give, at memory speed.
static const float *source_row_on_grid(const import_op *o, double u0, double v, int64_t n) {
    if (o->blend != IMPORT_REPLACE || o->falloff > 0 || o->sx != o->grid_spacing) return NULL;
    const double su = snap(u0), sv = snap(v);
    if (su != round(su) || sv != round(sv)) return NULL;
    if (su < 0 || sv < 0 || su + (double)n > o->width || sv >= o->height) return NULL;
    return o->src + (size_t)sv * (size_t)o->width + (size_t)su;
}

static void import_row(void *user, void *row, int64_t z, int64_t x0, int64_t x1) {
    const import_op *o = user;
    float *h = row;
    const double wz = (double)z * o->grid_spacing;
    const double v = (wz - o->z0) / o->sz;
    const float *copy =
        source_row_on_grid(o, ((double)x0 * o->grid_spacing - o->x0) / o->sx, v, x1 - x0);
    if (copy) {
        memcpy(h, copy, sizeof(float) * (size_t)(x1 - x0));
        return;
    }
    const double span_x = (o->width - 1) * o->sx, span_z = (o->height - 1) * o->sz;
    for (int64_t x = x0; x < x1; x++) {
        const double wx = (double)x * o->grid_spacing;
        double val = sample(o, (wx - o->x0) / o->sx, v);
        double weight = 1.0;
        if (o->falloff > 0) {
            double d =
                fmin(fmin(wx - o->x0, o->x0 + span_x - wx), fmin(wz - o->z0, o->z0 + span_z - wz));
            double t = fmax(0.0, fmin(1.0, d / o->falloff));
            weight = t * t * (3 - 2 * t);
        }
        const double old = h[x - x0];
        double target = val;
        switch (o->blend) {
        case IMPORT_REPLACE:
            break;
        case IMPORT_ADD:
            target = old + val;
            break;
        case IMPORT_MAX:
            target = fmax(old, val);
            break;
        case IMPORT_MIN:
            target = fmin(old, val);
            break;
        }
        h[x - x0] = weight == 1.0 ? (float)target : (float)(old + (target - old) * weight);
    }
}

void import_source_free(import_source *s) {
    raster_free(&s->raster);
}

// h = h x scale + offset (when mapped), and the lowest and highest of h, and whether
// any is not finite: one pass, eight lanes at a time, which the compiler vectorises
// (16.8 M samples of a 4097^2 PNG took 45 ms one at a time, a fixed cost of every
// shard of a world made from it). Inlined with mapped a constant: no test per sample.
static inline __attribute__((always_inline)) void map_heights(float *h, size_t n, int mapped,
                                                              double scale, double offset,
                                                              float *lo, float *hi,
                                                              int *not_finite) {
    float lo8[8], hi8[8];
    int bad8[8] = {0};
    for (int j = 0; j < 8; j++)
        lo8[j] = INFINITY, hi8[j] = -INFINITY;
    size_t i = 0;
    for (; i + 8 <= n; i += 8)
        for (int j = 0; j < 8; j++) {
            const float v = mapped ? (float)((double)h[i + j] * scale + offset) : h[i + j];
            h[i + j] = v;
            bad8[j] |= !(fabsf(v) <= FLT_MAX);
            lo8[j] = v < lo8[j] ? v : lo8[j];
            hi8[j] = v > hi8[j] ? v : hi8[j];
        }
    for (int j = 0; i < n; i++, j++) {
        const float v = mapped ? (float)((double)h[i] * scale + offset) : h[i];
        h[i] = v;
        bad8[j] |= !(fabsf(v) <= FLT_MAX);
        lo8[j] = v < lo8[j] ? v : lo8[j];
        hi8[j] = v > hi8[j] ? v : hi8[j];
    }
    for (int j = 0; j < 8; j++) {
        *not_finite |= bad8[j];
        *lo = lo8[j] < *lo ? lo8[j] : *lo;
        *hi = hi8[j] > *hi ? hi8[j] : *hi;
    }
}

int import_source_read(const char *path, const import_options *o, double default_max,
                       import_source *s, og_error *err) {
    memset(s, 0, sizeof *s);
    sidecar sc;
    int has_sidecar = sidecar_read(path, &sc, err);
    if (has_sidecar < 0) return -1;
    if (raster_read(path, &o->read, &s->raster, err) != 0) return -1;
    raster *r = &s->raster;
    double scale = 1.0, offset = 0.0;
    if (height_mapping(path, r, o, has_sidecar ? &sc : NULL, default_max, &scale, &offset,
                       s->mapping, sizeof s->mapping, err) != 0) {
        import_source_free(s);
        return -1;
    }
    const size_t n = (size_t)r->width * (size_t)r->height;
    float *h = r->samples, lo = INFINITY, hi = -INFINITY;
    int not_finite = 0;
    if (scale != 1.0 || offset != 0.0)
        map_heights(h, n, 1, scale, offset, &lo, &hi, &not_finite);
    else
        map_heights(h, n, 0, 1.0, 0.0, &lo, &hi, &not_finite);
    for (size_t i = 0; not_finite && i < n; i++)
        if (!isfinite(h[i])) {
            og_error_set(err, "%s: sample (%zu, %zu) maps to %g m, not a height", path,
                         i % (size_t)r->width, i / (size_t)r->width, (double)h[i]);
            import_source_free(s);
            return -1;
        }
    s->min = lo;
    s->max = hi;
    // Orogen's sidecar says how far apart the samples were in the world they came from
    // (a georeferenced export's own georeferencing may be in degrees).
    s->spacing_x = o->spacing > 0 ? o->spacing : has_sidecar ? sc.spacing : r->spacing_x;
    s->spacing_z = o->spacing > 0 ? o->spacing : has_sidecar ? sc.spacing_z : r->spacing_z;
    // A file Orogen exported from a georeferenced world keeps its place in its sidecar
    // (a PNG or EXR has no room for it).
    gdal_georef *geo = &r->georef;
    const int georeferenced =
        geo->geotransform[1] * geo->geotransform[5] - geo->geotransform[2] * geo->geotransform[4] !=
        0;
    if (has_sidecar && sc.has_georef && !georeferenced) {
        memcpy(geo->geotransform, sc.geotransform, sizeof geo->geotransform);
        snprintf(geo->crs, sizeof geo->crs, "%s", sc.crs);
    }
    if (has_sidecar) {
        s->has_origin = 1;
        s->origin_x = sc.origin_x;
        s->origin_z = sc.origin_z;
    }
    return 0;
}

int import_preview_read(const char *path, const import_options *o, import_preview *p,
                        og_error *err) {
    memset(p, 0, sizeof *p);
    p->has_sidecar = sidecar_read(path, &p->sc, err);
    if (p->has_sidecar < 0) return -1;
    raster r;
    if (raster_read(path, &o->read, &r, err) != 0) return -1;
    const size_t n = (size_t)r.width * (size_t)r.height;
    float lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        lo = fminf(lo, r.samples[i]);
        hi = fmaxf(hi, r.samples[i]);
    }
    p->stored_min = lo;
    p->stored_max = hi;
    const double bin = hi > lo ? ((double)hi - lo) / IMPORT_PREVIEW_BINS : 1.0;
    for (size_t i = 0; i < n; i++) {
        int b = (int)(((double)r.samples[i] - lo) / bin);
        p->histogram[b < IMPORT_PREVIEW_BINS ? b : IMPORT_PREVIEW_BINS - 1]++;
    }
    p->header = r;
    p->header.samples = NULL;
    raster_free(&r);
    return 0;
}

int import_preview_mapping(const char *path, const import_preview *p, const import_options *o,
                           double default_max, double *scale, double *offset, char *how,
                           size_t how_len, og_error *err) {
    return height_mapping(path, &p->header, o, p->has_sidecar ? &p->sc : NULL, default_max, scale,
                          offset, how, how_len, err);
}

// A world with no place on the Earth yet takes the raster's, in the same step. GDAL's
// geotransform maps pixel corners and a sample lies at its pixel's centre: world corner
// coordinate C is world sample C - 1/2, at raster sample u0 + (C - 1/2) du, whose corner
// coordinate is that + 1/2 (du = world spacing / raster spacing; the same down rows).
static int adopt_georef(world_params *next, const gdal_georef *geo, const import_op *op) {
    const double *a = geo->geotransform;
    if (world_georef_present(next) || a[1] * a[5] - a[2] * a[4] == 0) return 0;
    const double du = next->spacing / op->sx, dv = next->spacing / op->sz;
    const double u = -op->x0 / op->sx + 0.5 * (1 - du), v = -op->z0 / op->sz + 0.5 * (1 - dv);
    double *g = next->geo_transform;
    g[0] = a[0] + u * a[1] + v * a[2];
    g[1] = a[1] * du;
    g[2] = a[2] * dv;
    g[3] = a[3] + u * a[4] + v * a[5];
    g[4] = a[4] * du;
    g[5] = a[5] * dv;
    snprintf(next->geo_crs, sizeof next->geo_crs, "%s", geo->crs);
    return 1;
}

int import_apply(world *w, const char *path, const import_options *o, import_report *report,
                 og_error *err) {
    import_source s;
    if (import_source_read(path, o, world_get_params(w)->max_height, &s, err) != 0) return -1;
    int rc = import_apply_source(w, path, &s, o, report, err);
    import_source_free(&s);
    return rc;
}

// layer=new|NAME: the table with that layer made (named after the file) or picked, active.
static int aim_at_layer(layer_table *t, const import_options *o, const char *file, og_error *err) {
    if (strcmp(o->edit_layer, "new")) {
        int i = layer_table_find(t, o->edit_layer);
        if (i < 0)
            return og_error_set(err, "layer: no layer named '%s' (layer=new makes one)",
                                o->edit_layer);
        if (t->layers[i].kind != LAYER_KIND_HEIGHT)
            return og_error_set(err, "layer: '%s' is a paint layer: heights go into a height layer",
                                o->edit_layer);
        t->active = i;
        return 0;
    }
    char stem[LAYER_NAME_MAX - 8], name[LAYER_NAME_MAX];
    size_t n = 0;
    for (const char *c = file; *c && *c != '.' && n + 1 < sizeof stem; c++) // letters kept
        stem[n++] = (char)((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') ||
                                   (*c >= '0' && *c <= '9') || *c == '-'
                               ? *c
                               : '_');
    stem[n] = 0;
    if (!n) snprintf(stem, sizeof stem, "import");
    snprintf(name, sizeof name, "%s", stem);
    for (int k = 2; layer_table_find(t, name) >= 0 && k < 1000; k++)
        snprintf(name, sizeof name, "%s_%d", stem, k);
    og_error why;
    int at = layer_table_insert(t, t->count ? t->active + 1 : 0, name, LAYER_BLEND_ADD, 1.0, &why);
    if (at < 0) return og_error_set(err, "layer=new: %s", why.msg);
    t->active = at;
    return 0;
}

int import_apply_source(world *w, const char *path, const import_source *s, const import_options *o,
                        import_report *report, og_error *err) {
    const world_params *p = world_get_params(w);
    layer_grid g;
    if (layer_grid_init(&g, p, o->layer, 0, err) != 0) return -1;
    if (p->kind == WORLD_PLANET)
        return og_error_set(err, "import: planets take no rasters yet (import onto a flat world)");
    const raster *r = &s->raster;
    import_report rep;
    memset(&rep, 0, sizeof rep);
    snprintf(rep.mapping, sizeof rep.mapping, "%s", s->mapping);
    rep.min = s->min;
    rep.max = s->max;
    double sx = s->spacing_x, sz = s->spacing_z;
    if (sx <= 0) sx = sz = g.spacing; // one sample per pixel
    import_op op = {r->samples, r->width,  r->height,   0,        0,         sx,
                    sz,         g.spacing, o->resample, o->blend, o->falloff};
    if (o->has_position) {
        op.x0 = o->x;
        op.z0 = o->z;
    } else if (s->has_origin) {
        op.x0 = s->origin_x;
        op.z0 = s->origin_z;
    }
    if (o->anchor_centre) {
        // The middle sample (the lower of the two middles on an even side) goes to x, z:
        // an even-sized raster then lands on whole samples instead of half way between
        // them (which resampled it, each sample the mean of two, and lost a row).
        op.x0 -= (double)(r->width / 2) * sx;
        op.z0 -= (double)(r->height / 2) * sz;
    }
    const double x1 = op.x0 + (r->width - 1) * sx, z1 = op.z0 + (r->height - 1) * sz;
    if (layer_grid_check_position(&g, op.x0, op.z0, err) != 0 ||
        layer_grid_check_position(&g, x1, z1, err) != 0) {
        // Said as the import's placement, not as a bare position the user never typed.
        if (g.extent > 0 && isfinite(op.x0) && isfinite(x1) && isfinite(op.z0) && isfinite(z1))
            og_error_set(err,
                         "%s: placed at %.9g, %.9g .. %.9g, %.9g m (%.9g x %.9g m apart) it "
                         "reaches beyond the world (0 .. %.9g, 0 .. %.9g m): give a smaller "
                         "spacing= or another x=, z=",
                         path, op.x0, op.z0, x1, z1, sx, sz, (double)(g.extent - 1) * g.spacing,
                         (double)(g.extent_z - 1) * g.spacing);
        return -1;
    }
    // The layer samples the raster covers (within rounding of its edges).
    grid_rect want = {
        (int64_t)ceil(op.x0 / g.spacing - 1e-6), (int64_t)ceil(op.z0 / g.spacing - 1e-6),
        (int64_t)floor(x1 / g.spacing + 1e-6) + 1, (int64_t)floor(z1 / g.spacing + 1e-6) + 1};
    grid_rect rect = layer_grid_clip(&g, want);
    if (grid_rect_empty(rect)) {
        og_error_set(err,
                     "%s: placed at %.9g, %.9g .. %.9g, %.9g m it lies outside the world "
                     "(0 .. %.9g, 0 .. %.9g m)",
                     path, op.x0, op.z0, x1, z1, (double)(g.extent - 1) * g.spacing,
                     (double)(g.extent_z - 1) * g.spacing);
        return -1;
    }
    const double covered = (double)(rect.x1 - rect.x0) * (double)(rect.z1 - rect.z0);
    if (covered > (double)IMPORT_MAX_SAMPLES) {
        og_error_set(err,
                     "%s: it covers %lld x %lld samples of the world (%.3g m apart), over the "
                     "limit of %lld in one import: give a larger spacing= or make a world from "
                     "it (new flat from=FILE)",
                     path, (long long)(rect.x1 - rect.x0), (long long)(rect.z1 - rect.z0),
                     g.spacing, (long long)IMPORT_MAX_SAMPLES);
        return -1;
    }
    char label[300];
    const char *slash = strrchr(path, '/');
    snprintf(label, sizeof label, "import %s", slash ? slash + 1 : path);
    world_params next = *p;
    if (o->edit_layer[0] && aim_at_layer(&next.layers, o, slash ? slash + 1 : path, err) != 0)
        return -1;
    const grid_rect written = o->has_limit ? grid_rect_intersect(rect, o->limit) : rect;
    edit *e = edit_begin(w, label, err);
    if (!e) return -1;
    if (o->starting_state) edit_set_starting_state(e);
    rep.adopted_georef = adopt_georef(&next, &r->georef, &op);
    if (((o->edit_layer[0] || rep.adopted_georef) && edit_set_params(e, &next, err) != 0) ||
        (!grid_rect_empty(written) &&
         edit_rows_apply(e, &g, written, import_row, NULL, &op, err) != 0)) {
        edit_abort(e);
        return -1;
    }
    if (edit_commit(e, err) != 0) return -1;
    rep.width = r->width;
    rep.height = r->height;
    rep.spacing_x = sx;
    rep.spacing_z = sz;
    rep.voids = r->voids;
    rep.x0 = (double)rect.x0 * g.spacing;
    rep.z0 = (double)rect.z0 * g.spacing;
    rep.x1 = (double)(rect.x1 - 1) * g.spacing;
    rep.z1 = (double)(rect.z1 - 1) * g.spacing;
    rep.samples = (rect.x1 - rect.x0) * (rect.z1 - rect.z0);
    snprintf(rep.source, sizeof rep.source, "%s", r->description);
    if (report) *report = rep;
    return 0;
}
