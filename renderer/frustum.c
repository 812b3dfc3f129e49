// Frustum plane extraction (Gribb-Hartmann) and the box-against-planes test used to
// cull terrain patches before drawing.
#include "renderer/frustum.h"

#include <math.h>

void frustum_from_matrix(frustum *f, const float m[16]) {
    // Row i of the column-major matrix is m[i], m[4 + i], m[8 + i], m[12 + i].
    double row[4][4];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            row[i][j] = m[j * 4 + i];
    // Plane = row3 + sign * row[axis]; z uses 0 <= z <= w, so near = row3 - row2 (the
    // reversed-Z near plane is at z = w) and far = row2 (z >= 0).
    static const int axis[6] = {0, 0, 1, 1, 2, 2};
    static const double w3[6] = {1, 1, 1, 1, 1, 0}, s[6] = {1, -1, 1, -1, -1, 1};
    for (int p = 0; p < 6; p++) {
        double q[4];
        for (int j = 0; j < 4; j++)
            q[j] = w3[p] * row[3][j] + s[p] * row[axis[p]][j];
        double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        // A degenerate plane (the infinite far plane: z_clip = near everywhere) culls
        // nothing.
        if (!(len > 1e-12)) {
            q[0] = q[1] = q[2] = 0;
            q[3] = len = 1;
        }
        for (int j = 0; j < 4; j++)
            f->planes[p][j] = (float)(q[j] / len);
    }
}

int frustum_test_aabb(const frustum *f, const float min[3], const float max[3]) {
    for (int p = 0; p < 6; p++) {
        const float *q = f->planes[p];
        // The box corner furthest along the plane normal: if even it is outside, all are.
        double d = q[3];
        for (int i = 0; i < 3; i++)
            d += (double)q[i] * (q[i] >= 0 ? max[i] : min[i]);
        if (d < 0) return 0;
    }
    return 1;
}
