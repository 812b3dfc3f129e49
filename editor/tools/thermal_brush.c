// Thermal erosion at the brush's scale (thermal_brush.h).
#include "editor/tools/thermal_brush.h"

#include "io/progress.h"

#include <math.h>
#include <stdlib.h>

int thermal_brush_block(double radius_samples) {
    double b = floor(radius_samples / 8.0);
    return b < 1 ? 1 : b > 32 ? 32 : (int)b;
}

static float weight_of(float w) {
    return w > 0.0f ? (w < 1.0f ? w : 1.0f) : 0.0f; // NaN and negatives count as 0
}

// The block means of heights and weights (a zero weight counts as 0).
static void block_means(const erosion_grid *g, int block, int cw, int ch, float *h, float *w) {
    for (int J = 0; J < ch; J++)
        for (int I = 0; I < cw; I++) {
            double sh = 0, sw = 0;
            int n = 0;
            for (int j = J * block; j < (J + 1) * block && j < g->height; j++)
                for (int i = I * block; i < (I + 1) * block && i < g->width; i++, n++) {
                    sh += g->heights[(size_t)j * g->width + i];
                    sw += weight_of(g->weight[(size_t)j * g->width + i]);
                }
            h[(size_t)J * cw + I] = (float)(sh / n);
            w[(size_t)J * cw + I] = (float)(sw / n);
        }
}

// How much of block I's change sample i takes: a tent over the block's centre at
// (I + 0.5) x block - 0.5, one block wide each side (bilinear interpolation's weights).
static float tent(int i, int I, int block) {
    float u = fabsf(((float)i + 0.5f) / (float)block - 0.5f - (float)I);
    return u < 1.0f ? 1.0f - u : 0.0f;
}

// Spreads each block's change over the samples with weight > 0 around it, by the tent
// (so the result is smooth, as bilinear interpolation), normalised so that the block's
// whole change, block^2 samples' worth, lands: the height sum is kept.
static int spread_change(erosion_grid *g, int block, int cw, int ch, const float *delta) {
    float *add = calloc((size_t)g->width * g->height, sizeof *add);
    if (!add) return -1;
    for (int J = 0; J < ch; J++)
        for (int I = 0; I < cw; I++) {
            float d = delta[(size_t)J * cw + I];
            if (d == 0.0f) continue;
            int i0 = (I - 1) * block > 0 ? (I - 1) * block : 0,
                j0 = (J - 1) * block > 0 ? (J - 1) * block : 0;
            int i1 = (I + 2) * block < g->width ? (I + 2) * block : g->width;
            int j1 = (J + 2) * block < g->height ? (J + 2) * block : g->height;
            double sum = 0;
            for (int pass = 0; pass < 2; pass++) {
                float share = pass ? (float)((double)d * block * block / sum) : 0.0f;
                for (int j = j0; j < j1; j++) {
                    float tj = tent(j, J, block);
                    for (int i = i0; i < i1; i++) {
                        size_t k = (size_t)j * g->width + i;
                        float t = tj * tent(i, I, block);
                        if (!(t > 0.0f) || !(weight_of(g->weight[k]) > 0.0f)) continue;
                        if (pass)
                            add[k] += share * t;
                        else
                            sum += t;
                    }
                }
                if (!(sum > 0)) break; // no sample there may change (the block had none)
            }
        }
    for (size_t k = 0; k < (size_t)g->width * g->height; k++)
        g->heights[k] += add[k];
    free(add);
    return 0;
}

// Narrows the progress record's current part to [from, to) of it (og_progress_enter
// takes equal steps; the coarse pass is about 1 / block^2 of the work).
static og_progress_part progress_part(og_progress *p, double from, double to) {
    og_progress_part outer = {p ? p->base : 0, p ? p->width : 0};
    if (p) p->base = outer.base + from * outer.width, p->width = (to - from) * outer.width;
    return outer;
}

void thermal_brush_erode(erosion_grid *g, const thermal_params *p, int block) {
    if (erosion_grid_validate(g, NULL) || erosion_thermal_validate(p, NULL)) return;
    int cw = (g->width + block - 1) / block, ch = (g->height + block - 1) / block;
    if (block > 1 && cw >= 3 && ch >= 3) {
        size_t n = (size_t)cw * ch;
        float *h = malloc(3 * n * sizeof *h);
        if (!h) return;
        float *w = h + n, *before = h + 2 * n;
        block_means(g, block, cw, ch, h, w);
        for (size_t k = 0; k < n; k++)
            before[k] = h[k];
        erosion_grid coarse = {h, w, cw, ch, g->spacing * (float)block, g->progress};
        const double share = 1.0 / (1.0 + (double)block * block);
        og_progress_part outer = progress_part(g->progress, 0, share);
        erosion_thermal(&coarse, p);
        og_progress_leave(g->progress, outer);
        if (og_progress_cancelled(g->progress)) {
            free(h);
            return;
        }
        for (size_t k = 0; k < n; k++)
            before[k] = h[k] - before[k];
        int rc = spread_change(g, block, cw, ch, before);
        free(h);
        if (rc != 0) return;
        outer = progress_part(g->progress, share, 1);
        erosion_thermal(g, p);
        og_progress_leave(g->progress, outer);
        return;
    }
    erosion_thermal(g, p);
}
