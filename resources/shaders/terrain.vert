#version 450 core
// Geometry clipmap vertex: a fixed grid position, displaced by the level's height
// texture (Crause 2010's vertex displacement), morphed toward the coarser level at the edge.
#include "terrain_common.glsl"

layout(location = 0) in uvec2 a_grid; // local vertex, 0 .. n-1 (refined: half units)

out vec2 v_local;  // local position, level units
out vec3 v_rel;    // position relative to the camera, metres

#ifdef REFINED
// A part drawn at twice the density (renderer/clip_refine_mesh.h): its vertices go from
// the level's surface toward the finer shading heights by their refinement weight
// (renderer/clip_refine.h): 0 on the border of an unrefined part, of the trim or of the
// finer level, so such a vertex stays on the level's surface.
uniform sampler2DArray u_refine; // R8 per vertex of each level's local grid, linear

float refine_weight(vec2 p) {
    return texture(u_refine, vec3((p + 0.5) / 256.0, float(u_level))).r;
}

// The level's own surface at a half-unit point: a quad's centre lies on the diagonal the
// level's mesh splits it along (clipmap_mesh.c), elsewhere on the grid lines.
float level_surface(vec2 p) {
    vec4 src = u_lvl_src_a[u_level];
    if (fract(p.x) != 0.0 && fract(p.y) != 0.0)
        return 0.5 * (sample_height(src, p + vec2(0.5, -0.5)) + sample_height(src, p + vec2(-0.5, 0.5)));
    return sample_height(src, p);
}

float refined_height(vec2 p) {
    float h = level_surface(p);
    vec4 fine = u_lvl_slopes_a[u_level];
    float w = fine.w >= 0.0 ? refine_weight(p) : 0.0;
    if (w > 0.0) {
        vec2 t = (fine.xy + p * fine.z + 0.5) / float(textureSize(u_slopes, 0).x);
        h = mix(h, texture(u_slopes, vec3(t, fine.w)).r, w);
    }
    float alpha = morph_factor(p);
    return alpha > 0.0 ? mix(h, sample_height(u_lvl_src_b[u_level], p), alpha) : h;
}
#endif

void main() {
#ifdef REFINED
    vec2 p = vec2(a_grid & uvec2(0x7fffu, 0xffffu)) * 0.5;
    float h;
    if ((a_grid.x & 0x8000u) != 0u) { // the on-line copy: between its two neighbours
        vec2 e = fract(p.x) != 0.0 ? vec2(0.5, 0.0) : vec2(0.0, 0.5);
        h = 0.5 * (refined_height(p - e) + refined_height(p + e));
    } else {
        h = refined_height(p);
    }
#else
    vec2 p = vec2(a_grid);
    float h = level_height(p, morph_factor(p));
#endif
    vec4 off = u_lvl_offset[u_level];
    v_local = p;
    v_rel = vec3(off.x + p.x * off.z, h - u_cam_y, off.y + p.y * off.z);
    gl_Position = u_view_proj * vec4(v_rel, 1.0);
}
