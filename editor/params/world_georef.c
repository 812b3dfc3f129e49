#include "editor/params/world_georef.h"

int world_georef_present(const world_params *p) {
    const double *g = p->geo_transform;
    return g[1] * g[5] - g[2] * g[4] != 0;
}

void world_georef_region(const world_params *p, int ratio, int64_t x0, int64_t z0, double gt[6]) {
    const double s = p->spacing;
    const double local[6] = {-s / 2, s, 0, s / 2, 0, -s};
    const double *c = world_georef_present(p) ? p->geo_transform : local;
    const double r = ratio > 0 ? ratio : 1;
    // The first sample's centre in coarse samples, and there in the target coordinates.
    const double u = (double)x0 / r + 0.5, v = (double)z0 / r + 0.5;
    const double cx = c[0] + u * c[1] + v * c[2], cy = c[3] + u * c[4] + v * c[5];
    gt[1] = c[1] / r, gt[2] = c[2] / r, gt[4] = c[4] / r, gt[5] = c[5] / r;
    gt[0] = cx - 0.5 * (gt[1] + gt[2]);
    gt[3] = cy - 0.5 * (gt[4] + gt[5]);
}
