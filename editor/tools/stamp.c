#include "editor/tools/stamp.h"

#include "editor/tools/brush.h"
#include "editor/edit/edit.h"
#include "editor/edit/edit_commit.h"
#include "editor/edit/edit_rows.h"
#include "editor/world/layer_grid.h"
#include "editor/tools/stamp_library.h"
#include "editor/tools/stamp_shapes.h"
#include "io/image_read.h"
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

const char *stamp_mode_name(stamp_mode m) {
    return (unsigned)m < STAMP_MODE_COUNT ? mode_names[m] : "unknown";
}

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
    return image_read_luminance(path, &out->pixels, &out->width, &out->height, err);
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
} stamp_op;

// Stamp value at sample (x, z), and whether the sample lies inside the footprint.
static float stamp_value(const stamp_op *o, int64_t x, int64_t z, double *edge) {
    double dx = (double)x * o->spacing - o->p->x, dz = (double)z * o->spacing - o->p->z;
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

static void stamp_row(void *user, void *row, int64_t z, int64_t x0, int64_t x1) {
    const stamp_op *o = user;
    float *h = row;
    float k = (float)o->p->intensity;
    for (int64_t x = x0; x < x1; x++) {
        double edge;
        float a = stamp_value(o, x, z, &edge) * k, old = h[x - x0], v = old;
        if (!(edge < 1.0)) continue;
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
        h[x - x0] = fminf(fmaxf(v, (float)-BRUSH_HEIGHT_LIMIT), (float)BRUSH_HEIGHT_LIMIT);
    }
}

static int make_op(const world_params *params, const stamp_source *s, const stamp_placement *p,
                   layer_grid *g, stamp_op *o, grid_rect *rect, og_error *err) {
    if (layer_grid_init(g, params, p->layer, p->face, err) != 0) return -1;
    if (layer_grid_check_position(g, p->x, p->z, err) != 0) return -1;
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
    *rect = layer_grid_clip(g, (grid_rect){(int64_t)floor((p->x - ex) / g->spacing),
                                           (int64_t)floor((p->z - ez) / g->spacing),
                                           (int64_t)ceil((p->x + ex) / g->spacing) + 1,
                                           (int64_t)ceil((p->z + ez) / g->spacing) + 1});
    return 0;
}

// The base height the max, min and blend modes work from, over the footprint's heights.
static void find_base(stamp_op *o, const float *h, grid_rect r) {
    int64_t w = r.x1 - r.x0;
    float lo = INFINITY, hi = -INFINITY, centre = 0;
    double best = INFINITY;
    for (int64_t z = r.z0; z < r.z1; z++)
        for (int64_t x = r.x0; x < r.x1; x++) {
            double edge;
            stamp_value(o, x, z, &edge);
            float v = h[(z - r.z0) * w + (x - r.x0)];
            if (edge < 1.0) {
                lo = fminf(lo, v);
                hi = fmaxf(hi, v);
            }
            double dx = x * o->spacing - o->p->x, dz = z * o->spacing - o->p->z;
            if (dx * dx + dz * dz < best) {
                best = dx * dx + dz * dz;
                centre = v;
            }
        }
    o->base = o->p->mode == STAMP_MAX   ? (isfinite(lo) ? lo : 0)
              : o->p->mode == STAMP_MIN ? (isfinite(hi) ? hi : 0)
                                        : centre;
}

int stamp_apply(world *w, const stamp_source *s, const stamp_placement *p, og_error *err) {
    layer_grid g;
    stamp_op o;
    grid_rect r;
    if (make_op(world_get_params(w), s, p, &g, &o, &r, err) != 0) return -1;
    if (grid_rect_empty(r)) return 0;
    if (p->mode == STAMP_MAX || p->mode == STAMP_MIN || p->mode == STAMP_BLEND) {
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
    if (edit_rows_apply(e, &g, r, stamp_row, NULL, &o, err) != 0) {
        edit_abort(e);
        return -1;
    }
    return edit_commit(e, err);
}

int stamp_apply_array(const world_params *params, const stamp_source *s, const stamp_placement *p,
                      float *data, int64_t area_x0, int64_t area_z0, int64_t width, int64_t height,
                      og_error *err) {
    layer_grid g;
    stamp_op o;
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
