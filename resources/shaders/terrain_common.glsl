// Shared by terrain.vert and terrain.frag: the per-level uniforms of the clipmap and
// height sampling from the toroidal level textures (renderer/terrain_renderer.c fills
// them; positions are camera-relative so far from the origin nothing jitters).
#define MAX_LEVELS 12
const float CLIP_SIZE = 256.0;

uniform int u_level;                   // the level this draw call renders
uniform mat4 u_view_proj;              // camera-relative: the camera sits at the origin
uniform float u_cam_y;                 // camera height, metres
uniform vec2 u_morph;                  // (start, width) of the transition band, level units
uniform vec4 u_lvl_offset[MAX_LEVELS]; // xz of local vertex (0,0) relative to the camera; spacing
uniform vec4 u_lvl_view[MAX_LEVELS];   // camera in local units (xy); z = 1 if the level morphs
uniform vec4 u_lvl_src_a[MAX_LEVELS];  // heights: texel of local (0,0), texels per local unit, layer
uniform vec4 u_lvl_src_b[MAX_LEVELS];  // the same for the next coarser level (morph target)
uniform sampler2DArray u_heights;
// Shading slopes: heights up to 2 mip levels finer than each level's own, over its
// extent (renderer/clip_slopes.h): texel of local (0,0), texels per local unit, layer
// (-1: none, the level's own heights), for the level and the coarser one it morphs into;
// the refined parts' vertices take their heights from them too (terrain.vert).
uniform sampler2DArray u_slopes;
uniform vec4 u_lvl_slopes_a[MAX_LEVELS];
uniform vec4 u_lvl_slopes_b[MAX_LEVELS];

float sample_height(vec4 src, vec2 p) {
    vec2 t = (src.xy + p * src.z + 0.5) / CLIP_SIZE;
    return texture(u_heights, vec3(t, src.w)).r;
}

// 0 inside, rising to 1 at the level's outer edge, where the vertices take the coarser
// level's (interpolated) heights: no cracks between levels, no popping as they shift.
float morph_factor(vec2 p) {
#ifdef NO_MORPH
    return 0.0; // drawn only where the band does not reach (renderer/terrain_renderer.c)
#endif
    vec4 view = u_lvl_view[u_level];
    vec2 d = abs(p - view.xy);
    vec2 a = clamp((d - u_morph.x) / u_morph.y, 0.0, 1.0);
    return max(a.x, a.y) * view.z;
}

float level_height(vec2 p, float alpha) {
    float ha = sample_height(u_lvl_src_a[u_level], p);
    if (alpha <= 0.0) return ha;
    return mix(ha, sample_height(u_lvl_src_b[u_level], p), alpha);
}
