// The water plane's ripples (resources/shaders/water.frag): two crossed sine waves that
// tilt the normal so the sun's glint and the sky's reflection break up. Anchored to the
// world, not the camera: each wave's phase at the camera is reduced here in double
// precision, so the shader works in camera-relative floats (as the terrain does) and the
// ripples stay put while the camera flies, at any distance from the origin.
#ifndef OROGEN_RENDERER_WATER_RIPPLES_H
#define OROGEN_RENDERER_WATER_RIPPLES_H

#include <epoxy/gl.h>

// Sets u_ripple_waves (the waves' vectors, radians per metre along x and z) and
// u_ripple_phase (their phases at the camera, in [0, 2 pi)) on prog.
void water_ripple_uniforms(GLuint prog, const double camera_pos[3]);

#endif
