// The sun, sky and fog uniforms of resources/shaders/lighting.glsl, shared by every
// program that includes it (terrain, sky, water, the benchmark's reference mesh).
#ifndef OROGEN_RENDERER_LIGHTING_H
#define OROGEN_RENDERER_LIGHTING_H

#include "renderer/camera.h"
#include "renderer/render_settings.h"

#include <epoxy/gl.h>

// The unit vector toward the sun for the settings' sun yaw and pitch.
void render_sun_direction(const render_settings *s, float out[3]);
// Sets u_sun_dir, u_sun_colour, u_sky_zenith, u_sky_horizon and u_fog_density.
void render_lighting_uniforms(GLuint prog, const render_settings *s, double fog_density);

// The sky pass: prog is fullscreen.vert + sky.frag, drawn with an attribute-less VAO
// behind everything (no depth test or write).
void render_sky(GLuint prog, GLuint empty_vao, const camera *cam, const render_settings *s,
                double aspect, double fog_density);

#endif
