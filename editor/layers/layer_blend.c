#include "editor/layers/layer_blend.h"

#include <math.h>

float layer_blend_sample(layer_blend blend, float weight, float below, float value) {
    if (isnan(value) || !(weight > 0.0f)) return below;
    float top;
    switch (blend) {
    case LAYER_BLEND_ADD:
        return weight >= 1.0f ? below + value : below + weight * value;
    case LAYER_BLEND_REPLACE:
        top = value;
        break;
    case LAYER_BLEND_MAX:
        top = value > below ? value : below;
        break;
    case LAYER_BLEND_MIN:
        top = value < below ? value : below;
        break;
    default:
        return below;
    }
    return weight >= 1.0f ? top : below + weight * (top - below);
}

void layer_blend_row(layer_blend blend, float weight, const float *below, const float *value,
                     float *out, int n) {
    if (!(weight > 0.0f)) {
        for (int i = 0; i < n; i++)
            out[i] = below[i];
        return;
    }
    if (blend == LAYER_BLEND_ADD && weight >= 1.0f) { // the common case, vectorised
        for (int i = 0; i < n; i++)
            out[i] = value[i] == value[i] ? below[i] + value[i] : below[i];
        return;
    }
    for (int i = 0; i < n; i++)
        out[i] = layer_blend_sample(blend, weight, below[i], value[i]);
}

float layer_blend_solve(layer_blend blend, float weight, float below, float value, float target) {
    if (!(weight > 0.0f) || isnan(target)) return value;
    if (blend == LAYER_BLEND_MAX && target < below) return NAN; // the nearest: no effect
    if (blend == LAYER_BLEND_MIN && target > below) return NAN;
    if (layer_blend_sample(blend, weight, below, value) == target) return value;
    float v;
    if (blend == LAYER_BLEND_ADD)
        v = weight >= 1.0f ? target - below : (target - below) / weight;
    else
        v = weight >= 1.0f ? target : below + (target - below) / weight;
    // Rounding may miss target by an ulp or two: step v toward it while that helps.
    for (int i = 0; i < 8; i++) {
        float got = layer_blend_sample(blend, weight, below, v);
        if (got == target || isnan(got)) break;
        float next = nextafterf(v, got < target ? INFINITY : -INFINITY);
        float again = layer_blend_sample(blend, weight, below, next);
        if (fabsf(again - target) > fabsf(got - target)) break;
        v = next;
    }
    return v;
}
