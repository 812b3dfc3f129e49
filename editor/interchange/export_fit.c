#include "editor/interchange/export_fit.h"

#include "editor/params/world_georef.h"

#include <math.h>
#include <stdlib.h>

int export_fit_largest(const int *sizes, int count, int64_t n) {
    int best = 0;
    for (int i = 0; i < count; i++)
        if (sizes[i] <= n && sizes[i] > best) best = sizes[i];
    return best;
}

int export_fit_nearest(const int *sizes, int count, int64_t samples, int tiles) {
    int best = sizes[0];
    int64_t best_miss = INT64_MAX;
    for (int i = 0; i < count; i++) {
        int64_t spans = (int64_t)tiles * (sizes[i] - 1) + 1;
        int64_t miss = llabs(spans - samples);
        if (miss < best_miss) best = sizes[i], best_miss = miss;
    }
    return best;
}

double export_fit_position(int64_t i, int64_t out_n, int64_t region_n) {
    if (out_n < 2 || i >= out_n - 1) return (double)(region_n - 1) * (i > 0);
    return (double)i * (double)(region_n - 1) / (double)(out_n - 1);
}

void export_fit_source(int64_t i0, int64_t i1, int64_t out_n, int64_t region_n, int64_t *s0,
                       int64_t *s1) {
    *s0 = (int64_t)floor(export_fit_position(i0, out_n, region_n));
    *s1 = (int64_t)floor(export_fit_position(i1 - 1, out_n, region_n)) + 2;
    if (*s1 > region_n) *s1 = region_n;
}

// Where output sample i falls: region sample *k and the weight t of the next one.
static void locate(int64_t i, int64_t out_n, int64_t region_n, int64_t *k, double *t) {
    double u = export_fit_position(i, out_n, region_n);
    *k = (int64_t)floor(u);
    *t = u - (double)*k;
    if (*k >= region_n - 1) *k = region_n - 1, *t = 0;
}

void export_fit_resample(const export_fit *f, const float *src, int64_t sw, int64_t sx0,
                         int64_t sz0, int64_t i0, int64_t j0, int64_t ow, int64_t oh, float *out) {
    int64_t *kx = malloc(sizeof *kx * (size_t)ow);
    double *tx = malloc(sizeof *tx * (size_t)ow);
    if (!kx || !tx) { // callers size src by export_fit_source: a failed malloc is a crash
        free(kx), free(tx);
        abort();
    }
    for (int64_t a = 0; a < ow; a++) {
        locate(i0 + a, f->out_w, f->region_w, &kx[a], &tx[a]);
        kx[a] -= sx0;
    }
    for (int64_t b = 0; b < oh; b++) {
        int64_t kz;
        double tz;
        locate(j0 + b, f->out_h, f->region_h, &kz, &tz);
        const float *r0 = src + (size_t)(kz - sz0) * (size_t)sw;
        const float *r1 = tz > 0 ? r0 + sw : r0;
        float *o = out + (size_t)b * (size_t)ow;
        for (int64_t a = 0; a < ow; a++) {
            const int64_t k = kx[a];
            const double t = tx[a];
            double top = t > 0 ? r0[k] * (1 - t) + r0[k + 1] * t : r0[k];
            double bottom = t > 0 ? r1[k] * (1 - t) + r1[k + 1] * t : r1[k];
            o[a] = tz > 0 ? (float)(top * (1 - tz) + bottom * tz) : (float)top;
        }
    }
    free(kx);
    free(tx);
}

static double step(int64_t region_n, int64_t out_n) {
    return out_n > 1 ? (double)(region_n - 1) / (double)(out_n - 1) : 1.0;
}

double export_fit_spacing_x(const export_fit *f, double spacing) {
    return spacing * step(f->region_w, f->out_w);
}

double export_fit_spacing_z(const export_fit *f, double spacing) {
    return spacing * step(f->region_h, f->out_h);
}

void export_fit_georef(const world_params *p, int ratio, const export_fit *f, int64_t i0,
                       int64_t j0, double gt[6]) {
    double c[6];
    world_georef_region(p, ratio, 0, 0, c);
    const double fx = step(f->region_w, f->out_w), fz = step(f->region_h, f->out_h);
    // The first output sample's centre, in the grid's samples and then in the target's.
    const double u = (double)f->region_x0 + export_fit_position(i0, f->out_w, f->region_w) + 0.5,
                 v = (double)f->region_z0 + export_fit_position(j0, f->out_h, f->region_h) + 0.5;
    const double cx = c[0] + u * c[1] + v * c[2], cy = c[3] + u * c[4] + v * c[5];
    gt[1] = c[1] * fx, gt[2] = c[2] * fz, gt[4] = c[4] * fx, gt[5] = c[5] * fz;
    gt[0] = cx - 0.5 * (gt[1] + gt[2]);
    gt[3] = cy - 0.5 * (gt[4] + gt[5]);
}
