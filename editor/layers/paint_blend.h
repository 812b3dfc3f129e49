// How a paint layer lays its material weights over the layers below it, and the inverse
// the paint tool needs. Pure functions over one sample, so tests compare them against
// plain arrays.
//
// A paint layer sample holds TILE_MATERIALS weights L (uint8) summing to at most 255: its
// coverage is s = sum(L) / 255 (0: nothing painted), its mix L / sum(L). Over the
// composite weights B of the layers below (summing to 255), with weight w = opacity
// (times its mask):
//   shown = B (1 - w s) + w L
// so a fully covering layer at full weight shows its own mix, and stacking layers
// composes (the composite of two layers is one layer: paint_blend_merge). The composite
// is kept in floats through the stack and rounded once (paint_blend_round).
#ifndef OROGEN_EDITOR_LAYERS_PAINT_BLEND_H
#define OROGEN_EDITOR_LAYERS_PAINT_BLEND_H

#include "io/tile.h"

#include <stdint.h>

// acc = acc (1 - w s) + w L, for one sample's TILE_MATERIALS weights.
void paint_blend_sample(float *acc, float weight, const uint8_t *layer);
// The nearest weights summing to exactly 255 (acc scaled to sum 255, then largest
// remainder rounding; ties to the lower channel). acc all zero gives channel 0 (automatic).
void paint_blend_round(const float *acc, uint8_t *out);
// The least coverage that makes a layer show target over below (both summing to about
// 255) at weight w: the layer's new weights in out (summing to 255 x coverage).
// Where the target cannot be reached with coverage <= 1 (w < 1, or a target that keeps
// less of below than w allows), the nearest reachable is taken. w <= 0 leaves out as
// current.
void paint_blend_solve(const float *below, float weight, const float *target,
                       const uint8_t *current, uint8_t *out);
// The one layer (weight 1) that shows what lower (weight wl) then upper (weight wu) show
// together over any below: s = 1 - (1 - wl sl)(1 - wu su), L = wl Ll (1 - wu su) + wu Lu.
void paint_blend_merge(const uint8_t *lower, float wl, const uint8_t *upper, float wu,
                       uint8_t *out);

#endif
