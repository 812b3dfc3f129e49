#version 450 core
// Geometry clipmap vertex: a fixed grid position, displaced by the level's height
// texture (Crause 2010's vertex displacement), morphed toward the coarser level at the edge.
#include "terrain_common.glsl"

layout(location = 0) in uvec2 a_grid; // local vertex, 0 .. n-1 (refined: half units)

out vec2 v_local_vs; // local position, level units
out vec3 v_rel_vs;   // position relative to the camera, metres

#ifdef REFINED
// A part drawn at twice the density (renderer/clip_refine_mesh.h): its vertices go from
// the level's surface toward the finer shading heights by their refinement weight
// (renderer/clip_refine.h): 0 on the border of an unrefined part, of the trim or of the
// finer level, so such a vertex stays on the level's surface. No branches: a software
// renderer runs both sides of an `if` (4 texture reads a vertex; its seams' copies 8).
uniform sampler2DArray u_refine; // R8 per vertex of each level's local grid, linear

float refine_weight(vec2 p) {
    return texture(u_refine, vec3((p + 0.5) / 256.0, float(u_level))).r;
}

// The level's own surface (a refined level reads its own heights: a texel per unit) at
// a half-unit point, from its quad's corners in one read: a quad's centre lies on the
// diagonal the level's mesh splits it along (clipmap_mesh.c), an edge's midpoint halfway
// along the edge, a corner on its sample.
float level_surface(vec2 p) {
    vec4 src = u_lvl_src_a[u_level];
    vec2 q = floor(p), f = 2.0 * (p - q);
    // (q.x, q.y + 1), (q.x + 1, q.y + 1), (q.x + 1, q.y), (q.x, q.y)
    vec4 c = textureGather(u_heights, vec3((src.xy + q + 1.0) / CLIP_SIZE, src.w));
    return c.w * (1.0 - 0.5 * (f.x + f.y)) + 0.5 * (f.x * c.z + f.y * c.x);
}

float refined_height(vec2 p) {
    float h = level_surface(p);
    vec4 fine = u_lvl_slopes_a[u_level];
    float w = fine.w >= 0.0 ? refine_weight(p) : 0.0;
    vec2 t = (fine.xy + p * fine.z + 0.5) / float(textureSize(u_slopes, 0).x);
    h = w > 0.0 ? mix(h, texture(u_slopes, vec3(t, fine.w)).r, w) : h;
    float alpha = morph_factor(p);
    return alpha > 0.0 ? mix(h, sample_height(u_lvl_src_b[u_level], p), alpha) : h;
}
#endif

void main() {
#ifdef REFINED
    vec2 p = vec2(a_grid & uvec2(0x7fffu, 0xffffu)) * 0.5;
#ifdef SEAM
    // The seams (their own draws): an on-line copy lies between its two neighbours, the
    // other vertices at their own heights (the mean of one height with itself).
    vec2 e = (a_grid.x & 0x8000u) == 0u ? vec2(0.0) : fract(p.x) != 0.0 ? vec2(0.5, 0.0) : vec2(0.0, 0.5);
    float h = 0.5 * (refined_height(p - e) + refined_height(p + e));
#else
    float h = refined_height(p);
#endif
#else
    vec2 p = vec2(a_grid);
    float h = level_height(p, morph_factor(p));
#endif
    vec4 off = u_lvl_offset[u_level];
    v_local_vs = p;
    v_rel_vs = vec3(off.x + p.x * off.z, h - u_cam_y, off.y + p.y * off.z);
    gl_Position = u_view_proj * vec4(v_rel_vs, 1.0);
}
