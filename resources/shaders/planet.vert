#version 450 core
// A planet chunk: vertices relative to the chunk's origin, placed relative to the
// camera by u_offset (computed in double on the CPU). Ground below the sea is raised
// to the sea's surface (seed 004's ocean), keeping its depth for the water's colour.
// The atmosphere's integrals are taken here, per vertex, and interpolated: they vary
// smoothly over a chunk's cells (a few pixels wide), and per fragment they were most of
// a software renderer's frame. The variant defines are planet.frag's.
#include "planet_atmosphere.glsl"
#include "planet_climate.glsl"
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_up;
layout(location = 3) in float a_height;
layout(location = 4) in vec2 a_metres;
layout(location = 5) in vec4 a_coarse; // the vertex in the parent level's mesh, and its height
layout(location = 6) in uvec2 a_paint; // the 8 painted weights, a byte each
#ifdef SEAM // near a face's edge: the neighbouring faces' texture metres and weights
layout(location = 7) in vec3 a_other0;
layout(location = 8) in vec3 a_other1;
out vec3 v_other0, v_other1;
#endif
uniform mat4 u_view_proj;
uniform vec3 u_offset;
uniform float u_ocean_h; // the sea's height above the datum
uniform float u_morph;   // 1 / the distance where the parent level takes over (0: no morph)
out vec3 v_rel, v_normal, v_up;
out float v_height, v_depth;
out vec2 v_metres;
out vec4 v_paint0, v_paint1; // weights 0-3 and 4-7, 0..1
out vec3 v_air, v_transmittance; // the air between the camera and the surface
out vec3 v_sky_reflected;        // the sky the sea reflects
#if defined(SHADED) && !defined(BARE)
out vec3 v_climate; // planet_climate's moisture, breakup and patches
#endif
void main() {
    // Geomorphing: from half that distance on, the vertex slides onto the parent's mesh.
    float m = clamp(2.0 * length(a_pos + u_offset) * u_morph - 1.0, 0.0, 1.0);
    vec3 rel = mix(a_pos, a_coarse.xyz, m) + u_offset;
    float height = mix(a_height, a_coarse.w, m);
    v_depth = u_ocean_h - height;
    if (v_depth > 0.0) rel += a_up * v_depth;
    v_rel = rel;
    v_normal = a_normal;
    v_up = a_up;
    v_height = height;
#if defined(SHADED) && !defined(BARE)
    v_climate = planet_climate(a_up, length(rel));
#endif
    v_metres = a_metres;
#ifdef SEAM
    v_other0 = a_other0, v_other1 = a_other1;
#endif
    v_paint0 = vec4(a_paint.x & 255u, (a_paint.x >> 8) & 255u, (a_paint.x >> 16) & 255u,
                    a_paint.x >> 24) / 255.0;
    v_paint1 = vec4(a_paint.y & 255u, (a_paint.y >> 8) & 255u, (a_paint.y >> 16) & 255u,
                    a_paint.y >> 24) / 255.0;
    gl_Position = u_view_proj * vec4(rel, 1.0);
    float dist = length(rel);
    vec3 view_dir = rel / max(dist, 1e-6);
#ifdef SHADED
    float surface_h = v_depth > 0.0 ? u_ocean_h : height;
    v_air = atmosphere(view_dir, ray_to_height(view_dir, surface_h, dist), v_transmittance);
#endif
#ifdef SEA
    vec3 t;
    v_sky_reflected = atmosphere(reflect(view_dir, a_up), 1e30, t);
#endif
}
