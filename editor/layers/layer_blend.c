#include "editor/layers/layer_blend.h"

#include "io/avx2_clone.h"

#include <math.h>
#include <string.h>
#include <stdint.h>

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

// nextafterf(v, up ? INFINITY : -INFINITY), inline: the next float by its bits (the
// library call cost more than the rest of a solve, which takes a step in most calls
// where the sum's rounding misses).
static float step_toward(float v, int up) {
    if (v != v || v == (up ? INFINITY : -INFINITY)) return v;
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    if ((u & 0x7fffffffu) == 0) // either zero: the smallest subnormal of the direction's sign
        u = up ? 1u : 0x80000001u;
    else if (!(u >> 31) == !!up) // away from zero: the magnitude grows
        u++;
    else
        u--;
    memcpy(&v, &u, sizeof v);
    return v;
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
        float next = step_toward(v, got < target);
        float again = layer_blend_sample(blend, weight, below, next);
        if (fabsf(again - target) > fabsf(got - target)) break;
        v = next;
    }
    return v;
}

static uint32_t bits_of(float f) {
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static float float_of(uint32_t u) {
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

// layer_blend_solve's add case at full weight without branches: each of the 8 steps is
// taken on every sample of a chunk and kept only where the search would still be going.
AVX2_CLONE void layer_blend_solve_add_row(const float *below, const float *value,
                                          const float *target, float *out, int n) {
    enum { CHUNK = 256 };
    float s[CHUNK];
    int32_t stop[CHUNK];
    for (int c = 0; c < n; c += CHUNK) {
        const int m = n - c < CHUNK ? n - c : CHUNK;
        const float *b = below + c, *t = target + c;
        for (int i = 0; i < m; i++) {
            s[i] = t[i] - b[i];
            stop[i] = 0;
        }
        // Nearly every sample is done after a step or two: the chunk stops when all are
        // (a done sample never changes again, so the values are the same).
        for (int k = 0, going = 1; k < 8 && going; k++) {
            going = 0;
            for (int i = 0; i < m; i++) {
                float got = b[i] + s[i];
                int32_t up = got < t[i];
                int32_t done = stop[i] | (got == t[i]) | (got != got);
                // step_toward(s, up) by the bits
                uint32_t u = bits_of(s[i]);
                uint32_t zero = up ? 1u : 0x80000001u;
                uint32_t moved = (u & 0x7fffffffu) == 0   ? zero
                                 : ((u >> 31) == 0) == up ? u + 1
                                                          : u - 1;
                int32_t stuck = (s[i] != s[i]) | (s[i] == (up ? INFINITY : -INFINITY));
                float next = stuck ? s[i] : float_of(moved);
                float again = b[i] + next;
                done |= fabsf(again - t[i]) > fabsf(got - t[i]);
                s[i] = done ? s[i] : next;
                stop[i] = done;
                going |= !done;
            }
        }
        for (int i = 0; i < m; i++) {
            float v = value[c + i], shown = v == v ? b[i] + v : b[i];
            out[c + i] = (t[i] != t[i]) | (shown == t[i]) ? v : s[i];
        }
    }
}
