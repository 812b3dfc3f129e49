// Where faces meet: the two (or, at a cube corner, three) faces' own samples give a vertex
// on their shared edge different heights, a step of up to a cell's relief that showed as
// a line along the edge, and a camera standing on one face's side could stand under the
// other's ground. Every face containing a vertex on an edge gives it the mean of their
// heights, the same from each side; the ring of vertices past a face's edge (for the
// normals) takes the neighbouring face's ground, so the lighting runs on across the edge.
#include "renderer/planet_internal.h"

#include "io/tile_cache.h"

// A level's samples around (u, v) (sample coordinates on the face, clamped) from their
// tiles. 1 when read, 0 while a tile is pending.
static int face_bilinear(planet_renderer *r, int face, int level, double u, double v, float *out) {
    const int64_t m = level_samples(r, level);
    u = fmin(fmax(u, 0.0), (double)(m - 1)), v = fmin(fmax(v, 0.0), (double)(m - 1));
    const int64_t i0 = (int64_t)u, j0 = (int64_t)v;
    const int64_t i1 = i0 + 1 < m ? i0 + 1 : i0, j1 = j0 + 1 < m ? j0 + 1 : j0;
    const int64_t is[4] = {i0, i1, i0, i1}, js[4] = {j0, j0, j1, j1};
    float h[4];
    tile_cache *cache = world_cache(r->world);
    for (int k = 0; k < 4; k++) {
        tile_key key = {TILE_LAYER_COARSE, face, level, (int32_t)(is[k] / TILE_SIZE),
                        (int32_t)(js[k] / TILE_SIZE)};
        tile_view view;
        if (tile_cache_request(cache, key, &view) != TILE_READY) {
            if (view.data) tile_cache_release(cache, &view);
            return 0;
        }
        h[k] = ((const float *)view.data)[(js[k] % TILE_SIZE) * TILE_SIZE + is[k] % TILE_SIZE];
        tile_cache_release(cache, &view);
    }
    const double fu = u - (double)i0, fv = v - (double)j0;
    const double top = h[0] + (h[1] - h[0]) * fu, bottom = h[2] + (h[3] - h[2]) * fu;
    *out = (float)(top + (bottom - top) * fv);
    return 1;
}

int planet_face_height(planet_renderer *r, int face, int level, double u, double v, float *out) {
    return face_bilinear(r, face, level, u, v, out);
}

int planet_edge_height(planet_renderer *r, int level, const double dir[3], float *out) {
    const double n = (double)r->face_samples, cell = ldexp(1.0, level);
    double sum = 0;
    int faces = 0;
    for (int f = 0; f < 6; f++) {
        double s, t;
        if (!world_grid_face_coords_on(f, dir, &s, &t)) continue;
        if (fmax(fabs(s), fabs(t)) > 1.0 + 1e-9) continue;
        // Sample coordinates: level-0 cell c sits at c / 2^level - 1/2 level samples.
        float h;
        if (!face_bilinear(r, f, level, (s + 1.0) * 0.5 * n / cell - 0.5,
                           (t + 1.0) * 0.5 * n / cell - 0.5, &h))
            return 0;
        sum += h, faces++;
    }
    if (faces == 0) { // past a corner by float rounding: the face it points at
        int f;
        double s, t;
        world_grid_direction_face(dir, &f, &s, &t);
        float h;
        if (!face_bilinear(r, f, level, (s + 1.0) * 0.5 * n / cell - 0.5,
                           (t + 1.0) * 0.5 * n / cell - 0.5, &h))
            return 0;
        sum = h, faces = 1;
    }
    *out = (float)(sum / faces);
    return 1;
}

// A vertex on a face's edge took its normal from central differences along its own
// face's grid, whose lines past the edge run askew to the neighbour's (more so toward a
// corner): the two faces gave the vertex different normals and the light stepped along
// the edge. Here the differences are taken along a frame of the direction alone (east
// and north), the same from every face, a level's cell each way.
int planet_edge_normal(planet_renderer *r, int level, const double dir[3], double normal[3]) {
    const double step = ldexp(r->cell_arc, level) / r->params.radius; // radians
    double east[3] = {dir[2], 0.0, -dir[0]};                          // y up: y x dir
    double len = sqrt(dot3(east, east));
    if (len < 1e-9) east[0] = 1.0, east[2] = 0.0, len = 1.0; // at a pole (no edge is)
    for (int a = 0; a < 3; a++)
        east[a] /= len;
    const double north[3] = {dir[1] * east[2] - dir[2] * east[1],
                             dir[2] * east[0] - dir[0] * east[2],
                             dir[0] * east[1] - dir[1] * east[0]};
    double p[4][3];
    for (int k = 0; k < 4; k++) {
        const double *axis = k < 2 ? east : north, sign = k % 2 ? -1.0 : 1.0;
        double d[3];
        for (int a = 0; a < 3; a++)
            d[a] = dir[a] + sign * step * axis[a];
        const double dl = sqrt(dot3(d, d));
        float h;
        if (!planet_edge_height(r, level, d, &h)) return 0;
        for (int a = 0; a < 3; a++)
            p[k][a] = d[a] / dl * (r->params.radius + h);
    }
    double du[3], dv[3];
    for (int a = 0; a < 3; a++)
        du[a] = p[0][a] - p[1][a], dv[a] = p[2][a] - p[3][a];
    double n[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2],
                   du[0] * dv[1] - du[1] * dv[0]};
    const double nl = sqrt(dot3(n, n)), sign = dot3(n, dir) < 0 ? -1.0 : 1.0;
    for (int a = 0; a < 3; a++)
        normal[a] = nl > 0 ? sign * n[a] / nl : dir[a];
    return 1;
}
