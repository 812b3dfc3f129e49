#version 450 core
// Water: deep colour, sky reflection by Fresnel, the sun's glint, fog.
#include "lighting.glsl"
in vec3 v_rel;
out vec4 o_colour;
uniform float u_time;
void main() {
    vec3 view_dir = normalize(-v_rel);
    // Gentle procedural ripples so the sun's glint is not a mirror disc.
    vec2 q = v_rel.xz * 0.05;
    vec3 n = normalize(vec3(sin(q.x * 3.1 + q.y * 1.7) * 0.03, 1.0, cos(q.y * 2.9 - q.x * 1.3) * 0.03));
    float fresnel = 0.02 + 0.98 * pow(1.0 - max(dot(n, view_dir), 0.0), 5.0);
    vec3 deep = vec3(0.02, 0.09, 0.13);
    vec3 reflected = sky_colour(reflect(-view_dir, n));
    vec3 c = mix(deep * (0.4 + 0.6 * max(u_sun_dir.y, 0.0)), reflected, fresnel);
    vec3 h = normalize(u_sun_dir + view_dir);
    c += u_sun_colour * pow(max(dot(n, h), 0.0), 400.0) * 2.0;
    o_colour = vec4(apply_fog(c, v_rel), mix(0.82, 1.0, fresnel));
}
