// How a layer combines with the layers below it, sample by sample, and the inverse the
// tools need: what to store in a layer so the composite shows a given height. Pure
// functions over float rows, so tests compare them against plain arrays.
//
// A layer sample holds a value v (NaN: the layer has nothing there). With weight
// w = opacity (times a mask, later), over the composite b of the layers below:
//   add:     b + w*v
//   replace: v,          or b + w*(v - b) when w < 1
//   max:     max(b, v),  or b + w*(max(b, v) - b) when w < 1
//   min:     min(b, v),  likewise
// and b where v is NaN or w is 0.
#ifndef OROGEN_EDITOR_LAYER_BLEND_H
#define OROGEN_EDITOR_LAYER_BLEND_H

#include "editor/layers/layer_table.h"

// One sample.
float layer_blend_sample(layer_blend blend, float weight, float below, float value);

// out[i] = layer_blend_sample(blend, weight, below[i], value[i]) for n samples (out may
// be below).
void layer_blend_row(layer_blend blend, float weight, const float *below, const float *value,
                     float *out, int n);

// The value to store in a layer (currently holding value) so that the sample shows
// target over below: exact (layer_blend_sample gives target back) wherever a float
// does that; the nearest the layer can show otherwise. NaN when the layer cannot move
// the sample (weight 0, or a max layer asked to lower it under below, a min layer to
// raise it), so the caller leaves the sample as it was.
float layer_blend_solve(layer_blend blend, float weight, float below, float value, float target);

// out[i] = layer_blend_solve(LAYER_BLEND_ADD, w, below[i], value[i], target[i]) for any
// w >= 1, n samples, bit for bit: its ulp search taken on every sample at once (vectorised;
// a tall stroke's take solves a sixth of its samples, one by one that was 50 ns each).
void layer_blend_solve_add_row(const float *below, const float *value, const float *target,
                               float *out, int n);

#endif
