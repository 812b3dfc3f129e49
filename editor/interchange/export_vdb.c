#include "editor/interchange/export_vdb.h"

#include "editor/edit/parallel.h"
#include "editor/world/volume_grid.h"
#include "io/vdb_file.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

int export_vdb_wanted(const char *path) {
    const char *dot = strrchr(path, '.');
    return dot && !strcasecmp(dot, ".vdb");
}

typedef struct vdb_job {
    world *w;
    volume_grid g;
    double ev; // export voxel, metres
    float background;
    int64_t c0[2], c1[2]; // export columns [c0, c1) in x and z
    volume_heights vh;
    vdb_level_set **sets;
    int tasks;
    int64_t *jlo, *jhi; // per task: the rows of voxels computed
    long long *written;
    // Signing the inactive space: the solid reaches down to floor_y (index); per 8 x 8
    // column block (leaf-aligned, from block i0/k0) the lowest voxel computed and
    // whether a volume brick lies over it.
    int64_t floor_y, bi0, bk0, nbi, nbk;
    int64_t *block_low;
    unsigned char *block_brick;
    volume_reader *reader;
    og_error *err;
} vdb_job;

static int64_t floor_div8(int64_t v) {
    return v >= 0 ? v / 8 : -((-v + 7) / 8);
}

static size_t block_of(const vdb_job *j, int64_t i, int64_t k) {
    return (size_t)((floor_div8(k) - j->bk0) * j->nbi + (floor_div8(i) - j->bi0));
}

static void note_low(vdb_job *j, int64_t i, int64_t k, int64_t low, int brick) {
    size_t b = block_of(j, i, k);
    if (low < j->block_low[b]) j->block_low[b] = low;
    if (brick) j->block_brick[b] = 1;
}

static void note_rows(vdb_job *j, int t, int64_t lo, int64_t hi) {
    if (lo < j->jlo[t]) j->jlo[t] = lo;
    if (hi > j->jhi[t]) j->jhi[t] = hi;
}

// The heightfield's narrow band over a strip of rows (task t of tasks).
static int height_task(void *user, int t, og_error *err) {
    vdb_job *j = user;
    int64_t rows = j->c1[1] - j->c0[1];
    // Strips of whole 8-voxel leaf rows, so merging the strips moves whole leaves.
    int64_t per = ((rows + j->tasks - 1) / j->tasks + 7) / 8 * 8;
    int64_t k0 = j->c0[1] + t * per, k1 = k0 + per < j->c1[1] ? k0 + per : j->c1[1];
    double ev = j->ev, bg = j->background;
    float *values = NULL;
    size_t cap = 0;
    int rc = 0;
    for (int64_t k = k0; k < k1 && rc == 0; k++)
        for (int64_t i = j->c0[0]; i < j->c1[0]; i++) {
            size_t c = (size_t)((k - j->vh.k0) * j->vh.w + (i - j->vh.i0));
            double h = j->vh.height[c], s = j->vh.slope_scale[c];
            int64_t lo = (int64_t)floor((h - bg / s) / ev), hi = (int64_t)ceil((h + bg / s) / ev);
            size_t n = (size_t)(hi - lo + 1);
            if (n > cap) {
                float *grown = realloc(values, n * sizeof *values);
                if (!grown) {
                    rc = og_error_set(err, "out of memory");
                    break;
                }
                values = grown;
                cap = n;
            }
            for (size_t y = 0; y < n; y++)
                values[y] = (float)(((double)(lo + (int64_t)y) * ev - h) * s);
            if (vdb_level_set_column(j->sets[t], (int32_t)i, (int32_t)k, (int32_t)lo, (int32_t)n,
                                     values, 0, err) != 0) {
                rc = -1;
                break;
            }
            j->written[t] += (long long)n;
            note_rows(j, t, lo, hi);
        }
    free(values);
    return rc;
}

// Export columns [*lo, *hi) whose positions fall in voxels [v0, v1) of the world's voxel
// grid (a position belongs to the voxel at or below it).
static void export_span(double wv, double ev, int64_t v0, int64_t v1, int64_t *lo, int64_t *hi) {
    *lo = (int64_t)ceil(v0 * wv / ev - 1e-9);
    *hi = (int64_t)ceil(v1 * wv / ev - 1e-9);
}

// The combined field (heights with the volume edits) at export voxel (i, y, k) over a
// column of height h and slope scale s: trilinear over the world voxel's corners (one
// corner where the lattices meet).
static int combined_at(vdb_job *j, volume_reader *r, int64_t i, int64_t y, int64_t k, double h,
                       double s, float *out, og_error *err) {
    double wv = j->g.voxel, ev = j->ev;
    double f[3] = {i * ev / wv, y * ev / wv, k * ev / wv}, t[3];
    int64_t v[3];
    for (int a = 0; a < 3; a++) {
        v[a] = (int64_t)floor(f[a] + 1e-9);
        t[a] = f[a] - v[a];
        if (t[a] < 1e-9) t[a] = 0;
    }
    double d = 0;
    for (int corner = 0; corner < 8; corner++) {
        double weight = 1;
        int64_t c[3];
        for (int a = 0; a < 3; a++) {
            int up = corner >> a & 1;
            weight *= up ? t[a] : 1 - t[a];
            c[a] = v[a] + up;
        }
        if (weight == 0) continue;
        const int16_t *pair = volume_reader_pair(r, c[0], c[1], c[2], err);
        if (!pair) return -1;
        float dh = (float)((c[1] * wv - h) * s);
        d += weight *
             volume_combine(dh, volume_to_metres(pair[0], wv), volume_to_metres(pair[1], wv));
    }
    *out = (float)d;
    return 0;
}

// The combined field over one brick's voxels: heights with the volume edits.
static int brick_pass(vdb_job *j, tile_key key, volume_reader *r, float **values, size_t *cap,
                      og_error *err) {
    volume_box b = volume_brick_box(key);
    double wv = j->g.voxel, ev = j->ev;
    int64_t i0, i1, k0, k1, y0, y1;
    export_span(wv, ev, b.i0, b.i1, &i0, &i1);
    export_span(wv, ev, b.k0, b.k1, &k0, &k1);
    export_span(wv, ev, b.j0, b.j1, &y0, &y1);
    if (i0 < j->c0[0]) i0 = j->c0[0];
    if (k0 < j->c0[1]) k0 = j->c0[1];
    if (i1 > j->c1[0]) i1 = j->c1[0];
    if (k1 > j->c1[1]) k1 = j->c1[1];
    if (i0 >= i1 || k0 >= k1 || y0 >= y1) return 0;
    for (int64_t bk = floor_div8(k0); bk <= floor_div8(k1 - 1); bk++)
        for (int64_t bi = floor_div8(i0); bi <= floor_div8(i1 - 1); bi++)
            note_low(j, bi * 8, bk * 8, y0, 1);
    size_t n = (size_t)(y1 - y0);
    if (n > *cap) {
        float *grown = realloc(*values, n * sizeof *grown);
        if (!grown) return og_error_set(err, "out of memory");
        *values = grown;
        *cap = n;
    }
    for (int64_t k = k0; k < k1; k++)
        for (int64_t i = i0; i < i1; i++) {
            size_t c = (size_t)((k - j->vh.k0) * j->vh.w + (i - j->vh.i0));
            double h = j->vh.height[c], s = j->vh.slope_scale[c];
            for (int64_t y = y0; y < y1; y++)
                if (combined_at(j, r, i, y, k, h, s, &(*values)[y - y0], err) != 0) return -1;
            if (vdb_level_set_column(j->sets[0], (int32_t)i, (int32_t)k, (int32_t)y0, (int32_t)n,
                                     *values, 1, err) != 0)
                return -1;
            j->written[0] += (long long)n;
            note_rows(j, 0, y0, y1 - 1);
        }
    return 0;
}

// Whether export voxel (i, j, k) lies in the solid: within the region's columns, above
// the floor, and below the ground (with the volume edits where a brick lies over).
static int inside_at(void *user, int i, int j, int k) {
    vdb_job *job = user;
    if (i < job->c0[0] || i >= job->c1[0] || k < job->c0[1] || k >= job->c1[1] || j < job->floor_y)
        return 0;
    size_t c = (size_t)((k - job->vh.k0) * job->vh.w + (i - job->vh.i0));
    double h = job->vh.height[c];
    if (!job->block_brick[block_of(job, i, k)]) return j * job->ev < h;
    float d;
    if (combined_at(job, job->reader, i, j, k, h, job->vh.slope_scale[c], &d, job->err) != 0)
        return -1;
    return d < 0;
}

// The inactive space's signs: the interior under each block's lowest computed voxel
// down to the floor as tiles, then every value still unsigned asks inside_at.
static int sign_space(vdb_job *j, const export_options *o, og_error *err) {
    double depth = o->depth >= 0 ? o->depth : 16 * j->ev, lowest = INFINITY;
    size_t columns = (size_t)(j->vh.w * j->vh.h);
    for (size_t c = 0; c < columns; c++)
        if (j->vh.height[c] < lowest) lowest = j->vh.height[c];
    j->floor_y = (int64_t)floor((lowest - depth) / j->ev + 1e-9);
    for (int64_t k = j->c0[1]; k < j->c1[1]; k++)
        for (int64_t i = j->c0[0]; i < j->c1[0]; i++) {
            size_t c = (size_t)((k - j->vh.k0) * j->vh.w + (i - j->vh.i0));
            double h = j->vh.height[c], s = j->vh.slope_scale[c];
            note_low(j, i, k, (int64_t)floor((h - j->background / s) / j->ev), 0);
        }
    for (int64_t bk = 0; bk < j->nbk; bk++)
        for (int64_t bi = 0; bi < j->nbi; bi++) {
            int64_t top = floor_div8(j->block_low[bk * j->nbi + bi]) * 8 - 1;
            int64_t i0 = (j->bi0 + bi) * 8, k0 = (j->bk0 + bk) * 8;
            int32_t box[6] = {(int32_t)(i0 > j->c0[0] ? i0 : j->c0[0]),
                              (int32_t)j->floor_y,
                              (int32_t)(k0 > j->c0[1] ? k0 : j->c0[1]),
                              (int32_t)(i0 + 7 < j->c1[0] ? i0 + 7 : j->c1[0] - 1),
                              (int32_t)top,
                              (int32_t)(k0 + 7 < j->c1[1] ? k0 + 7 : j->c1[1] - 1)};
            if (top >= j->floor_y && vdb_level_set_fill_inside(j->sets[0], box, err) != 0)
                return -1;
        }
    j->err = err;
    // Where inside_at can say inside: the region's columns, from the floor up.
    const int32_t solid[6] = {(int32_t)j->c0[0],     (int32_t)j->floor_y, (int32_t)j->c0[1],
                              (int32_t)j->c1[0] - 1, INT32_MAX / 2,       (int32_t)j->c1[1] - 1};
    return vdb_level_set_sign(j->sets[0], solid, inside_at, j, err);
}

static int region_columns(world *w, const export_options *o, double ev, int64_t c0[2],
                          int64_t c1[2], og_error *err) {
    const world_params *p = world_get_params(w);
    double x0, z0, x1, z1;
    if (o->has_region) {
        x0 = o->x0, z0 = o->z0, x1 = o->x1, z1 = o->z1;
    } else if (p->size > 0) {
        x0 = z0 = 0;
        x1 = (double)(p->size - 1) * p->spacing;
        z1 = (double)(world_params_size_z(p) - 1) * p->spacing;
    } else {
        return og_error_set(err, "export: a .vdb of an unbounded world needs region=X0,Z0,X1,Z1");
    }
    if (p->size > 0) {
        double right = (double)(p->size - 1) * p->spacing;
        double bottom = (double)(world_params_size_z(p) - 1) * p->spacing;
        if (x0 < 0 || z0 < 0 || x1 > right || z1 > bottom)
            return og_error_set(err,
                                "region: %g,%g,%g,%g m lies outside the world (0 to %g m along X, "
                                "0 to %g m along Z)",
                                x0, z0, x1, z1, right, bottom);
    }
    c0[0] = (int64_t)ceil(x0 / ev - 1e-9), c0[1] = (int64_t)ceil(z0 / ev - 1e-9);
    c1[0] = (int64_t)floor(x1 / ev + 1e-9) + 1, c1[1] = (int64_t)floor(z1 / ev + 1e-9) + 1;
    double limit = (double)INT32_MAX / 2;
    if (fabs(x0 / ev) > limit || fabs(x1 / ev) > limit || fabs(z0 / ev) > limit ||
        fabs(z1 / ev) > limit)
        return og_error_set(err,
                            "region: %g,%g,%g,%g m is beyond OpenVDB's int32 voxel indices "
                            "at voxel %g m",
                            x0, z0, x1, z1, ev);
    double columns = (double)(c1[0] - c0[0]) * (double)(c1[1] - c0[1]);
    if (c1[0] <= c0[0] || c1[1] <= c0[1])
        return og_error_set(err, "region: %g,%g,%g,%g m holds no voxel column at voxel %g m", x0,
                            z0, x1, z1, ev);
    if (columns > (double)EXPORT_MAX_SAMPLES)
        return og_error_set(err,
                            "region: %.0f voxel columns at voxel %g m; one export takes at most "
                            "%lld (a smaller region or a larger voxel=)",
                            columns, ev, (long long)EXPORT_MAX_SAMPLES);
    return 0;
}

int export_vdb_file(world *w, const char *path, const export_options *o, export_vdb_report *rep,
                    og_error *err) {
    memset(rep, 0, sizeof *rep);
    vdb_job j = {.w = w};
    if (volume_grid_init(&j.g, world_get_params(w), err) != 0) return -1;
    j.ev = o->voxel > 0 ? o->voxel : j.g.voxel;
    j.background = (float)(o->band * j.ev);
    if (region_columns(w, o, j.ev, j.c0, j.c1, err) != 0) return -1;
    tile_key *bricks = NULL;
    size_t brick_count = 0;
    if (volume_list_bricks(w, &bricks, &brick_count, err) != 0) return -1;
    if (volume_heights_read(w, &j.g, j.ev, j.c0[0], j.c0[1], j.c1[0], j.c1[1], &j.vh, err) != 0) {
        free(bricks);
        return -1;
    }
    j.tasks = parallel_threads();
    j.sets = calloc((size_t)j.tasks, sizeof *j.sets);
    j.jlo = malloc((size_t)j.tasks * sizeof *j.jlo);
    j.jhi = malloc((size_t)j.tasks * sizeof *j.jhi);
    j.written = calloc((size_t)j.tasks, sizeof *j.written);
    int rc = -1;
    if (!j.sets || !j.jlo || !j.jhi || !j.written) {
        og_error_set(err, "out of memory");
        goto done;
    }
    for (int t = 0; t < j.tasks; t++) {
        j.jlo[t] = INT64_MAX;
        j.jhi[t] = INT64_MIN;
        if (!(j.sets[t] = vdb_level_set_create(j.ev, j.background, err))) goto done;
    }
    if (parallel_run(j.tasks, height_task, &j, err) != 0) goto done;
    for (int t = 1; t < j.tasks; t++)
        if (vdb_level_set_merge(j.sets[0], j.sets[t], err) != 0) goto done;
    // The volume edits replace the heightfield's values over their bricks.
    j.bi0 = floor_div8(j.c0[0]), j.bk0 = floor_div8(j.c0[1]);
    j.nbi = floor_div8(j.c1[0] - 1) - j.bi0 + 1, j.nbk = floor_div8(j.c1[1] - 1) - j.bk0 + 1;
    j.block_low = malloc((size_t)(j.nbi * j.nbk) * sizeof *j.block_low);
    j.block_brick = calloc((size_t)(j.nbi * j.nbk), 1);
    if (!j.block_low || !j.block_brick) {
        og_error_set(err, "out of memory");
        goto done;
    }
    for (int64_t b = 0; b < j.nbi * j.nbk; b++)
        j.block_low[b] = INT64_MAX;
    volume_reader reader;
    volume_reader_init(&reader, w);
    j.reader = &reader;
    float *values = NULL;
    size_t cap = 0;
    int brick_rc = 0;
    for (size_t b = 0; b < brick_count && brick_rc == 0; b++) {
        volume_box box = volume_brick_box(bricks[b]);
        int64_t i0, i1, k0, k1;
        export_span(j.g.voxel, j.ev, box.i0, box.i1, &i0, &i1);
        export_span(j.g.voxel, j.ev, box.k0, box.k1, &k0, &k1);
        if (i1 <= j.c0[0] || i0 >= j.c1[0] || k1 <= j.c0[1] || k0 >= j.c1[1]) continue;
        brick_rc = brick_pass(&j, bricks[b], &reader, &values, &cap, err);
        rep->bricks++;
    }
    free(values);
    if (brick_rc == 0) brick_rc = sign_space(&j, o, err);
    volume_reader_close(&reader);
    if (brick_rc != 0) goto done;

    char spacing[64], voxel[64], region[192], volume_ratio[16];
    snprintf(spacing, sizeof spacing, "%.17g", j.g.spacing);
    snprintf(voxel, sizeof voxel, "%.17g", j.ev);
    snprintf(region, sizeof region, "%.17g,%.17g,%.17g,%.17g", j.c0[0] * j.ev, j.c0[1] * j.ev,
             (j.c1[0] - 1) * j.ev, (j.c1[1] - 1) * j.ev);
    snprintf(volume_ratio, sizeof volume_ratio, "%d", j.g.ratio);
    const char *world_name = world_path(w)[0] ? world_path(w) : "(unsaved world)";
    const char *meta[] = {"creator",      "Orogen",     "world",  world_name, "spacing",
                          spacing,        "voxel_size", voxel,    "region",   region,
                          "volume_ratio", volume_ratio, "y_axis", "up"};
    rep->active_voxels = vdb_level_set_active_voxels(j.sets[0]);
    if (vdb_level_set_write(j.sets[0], path, o->fog, meta, (int)(sizeof meta / sizeof *meta / 2),
                            err) != 0)
        goto done;
    struct stat st;
    rep->bytes = stat(path, &st) == 0 ? (long long)st.st_size : 0;
    rep->voxel = j.ev;
    rep->band = o->band;
    rep->floor = j.floor_y * j.ev;
    rep->columns = (long long)(j.c1[0] - j.c0[0]) * (j.c1[1] - j.c0[1]);
    rep->lo[0] = j.c0[0], rep->lo[2] = j.c0[1];
    rep->hi[0] = j.c1[0] - 1, rep->hi[2] = j.c1[1] - 1;
    rep->lo[1] = INT64_MAX, rep->hi[1] = INT64_MIN;
    for (int t = 0; t < j.tasks; t++) {
        rep->voxels_written += j.written[t];
        if (j.jlo[t] < rep->lo[1]) rep->lo[1] = j.jlo[t];
        if (j.jhi[t] > rep->hi[1]) rep->hi[1] = j.jhi[t];
    }
    rc = 0;
done:
    for (int t = 0; j.sets && t < j.tasks; t++)
        vdb_level_set_free(j.sets[t]);
    free(j.sets);
    free(j.jlo);
    free(j.jhi);
    free(j.written);
    free(j.block_low);
    free(j.block_brick);
    free(bricks);
    volume_heights_free(&j.vh);
    return rc;
}
