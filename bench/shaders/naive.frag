#version 450 core
// The clipmap's height view (resources/shaders/terrain.frag, VIEW_HEIGHT) on the
// full-resolution mesh: the same colour ramp and sun, so the images compare.
#include "lighting.glsl"
#include "colour_ramp.glsl"

in vec3 v_rel;
in vec2 v_grad;
in float v_height;
out vec4 o_colour;

uniform float u_max_height;

void main() {
    vec3 n = normalize(vec3(-v_grad.x, 1.0, -v_grad.y));
    float t = (v_height + u_max_height) / (2.0 * u_max_height);
    o_colour = vec4(ramp(t) * (0.55 + 0.45 * max(dot(n, u_sun_dir), 0.0)), 1.0);
}
