// The brush radius the window offers, in metres, for a world of a given sample
// spacing. A fixed range in metres suits a 2 m world and fails an 89 m one (an SRTM
// tile): there the first auto radius lay under one sample and the slider stopped at
// 500 m, under six samples, so a stroke left a faint streak. The ranges grow with the
// spacing, so a brush always covers samples and can cover a mountain.
#ifndef OROGEN_APP_BRUSH_SIZE_H
#define OROGEN_APP_BRUSH_SIZE_H

// The Radius slider's top: 500 m, or 64 samples on coarse worlds.
double brush_radius_slider_max(double spacing);

// The top for the [ and ] keys and the resize drag: 5000 m, or 64 samples.
double brush_radius_key_max(double spacing);

// The radius that follows the view: wanted (from the distance to the ground) kept
// between two samples (at least 1 m) and the slider's top, to two significant digits.
double brush_radius_auto(double wanted, double spacing);

#endif
