#include "editor/tools/stamp.h"

#include "editor/tools/brush.h"
#include "editor/tools/planet_dab.h"
#include "editor/edit/edit.h"
#include "editor/edit/edit_commit.h"
#include "editor/edit/edit_rows.h"
#include "editor/world/layer_grid.h"
#include "editor/tools/stamp_image.h"
#include "editor/tools/stamp_image_cache.h"
#include "editor/tools/stamp_library.h"
#include "editor/tools/stamp_shapes.h"
#include "io/parse.h"

#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *mode_names[STAMP_MODE_COUNT] = {"add", "subtract", "max", "min", "blend"};
static const char *image_exts[] = {".png", ".tif",  ".tiff", ".exr",
                                   ".jpg", ".jpeg", ".pgm",  ".hdr"};
#define IMAGE_EXT_COUNT (sizeof image_exts / sizeof image_exts[0])

void stamp_placement_defaults(stamp_placement *p) {
    memset(p, 0, sizeof *p);
    p->scale = 1.0;
    p->intensity = 50.0;
    p->mode = STAMP_ADD;
    p->layer = TILE_LAYER_COARSE;
}

int stamp_placement_set(stamp_placement *p, const char *key, const char *value, og_error *err) {
    double v;
    if (strcmp(key, "mode") == 0) {
        for (int m = 0; m < STAMP_MODE_COUNT; m++)
            if (strcmp(value, mode_names[m]) == 0) {
                p->mode = (stamp_mode)m;
                return 0;
            }
        return og_error_set(err, "mode: '%s' is not add, subtract, max, min or blend", value);
    }
    if (strcmp(key, "layer") == 0 || strcmp(key, "target") == 0) {
        if (strcmp(value, "coarse") == 0)
            p->layer = TILE_LAYER_COARSE;
        else if (strcmp(value, "detail") == 0)
            p->layer = TILE_LAYER_DETAIL;
        else
            return og_error_set(err, "%s: '%s' is not coarse or detail", key, value);
        return 0;
    }
    if (strcmp(key, "mirror") == 0) {
        int x = 0, z = 0;
        if (strcmp(value, "x") == 0)
            x = 1;
        else if (strcmp(value, "z") == 0)
            z = 1;
        else if (strcmp(value, "xz") == 0 || strcmp(value, "both") == 0)
            x = z = 1;
        else if (strcmp(value, "none") != 0)
            return og_error_set(err, "mirror: '%s' is not none, x, z or xz", value);
        p->mirror_x = x;
        p->mirror_z = z;
        return 0;
    }
    if (parse_number(value, key, &v, err) != 0) return -1;
    if (strcmp(key, "scale") == 0) {
        if (!(v > 0 && v <= 1000))
            return og_error_set(err, "scale: expected a number in (0, 1000], got '%g'", v);
        p->scale = v;
    } else if (strcmp(key, "rot") == 0 || strcmp(key, "rotation") == 0) {
        if (!(fabs(v) <= 1e6))
            return og_error_set(err, "%s: expected degrees in [-1e6, 1e6], got '%g'", key, v);
        p->rotation = v;
    } else if (strcmp(key, "intensity") == 0) {
        if (!(fabs(v) <= 1e5))
            return og_error_set(err, "intensity: expected metres in [-1e5, 1e5], got '%g'", v);
        p->intensity = v;
    } else if (strcmp(key, "face") == 0) {
        if (!(v >= 0 && v <= 5 && v == floor(v)))
            return og_error_set(err, "face: expected an integer in [0, 5], got '%g'", v);
        p->face = (int)v;
    } else {
        return og_error_set(
            err, "unknown stamp setting '%s' (scale rot mirror intensity mode layer face)", key);
    }
    return 0;
}

// ---- finding stamps ---------------------------------------------------------------------

static int load_image(const char *path, const char *name, stamp_source *out, og_error *err) {
    memset(out, 0, sizeof *out);
    out->shape = -1;
    snprintf(out->name, sizeof out->name, "%s", name);
    return stamp_image_cache_read(path, &out->pixels, &out->width, &out->height, &out->support,
                                  err);
}

static int find_in(const char *dir, const char *name, char *path, size_t size) {
    if (!dir || !*dir) return 0;
    for (size_t i = 0; i < IMAGE_EXT_COUNT; i++) {
        snprintf(path, size, "%s/%s%s", dir, name, image_exts[i]);
        if (access(path, R_OK) == 0) return 1;
    }
    return 0;
}

int stamp_find(const char *name, const char *resource_dir, const char *user_dir, stamp_source *out,
               og_error *err) {
    memset(out, 0, sizeof *out);
    int shape = stamp_shape_from_name(name);
    if (shape >= 0) {
        out->shape = shape;
        snprintf(out->name, sizeof out->name, "%s", name);
        return 0;
    }
    char path[8300], dir[4200];
    snprintf(dir, sizeof dir, "%s/stamps", resource_dir ? resource_dir : ".");
    // A bare name is a library or user stamp; anything with a slash or dot is a file.
    if (!strchr(name, '/') && !strchr(name, '.')) {
        if (find_in(dir, name, path, sizeof path) || find_in(user_dir, name, path, sizeof path))
            return load_image(path, name, out, err);
        return og_error_set(
            err, "unknown stamp '%s' (see `stamps` for the list, or give an image file)", name);
    }
    if (access(name, F_OK) != 0) return og_error_set(err, "stamp image '%s' does not exist", name);
    return load_image(name, name, out, err);
}

void stamp_source_free(stamp_source *s) {
    if (!s) return;
    free(s->pixels);
    s->pixels = NULL;
}

static int has_image_ext(const char *file, size_t *stem) {
    const char *dot = strrchr(file, '.');
    if (!dot) return 0;
    for (size_t i = 0; i < IMAGE_EXT_COUNT; i++)
        if (strcasecmp(dot, image_exts[i]) == 0) {
            *stem = (size_t)(dot - file);
            return 1;
        }
    return 0;
}

int stamp_is_image_file(const char *file) {
    size_t stem;
    return has_image_ext(file, &stem);
}

static int compare_names(const void *a, const void *b) {
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static void list_dir(const char *dir, const char *kind, FILE *out) {
    DIR *d = dir && *dir ? opendir(dir) : NULL;
    if (!d) return;
    char *names[1024];
    size_t n = 0;
    struct dirent *ent;
    while ((ent = readdir(d)) && n < 1024) {
        size_t stem;
        if (ent->d_name[0] != '.' && has_image_ext(ent->d_name, &stem))
            names[n++] = strndup(ent->d_name, stem);
    }
    closedir(d);
    qsort(names, n, sizeof *names, compare_names);
    for (size_t i = 0; i < n; i++) {
        const char *about = "";
        for (int k = 0; k < stamp_library_count() && strcmp(kind, "library") == 0; k++)
            if (strcmp(stamp_library_entry_at(k)->name, names[i]) == 0)
                about = stamp_library_entry_at(k)->about;
        fprintf(out, "%s %s%s%s\n", names[i], kind, *about ? " " : "", about);
        free(names[i]);
    }
}

void stamp_list(const char *resource_dir, const char *user_dir, FILE *out) {
    for (int s = 0; s < STAMP_SHAPE_COUNT; s++)
        fprintf(out, "%s functional\n", stamp_shape_name((stamp_shape)s));
    char dir[4200];
    snprintf(dir, sizeof dir, "%s/stamps", resource_dir ? resource_dir : ".");
    list_dir(dir, "library", out);
    list_dir(user_dir, "user", out);
}

// ---- placing ------------------------------------------------------------------------------

typedef struct stamp_op {
    const stamp_source *s;
    const stamp_placement *p;
    double spacing; // metres per sample of the layer
    double cos_r, sin_r;
    double half_w, half_h; // metres
    float base;            // max: lowest, min: highest, blend: centre height
    // Planets: the footprint laid on the sphere around its centre (azimuthal
    // equidistant: metres along great circles, in the directions the stamp's face's x and
    // z run at the centre), on whichever face `geo.face` is being written.
    int sphere;
    brush_dab geo;       // the face, its samples and the centre direction
    double ex[3], ez[3]; // the stamp's x and z directions at its centre
    // Flat worlds and image stamps: the image read a row span at a time (stamp_image.h).
    int by_rows;
    stamp_image_map image;
} stamp_op;

// Metres from the stamp's centre to sample (x, z), along the stamp's x and z.
static void sample_offset(const stamp_op *o, int64_t x, int64_t z, double *dx, double *dz) {
    if (!o->sphere) {
        *dx = (double)x * o->spacing - o->p->x, *dz = (double)z * o->spacing - o->p->z;
        return;
    }
    double d[3];
    brush_dab_sample_direction(&o->geo, (double)x, (double)z, d);
    const double *c = o->geo.centre_dir;
    double along = d[0] * c[0] + d[1] * c[1] + d[2] * c[2];
    double q[3] = {d[0] - along * c[0], d[1] - along * c[1], d[2] - along * c[2]};
    double sin_a = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    double metres = atan2(sin_a, along) * o->geo.planet_radius, k = sin_a > 0 ? metres / sin_a : 0;
    *dx = k * (q[0] * o->ex[0] + q[1] * o->ex[1] + q[2] * o->ex[2]);
    *dz = k * (q[0] * o->ez[0] + q[1] * o->ez[1] + q[2] * o->ez[2]);
}

// Stamp value at sample (x, z), and whether the sample lies inside the footprint.
static float stamp_value(const stamp_op *o, int64_t x, int64_t z, double *edge) {
    double dx, dz;
    sample_offset(o, x, z, &dx, &dz);
    double u = (o->cos_r * dx + o->sin_r * dz) / o->half_w;
    double v = (-o->sin_r * dx + o->cos_r * dz) / o->half_h;
    *edge = fmax(fabs(u), fabs(v));
    if (!(*edge < 1.0)) return 0.0f;
    if (o->p->mirror_x) u = -u;
    if (o->p->mirror_z) v = -v;
    if (o->s->shape >= 0) return stamp_shape_value((stamp_shape)o->s->shape, (float)u, (float)v);
    double px = (u + 1.0) * 0.5 * o->s->width - 0.5, py = (v + 1.0) * 0.5 * o->s->height - 0.5;
    px = fmin(fmax(px, 0.0), o->s->width - 1.0);
    py = fmin(fmax(py, 0.0), o->s->height - 1.0);
    int ix = (int)px, iy = (int)py;
    int jx = ix + 1 < o->s->width ? ix + 1 : ix, jy = iy + 1 < o->s->height ? iy + 1 : iy;
    double ax = px - ix, ay = py - iy;
    const float *im = o->s->pixels;
    double top =
        im[(size_t)iy * o->s->width + ix] * (1 - ax) + im[(size_t)iy * o->s->width + jx] * ax;
    double bot =
        im[(size_t)jy * o->s->width + ix] * (1 - ax) + im[(size_t)jy * o->s->width + jx] * ax;
    return (float)(top * (1 - ay) + bot * ay);
}

// A sample's new height from its old one, a = the stamp's value times the intensity,
// and its edge (< 1: inside the footprint).
static inline float stamp_mix(const stamp_op *o, float old, float a, double edge) {
    float v = old;
    switch (o->p->mode) {
    case STAMP_ADD:
        v = old + a;
        break;
    case STAMP_SUBTRACT:
        v = old - a;
        break;
    case STAMP_MAX:
        v = fmaxf(old, o->base + a);
        break;
    case STAMP_MIN:
        v = fminf(old, o->base - a);
        break;
    default: {
        double t = edge < 0.7 ? 0.0 : (edge - 0.7) / 0.3;
        float m = (float)(1.0 - t * t * (3.0 - 2.0 * t));
        v = old + m * (o->base + a - old);
    }
    }
    if (v != v) v = old;
    return fminf(fmaxf(v, (float)-BRUSH_HEIGHT_LIMIT), (float)BRUSH_HEIGHT_LIMIT);
}

// An image stamp on a flat world: the row's span under the footprint, in chunks whose
// values are read together; add and subtract (old -+ a, a = value * k) mix them in one pass.
#define STAMP_CHUNK 256
static void stamp_row_image(const stamp_op *o, float *h, int64_t z, int64_t x0, int64_t x1) {
    int64_t a, b;
    stamp_image_span(&o->image, z, x0, x1, &a, &b);
    float value[STAMP_CHUNK], k = (float)o->p->intensity;
    double edge[STAMP_CHUNK];
    for (int64_t s = a; s < b; s += STAMP_CHUNK) {
        int n = b - s < STAMP_CHUNK ? (int)(b - s) : STAMP_CHUNK;
        float *row = h + (s - x0);
        stamp_image_values(&o->image, z, s, n, value, edge);
        if (o->p->mode == STAMP_ADD || o->p->mode == STAMP_SUBTRACT) {
            stamp_image_add(row, value, edge, o->p->mode == STAMP_ADD ? k : -k,
                            (float)BRUSH_HEIGHT_LIMIT, n);
            continue;
        }
        for (int i = 0; i < n; i++)
            if (edge[i] < 1.0) row[i] = stamp_mix(o, row[i], value[i] * k, edge[i]);
    }
}

static void stamp_row(void *user, void *row, int64_t z, int64_t x0, int64_t x1) {
    const stamp_op *o = user;
    float *h = row;
    if (o->by_rows && !o->sphere) {
        stamp_row_image(o, h, z, x0, x1);
        return;
    }
    float k = (float)o->p->intensity;
    for (int64_t x = x0; x < x1; x++) {
        double edge;
        float a = stamp_value(o, x, z, &edge) * k;
        if (edge < 1.0) h[x - x0] = stamp_mix(o, h[x - x0], a, edge);
    }
}

static int make_op(const world_params *params, const stamp_source *s, const stamp_placement *p,
                   layer_grid *g, stamp_op *o, grid_rect *rect, og_error *err) {
    if (layer_grid_init(g, params, p->layer, p->face, err) != 0) return -1;
    if (params->kind == WORLD_PLANET ? planet_dab_check_position(g, p->x, p->z, err) != 0
                                     : layer_grid_check_position(g, p->x, p->z, err) != 0)
        return -1;
    if (s->shape < 0 && (!s->pixels || s->width < 1 || s->height < 1))
        return og_error_set(err, "stamp '%s' has no image", s->name);
    o->s = s;
    o->p = p;
    o->spacing = g->spacing;
    double r = p->rotation * (M_PI / 180.0);
    o->cos_r = cos(r);
    o->sin_r = sin(r);
    double w = s->shape >= 0 ? STAMP_FUNCTIONAL_SAMPLES : s->width;
    double h = s->shape >= 0 ? STAMP_FUNCTIONAL_SAMPLES : s->height;
    o->half_w = 0.5 * w * p->scale * g->spacing;
    o->half_h = 0.5 * h * p->scale * g->spacing;
    if (fmax(o->half_w, o->half_h) / g->spacing > BRUSH_MAX_RADIUS_SAMPLES)
        return og_error_set(err, "scale: %g makes the stamp %g samples across; the limit is %g",
                            p->scale, 2 * fmax(o->half_w, o->half_h) / g->spacing,
                            2 * BRUSH_MAX_RADIUS_SAMPLES);
    double ex = fabs(o->cos_r) * o->half_w + fabs(o->sin_r) * o->half_h;
    double ez = fabs(o->sin_r) * o->half_w + fabs(o->cos_r) * o->half_h;
    o->by_rows = s->shape < 0 && (double)s->width * s->height < 2147483647.0;
    o->image = (stamp_image_map){.pixels = s->pixels,
                                 .width = s->width,
                                 .height = s->height,
                                 .spacing = g->spacing,
                                 .x = p->x,
                                 .z = p->z,
                                 .cos_r = o->cos_r,
                                 .sin_r = o->sin_r,
                                 .half_w = o->half_w,
                                 .half_h = o->half_h,
                                 .mirror_x = p->mirror_x,
                                 .mirror_z = p->mirror_z};
    // Adding or subtracting 0 changes nothing: rows, snapshots, the take and the undo
    // step keep to the image's support (a library stamp's inscribed circle holds 4/5 of
    // its square, and the tiles' parts hug it).
    if (s->shape < 0 && s->support > 0.0 && (p->mode == STAMP_ADD || p->mode == STAMP_SUBTRACT)) {
        o->image.support = s->support * fmax(2.0 * o->half_w / w, 2.0 * o->half_h / h);
        ex = fmin(ex, o->image.support + 2.0 * g->spacing);
        ez = fmin(ez, o->image.support + 2.0 * g->spacing);
    }
    *rect = layer_grid_clip(g, (grid_rect){(int64_t)floor((p->x - ex) / g->spacing),
                                           (int64_t)floor((p->z - ez) / g->spacing),
                                           (int64_t)ceil((p->x + ex) / g->spacing) + 1,
                                           (int64_t)ceil((p->z + ez) / g->spacing) + 1});
    return 0;
}

// Whether a tile's part of a flat stamp's rect can hold a sample of its rotated
// footprint (|u|, |v| < 1): the rect's corners stick out past the square, and a tile
// there left untouched is not snapshotted, compared, or regenerated after the step.
// Separating axes of the part (grown by a sample: conservative) and the footprint.
static int stamp_wanted(void *user, grid_rect part) {
    const stamp_op *o = user;
    if (o->sphere) return 1;
    double x0 = (double)(part.x0 - 1) * o->spacing - o->p->x;
    double x1 = (double)part.x1 * o->spacing - o->p->x;
    double z0 = (double)(part.z0 - 1) * o->spacing - o->p->z;
    double z1 = (double)part.z1 * o->spacing - o->p->z;
    double ex = fabs(o->cos_r) * o->half_w + fabs(o->sin_r) * o->half_h;
    double ez = fabs(o->sin_r) * o->half_w + fabs(o->cos_r) * o->half_h;
    if (x0 > ex || x1 < -ex || z0 > ez || z1 < -ez) return 0;
    double umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
    for (int c = 0; c < 4; c++) {
        double dx = c & 1 ? x1 : x0, dz = c & 2 ? z1 : z0;
        double u = (o->cos_r * dx + o->sin_r * dz) / o->half_w;
        double v = (-o->sin_r * dx + o->cos_r * dz) / o->half_h;
        umin = fmin(umin, u), umax = fmax(umax, u), vmin = fmin(vmin, v), vmax = fmax(vmax, v);
    }
    return !(umin > 1.0 || umax < -1.0 || vmin > 1.0 || vmax < -1.0);
}

// stamp_wanted, then the part narrowed to the rows and columns whose spans (a sample or
// two wider than the footprint: stamp_image_span) it crosses.
static int stamp_narrow(void *user, grid_rect *part) {
    const stamp_op *o = user;
    if (!stamp_wanted(user, *part)) return 0;
    grid_rect box = {part->x1, part->z1, part->x0, part->z0};
    for (int64_t z = part->z0; z < part->z1; z++) {
        int64_t a, b;
        stamp_image_span(&o->image, z, part->x0, part->x1, &a, &b);
        if (a >= b) continue;
        box.x0 = a < box.x0 ? a : box.x0, box.x1 = b > box.x1 ? b : box.x1;
        box.z0 = z < box.z0 ? z : box.z0, box.z1 = z + 1;
    }
    *part = box;
    return !grid_rect_empty(box);
}

// The base height the max, min and blend modes work from, over the footprint's heights
// (gathered over every face a planet's footprint covers, then settled).
typedef struct base_scan {
    float lo, hi, centre;
    double best;
} base_scan;

static void scan_base(const stamp_op *o, const float *h, grid_rect r, base_scan *b) {
    int64_t w = r.x1 - r.x0;
    for (int64_t z = r.z0; z < r.z1; z++)
        for (int64_t x = r.x0; x < r.x1; x++) {
            double edge, dx, dz;
            stamp_value(o, x, z, &edge);
            float v = h[(z - r.z0) * w + (x - r.x0)];
            if (edge < 1.0) {
                b->lo = fminf(b->lo, v);
                b->hi = fmaxf(b->hi, v);
            }
            sample_offset(o, x, z, &dx, &dz);
            if (dx * dx + dz * dz < b->best) {
                b->best = dx * dx + dz * dz;
                b->centre = v;
            }
        }
}

static void settle_base(stamp_op *o, const base_scan *b) {
    o->base = o->p->mode == STAMP_MAX   ? (isfinite(b->lo) ? b->lo : 0)
              : o->p->mode == STAMP_MIN ? (isfinite(b->hi) ? b->hi : 0)
                                        : b->centre;
}

static void find_base(stamp_op *o, const float *h, grid_rect r) {
    base_scan b = {INFINITY, -INFINITY, 0, INFINITY};
    scan_base(o, h, r, &b);
    settle_base(o, &b);
}

static int needs_base(const stamp_placement *p) {
    return p->mode == STAMP_MAX || p->mode == STAMP_MIN || p->mode == STAMP_BLEND;
}

// Planets: the footprint's directions at its centre and each face's samples under it.
static void sphere_setup(stamp_op *o, const world_params *params, const layer_grid *g) {
    o->sphere = 1;
    o->geo =
        (brush_dab){.cx = o->p->x / g->spacing, .cz = o->p->z / g->spacing, .spacing = g->spacing};
    planet_dab_prepare(&o->geo, params, g->layer, g->face);
    // The face's x and z directions at the centre, made orthonormal on the tangent plane.
    double a[3], b[3];
    brush_dab_sample_direction(&o->geo, o->geo.cx + 0.5, o->geo.cz, a);
    brush_dab_sample_direction(&o->geo, o->geo.cx - 0.5, o->geo.cz, b);
    const double *c = o->geo.centre_dir;
    for (int k = 0; k < 3; k++)
        o->ex[k] = a[k] - b[k];
    double d = o->ex[0] * c[0] + o->ex[1] * c[1] + o->ex[2] * c[2], len;
    for (int k = 0; k < 3; k++)
        o->ex[k] -= d * c[k];
    len = sqrt(o->ex[0] * o->ex[0] + o->ex[1] * o->ex[1] + o->ex[2] * o->ex[2]);
    for (int k = 0; k < 3; k++)
        o->ex[k] /= len;
    // z = c x ex or ex x c: whichever agrees with the face's own z direction.
    double ez[3] = {c[1] * o->ex[2] - c[2] * o->ex[1], c[2] * o->ex[0] - c[0] * o->ex[2],
                    c[0] * o->ex[1] - c[1] * o->ex[0]};
    brush_dab_sample_direction(&o->geo, o->geo.cx, o->geo.cz + 0.5, a);
    brush_dab_sample_direction(&o->geo, o->geo.cx, o->geo.cz - 0.5, b);
    double sign =
        (a[0] - b[0]) * ez[0] + (a[1] - b[1]) * ez[1] + (a[2] - b[2]) * ez[2] < 0 ? -1 : 1;
    for (int k = 0; k < 3; k++)
        o->ez[k] = sign * ez[k];
    // The cap around the footprint's corners, for each face's rectangle.
    o->geo.radius = sqrt(o->half_w * o->half_w + o->half_h * o->half_h) / g->spacing + 2.0;
}

// A stamp on a planet: one edit over every face its footprint reaches.
static int stamp_apply_planet(world *w, stamp_op *o, const layer_grid *g, edit *e, og_error *err) {
    grid_rect rects[6];
    layer_grid grids[6];
    base_scan b = {INFINITY, -INFINITY, 0, INFINITY};
    for (int f = 0; f < 6; f++) {
        grids[f] = *g;
        grids[f].face = f;
        rects[f] = planet_dab_face_rect(&o->geo, f, g->extent);
        if (grid_rect_empty(rects[f]) || !needs_base(o->p)) continue;
        o->geo.face = f;
        float *h =
            malloc((size_t)((rects[f].x1 - rects[f].x0) * (rects[f].z1 - rects[f].z0)) * sizeof *h);
        if (!h) return og_error_set(err, "out of memory reading under the stamp");
        int rc = layer_grid_read(w, &grids[f], rects[f], h, err);
        if (rc == 0) scan_base(o, h, rects[f], &b);
        free(h);
        if (rc != 0) return -1;
    }
    if (needs_base(o->p)) settle_base(o, &b);
    for (int f = 0; f < 6; f++) {
        if (grid_rect_empty(rects[f])) continue;
        o->geo.face = f;
        if (edit_rows_apply(e, &grids[f], rects[f], stamp_row, NULL, o, err) != 0) return -1;
    }
    return 0;
}

int stamp_apply(world *w, const stamp_source *s, const stamp_placement *p, og_error *err) {
    layer_grid g;
    stamp_op o = {0};
    grid_rect r;
    if (make_op(world_get_params(w), s, p, &g, &o, &r, err) != 0) return -1;
    if (world_get_params(w)->kind == WORLD_PLANET) {
        sphere_setup(&o, world_get_params(w), &g);
        if (o.geo.radius * g.spacing / world_get_params(w)->radius > PLANET_DAB_MAX_ANGLE)
            return og_error_set(err, "scale: the stamp would cover more than 1/16 of the planet");
        char label[300];
        snprintf(label, sizeof label, "stamp %s", s->name);
        edit *e = edit_begin(w, label, err);
        if (!e) return -1;
        if (p->mode == STAMP_ADD || p->mode == STAMP_SUBTRACT)
            edit_set_layer_mode(e, EDIT_LAYER_DELTA);
        if (stamp_apply_planet(w, &o, &g, e, err) != 0) {
            edit_abort(e);
            return -1;
        }
        return edit_commit(e, err);
    }
    if (grid_rect_empty(r)) return 0;
    if (needs_base(p)) {
        float *h = malloc((size_t)((r.x1 - r.x0) * (r.z1 - r.z0)) * sizeof *h);
        if (!h) return og_error_set(err, "out of memory reading under the stamp");
        int rc = layer_grid_read(w, &g, r, h, err);
        if (rc == 0) find_base(&o, h, r);
        free(h);
        if (rc != 0) return -1;
    }
    char label[300];
    snprintf(label, sizeof label, "stamp %s", s->name);
    edit *e = edit_begin(w, label, err);
    if (!e) return -1;
    if (p->mode == STAMP_ADD || p->mode == STAMP_SUBTRACT) edit_set_layer_mode(e, EDIT_LAYER_DELTA);
    if (edit_rows_apply_narrowed(e, &g, r, stamp_row, stamp_narrow, &o, err) != 0) {
        edit_abort(e);
        return -1;
    }
    return edit_commit(e, err);
}

int stamp_apply_array(const world_params *params, const stamp_source *s, const stamp_placement *p,
                      float *data, int64_t area_x0, int64_t area_z0, int64_t width, int64_t height,
                      og_error *err) {
    layer_grid g;
    stamp_op o = {0};
    grid_rect r;
    if (make_op(params, s, p, &g, &o, &r, err) != 0) return -1;
    grid_rect area = {area_x0, area_z0, area_x0 + width, area_z0 + height};
    r = grid_rect_intersect(r, area);
    if (grid_rect_empty(r)) return 0;
    if (p->mode == STAMP_MAX || p->mode == STAMP_MIN || p->mode == STAMP_BLEND) {
        float *h = malloc((size_t)((r.x1 - r.x0) * (r.z1 - r.z0)) * sizeof *h);
        if (!h) return og_error_set(err, "out of memory");
        for (int64_t z = r.z0; z < r.z1; z++)
            memcpy(h + (z - r.z0) * (r.x1 - r.x0), data + (z - area_z0) * width + (r.x0 - area_x0),
                   (size_t)(r.x1 - r.x0) * sizeof *h);
        find_base(&o, h, r);
        free(h);
    }
    edit_rows_apply_array(p->layer, data, area, r, stamp_row, &o);
    return 0;
}
