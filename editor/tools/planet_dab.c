#include "editor/tools/planet_dab.h"

#include "editor/edit/edit_rows.h"
#include "editor/world/layer_grid.h"

#include <math.h>
#include <string.h>

static int64_t layer_ratio(const world_params *p, tile_layer layer) {
    return layer == TILE_LAYER_DETAIL || layer == TILE_LAYER_DETAIL_PD ? p->detail_ratio : 1;
}

void planet_dab_prepare(brush_dab *d, const world_params *p, tile_layer layer, int face) {
    d->sphere = 1;
    d->face = face;
    d->face_samples = world_grid_face_samples(p);
    d->index_scale = 1.0 / (double)layer_ratio(p, layer);
    d->planet_radius = p->radius;
    brush_dab_sample_direction(d, d->cx, d->cz, d->centre_dir);
    if (d->brush && d->brush->tool == BRUSH_RAMP) { // its cap: around the segment's middle
        brush_dab_sample_direction(d, d->ax, d->az, d->ramp_a);
        brush_dab_sample_direction(d, d->bx, d->bz, d->ramp_b);
        double len = 0;
        for (int k = 0; k < 3; k++)
            d->centre_dir[k] = d->ramp_a[k] + d->ramp_b[k],
            len += d->centre_dir[k] * d->centre_dir[k];
        for (int k = 0; k < 3; k++)
            d->centre_dir[k] = len > 0 ? d->centre_dir[k] / sqrt(len) : d->ramp_a[k];
    }
}

// The cap's angle: the dab's radius, and for a ramp half its length more.
static double cap_angle(const brush_dab *d) {
    double angle = d->radius * d->spacing / d->planet_radius;
    if (d->brush && d->brush->tool == BRUSH_RAMP) {
        const double *a = d->ramp_a, *b = d->ramp_b;
        double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
        angle += asin(fmin(1.0, 0.5 * sqrt(dx * dx + dy * dy + dz * dz)));
    }
    return angle;
}

int planet_dab_check_position(const layer_grid *g, double x, double z, og_error *err) {
    const double n = (double)g->extent * g->spacing;
    if (!isfinite(x) || !isfinite(z) || x < -0.5 * n || z < -0.5 * n || x > 1.5 * n || z > 1.5 * n)
        return og_error_set(err,
                            "position (%g, %g) m lies too far past face %d (-%g to %g m: half a "
                            "face beyond its edges)",
                            x, z, g->face, 0.5 * n, 1.5 * n);
    return 0;
}

// The samples of face target's (extended) grid within the dab's cap; clipped to the
// face when clip is set.
static grid_rect cap_rect(const brush_dab *d, int target, int64_t layer_samples, int clip) {
    const double angle = cap_angle(d);
    const double *c = d->centre_dir;
    // An orthonormal pair across the centre, to walk the cap's rim.
    double u[3] = {0, 0, 0};
    u[fabs(c[0]) < 0.6 ? 0 : fabs(c[1]) < 0.6 ? 1 : 2] = 1;
    double dot = u[0] * c[0] + u[1] * c[1] + u[2] * c[2];
    for (int k = 0; k < 3; k++)
        u[k] -= dot * c[k];
    double len = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int k = 0; k < 3; k++)
        u[k] /= len;
    double v[3] = {c[1] * u[2] - c[2] * u[1], c[2] * u[0] - c[0] * u[2], c[0] * u[1] - c[1] * u[0]};
    double smin = INFINITY, smax = -INFINITY, tmin = INFINITY, tmax = -INFINITY;
    const int rim = 96;
    for (int k = -1; k < rim; k++) { // the centre, then the rim
        double p[3], s, t;
        double ca = k < 0 ? 1.0 : cos(angle), sa = k < 0 ? 0.0 : sin(angle);
        double phi = 2.0 * M_PI * k / rim;
        for (int a = 0; a < 3; a++)
            p[a] = ca * c[a] + sa * (cos(phi) * u[a] + sin(phi) * v[a]);
        if (!world_grid_face_coords_on(target, p, &s, &t)) continue;
        smin = fmin(smin, s), smax = fmax(smax, s), tmin = fmin(tmin, t), tmax = fmax(tmax, t);
    }
    grid_rect none = {0, 0, 0, 0};
    if (!(smin <= smax)) return none;
    if (clip && (smax < -1.0 || smin > 1.0 || tmax < -1.0 || tmin > 1.0)) return none;
    // Sample index of a face coordinate (sample i's centre sits at (i k + 0.5) / n x 2 - 1),
    // a sample's margin for the rim between the walked points.
    const double n = (double)d->face_samples, k = d->index_scale;
    int64_t x0 = (int64_t)floor(((smin + 1.0) * 0.5 * n - 0.5) / k) - 1;
    int64_t x1 = (int64_t)ceil(((smax + 1.0) * 0.5 * n - 0.5) / k) + 2;
    int64_t z0 = (int64_t)floor(((tmin + 1.0) * 0.5 * n - 0.5) / k) - 1;
    int64_t z1 = (int64_t)ceil(((tmax + 1.0) * 0.5 * n - 0.5) / k) + 2;
    grid_rect r = {x0, z0, x1, z1};
    if (clip)
        r = (grid_rect){x0 < 0 ? 0 : x0, z0 < 0 ? 0 : z0, x1 > layer_samples ? layer_samples : x1,
                        z1 > layer_samples ? layer_samples : z1};
    return grid_rect_empty(r) ? none : r;
}

grid_rect planet_dab_face_rect(const brush_dab *d, int target, int64_t layer_samples) {
    return cap_rect(d, target, layer_samples, 1);
}

// ---- erosion: one simulation over the whole cap --------------------------------

// The dab placed on face g: its samples and its centre in g's own (extended) samples.
static brush_dab on_face(const brush_dab *base, const world_params *p, tile_layer layer, int g,
                         int64_t layer_samples) {
    brush_dab fd = *base;
    fd.face = g;
    fd.rect = cap_rect(base, g, layer_samples, 1);
    double s, t;
    int64_t ratio = layer_ratio(p, layer);
    if (world_grid_face_coords_on(g, base->centre_dir, &s, &t)) {
        fd.cx = ((s + 1.0) * 0.5 * (double)base->face_samples - 0.5) * (double)ratio;
        fd.cz = ((t + 1.0) * 0.5 * (double)base->face_samples - 0.5) * (double)ratio;
    }
    return fd;
}

typedef struct flow_rows {
    const brush_dab_area *a;
    const brush_dab *home, *face; // the dab on the face simulated, and on the face written
} flow_rows;

// A face's samples take the simulation's change where they lie in it: exactly on the
// face it ran on, bilinear elsewhere (where the grids' samples nearly align), wherever
// the weight there is > 0.
static void flow_row(void *user, void *row, int64_t z, int64_t x0, int64_t x1) {
    const flow_rows *f = user;
    const brush_dab_area *a = f->a;
    const int64_t aw = a->area.x1 - a->area.x0, ah = a->area.z1 - a->area.z0;
    const double n = (double)f->home->face_samples, k = f->home->index_scale;
    float *dst = row;
    for (int64_t x = x0; x < x1; x++) {
        double u = (double)x, v = (double)z;
        if (f->face->face != f->home->face) {
            double dir[3], s, t;
            brush_dab_sample_direction(f->face, (double)x, (double)z, dir);
            if (!world_grid_face_coords_on(f->home->face, dir, &s, &t)) continue;
            u = ((s + 1.0) * 0.5 * n - 0.5) / k, v = ((t + 1.0) * 0.5 * n - 0.5) / k;
        }
        u -= (double)a->area.x0, v -= (double)a->area.z0;
        int64_t i = (int64_t)floor(u), j = (int64_t)floor(v);
        if (i < 0 || j < 0 || i >= aw || j >= ah) continue;
        const int64_t i1 = i + 1 < aw ? i + 1 : i, j1 = j + 1 < ah ? j + 1 : j;
        const double fu = u - (double)i, fv = v - (double)j;
        const int64_t at[4] = {j * aw + i, j * aw + i1, j1 * aw + i, j1 * aw + i1};
        const double wt[4] = {(1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv};
        double weight = 0, delta = 0;
        for (int q = 0; q < 4; q++) {
            weight += wt[q] * a->weight[at[q]];
            delta += wt[q] * ((double)a->after[at[q]] - (double)a->before[at[q]]);
        }
        if (weight > 0 && isfinite(delta)) dst[x - x0] += (float)delta;
    }
}

// Thermal and hydraulic erosion move material: run on each face apart, what flows
// toward an edge would stop there. So they run once, on the face under the dab's
// centre, over its samples extended past its edges to the whole cap (one-to-one: the
// cap lies well inside that face's hemisphere), and every face takes the change.
static int flow_apply(edit *e, const world_params *p, tile_layer layer, const brush_dab *base,
                      og_error *err) {
    int home;
    double s, t;
    world_grid_direction_face(base->centre_dir, &home, &s, &t);
    layer_grid hg;
    if (layer_grid_init(&hg, p, layer, home, err) != 0) return -1;
    brush_dab hd = on_face(base, p, layer, home, hg.extent);
    hd.rect = cap_rect(base, home, hg.extent, 0);
    if (grid_rect_empty(hd.rect)) return 0;
    brush_dab_area a;
    if (brush_dab_compute_area(e, &hg, &hd, hd.rect, &a, err) != 0) return -1;
    int rc = 0;
    for (int g = 0; g < 6 && rc == 0; g++) {
        layer_grid grid;
        if (layer_grid_init(&grid, p, layer, g, err) != 0) {
            rc = -1;
            break;
        }
        brush_dab fd = on_face(base, p, layer, g, grid.extent);
        if (grid_rect_empty(fd.rect)) continue;
        flow_rows rows = {&a, &hd, &fd};
        rc = edit_rows_apply(e, &grid, fd.rect, flow_row, NULL, &rows, err);
    }
    brush_dab_area_free(&a);
    return rc;
}

int planet_dab_apply(edit *e, const world_params *p, tile_layer layer, int face, const brush_dab *d,
                     og_error *err) {
    brush_dab base = *d;
    planet_dab_prepare(&base, p, layer, face);
    if (d->radius * d->spacing / p->radius > PLANET_DAB_MAX_ANGLE)
        return og_error_set(err,
                            "radius: %g m is more than 1/16 of this planet's circumference; a "
                            "dab may reach at most %g m",
                            d->radius * d->spacing, PLANET_DAB_MAX_ANGLE * p->radius);
    if (cap_angle(&base) > 2.0 * PLANET_DAB_MAX_ANGLE)
        return og_error_set(err,
                            "ramp: from end to end and its width it reaches %g m from its middle; "
                            "on this planet a ramp may reach at most %g m",
                            cap_angle(&base) * p->radius, 2.0 * PLANET_DAB_MAX_ANGLE * p->radius);
    if (layer != TILE_LAYER_MATERIAL &&
        (d->brush->tool == BRUSH_THERMAL || d->brush->tool == BRUSH_HYDRAULIC))
        return flow_apply(e, p, layer, &base, err);
    brush_dab_job *jobs[6] = {0};
    int rc = 0;
    for (int g = 0; g < 6 && rc == 0; g++) {
        layer_grid grid;
        if (layer_grid_init(&grid, p, layer, g, err) != 0) {
            rc = -1;
            break;
        }
        brush_dab fd = on_face(&base, p, layer, g, grid.extent); // centre in g's samples
        if (grid_rect_empty(fd.rect)) continue;
        rc = brush_dab_begin(e, &grid, &fd, &jobs[g], err);
    }
    // Every face read before any is written.
    for (int g = 0; g < 6; g++)
        if (rc == 0)
            rc = brush_dab_finish(jobs[g], err);
        else
            brush_dab_discard(jobs[g]);
    return rc;
}
