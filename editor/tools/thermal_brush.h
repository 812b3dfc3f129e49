// Thermal erosion as the brush applies it: at the brush's scale, then at the grid's.
// The kernel (erosion.h) compares neighbouring samples only, so on its own it relaxes
// slopes a couple of metres long: on the default world's gentle land a dab tens of
// metres wide moved centimetres, and nothing showed from the first view. Gaea's and
// World Machine's thermal nodes erode at the terrain's resolution, where the slopes a
// viewer sees are a few samples long; the brush does the same at its own size: the
// kernel first runs on a copy averaged over blocks of samples (so the brush spans at
// least 16 blocks), that change is spread back smoothly (bilinear tents) over the samples with
// weight > 0, then the kernel runs at the grid's spacing. A slope above the talus at the scale of
// the brush collapses, and so does one between neighbouring samples.
#ifndef OROGEN_EDITOR_THERMAL_BRUSH_H
#define OROGEN_EDITOR_THERMAL_BRUSH_H

#include "editor/tools/erosion.h"

// Samples per block for a brush of this radius (in samples): radius / 8, 1 to 32.
int thermal_brush_block(double radius_samples);

// Erodes g as above (block 1: the kernel alone). Same contract as erosion_thermal: a
// cell whose weight is 0 keeps its bits; out of memory leaves the grid untouched;
// mass is conserved up to float rounding.
void thermal_brush_erode(erosion_grid *g, const thermal_params *p, int block);

#endif
