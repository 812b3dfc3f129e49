#include "editor/layers/paint_blend.h"

#include <math.h>

static float coverage(const uint8_t *l) {
    int sum = 0;
    for (int c = 0; c < TILE_MATERIALS; c++)
        sum += l[c];
    return (float)sum / 255.0f;
}

void paint_blend_sample(float *acc, float weight, const uint8_t *layer) {
    if (!(weight > 0.0f)) return;
    float s = coverage(layer);
    if (s <= 0.0f) return;
    float keep = 1.0f - weight * s;
    for (int c = 0; c < TILE_MATERIALS; c++)
        acc[c] = acc[c] * keep + weight * (float)layer[c];
}

// Rounds want (non-negative) to integers summing to total by largest remainder.
static void round_to(const double *want, int total, uint8_t *out) {
    int sum = 0;
    double frac[TILE_MATERIALS];
    int v[TILE_MATERIALS];
    for (int c = 0; c < TILE_MATERIALS; c++) {
        v[c] = (int)floor(want[c]);
        if (v[c] < 0) v[c] = 0;
        frac[c] = want[c] - v[c];
        sum += v[c];
    }
    while (sum > total) { // only from float error: take from the smallest remainders
        int worst = -1;
        for (int c = 0; c < TILE_MATERIALS; c++)
            if (v[c] > 0 && (worst < 0 || frac[c] < frac[worst])) worst = c;
        v[worst]--;
        frac[worst] += 1.0;
        sum--;
    }
    while (sum < total) {
        int best = 0;
        for (int c = 1; c < TILE_MATERIALS; c++)
            if (frac[c] > frac[best]) best = c;
        v[best]++;
        frac[best] = -1.0;
        sum++;
    }
    for (int c = 0; c < TILE_MATERIALS; c++)
        out[c] = (uint8_t)(v[c] > 255 ? 255 : v[c]);
}

void paint_blend_round(const float *acc, uint8_t *out) {
    double sum = 0.0, want[TILE_MATERIALS];
    for (int c = 0; c < TILE_MATERIALS; c++)
        sum += acc[c] > 0.0f ? acc[c] : 0.0f;
    for (int c = 0; c < TILE_MATERIALS; c++)
        want[c] = sum > 0.0 ? (acc[c] > 0.0f ? acc[c] : 0.0f) * 255.0 / sum : (c == 0 ? 255 : 0);
    round_to(want, 255, out);
}

void paint_blend_solve(const float *below, float weight, const float *target,
                       const uint8_t *current, uint8_t *out) {
    if (!(weight > 0.0f)) {
        for (int c = 0; c < TILE_MATERIALS; c++)
            out[c] = current[c];
        return;
    }
    // shown = B (1 - k) + w L with k = w s: the least k keeping w L = target - B (1 - k)
    // non-negative is 1 - min(target / B) over B's channels.
    double bs = 0.0, ts = 0.0;
    for (int c = 0; c < TILE_MATERIALS; c++) {
        bs += below[c] > 0.0f ? below[c] : 0.0f;
        ts += target[c] > 0.0f ? target[c] : 0.0f;
    }
    double keep = 1.0;
    for (int c = 0; c < TILE_MATERIALS; c++) {
        double b = below[c] > 0.0f ? below[c] / bs : 0.0,
               t = target[c] > 0.0f ? target[c] / ts : 0.0;
        if (b > 0.0 && t / b < keep) keep = t / b;
    }
    if (bs <= 0.0) keep = 0.0;
    if (keep < 1.0 - weight) keep = 1.0 - weight; // coverage at most 1
    double k = 1.0 - keep, want[TILE_MATERIALS], sum = 0.0;
    for (int c = 0; c < TILE_MATERIALS; c++) {
        double b = below[c] > 0.0f ? below[c] / bs : 0.0,
               t = target[c] > 0.0f ? target[c] / ts : 0.0;
        double v = (t - b * keep) / weight * 255.0;
        want[c] = v > 0.0 ? v : 0.0;
        sum += want[c];
    }
    // Coverage k / w: the weights sum to 255 k / w.
    int total = (int)lround(255.0 * k / weight);
    if (total > 255) total = 255;
    if (sum > 0.0)
        for (int c = 0; c < TILE_MATERIALS; c++)
            want[c] *= 255.0 * k / weight / sum;
    round_to(want, total, out);
}

void paint_blend_merge(const uint8_t *lower, float wl, const uint8_t *upper, float wu,
                       uint8_t *out) {
    float su = wu > 0.0f ? coverage(upper) : 0.0f;
    double want[TILE_MATERIALS], sum = 0.0;
    for (int c = 0; c < TILE_MATERIALS; c++) {
        want[c] = (wl > 0.0f ? (double)wl * lower[c] : 0.0) * (1.0 - (double)wu * su) +
                  (wu > 0.0f ? (double)wu * upper[c] : 0.0);
        sum += want[c];
    }
    int total = (int)lround(sum);
    if (total > 255) total = 255;
    round_to(want, total, out);
}
