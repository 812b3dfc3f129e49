#include "renderer/planet_camera.h"

#include "editor/params/world_grid.h"

#include <math.h>

static const double DEG = 3.14159265358979323846 / 180.0;

static void normalize(double v[3]) {
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len > 0)
        for (int k = 0; k < 3; k++)
            v[k] /= len;
}

static void cross(const double a[3], const double b[3], double out[3]) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

void planet_local_frame(const double pos[3], double east[3], double north[3], double up[3]) {
    for (int k = 0; k < 3; k++)
        up[k] = pos[k];
    normalize(up);
    if (!(up[0] * up[0] + up[1] * up[1] + up[2] * up[2] > 0.5)) up[0] = 0, up[1] = 1, up[2] = 0;
    // North: the +Y axis projected on the tangent plane; -Z at the poles.
    double axis[3] = {0, 1, 0};
    if (fabs(up[1]) > 0.999999) axis[0] = 0, axis[1] = 0, axis[2] = up[1] > 0 ? -1 : 1;
    double d = axis[0] * up[0] + axis[1] * up[1] + axis[2] * up[2];
    for (int k = 0; k < 3; k++)
        north[k] = axis[k] - d * up[k];
    normalize(north);
    cross(north, up, east);
}

void planet_camera_basis(const camera *c, double forward[3], double right[3], double up[3]) {
    double e[3], n[3], u[3];
    planet_local_frame(c->pos, e, n, u);
    double pitch = c->pitch;
    if (!(pitch > -CAMERA_PITCH_LIMIT)) pitch = -CAMERA_PITCH_LIMIT;
    if (pitch > CAMERA_PITCH_LIMIT) pitch = CAMERA_PITCH_LIMIT;
    double y = c->yaw * DEG, p = pitch * DEG;
    for (int k = 0; k < 3; k++) {
        double level = cos(y) * n[k] + sin(y) * e[k];
        forward[k] = cos(p) * level + sin(p) * u[k];
        right[k] = cos(y) * e[k] - sin(y) * n[k];
    }
    cross(right, forward, up);
}

void planet_camera_view_projection(const camera *c, double aspect, float m[16]) {
    double f[3], r[3], u[3];
    planet_camera_basis(c, f, r, u);
    camera_basis_view_projection(c, r, u, f, aspect, m);
}

void planet_camera_ray(const camera *c, double aspect, double sx, double sy, double dir[3]) {
    double f[3], r[3], u[3];
    planet_camera_basis(c, f, r, u);
    camera_basis_ray(c, r, u, f, aspect, sx, sy, dir);
}

void planet_position(double lat, double lon, double distance, double pos[3]) {
    double la = lat * DEG, lo = lon * DEG;
    pos[0] = distance * cos(la) * sin(lo);
    pos[1] = distance * sin(la);
    pos[2] = distance * cos(la) * cos(lo);
}

void planet_lat_lon(const double pos[3], double *lat, double *lon) {
    double horizontal = sqrt(pos[0] * pos[0] + pos[2] * pos[2]);
    *lat = atan2(pos[1], horizontal) / DEG;
    *lon = horizontal > 0 ? atan2(pos[0], pos[2]) / DEG : 0.0;
}

// Level-0 mesh vertex (corner e, f of the cells, 0..n) of a face: the bilinear height
// between the samples around it, and on the face's edge the mean of every face there
// (renderer/planet_face_edges.c: the same from each side).
static int corner_height(world *w, int face, double e, double f, double *height, og_error *err) {
    const world_params *p = world_get_params(w);
    const double n = (double)world_grid_face_samples(p), sp = world_grid_sample_metres(p),
                 last = (n - 1.0) * sp;
    if (e > 0 && e < n && f > 0 && f < n)
        return world_sample(w, face, (e - 0.5) * sp, (f - 0.5) * sp, height, err);
    double dir[3], sum = 0;
    int faces = 0;
    world_grid_face_direction(face, e / n * 2.0 - 1.0, f / n * 2.0 - 1.0, dir);
    for (int g = 0; g < 6; g++) {
        double s, t, h;
        if (!world_grid_face_coords_on(g, dir, &s, &t) || fmax(fabs(s), fabs(t)) > 1.0 + 1e-9)
            continue;
        const double x = (s + 1.0) * 0.5 * n - 0.5, z = (t + 1.0) * 0.5 * n - 0.5;
        if (world_sample(w, g, fmin(fmax(x * sp, 0.0), last), fmin(fmax(z * sp, 0.0), last), &h,
                         err) != 0)
            return -1;
        sum += h, faces++;
    }
    if (faces == 0)
        return world_sample(w, face, fmin(fmax((e - 0.5) * sp, 0.0), last),
                            fmin(fmax((f - 0.5) * sp, 0.0), last), height, err);
    *height = sum / faces;
    return 0;
}

// The level-0 mesh's height at pos, its vertices raised to raise_to (the sea's surface
// is drawn so: each vertex under it raised to it, the triangles between them flat).
static int mesh_height(world *w, const double pos[3], double raise_to, double *height,
                       og_error *err) {
    const world_params *p = world_get_params(w);
    int face;
    double s, t;
    world_grid_direction_face(pos, &face, &s, &t);
    // The finest level's mesh (renderer/planet_uploads.c): vertices on the cells'
    // corners, each the bilinear height between the samples around it (sample i's centre
    // sits at face-local metres i x spacing, corner e at e - 1/2 samples), two triangles
    // a cell split along (e + 1, f) - (e, f + 1). Where the ground is rough the mesh and
    // the bilinear samples differ by metres: the camera and the brush stand on the mesh.
    const double n = (double)world_grid_face_samples(p);
    const double es = (s + 1.0) * 0.5 * n, et = (t + 1.0) * 0.5 * n;
    const double i = fmin(floor(es), n - 1.0), j = fmin(floor(et), n - 1.0);
    const double fu = es - i, fv = et - j;
    double corner[4]; // (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)
    for (int k = 0; k < 4; k++)
        if (corner_height(w, face, i + (k & 1), j + (k >> 1), &corner[k], err) != 0)
            return -1;
        else
            corner[k] = fmax(corner[k], raise_to);
    *height = fu + fv <= 1.0
                  ? corner[0] + (corner[1] - corner[0]) * fu + (corner[2] - corner[0]) * fv
                  : corner[3] + (corner[2] - corner[3]) * (1.0 - fu) +
                        (corner[1] - corner[3]) * (1.0 - fv);
    return 0;
}

int planet_ground_height(world *w, const double pos[3], double *height, og_error *err) {
    return mesh_height(w, pos, -INFINITY, height, err);
}

// Where a cell spans the coast its drawn surface lies above both the ground and the
// sea between its vertices: a camera 2 m over max(ground, sea) stood under it (in hilly
// coasts, metres under), so the surface is the mesh as drawn.
int planet_surface_height(world *w, const double pos[3], double *height, og_error *err) {
    return mesh_height(w, pos, world_params_ocean_height(world_get_params(w)), height, err);
}
