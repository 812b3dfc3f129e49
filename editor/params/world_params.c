#include "editor/params/world_params.h"

#include "io/crc32c.h"

#include "io/param_file.h"
#include "io/parse.h"

#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

// Largest flat world: 2^31 tiles of 256 samples per side, what int32 tile ids
// address from the origin outwards.
#define WORLD_SIZE_MAX (INT64_C(1) << 39)

typedef enum value_type {
    V_KIND,
    V_GEN,
    V_I64,
    V_I32,
    V_F64,
    V_STR,
    V_ID,
    V_CRS,
    V_GEOT
} value_type;

// Range flags: whether lo / hi are themselves allowed.
enum { LO_OPEN = 1, HI_OPEN = 2, NO_LO = 4, NO_HI = 8 };

typedef struct key_def {
    const char *name;
    value_type type;
    size_t offset;
    double lo, hi;
    int range;
    const char *help;
} key_def;

#define F(field) offsetof(world_params, field)

// Canonical order: the order of `params` and of saved files.
static const key_def KEYS[] = {
    {"kind", V_KIND, F(kind), 0, 0, 0, "what the world is: flat or planet"},
    {"generator", V_GEN, F(generator), 0, 0, 0,
     "terrain generator: fbm (0), fbm_advanced (1), ridged (2), diamond_square (3), faults (4), "
     "flat (5), planet (6), craters (7)"},
    {"seed", V_I64, F(seed), 0, 0, NO_LO | NO_HI,
     "random seed, any integer (the generators use it modulo 2^32)"},
    {"octaves", V_F64, F(octaves), 0, 30, LO_OPEN,
     "fBm octave count, 0 < octaves <= 30; a fractional part fades in the last octave"},
    {"w_factor", V_F64, F(w_factor), 0, 1.5, LO_OPEN | HI_OPEN,
     "fBm gain: amplitude multiplier per octave, 0 < w_factor < 1.5"},
    {"exponent", V_F64, F(exponent), 1, 8, LO_OPEN,
     "fBm lacunarity: frequency multiplier per octave, 1 < exponent <= 8"},
    {"max_height", V_F64, F(max_height), 0, 1e6, LO_OPEN,
     "metres: generated heights lie within +-max_height, 0 < max_height <= 1e6"},
    {"ocean_level", V_F64, F(ocean_level), 0, 0, NO_LO | NO_HI,
     "metres: flat worlds: height of the water plane above the datum; planets: the sea's radius "
     "from the centre (seed 004), e.g. radius + 10 puts the sea 10 m above the datum"},
    {"radius", V_F64, F(radius), 0, 1e9, LO_OPEN,
     "planets: metres from the centre to the datum, 0 < radius <= 1e9"},
    {"omega", V_F64, F(omega), 0, 0, NO_LO | NO_HI,
     "planets: angular velocity in radians per second (turns the light)"},
    {"atmosphere", V_F64, F(atmosphere), 0, 100, 0,
     "planets: how much air, relative to Earth's (its scale height follows the radius): 1 "
     "Earth-like, 0 none (the sky is black), 0 .. 100"},
    {"spacing", V_F64, F(spacing), 0, 1e5, LO_OPEN,
     "metres between coarse height samples, 0 < spacing <= 1e5"},
    {"size", V_I64, F(size), 0, (double)WORLD_SIZE_MAX, 0,
     "flat worlds: coarse samples along X (and along Z unless size_z says), 0 = unbounded, "
     "else 2 .. 2^39"},
    {"size_z", V_I64, F(size_z), 0, (double)WORLD_SIZE_MAX, 0,
     "flat worlds: coarse samples along Z when the world is not square (a DEM's rows), 0 = as "
     "size, else 2 .. 2^39"},
    {"detail_ratio", V_I32, F(detail_ratio), 1, 64, 0,
     "detail samples per coarse sample, per side, 1 .. 64"},
    {"volume_ratio", V_I32, F(volume_ratio), 1, 8, 0,
     "volume voxels (overhangs, caves) per coarse spacing, per side, 1 .. 8: voxel size = "
     "spacing / volume_ratio"},
    {"feature_size", V_F64, F(feature_size), 0, 1e9, 0,
     "metres: wavelength of the lowest octave, 0 = automatic"},
    {"base_height", V_F64, F(base_height), 0, 0, NO_LO | NO_HI,
     "metres added to every generated height (the flat generator's height)"},
    {"roughness", V_F64, F(roughness), 0, 2, 0,
     "diamond-square: first displacement as a fraction of max_height, 0 .. 2"},
    {"smoothing", V_F64, F(smoothing), 0, 1, 0,
     "diamond-square: roughness multiplier per subdivision, 0 .. 1"},
    {"ridge_offset", V_F64, F(ridge_offset), 0, 2, 0,
     "ridged multifractal: offset subtracted from |noise|, 0 .. 2"},
    {"fault_count", V_I32, F(fault_count), 0, 10000, 0,
     "faults: fault lines per 64 km x 64 km cell, 0 .. 10000"},
    {"geo_crs", V_CRS, F(geo_crs), 0, 0, 0,
     "georeferenced worlds: the source data's coordinate reference system (WKT or EPSG:N), "
     "written into GeoTIFF exports and sidecars; empty = none"},
    {"geo_transform", V_GEOT, F(geo_transform), 0, 0, 0,
     "georeferenced worlds: GDAL's geotransform from coarse sample (column, row) to geo_crs "
     "coordinates (X0, dX per column, dX per row, Y0, dY per column, dY per row; X0, Y0 the "
     "outer corner of sample 0, 0's cell); empty = none"},
    {"tiles", V_STR, F(tiles), 0, 0, 0,
     "tile store (sculpted and painted data), relative to this file; empty = <name>.tiles"},
    {"tiles_id", V_ID, F(tiles_id), 0, 0, 0,
     "written by save: the world's id, also kept in its tile store (a missing or other store "
     "is noticed); empty = not recorded"},
    {"tiles_saved", V_I64, F(tiles_saved), -1, 1e15, 0,
     "written by save: how many tiles the store held (an emptied store is noticed); -1 = not "
     "recorded"},
};

#undef F

#define KEY_COUNT (sizeof KEYS / sizeof KEYS[0])

static const char *const GEN_NAMES[GEN_COUNT] = {
    "fbm", "fbm_advanced", "ridged", "diamond_square", "faults", "flat", "planet", "craters"};

static const char *const KIND_NAMES[] = {"flat", "planet"};

void world_params_default(world_params *p, world_kind kind) {
    *p = (world_params){
        .kind = kind,
        .generator = GEN_FBM,
        .seed = 1337,
        .octaves = 8,
        .w_factor = 0.5,
        .exponent = 2.0,
        .max_height = 1200,
        // Below most of the land: water only fills the low basins.
        .ocean_level = -400,
        .radius = 6371000,
        .omega = 0, // a still sun: an editor wants steady light
        .atmosphere = 1,
        .spacing = 2,
        .size = 0,
        .detail_ratio = 4,
        .volume_ratio = 1,
        .feature_size = 0,
        .base_height = 0,
        .roughness = 0.4, // Harris 2011
        .smoothing = 0.5, // Harris 2011
        .ridge_offset = 1.0,
        .fault_count = 100,
        .tiles = "",
        .tiles_id = "",
        .tiles_saved = -1,
    };
    if (kind == WORLD_PLANET) {
        // Earth-sized, with Kahoun 2010's advanced generator, gain and lacunarity.
        p->generator = GEN_FBM_ADVANCED;
        p->octaves = 12.5;
        p->max_height = 8848;
        p->ocean_level = p->radius; // a radius on planets (seed 004): the sea at the datum
        p->omega = 7.2921e-5;
        p->spacing = 100;
    }
    if (kind == WORLD_PLANET)
        material_rules_planet_default(&p->material_rules);
    else
        material_rules_default(&p->material_rules);
}

double world_params_ocean_height(const world_params *p) {
    return p->kind == WORLD_PLANET ? p->ocean_level - p->radius : p->ocean_level;
}

const char *gen_kind_name(gen_kind g) {
    return (unsigned)g < GEN_COUNT ? GEN_NAMES[g] : NULL;
}

int gen_kind_parse(const char *text) {
    if (!text) return -1;
    for (int i = 0; i < GEN_COUNT; i++)
        if (!strcasecmp(text, GEN_NAMES[i])) return i;
    if (text[0] >= '0' && text[0] <= '9' && text[1] == 0 && text[0] - '0' < GEN_COUNT)
        return text[0] - '0';
    return -1;
}

static const key_def *find_def(const char *key) {
    for (size_t i = 0; i < KEY_COUNT; i++)
        if (!strcmp(KEYS[i].name, key)) return &KEYS[i];
    return NULL;
}

size_t world_params_key_count(void) {
    return KEY_COUNT;
}

const char *world_params_key(size_t i) {
    return i < KEY_COUNT ? KEYS[i].name : NULL;
}

const char *world_params_key_help(const char *key) {
    const key_def *d = key ? find_def(key) : NULL;
    return d ? d->help : NULL;
}

static int bad_value(og_error *err, const key_def *d, const char *expected, const char *value) {
    char q[64];
    parse_quote(q, sizeof q, value);
    return og_error_set(err, "%s: expected %s, got %s", d->name, expected, q);
}

static int in_range(const key_def *d, double v) {
    if (!(d->range & NO_LO) && ((d->range & LO_OPEN) ? !(v > d->lo) : !(v >= d->lo))) return 0;
    if (!(d->range & NO_HI) && ((d->range & HI_OPEN) ? !(v < d->hi) : !(v <= d->hi))) return 0;
    return 1;
}

// "a number with 0 < x <= 30" etc., for messages.
static void describe_range(char *buf, size_t len, const key_def *d, const char *what) {
    char lo[32], hi[32];
    parse_format_f64(lo, sizeof lo, d->lo);
    parse_format_f64(hi, sizeof hi, d->hi);
    if ((d->range & (NO_LO | NO_HI)) == (NO_LO | NO_HI))
        snprintf(buf, len, "%s", what);
    else if (d->range & NO_HI)
        snprintf(buf, len, "%s %s %s", what, (d->range & LO_OPEN) ? ">" : ">=", lo);
    else
        snprintf(buf, len, "%s with %s %s %s %s %s", what, lo,
                 (d->range & LO_OPEN) ? "<" : "<=", d->name, (d->range & HI_OPEN) ? "<" : "<=", hi);
}

// A tiles value must survive a save: no characters the file syntax gives a meaning to.
static int tiles_value_ok(const char *v) {
    size_t n = strlen(v);
    if (n >= sizeof(((world_params *)0)->tiles)) return 0;
    if (n && (v[0] == ' ' || v[0] == '\t' || v[n - 1] == ' ' || v[n - 1] == '\t')) return 0;
    for (const unsigned char *c = (const unsigned char *)v; *c; c++)
        if (*c < 0x20 || *c == 0x7f || *c == ';' || *c == '#') return 0;
    return 1;
}

int world_params_set(world_params *p, const char *key, const char *value, og_error *err) {
    const key_def *d = key ? find_def(key) : NULL;
    if (!d) {
        og_error_set(err, "unknown key '%s'", key ? key : "(null)");
        return 1;
    }
    if (!value) value = "";
    void *field = (char *)p + d->offset;
    char what[128];
    switch (d->type) {
    case V_KIND:
        for (int k = 0; k < 2; k++) {
            if (!strcasecmp(value, KIND_NAMES[k])) {
                p->kind = (world_kind)k;
                return 0;
            }
        }
        return bad_value(err, d, "flat or planet", value);
    case V_GEN: {
        int g = gen_kind_parse(value);
        if (g < 0)
            return bad_value(err, d,
                             "a generator name (fbm, fbm_advanced, ridged, diamond_square, "
                             "faults, flat, planet, craters) or index 0..7",
                             value);
        p->generator = (gen_kind)g;
        return 0;
    }
    case V_I64:
    case V_I32: {
        int64_t v;
        describe_range(what, sizeof what, d, "an integer");
        if (parse_i64(value, &v) != 0 || !in_range(d, (double)v))
            return bad_value(err, d, what, value);
        if (d->type == V_I64)
            memcpy(field, &v, sizeof v);
        else
            *(int32_t *)field = (int32_t)v;
        return 0;
    }
    case V_F64: {
        double v;
        describe_range(what, sizeof what, d, "a finite number");
        if (parse_f64(value, &v) != 0 || !in_range(d, v)) return bad_value(err, d, what, value);
        memcpy(field, &v, sizeof v);
        return 0;
    }
    case V_STR:
        if (!tiles_value_ok(value))
            return bad_value(err, d,
                             "a relative path under 1024 bytes without ';', '#', control "
                             "characters or surrounding blanks",
                             value);
        memcpy(p->tiles, value, strlen(value) + 1);
        return 0;
    case V_CRS:
        // Kept as written; it must survive a save (one line, no ';' or '#').
        if (strlen(value) >= WORLD_CRS_MAX || strpbrk(value, ";#\n\r"))
            return bad_value(err, d,
                             "a coordinate reference system as WKT or EPSG:N, one line under "
                             "3584 bytes without ';' or '#'",
                             value);
        memcpy(p->geo_crs, value, strlen(value) + 1);
        return 0;
    case V_GEOT: {
        double gt[6] = {0};
        const char *at = value;
        if (*value) {
            for (int k = 0; k < 6; k++) {
                const char *end;
                if (parse_scan_f64(at, &gt[k], &end) != 0 || !isfinite(gt[k]) ||
                    (k < 5 && *end != ',') || (k == 5 && *end))
                    return bad_value(err, d, "six numbers apart by commas, or nothing", value);
                if (k == 5) break; // end is the terminator: nothing after it to read
                at = end + 1;
                while (*at == ' ')
                    at++;
            }
            if (gt[1] * gt[5] - gt[2] * gt[4] == 0)
                return bad_value(err, d, "a geotransform whose columns and rows are independent",
                                 value);
        }
        memcpy(p->geo_transform, gt, sizeof gt);
        return 0;
    }
    case V_ID: {
        size_t n = strlen(value);
        int ok = n == 0 || n == WORLD_ID_CHARS;
        for (size_t i = 0; ok && i < n; i++)
            ok = (value[i] >= '0' && value[i] <= '9') || (value[i] >= 'a' && value[i] <= 'f');
        if (!ok) return bad_value(err, d, "32 lowercase hexadecimal digits, or nothing", value);
        memcpy(p->tiles_id, value, n + 1);
        return 0;
    }
    }
    return -1;
}

int world_params_read_entry(world_params *p, const char *key, const char *value, og_error *err) {
    int rc = layer_table_read_entry(&p->layers, key, value, err);
    if (rc == 1) rc = material_rules_read_entry(&p->material_rules, key, value, err);
    return rc == 1 ? world_params_set(p, key, value, err) : rc;
}

int world_params_get(const world_params *p, const char *key, char *buf, size_t len) {
    const key_def *d = key ? find_def(key) : NULL;
    if (!d || !buf || !len) return -1;
    const void *field = (const char *)p + d->offset;
    char tmp[200];
    const char *text = tmp;
    switch (d->type) {
    case V_KIND:
        text = (unsigned)p->kind < 2 ? KIND_NAMES[p->kind] : "?";
        break;
    case V_GEN:
        text = gen_kind_name(p->generator);
        if (!text) text = "?";
        break;
    case V_I64: {
        int64_t v;
        memcpy(&v, field, sizeof v);
        snprintf(tmp, sizeof tmp, "%" PRId64, v);
        break;
    }
    case V_I32:
        snprintf(tmp, sizeof tmp, "%" PRId32, *(const int32_t *)field);
        break;
    case V_F64: {
        double v;
        memcpy(&v, field, sizeof v);
        parse_format_f64(tmp, sizeof tmp, v);
        break;
    }
    case V_STR:
        text = p->tiles;
        break;
    case V_ID:
        text = p->tiles_id;
        break;
    case V_CRS:
        text = p->geo_crs;
        break;
    case V_GEOT: {
        const double *gt = p->geo_transform;
        tmp[0] = 0;
        if (gt[0] || gt[1] || gt[2] || gt[3] || gt[4] || gt[5])
            for (int k = 0; k < 6; k++) {
                size_t n = strlen(tmp);
                if (k) n += (size_t)snprintf(tmp + n, sizeof tmp - n, ", ");
                parse_format_f64(tmp + n, sizeof tmp - n, gt[k]);
            }
        break;
    }
    }
    size_t n = strnlen(text, len);
    if (n >= len) return -1;
    memcpy(buf, text, n + 1);
    return 0;
}

int world_params_validate(const world_params *p, og_error *err) {
    char buf[WORLD_VALUE_MAX];
    // Every field must also be a value `set` would accept (structs can be filled directly).
    for (size_t i = 0; i < KEY_COUNT; i++) {
        if (world_params_get(p, KEYS[i].name, buf, sizeof buf) != 0)
            return og_error_set(err, "%s: invalid value", KEYS[i].name);
        world_params probe = *p;
        if (world_params_set(&probe, KEYS[i].name, buf, err) != 0) return -1;
    }
    if (p->kind == WORLD_PLANET) {
        if (!(p->max_height < p->radius))
            return og_error_set(err, "max_height: must be below radius (%g m), got %g m", p->radius,
                                p->max_height);
        // A radius (seed 004); 0 .. below the lowest ground is a planet without a sea.
        if (!(p->ocean_level >= 0 && p->ocean_level <= p->radius + p->max_height))
            return og_error_set(err,
                                "ocean_level: on a planet the sea's radius (seed 004), 0 .. radius "
                                "+ max_height = %.9g m, got %.9g (the datum is radius = %.9g m)",
                                p->radius + p->max_height, p->ocean_level, p->radius);
    } else if (p->size == 1) {
        return og_error_set(err, "size: a flat world needs 0 (unbounded) or at least 2 samples "
                                 "per side, got 1");
    } else if (p->size_z == 1 || (p->size_z > 0 && p->size == 0)) {
        return og_error_set(err,
                            "size_z: a bounded flat world's rows: 0 (as size) or at least 2, "
                            "with size set; got %lld with size %lld",
                            (long long)p->size_z, (long long)p->size);
    }
    return 0;
}

static const char *path_ext(const char *path) {
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    return dot && dot != base ? dot : NULL;
}

static void emit(void (*report)(void *, const char *), void *user, const char *path,
                 const param_diag *d) {
    if (!report) return;
    char msg[4096 + 512];
    const char *sev = d->severity == PARAM_ERROR ? "error" : "warning";
    if (d->line > 0)
        snprintf(msg, sizeof msg, "%s:%d: %s: %s", path, d->line, sev, d->message);
    else
        snprintf(msg, sizeof msg, "%s: %s: %s", path, sev, d->message);
    report(user, msg);
}

// Stable sort by line; whole-file messages (line 0) go after the line-by-line ones.
static void sort_diags(param_diag *d, size_t n) {
    for (size_t i = 1; i < n; i++) {
        param_diag x = d[i];
        long lx = x.line > 0 ? x.line : INT_MAX;
        size_t j = i;
        for (; j > 0 && (d[j - 1].line > 0 ? d[j - 1].line : INT_MAX) > lx; j--)
            d[j] = d[j - 1];
        d[j] = x;
    }
}

// Refuses what is not ours: bytes that are not text, or text in which no line sets a
// key Orogen knows (a file with only blank and comment lines is an empty one).
static int refuse_foreign(const char *path, const param_file *pf, og_error *err) {
    const char *what = "not an Orogen world or planet parameter file";
    if (pf->not_text[0]) return og_error_set(err, "%s: %s (%s)", path, what, pf->not_text);
    if (!pf->has_lines)
        return og_error_set(err,
                            "%s: %s (it is empty: no line sets a key; Orogen never saves "
                            "an empty file)",
                            path, what);
    for (size_t i = 0; i < pf->count; i++)
        if (find_def(pf->entries[i].key)) return 0;
    if (pf->count)
        return og_error_set(err, "%s: %s (no line sets a known key; line %d sets '%.60s')", path,
                            what, pf->entries[0].line, pf->entries[0].key);
    return og_error_set(err, "%s: %s (no line has the form 'key = value;')", path, what);
}

int world_params_check_file(const char *path, og_error *err) {
    param_file pf;
    if (param_file_read(path, &pf, err) != 0) return -1;
    int rc = refuse_foreign(path, &pf, err);
    param_file_free(&pf);
    return rc;
}

int world_params_load(const char *path, world_params *p, int *errors,
                      void (*report)(void *user, const char *message), void *user, og_error *err) {
    return world_params_load_whole(path, p, errors, report, user, NULL, 0, err);
}

int world_params_load_whole(const char *path, world_params *p, int *errors,
                            void (*report)(void *user, const char *message), void *user,
                            char *cut_short, size_t cut_len, og_error *err) {
    if (errors) *errors = 0;
    if (cut_short) cut_short[0] = 0;
    param_file pf;
    if (param_file_read(path, &pf, err) != 0) return -1;
    if (refuse_foreign(path, &pf, err) != 0) {
        param_file_free(&pf);
        return -1;
    }
    char why[1200];
    int seal = world_params_seal_check(pf.text, pf.text_len, why, sizeof why);

    const char *ext = path_ext(path);
    world_kind kind = ext && !strcasecmp(ext, ".planet") ? WORLD_PLANET : WORLD_FLAT;
    // A `kind` in the file picks the defaults the other keys then override.
    for (size_t i = 0; i < pf.count; i++) {
        if (strcmp(pf.entries[i].key, "kind")) continue;
        world_params probe;
        world_params_default(&probe, kind);
        if (world_params_set(&probe, "kind", pf.entries[i].value, NULL) == 0) kind = probe.kind;
    }
    world_params_default(p, kind);

    for (size_t i = 0; i < pf.count; i++) {
        const param_entry *e = &pf.entries[i];
        og_error e_err;
        int rc = world_params_read_entry(p, e->key, e->value, &e_err);
        if (rc < 0)
            param_file_diag(&pf, PARAM_ERROR, e->line, "%s", e_err.msg);
        else if (rc > 0)
            param_file_diag(&pf, PARAM_WARNING, e->line, "unknown key '%s'", e->key);
    }
    og_error v_err;
    layer_table_finish(&p->layers, NULL);
    material_rules_finish(&p->material_rules);
    if (p->kind == WORLD_PLANET) material_rules_planet_adopt(&p->material_rules);
    if (pf.count && world_params_validate(p, &v_err) != 0)
        param_file_diag(&pf, PARAM_ERROR, 0, "%s", v_err.msg);
    // Changed since saved, with lines that no longer read: damage, not an edit by hand.
    if (seal == 2 && pf.diag_count)
        seal = 1, snprintf(why, sizeof why,
                           "damaged: it changed after Orogen saved it and has lines that do not "
                           "read (reported above)");
    if (seal == 1 && cut_short) // the caller reports it, in full
        snprintf(cut_short, cut_len, "%s", why);
    else if (seal)
        param_file_diag(&pf, seal == 1 ? PARAM_ERROR : PARAM_WARNING, 0, "%s", why);

    sort_diags(pf.diags, pf.diag_count);
    for (size_t i = 0; i < pf.diag_count; i++) {
        if (pf.diags[i].severity == PARAM_ERROR && errors) ++*errors;
        emit(report, user, path, &pf.diags[i]);
    }
    param_file_free(&pf);
    return 0;
}

char *world_params_format(const world_params *p) {
    size_t cap = 8192, len = 0;
    char *out = malloc(cap);
    if (!out) return NULL;
    char value[WORLD_VALUE_MAX];
    world_params_get(p, "kind", value, sizeof value);
    len += (size_t)snprintf(out, cap,
                            "# Orogen world parameters (kind %s). Syntax: key = value; '#' "
                            "starts a comment.\n",
                            value);
    for (size_t i = 0; i < KEY_COUNT; i++) {
        if (world_params_get(p, KEYS[i].name, value, sizeof value) != 0) value[0] = 0;
        size_t need = strlen(KEYS[i].help) + strlen(KEYS[i].name) + strlen(value) + 16;
        if (len + need >= cap) {
            cap = (len + need) * 2;
            char *grown = realloc(out, cap);
            if (!grown) {
                free(out);
                return NULL;
            }
            out = grown;
        }
        len += (size_t)snprintf(out + len, cap - len, "\n# %s\n%s = %s;\n", KEYS[i].help,
                                KEYS[i].name, value);
    }
    if ((p->layers.count && layer_table_format(&p->layers, &out, &len, &cap) != 0) ||
        material_rules_format_lines(&p->material_rules, &out, &len, &cap) != 0) {
        free(out);
        return NULL;
    }
    return out;
}

// What save adds: a line after the header saying the file is sealed, and the seal as the
// last line (the length and checksum of everything before it), so a file cut short (an
// interrupted copy, a sync tool) is told from a complete one.
#define SEALED_LINE                                                                                \
    "# Saved by Orogen: the last line seals the file (its length and checksum); a file "           \
    "that lacks it was cut short.\n"
#define SEAL_FORMAT "# end of file: %zu bytes before this line, crc32c %08x\n"

int world_params_save(const char *path, const world_params *p, og_error *err) {
    char *text = world_params_format(p);
    if (!text) return og_error_set(err, "%s: out of memory", path);
    size_t len = strlen(text), head = strcspn(text, "\n") + 1;
    size_t cap = len + sizeof SEALED_LINE + 128;
    char *sealed = malloc(cap);
    if (!sealed) {
        free(text);
        return og_error_set(err, "%s: out of memory", path);
    }
    memcpy(sealed, text, head);
    memcpy(sealed + head, SEALED_LINE, sizeof SEALED_LINE - 1);
    memcpy(sealed + head + sizeof SEALED_LINE - 1, text + head, len - head);
    size_t n = len + sizeof SEALED_LINE - 1;
    n += (size_t)snprintf(sealed + n, cap - n, SEAL_FORMAT, n, crc32c_update(0, sealed, n));
    free(text);
    int rc = param_file_write_atomic(path, sealed, n, err);
    free(sealed);
    return rc;
}

// Whether the key is set on some line of the text (at a line's start, before '=').
static int sets_key(const char *text, size_t len, const char *key) {
    size_t k = strlen(key);
    for (size_t i = 0; i < len;) {
        const char *nl = memchr(text + i, '\n', len - i);
        size_t end = nl ? (size_t)(nl - text) : len, j = i;
        while (j < end && (text[j] == ' ' || text[j] == '\t'))
            j++;
        if (end - j > k && !strncmp(text + j, key, k)) {
            size_t e = j + k;
            while (e < end && (text[e] == ' ' || text[e] == '\t'))
                e++;
            if (e < end && text[e] == '=') return 1;
        }
        i = end + 1;
    }
    return 0;
}

int world_params_seal_check(const char *text, size_t len, char *why, size_t why_len) {
    why[0] = 0;
    if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) text += 3, len -= 3;
    // Sealed: it says so after its header, or ends in a seal (also when the line saying
    // so was damaged). Otherwise written by hand, or by an Orogen from before seals.
    int says_sealed = memmem(text, len, SEALED_LINE, sizeof SEALED_LINE - 1) != NULL;
    int ends_sealed = len > 16 && memmem(text + (len > 100 ? len - 100 : 0), len > 100 ? 100 : len,
                                         "\n# end of file: ", 16);
    if (!says_sealed && !ends_sealed) return 0;
    // The last line (without its newline).
    size_t end = len;
    while (end > 0 && text[end - 1] == '\n')
        end--;
    size_t start = end;
    while (start > 0 && text[start - 1] != '\n')
        start--;
    size_t bytes = 0;
    unsigned crc = 0;
    char tail[160];
    snprintf(tail, sizeof tail, "%.*s\n", (int)(end - start < 150 ? end - start : 150),
             text + start);
    // A whole seal: all its text, 8 hex digits and the newline (a cut one is no seal).
    int used = 0, sealed = 0;
    if (end < len &&
        sscanf(tail, "# end of file: %zu bytes before this line, crc32c %x%n", &bytes, &crc,
               &used) == 2 &&
        used == (int)(end - start) && end - start >= 8 &&
        strspn(text + end - 8, "0123456789abcdef") >= 8) {
        if (bytes == start && crc32c_update(0, text, start) == crc) return 0;
        sealed = 1;
    }
    char missing[1024] = "";
    size_t n = 0, count = 0;
    for (size_t i = 0; i < KEY_COUNT; i++) {
        if (sets_key(text, len, KEYS[i].name)) continue;
        count++;
        if (n < sizeof missing - 64)
            n += (size_t)snprintf(missing + n, sizeof missing - n, "%s%s", n ? ", " : "",
                                  KEYS[i].name);
    }
    const char *lacking = count == 1 ? "; missing key: " : "; missing keys: ";
    if (sealed && !count) { // every key still there: an edit by hand
        snprintf(why, why_len,
                 "it was changed after Orogen saved it (its last line's length or checksum no "
                 "longer matches); it is read as it is");
        return 2;
    }
    if (sealed)
        snprintf(why, why_len, "damaged: it changed after Orogen saved it and lost keys%s%s",
                 lacking, missing);
    else
        snprintf(why, why_len, "cut short: it lacks the last line Orogen's save writes%s%s",
                 count ? lacking : "", missing);
    return 1;
}

// Appends "/name" (or "name" when dst is empty) to dst; -1 when it does not fit.
static int path_join(char *dst, size_t len, const char *name, size_t name_len) {
    size_t n = strlen(dst);
    size_t sep = n && dst[n - 1] != '/';
    if (n + sep + name_len + 1 > len) return -1;
    if (sep) dst[n++] = '/';
    memcpy(dst + n, name, name_len);
    dst[n + name_len] = 0;
    return 0;
}

// Whether `path` (inside a folder, possibly not existing yet) resolves inside `root`
// (already resolved): the deepest existing ancestor is resolved, so a symlinked
// folder or file pointing out of the folder is caught.
static int stays_inside(const char *root, const char *path) {
    char probe[PATH_MAX], real[PATH_MAX];
    if (strlen(path) >= sizeof probe) return 0;
    strcpy(probe, path);
    for (;;) {
        if (realpath(probe, real)) break;
        char *slash = strrchr(probe, '/');
        if (!slash || slash == probe) return 1; // nothing exists to follow
        *slash = 0;
    }
    size_t n = strlen(root);
    if (!strcmp(root, "/")) return 1;
    return !strncmp(real, root, n) && (real[n] == 0 || real[n] == '/');
}

int world_params_tiles_path(const world_params *p, const char *param_path, char *out, size_t len,
                            og_error *err) {
    const char *slash = strrchr(param_path, '/');
    const char *base = slash ? slash + 1 : param_path;
    char rel[1100] = "";
    const char *value = p->tiles;
    char q[64];
    parse_quote(q, sizeof q, value);
    if (!value[0]) {
        // Default: the parameter file's name with .tiles for its extension.
        const char *ext = path_ext(param_path);
        size_t stem = ext ? (size_t)(ext - base) : strlen(base);
        if (!stem) return og_error_set(err, "%s: not a file name", param_path);
        if (stem + 7 > sizeof rel) return og_error_set(err, "%s: path too long", param_path);
        snprintf(rel, sizeof rel, "%.*s.tiles", (int)stem, base);
    } else {
        if (value[0] == '/')
            return og_error_set(err,
                                "tiles: %s is an absolute path; it must be relative to the "
                                "parameter file's folder",
                                q);
        // Normalise lexically, refusing any `..` that climbs above the folder.
        int depth = 0;
        for (const char *s = value; *s;) {
            const char *e = strchr(s, '/');
            size_t n = e ? (size_t)(e - s) : strlen(s);
            if (n == 2 && s[0] == '.' && s[1] == '.') {
                if (--depth < 0)
                    return og_error_set(err, "tiles: %s leaves the parameter file's folder", q);
                char *cut = strrchr(rel, '/');
                if (cut)
                    *cut = 0;
                else
                    rel[0] = 0;
            } else if (n && !(n == 1 && s[0] == '.')) {
                depth++;
                if (path_join(rel, sizeof rel, s, n) != 0)
                    return og_error_set(err, "tiles: %s is too long", q);
            }
            s += n;
            if (*s == '/') s++;
        }
        const char *last = strrchr(value, '/');
        last = last ? last + 1 : value;
        if (!rel[0] || !*last || !strcmp(last, ".") || !strcmp(last, ".."))
            return og_error_set(err, "tiles: %s does not name a file", q);
    }

    char dir[PATH_MAX];
    size_t dir_len = slash ? (size_t)(slash - param_path) : 0;
    if (slash && dir_len == 0) dir_len = 1; // the file lives in "/"
    if (dir_len >= sizeof dir) return og_error_set(err, "%s: path too long", param_path);
    memcpy(dir, param_path, dir_len);
    dir[dir_len] = 0;

    char full[PATH_MAX];
    snprintf(full, sizeof full, "%s", dir);
    if (path_join(full, sizeof full, rel, strlen(rel)) != 0)
        return og_error_set(err, "tiles: %s gives a path too long", q);

    char root[PATH_MAX];
    if (realpath(dir_len ? dir : ".", root) && !stays_inside(root, full))
        return og_error_set(err,
                            "tiles: %s leads out of the parameter file's folder through a "
                            "symbolic link",
                            q);

    if (strlen(full) + 1 > len)
        return og_error_set(err, "tiles: resolved path for %s does not fit", q);
    memcpy(out, full, strlen(full) + 1);
    return 0;
}
