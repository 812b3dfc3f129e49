#include "editor/tools/volume_shapes.h"

#include "editor/tools/brush.h"
#include "editor/tools/volume_brush.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static brush shape_brush(brush_tool tool, double radius) {
    brush b;
    brush_defaults(&b, tool);
    b.radius = radius;
    b.strength = 1;
    b.falloff = FALLOFF_CONSTANT;
    return b;
}

static int positive(const char *name, double v, og_error *err) {
    if (!(v > 0) || !isfinite(v))
        return og_error_set(err, "%s: expected a positive number of metres, got %g", name, v);
    return 0;
}

// Points every half radius or closer along the curve: the capsules between them follow it.
static int curve_pieces(double length, double radius) {
    int n = (int)ceil(length / fmax(radius * 0.5, 1e-9));
    return n < 2 ? 2 : n > 4096 ? 4096 : n;
}

static int finish(volume_stroke *s, int rc, og_error *err) {
    if (rc != 0) {
        volume_stroke_cancel(s);
        return -1;
    }
    return volume_stroke_end(s, err);
}

int volume_arch(world *w, const double a[3], const double b[3], double rise, double thickness,
                og_error *err) {
    if (!isfinite(rise))
        return og_error_set(err, "rise: expected a finite number of metres, got %g", rise);
    if (positive("thickness", thickness, err) != 0) return -1;
    brush br = shape_brush(BRUSH_FILL, thickness / 2);
    volume_stroke *s = volume_stroke_begin_labelled(w, &br, "arch", err);
    if (!s) return -1;
    double span = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[2] - a[2]) * (b[2] - a[2]));
    int n = curve_pieces(span + 2 * fabs(rise), thickness / 2);
    int rc = 0;
    for (int i = 0; i <= n && rc == 0; i++) {
        double t = (double)i / n;
        double p[3] = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]) + 4 * rise * t * (1 - t),
                       a[2] + t * (b[2] - a[2])};
        rc = volume_stroke_to(s, p, 1.0, err);
    }
    return finish(s, rc, err);
}

int volume_tunnel(world *w, const double (*points)[3], const double *radius, size_t count,
                  og_error *err) {
    if (count < 2) return og_error_set(err, "tunnel: needs at least 2 points");
    double widest = 0;
    for (size_t i = 0; i < count; i++) {
        char name[32];
        snprintf(name, sizeof name, "radius %zu", i + 1);
        if (positive(name, radius[i], err) != 0) return -1;
        widest = fmax(widest, radius[i]);
    }
    brush br = shape_brush(BRUSH_CARVE, widest);
    volume_stroke *s = volume_stroke_begin_labelled(w, &br, "tunnel", err);
    if (!s) return -1;
    int rc = 0;
    for (size_t i = 0; i < count && rc == 0; i++) // the radius profile rides on pressure
        rc = volume_stroke_to(s, points[i], radius[i] / widest, err);
    return finish(s, rc, err);
}

int volume_spire(world *w, const double base[3], double height, double radius, double taper,
                 double cap, og_error *err) {
    if (positive("height", height, err) != 0 || positive("radius", radius, err) != 0) return -1;
    if (!(taper >= 0 && taper <= 1))
        return og_error_set(err, "taper: expected 0 to 1 (top radius / foot radius), got %g",
                            taper);
    if (!(cap >= 0) || !isfinite(cap))
        return og_error_set(err, "cap: expected 0 or a radius in metres, got %g", cap);
    double widest = fmax(radius, cap);
    brush br = shape_brush(BRUSH_FILL, widest);
    volume_stroke *s = volume_stroke_begin_labelled(w, &br, cap > 0 ? "hoodoo" : "spire", err);
    if (!s) return -1;
    double top[3] = {base[0], base[1] + height, base[2]};
    // A round cone from the foot to the top; the capstone sits on it.
    int rc = volume_stroke_to(s, base, radius / widest, err);
    if (rc == 0) rc = volume_stroke_to(s, top, fmax(radius * taper, 1e-3) / widest, err);
    if (rc == 0 && cap > 0) {
        // A flat capstone: spokes of rock, cap x 0.4 thick, out to cap from the middle.
        double thick = cap * 0.4, mid[3] = {top[0], top[1] + thick * 0.5, top[2]};
        for (int k = 0; k < 6 && rc == 0; k++) {
            double a = k * M_PI / 6, reach = cap - thick;
            double p0[3] = {mid[0] - reach * cos(a), mid[1], mid[2] - reach * sin(a)};
            double p1[3] = {mid[0] + reach * cos(a), mid[1], mid[2] + reach * sin(a)};
            rc = volume_stroke_move(s, p0, thick / widest, err);
            if (rc == 0) rc = volume_stroke_to(s, p1, thick / widest, err);
        }
    }
    return finish(s, rc, err);
}

static int ground(world *w, double x, double z, double *h, og_error *err) {
    return world_sample(w, 0, x, z, h, err);
}

int volume_overhang(world *w, double x0, double z0, double x1, double z1, double distance,
                    double thickness, og_error *err) {
    if (positive("distance", distance, err) != 0 || positive("thickness", thickness, err) != 0)
        return -1;
    double dx = x1 - x0, dz = z1 - z0, len = sqrt(dx * dx + dz * dz);
    if (!(len > 0)) return og_error_set(err, "overhang: the edge's two ends are the same point");
    // Outward: the side of the edge where the ground is lower.
    double nx = -dz / len, nz = dx / len, mx = (x0 + x1) / 2, mz = (z0 + z1) / 2;
    double probe = fmax(thickness, distance / 2), left, right;
    if (ground(w, mx + nx * probe, mz + nz * probe, &left, err) != 0 ||
        ground(w, mx - nx * probe, mz - nz * probe, &right, err) != 0)
        return -1;
    if (left > right) nx = -nx, nz = -nz;
    brush br = shape_brush(BRUSH_FILL, thickness / 2);
    volume_stroke *s = volume_stroke_begin_labelled(w, &br, "overhang", err);
    if (!s) return -1;
    int n = curve_pieces(len, thickness / 2), rc = 0;
    for (int i = 0; i <= n && rc == 0; i++) {
        double t = (double)i / n, ex = x0 + t * dx, ez = z0 + t * dz, h;
        rc = ground(w, ex, ez, &h, err);
        // The shelf's top meets the ground at the edge (slightly inside it, so no seam).
        double y = h - thickness / 2;
        double from[3] = {ex - nx * thickness / 2, y, ez - nz * thickness / 2};
        double to[3] = {ex + nx * distance, y, ez + nz * distance};
        if (rc == 0) rc = volume_stroke_move(s, from, 1.0, err);
        if (rc == 0) rc = volume_stroke_to(s, to, 1.0, err);
    }
    return finish(s, rc, err);
}
