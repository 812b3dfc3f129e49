#include "editor/params/world_grid.h"

#include <math.h>

int64_t world_grid_face_samples(const world_params *p) {
    double cells = (M_PI / 2.0) * p->radius / p->spacing;
    int64_t tiles = (int64_t)ceil(cells / TILE_SIZE);
    if (tiles < 1) tiles = 1;
    return tiles * TILE_SIZE;
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

void world_grid_direction_face(const double dir[3], int *face, double *s, double *t) {
    const double x = dir[0], y = dir[1], z = dir[2];
    const double ax = fabs(x), ay = fabs(y), az = fabs(z);
    double a, b; // the inverse of world_grid_face_direction_warped's axes
    if (ax >= ay && ax >= az) {
        *face = x >= 0 ? 0 : 1;
        a = (x >= 0 ? -z : z) / ax, b = y / ax;
    } else if (ay >= az) {
        *face = y >= 0 ? 2 : 3;
        a = x / ay, b = (y >= 0 ? -z : z) / ay;
    } else {
        *face = z >= 0 ? 4 : 5;
        a = (z >= 0 ? x : -x) / az, b = y / az;
    }
    *s = atan(a) * (4.0 / M_PI);
    *t = atan(b) * (4.0 / M_PI);
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
