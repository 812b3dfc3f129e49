#include "editor/tools/volume_brush.h"

#include "editor/edit/edit.h"
#include "editor/edit/edit_commit.h"
#include "editor/edit/parallel.h"
#include "editor/world/volume_grid.h"

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// A dab box beyond this many voxels across would take minutes and gigabytes.
#define VOLUME_MAX_RADIUS_VOXELS 512.0
// Bricks one piece of a stroke may span (its bounding box), and vsmooth / vflatten dabs
// one piece may lay: more is a typo'd coordinate, not a stroke.
#define VOLUME_MAX_PIECE_BRICKS (1 << 22)
#define VOLUME_MAX_PIECE_DABS 100000

static _Atomic long long last_voxels;

long long volume_brush_last_voxels(void) {
    return atomic_load(&last_voxels);
}

// Polynomial smooth minimum (Quilez): min(a, b) rounded over a width k.
static float smin(float a, float b, float k) {
    if (k <= 0) return fminf(a, b);
    float h = fmaxf(k - fabsf(a - b), 0.0f) / k;
    return fminf(a, b) - h * h * k * 0.25f;
}

static float smax(float a, float b, float k) {
    return -smin(-a, -b, k);
}

typedef struct vol_job {
    world *w;
    edit *e;
    const brush *b;
    volume_grid g;
    volume_box box;
    tile_key *bricks;
    size_t brick_count;
    _Atomic long long voxels;
    // fill / carve: the piece of the path (a round cone between two points), the seam's
    // blend width and how far beyond the shape distances are written.
    double seg[2][3], seg_radius[2];
    double blend, margin;
    // The stroke's previous piece: voxels nearer to it than to this one were shaped by
    // it already (no second blend at the joints).
    int has_prev;
    double prev[2][3], prev_radius[2];
    // vsmooth / vflatten: one dab's target surface over box (row-major x, z, y slowest).
    float *target, *now;
    volume_box field_box; // box grown by one voxel: where `now` is known
    volume_heights vh;
} vol_job;

// Signed distance from p to the round cone around segment a-b (radii ra, rb).
static double segment_distance(const double p[3], const double a[3], const double b[3], double ra,
                               double rb) {
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    double len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    double t = len2 > 0 ? (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / len2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double d[3] = {ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - (ra + t * (rb - ra));
}

static double piece_distance(const vol_job *j, const double p[3]) {
    return segment_distance(p, j->seg[0], j->seg[1], j->seg_radius[0], j->seg_radius[1]);
}

// Whether a brick lies farther than the margin from the piece (skipped: untouched).
static int brick_beyond_piece(const vol_job *j, tile_key key) {
    volume_box b = volume_brick_box(key);
    double v = j->g.voxel;
    double c[3] = {(b.i0 + b.i1 - 1) * 0.5 * v, (b.j0 + b.j1 - 1) * 0.5 * v,
                   (b.k0 + b.k1 - 1) * 0.5 * v};
    double half = 0.5 * v *
                  sqrt((double)(VOLUME_BRICK_X * VOLUME_BRICK_X + VOLUME_BRICK_Y * VOLUME_BRICK_Y +
                                VOLUME_BRICK_Z * VOLUME_BRICK_Z));
    return piece_distance(j, c) > half + j->margin;
}

static int list_bricks(vol_job *j, int skip_beyond_piece, og_error *err) {
    int64_t n = volume_box_bricks(j->box);
    if (n > VOLUME_MAX_PIECE_BRICKS)
        return og_error_set(err, "%s: one piece of the stroke spans %lld bricks (the limit is %d)",
                            brush_tool_name(j->b->tool), (long long)n, VOLUME_MAX_PIECE_BRICKS);
    free(j->bricks);
    j->bricks = malloc((size_t)(n > 0 ? n : 1) * sizeof *j->bricks);
    if (!j->bricks) return og_error_set(err, "out of memory listing %lld bricks", (long long)n);
    size_t all = volume_box_brick_keys(j->box, j->bricks);
    j->brick_count = 0;
    for (size_t i = 0; i < all; i++)
        if (!skip_beyond_piece || !brick_beyond_piece(j, j->bricks[i]))
            j->bricks[j->brick_count++] = j->bricks[i];
    return 0;
}

// fill / carve on one brick.
static int shape_task(void *user, int t, og_error *err) {
    vol_job *j = user;
    tile_key key = j->bricks[t];
    volume_box b = volume_box_intersect(volume_brick_box(key), j->box);
    tile_view view;
    if (edit_tile_acquire(j->e, key, &view, err) != 0) return -1;
    int16_t *data = view.data;
    double v = j->g.voxel;
    float k = (float)j->blend;
    int fill = j->b->tool == BRUSH_FILL;
    long long visited = 0;
    for (int64_t y = b.j0; y < b.j1; y++)
        for (int64_t z = b.k0; z < b.k1; z++)
            for (int64_t x = b.i0; x < b.i1; x++) {
                double p[3] = {x * v, y * v, z * v};
                double d = piece_distance(j, p);
                visited++;
                if (d > j->margin) continue;
                if (j->has_prev && segment_distance(p, j->prev[0], j->prev[1], j->prev_radius[0],
                                                    j->prev_radius[1]) <= d)
                    continue;
                int16_t *pair = data + 2 * volume_brick_offset(key, x, y, z);
                float add = volume_to_metres(pair[0], v), sub = volume_to_metres(pair[1], v);
                float df = (float)d;
                if (fill) {
                    add = smin(add, df, k);
                    sub = smax(sub, -df, k);
                } else {
                    sub = smin(sub, df, k);
                    add = smax(add, -df, k);
                }
                pair[0] = volume_from_metres(add, v);
                pair[1] = volume_from_metres(sub, v);
            }
    edit_tile_release(j->e, &view);
    atomic_fetch_add(&j->voxels, visited);
    return 0;
}

// Makes the combined distance at a voxel equal t by changing ADD and SUB only
// (volume_grid.h: d = max(min(h, add), -sub)): lowering it needs add <= t and
// sub >= -t; raising it, -sub >= t.
static void set_combined(int16_t *pair, float d_height, float t, double v) {
    float add = volume_to_metres(pair[0], v), sub = volume_to_metres(pair[1], v);
    float now = volume_combine(d_height, add, sub);
    if (t < now) {
        pair[0] = volume_from_metres(fminf(add, t), v);
        pair[1] = volume_from_metres(fmaxf(sub, -t), v);
    } else if (t > now) {
        pair[1] = volume_from_metres(fminf(sub, -t), v);
    }
}

static size_t field_index(const volume_box *f, int64_t x, int64_t y, int64_t z) {
    return (size_t)(((y - f->j0) * (f->k1 - f->k0) + (z - f->k0)) * (f->i1 - f->i0) + (x - f->i0));
}

// Reads the combined distance over field_box into now.
static int read_field(vol_job *j, og_error *err) {
    return volume_field_read(j->w, &j->g, &j->vh, j->field_box, j->now, err);
}

// vsmooth / vflatten: writes the target into one brick.
static int surface_task(void *user, int t, og_error *err) {
    vol_job *j = user;
    tile_key key = j->bricks[t];
    volume_box b = volume_box_intersect(volume_brick_box(key), j->box);
    tile_view view;
    if (edit_tile_acquire(j->e, key, &view, err) != 0) return -1;
    int16_t *data = view.data;
    double v = j->g.voxel;
    long long visited = 0;
    for (int64_t y = b.j0; y < b.j1; y++)
        for (int64_t z = b.k0; z < b.k1; z++)
            for (int64_t x = b.i0; x < b.i1; x++) {
                size_t f = field_index(&j->field_box, x, y, z);
                visited++;
                if (j->target[f] == j->now[f]) continue;
                set_combined(data + 2 * volume_brick_offset(key, x, y, z),
                             volume_heights_distance(&j->vh, x, z, (double)y * v), j->target[f], v);
            }
    edit_tile_release(j->e, &view);
    atomic_fetch_add(&j->voxels, visited);
    return 0;
}

// One vsmooth / vflatten dab at c with pressure.
static int surface_dab(vol_job *j, const double c[3], double pressure, double plane_y,
                       og_error *err) {
    const brush *b = j->b;
    double v = j->g.voxel, r = b->radius;
    double lo[3] = {c[0], c[1], c[2]};
    j->box = volume_grid_box_around(&j->g, lo, lo, r);
    volume_box f = {j->box.i0 - 1, j->box.j0 - 1, j->box.k0 - 1,
                    j->box.i1 + 1, j->box.j1 + 1, j->box.k1 + 1};
    j->field_box = f;
    size_t n = (size_t)volume_box_voxels(f);
    free(j->now);
    free(j->target);
    j->now = malloc(n * sizeof *j->now);
    j->target = malloc(n * sizeof *j->target);
    if (!j->now || !j->target) return og_error_set(err, "out of memory for a %zu-voxel dab", n);
    volume_heights_free(&j->vh);
    if (volume_heights_read(j->w, &j->g, j->g.voxel, f.i0, f.k0, f.i1, f.k1, &j->vh, err) != 0 ||
        read_field(j, err) != 0)
        return -1;
    memcpy(j->target, j->now, n * sizeof *j->target);
    double strength = b->strength * pressure;
    int64_t sx = f.i1 - f.i0, sxz = sx * (f.k1 - f.k0);
    for (int64_t y = j->box.j0; y < j->box.j1; y++)
        for (int64_t z = j->box.k0; z < j->box.k1; z++)
            for (int64_t x = j->box.i0; x < j->box.i1; x++) {
                double dx = x * v - c[0], dy = y * v - c[1], dz = z * v - c[2];
                float w = (float)strength *
                          brush_falloff_weight(b, (float)(sqrt(dx * dx + dy * dy + dz * dz) / r));
                if (w <= 0) continue;
                size_t i = field_index(&f, x, y, z);
                float goal;
                if (b->tool == BRUSH_VSMOOTH) {
                    double sum = 0;
                    for (int64_t oy = -1; oy <= 1; oy++)
                        for (int64_t oz = -1; oz <= 1; oz++)
                            for (int64_t ox = -1; ox <= 1; ox++)
                                sum += j->now[(int64_t)i + oy * sxz + oz * sx + ox];
                    goal = (float)(sum / 27.0);
                } else {
                    goal = (float)(y * v - plane_y);
                }
                j->target[i] = j->now[i] + w * (goal - j->now[i]);
            }
    if (list_bricks(j, 0, err) != 0) return -1;
    if (parallel_run((int)j->brick_count, surface_task, j, err) != 0) return -1;
    edit_dirty(j->e, TILE_LAYER_VOLUME, 0, (grid_rect){j->box.i0, j->box.k0, j->box.i1, j->box.k1});
    return 0;
}

// Checks that hold for the whole stroke (the tool, the world, the radius).
static int check_brush(const volume_grid *g, const brush *b, og_error *err) {
    const char *name = brush_tool_name(b->tool);
    if (!(b->radius > 0) || b->radius / g->voxel > VOLUME_MAX_RADIUS_VOXELS)
        return og_error_set(err,
                            "%s: radius %g m is %.0f voxels of %g m; the volume tools take up to "
                            "%.0f (a smaller radius, or coarser voxels: a lower volume_ratio)",
                            name, b->radius, b->radius / g->voxel, g->voxel,
                            VOLUME_MAX_RADIUS_VOXELS);
    return 0;
}

// Checks one point: where it is, its pressure, and that the bricks one dab there keeps
// pinned fit the cache.
static int check_point(const volume_grid *g, const brush *b, const double p[3], double pressure,
                       tile_cache *cache, og_error *err) {
    const char *name = brush_tool_name(b->tool);
    og_error where;
    if (volume_grid_check_position(g, p, &where) != 0)
        return og_error_set(err, "%s: %s", name, where.msg);
    if (!(pressure >= 0 && pressure <= 1))
        return og_error_set(err, "%s: pressure %g must be 0 to 1", name, pressure);
    volume_box one = volume_grid_box_around(g, p, p, b->radius + VOLUME_EXACT_VOXELS * g->voxel);
    tile_cache_stats st;
    tile_cache_stats_get(cache, &st);
    double need = (double)volume_box_bricks(one) * (double)tile_layer_bytes(TILE_LAYER_VOLUME);
    if (need > st.budget_bytes / 2.0)
        return og_error_set(err,
                            "%s: a %g m dab at %g m voxels touches %.0f MiB of volume bricks, more "
                            "than half the tile cache (%.0f MiB)",
                            name, b->radius, g->voxel, need / 1048576.0,
                            st.budget_bytes / 1048576.0);
    return 0;
}

struct volume_stroke {
    vol_job job;
    brush b;
    long dabs;
    double last[3], last_radius, last_pressure;
    double carry;   // vsmooth / vflatten: distance since the last dab
    double plane_y; // vflatten
};

volume_stroke *volume_stroke_begin(world *w, const brush *b, og_error *err) {
    char label[64];
    snprintf(label, sizeof label, "%s stroke", brush_tool_name(b->tool));
    return volume_stroke_begin_labelled(w, b, label, err);
}

volume_stroke *volume_stroke_begin_labelled(world *w, const brush *b, const char *label,
                                            og_error *err) {
    if (!brush_tool_is_volume(b->tool)) {
        og_error_set(err, "%s is not a volume tool (fill, carve, vsmooth, vflatten)",
                     brush_tool_name(b->tool));
        return NULL;
    }
    volume_stroke *s = calloc(1, sizeof *s);
    if (!s) {
        og_error_set(err, "out of memory");
        return NULL;
    }
    s->b = *b;
    s->job.w = w;
    s->job.b = &s->b;
    if (volume_grid_init(&s->job.g, world_get_params(w), err) != 0 ||
        check_brush(&s->job.g, b, err) != 0 || !(s->job.e = edit_begin(w, label, err))) {
        free(s);
        return NULL;
    }
    return s;
}

// fill / carve: the ball at the first point, then each piece of the path.
static int shape_piece(volume_stroke *s, const double p[3], double radius, og_error *err) {
    vol_job *j = &s->job;
    const brush *b = &s->b;
    double(*pts)[3] = j->seg, *radii = j->seg_radius;
    memcpy(pts[1], p, sizeof pts[1]);
    radii[1] = radius;
    memcpy(pts[0], s->dabs > 0 ? s->last : p, sizeof pts[0]);
    radii[0] = s->dabs > 0 ? s->last_radius : radius;
    j->blend = b->falloff == FALLOFF_CONSTANT
                   ? 0
                   : b->radius * (1.0 - brush_falloff_weight(b, 0.5f)) * 0.5;
    j->margin = VOLUME_EXACT_VOXELS * j->g.voxel + j->blend;
    double lo[3], hi[3];
    for (int a = 0; a < 3; a++)
        lo[a] = fmin(pts[0][a], pts[1][a]), hi[a] = fmax(pts[0][a], pts[1][a]);
    j->box = volume_grid_box_around(&j->g, lo, hi, fmax(radii[0], radii[1]) + j->margin);
    int rc = list_bricks(j, 1, err);
    // A piece whose bricks would not fit the cache (a typo'd coordinate, not a stroke).
    tile_cache_stats st;
    tile_cache_stats_get(world_cache(j->w), &st);
    double need = (double)j->brick_count * (double)tile_layer_bytes(TILE_LAYER_VOLUME);
    if (rc == 0 && need > st.budget_bytes / 2.0)
        rc = og_error_set(err,
                          "%s: the piece from (%g, %g, %g) to (%g, %g, %g) m touches %.0f MiB of "
                          "volume bricks, more than half the tile cache (%.0f MiB)",
                          brush_tool_name(b->tool), pts[0][0], pts[0][1], pts[0][2], pts[1][0],
                          pts[1][1], pts[1][2], need / 1048576.0, st.budget_bytes / 1048576.0);
    if (rc == 0) rc = parallel_run((int)j->brick_count, shape_task, j, err);
    if (rc == 0)
        edit_dirty(j->e, TILE_LAYER_VOLUME, 0,
                   (grid_rect){j->box.i0, j->box.k0, j->box.i1, j->box.k1});
    j->has_prev = 1;
    memcpy(j->prev, j->seg, sizeof j->prev);
    memcpy(j->prev_radius, j->seg_radius, sizeof j->prev_radius);
    return rc;
}

// vsmooth / vflatten: dabs every spacing x radius from the last point to p.
static int surface_piece(volume_stroke *s, const double p[3], double pressure, og_error *err) {
    const brush *b = &s->b;
    if (s->dabs == 0) {
        s->plane_y = b->has_height ? b->height : p[1];
        return surface_dab(&s->job, p, pressure, s->plane_y, err);
    }
    const double *a = s->last;
    double step = b->spacing * b->radius;
    double len = sqrt((p[0] - a[0]) * (p[0] - a[0]) + (p[1] - a[1]) * (p[1] - a[1]) +
                      (p[2] - a[2]) * (p[2] - a[2]));
    double at = step - s->carry;
    if ((len - at) / step > VOLUME_MAX_PIECE_DABS)
        return og_error_set(err, "%s: a piece of %g m would need more than %d dabs",
                            brush_tool_name(b->tool), len, VOLUME_MAX_PIECE_DABS);
    for (; at <= len; at += step) {
        double t = len > 0 ? at / len : 1;
        double q[3] = {a[0] + t * (p[0] - a[0]), a[1] + t * (p[1] - a[1]),
                       a[2] + t * (p[2] - a[2])};
        double pr = s->last_pressure + t * (pressure - s->last_pressure);
        if (surface_dab(&s->job, q, pr, s->plane_y, err) != 0) return -1;
    }
    s->carry = len - (at - step);
    return 0;
}

int volume_stroke_to(volume_stroke *s, const double p[3], double pressure, og_error *err) {
    vol_job *j = &s->job;
    if (check_point(&j->g, &s->b, p, pressure, world_cache(j->w), err) != 0) return -1;
    atomic_store(&j->voxels, 0);
    int shape = s->b.tool == BRUSH_FILL || s->b.tool == BRUSH_CARVE;
    double radius = s->b.radius * s->b.strength * pressure;
    int rc = shape ? shape_piece(s, p, radius, err) : surface_piece(s, p, pressure, err);
    atomic_store(&last_voxels, atomic_load(&j->voxels));
    if (rc != 0) return -1;
    memcpy(s->last, p, sizeof s->last);
    s->last_radius = radius;
    s->last_pressure = pressure;
    s->dabs++;
    return 0;
}

int volume_stroke_move(volume_stroke *s, const double p[3], double pressure, og_error *err) {
    if (check_point(&s->job.g, &s->b, p, pressure, world_cache(s->job.w), err) != 0) return -1;
    if (s->dabs == 0) return volume_stroke_to(s, p, pressure, err);
    memcpy(s->last, p, sizeof s->last);
    s->last_radius = s->b.radius * s->b.strength * pressure;
    s->last_pressure = pressure;
    s->carry = 0;
    s->job.has_prev = 0;
    return 0;
}

static void free_stroke(volume_stroke *s) {
    free(s->job.bricks);
    free(s->job.now);
    free(s->job.target);
    volume_heights_free(&s->job.vh);
    free(s);
}

int volume_stroke_end(volume_stroke *s, og_error *err) {
    edit *e = s->job.e;
    long dabs = s->dabs;
    free_stroke(s);
    if (dabs == 0) { // nothing laid: no step
        edit_abort(e);
        return 0;
    }
    return edit_commit(e, err);
}

void volume_stroke_cancel(volume_stroke *s) {
    edit_abort(s->job.e);
    free_stroke(s);
}

long volume_stroke_dabs(const volume_stroke *s) {
    return s->dabs;
}

int volume_brush_apply(world *w, const brush *b, const double (*points)[3], const double *pressure,
                       size_t count, og_error *err) {
    if (count == 0)
        return og_error_set(err, "%s: needs at least one X Y Z point", brush_tool_name(b->tool));
    volume_stroke *s = volume_stroke_begin(w, b, err);
    if (!s) return -1;
    // Every point is checked before anything changes.
    for (size_t i = 0; i < count; i++) {
        og_error why;
        if (check_point(&s->job.g, b, points[i], pressure ? pressure[i] : 1.0, world_cache(w),
                        &why) != 0) {
            og_error_set(err, "point %zu: %s", i + 1, why.msg);
            volume_stroke_cancel(s);
            return -1;
        }
    }
    for (size_t i = 0; i < count; i++)
        if (volume_stroke_to(s, points[i], pressure ? pressure[i] : 1.0, err) != 0) {
            volume_stroke_cancel(s);
            return -1;
        }
    return volume_stroke_end(s, err);
}
