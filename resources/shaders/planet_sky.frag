#version 450 core
// Behind the planet: black space, the sun's disc and the atmosphere's glow (the blue
// sky from the ground, the rim from orbit).
#include "planet_atmosphere.glsl"
in vec2 v_ndc;
out vec4 o_colour;
uniform vec3 u_cam_forward, u_cam_right, u_cam_upv; // camera basis, planet coordinates
uniform vec2 u_tan_half;
void main() {
    vec3 dir = normalize(u_cam_forward + v_ndc.x * u_tan_half.x * u_cam_right +
                         v_ndc.y * u_tan_half.y * u_cam_upv);
    // Rays that meet the planet stop at its datum (the ground drawn over them).
    float mu = dot(dir, u_cam_up), rm = u_cam_r * mu;
    float disc = rm * rm - u_cam_alt * (2.0 * u_radius + u_cam_alt);
    float t_end = mu < 0.0 && disc > 0.0 ? -rm - sqrt(disc) : 1e30;
    vec3 transmittance;
    vec3 c = atmosphere(dir, t_end, transmittance);
    if (t_end < 1e30) transmittance = vec3(0.0); // no sun through the planet
    float sun = max(dot(dir, u_sun_dir), 0.0);
    c += u_sun_colour * transmittance * (smoothstep(0.99995, 0.99999, sun) * 20.0 + pow(sun, 2000.0) * 2.0);
    o_colour = vec4(1.0 - exp(-c * 1.8), 1.0); // exposure
}
