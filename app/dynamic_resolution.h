// Dynamic resolution (as Blender and Unreal do during navigation): while the camera
// moves or a stroke is drawn, the viewport renders at a fraction of its size chosen to
// keep each terrain frame near a time goal, and at full size once still.
#ifndef OROGEN_APP_DYNAMIC_RESOLUTION_H
#define OROGEN_APP_DYNAMIC_RESOLUTION_H

#define DYNAMIC_RESOLUTION_MIN 0.25f // never below a quarter of the viewport's side

// The scale for the next moving frame, from the scale and wall time of the last one:
// pixels (the cost) go with the square of the scale, and half of each step is taken so
// one noisy frame does not make the picture jump.
float dynamic_resolution_next(float scale, double frame_ms, double target_ms);

#endif
