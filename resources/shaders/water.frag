#version 450 core
// Water: deep colour, sky reflection by Fresnel, the sun's glint, fog.
#include "lighting.glsl"
in vec3 v_rel;
out vec4 o_colour;
uniform vec4 u_ripple_waves; // two waves' vectors (x, z), radians per metre
uniform vec2 u_ripple_phase; // their phases at the camera (renderer/water_ripples.h)
// Ripple slope and the glint's exponent on calm water.
const float RIPPLE = 0.03;
const float GLINT = 400.0;
void main() {
    vec3 view_dir = normalize(-v_rel);
    // Gentle ripples so the sun's glint is not a mirror disc, anchored to the world.
    float p1 = dot(v_rel.xz, u_ripple_waves.xy) + u_ripple_phase.x;
    float p2 = dot(v_rel.xz, u_ripple_waves.zw) + u_ripple_phase.y;
    // A wave a pixel spans much of a period of only aliases (moire rings toward the
    // horizon): it fades out between 2.5 and 3.5 radians a pixel (pi: two pixels a period).
    float f1 = 1.0 - smoothstep(2.5, 3.5, fwidth(p1));
    float f2 = 1.0 - smoothstep(2.5, 3.5, fwidth(p2));
    vec3 n = normalize(vec3(sin(p1) * RIPPLE * f1, 1.0, cos(p2) * RIPPLE * f2));
    float fresnel = 0.02 + 0.98 * pow(1.0 - max(dot(n, view_dir), 0.0), 5.0);
    vec3 deep = vec3(0.02, 0.09, 0.13);
    vec3 reflected = sky_colour(reflect(-view_dir, n));
    vec3 c = mix(deep * (0.4 + 0.6 * max(u_sun_dir.y, 0.0)), reflected, fresnel);
    // The slopes the faded waves no longer show widen the glint instead (Toksvig): each
    // wave's slope varies by RIPPLE^2 / 2 about its mean; the lobe keeps its energy.
    float variance = 0.5 * RIPPLE * RIPPLE * ((1.0 - f1 * f1) + (1.0 - f2 * f2));
    float glint = GLINT / (1.0 + GLINT * variance);
    vec3 h = normalize(u_sun_dir + view_dir);
    c += u_sun_colour * pow(max(dot(n, h), 0.0), glint) * 2.0 * (glint + 8.0) / (GLINT + 8.0);
    o_colour = vec4(apply_fog(c, v_rel), mix(0.82, 1.0, fresnel));
}
