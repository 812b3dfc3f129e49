#version 450 core
// The sky behind the terrain: a gradient from horizon to zenith and the sun's disc.
#include "lighting.glsl"
in vec2 v_ndc;
out vec4 o_colour;
uniform vec3 u_cam_forward, u_cam_right, u_cam_up; // world-space camera basis
uniform vec2 u_tan_half; // tan of half the field of view, horizontally and vertically
void main() {
    vec3 dir = normalize(u_cam_forward + v_ndc.x * u_tan_half.x * u_cam_right +
                         v_ndc.y * u_tan_half.y * u_cam_up);
    o_colour = vec4(sky_colour(dir), 1.0);
}
