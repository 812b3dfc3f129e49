// View-frustum planes for culling terrain patches on the CPU, extracted from the
// camera-relative view-projection matrix (so boxes are tested camera-relative too).
#ifndef OROGEN_RENDERER_FRUSTUM_H
#define OROGEN_RENDERER_FRUSTUM_H

// ax + by + cz + d >= 0 inside; (a, b, c) unit length. Order: left, right, bottom, top,
// near, far. With the reversed-Z infinite projection the far plane is degenerate and is
// stored as (0, 0, 0, 1), which always passes.
typedef struct frustum {
    float planes[6][4];
} frustum;

// Gribb-Hartmann extraction for clip space -w <= x, y <= w, 0 <= z <= w.
void frustum_from_matrix(frustum *f, const float view_proj[16]);
// 0 = entirely outside, 1 = intersects or inside (conservative: a box outside the
// frustum but not outside any single plane reports 1).
int frustum_test_aabb(const frustum *f, const float min[3], const float max[3]);

#endif
