#include "editor/params/world_grid.h"

#include <math.h>

int64_t world_grid_face_samples(const world_params *p) {
    double cells = (M_PI / 2.0) * p->radius / p->spacing;
    int64_t tiles = (int64_t)ceil(cells / TILE_SIZE);
    if (tiles < 1) tiles = 1;
    return tiles * TILE_SIZE;
}

double world_grid_sample_metres(const world_params *p) {
    if (p->kind != WORLD_PLANET) return p->spacing;
    return (M_PI / 2.0) * p->radius / (double)world_grid_face_samples(p);
}

void world_grid_face_direction(int face, double s, double t, double dir[3]) {
    // Tangent warp: equal steps in s map to equal angles, so cells near face
    // corners are not squeezed as in the plain gnomonic projection.
    world_grid_face_direction_warped(face, tan(s * (M_PI / 4.0)), tan(t * (M_PI / 4.0)), dir);
}

void world_grid_face_direction_warped(int face, double a, double b, double dir[3]) {
    double v[3];
    switch (face) {
    case 0:
        v[0] = 1, v[1] = b, v[2] = -a;
        break;
    case 1:
        v[0] = -1, v[1] = b, v[2] = a;
        break;
    case 2:
        v[0] = a, v[1] = 1, v[2] = -b;
        break;
    case 3:
        v[0] = a, v[1] = -1, v[2] = b;
        break;
    case 4:
        v[0] = a, v[1] = b, v[2] = 1;
        break;
    default:
        v[0] = -a, v[1] = b, v[2] = -1;
        break;
    }
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        dir[k] = v[k] / len;
}

int world_grid_face_coords_on(int face, const double dir[3], double *s, double *t) {
    static const double axes[6][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                      {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    const double *ax = axes[face < 0 || face > 5 ? 0 : face];
    const double along = dir[0] * ax[0] + dir[1] * ax[1] + dir[2] * ax[2];
    if (!(along > 1e-12)) return 0;
    double a, b; // the inverse of world_grid_face_direction_warped's axes
    switch (face) {
    case 0:
        a = -dir[2] / along, b = dir[1] / along;
        break;
    case 1:
        a = dir[2] / along, b = dir[1] / along;
        break;
    case 2:
        a = dir[0] / along, b = -dir[2] / along;
        break;
    case 3:
        a = dir[0] / along, b = dir[2] / along;
        break;
    case 4:
        a = dir[0] / along, b = dir[1] / along;
        break;
    default:
        a = -dir[0] / along, b = dir[1] / along;
        break;
    }
    *s = atan(a) * (4.0 / M_PI);
    *t = atan(b) * (4.0 / M_PI);
    return 1;
}

void world_grid_direction_face(const double dir[3], int *face, double *s, double *t) {
    const double ax = fabs(dir[0]), ay = fabs(dir[1]), az = fabs(dir[2]);
    if (ax >= ay && ax >= az)
        *face = dir[0] >= 0 ? 0 : 1;
    else if (ay >= az)
        *face = dir[1] >= 0 ? 2 : 3;
    else
        *face = dir[2] >= 0 ? 4 : 5;
    if (!world_grid_face_coords_on(*face, dir, s, t)) *s = *t = 0; // a zero vector
}

double world_grid_face_coord(const world_params *p, int level, int64_t i) {
    double n = (double)world_grid_face_samples(p);
    double cell = (double)((int64_t)1 << level);
    return ((double)i + 0.5) * cell / n * 2.0 - 1.0;
}

static int64_t min64(int64_t a, int64_t b) {
    return a < b ? a : b;
}
static int64_t max64(int64_t a, int64_t b) {
    return a > b ? a : b;
}

grid_rect grid_rect_intersect(grid_rect a, grid_rect b) {
    return (grid_rect){max64(a.x0, b.x0), max64(a.z0, b.z0), min64(a.x1, b.x1), min64(a.z1, b.z1)};
}

grid_rect grid_rect_union(grid_rect a, grid_rect b) {
    return (grid_rect){min64(a.x0, b.x0), min64(a.z0, b.z0), max64(a.x1, b.x1), max64(a.z1, b.z1)};
}
