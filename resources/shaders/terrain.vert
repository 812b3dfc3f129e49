#version 450 core
// Geometry clipmap vertex: a fixed grid position, displaced by the level's height
// texture (Crause 2010's vertex displacement), morphed toward the coarser level at the edge.
#include "terrain_common.glsl"

layout(location = 0) in uvec2 a_grid; // local vertex, 0 .. n-1

out vec2 v_local;  // local position, level units
out vec3 v_rel;    // position relative to the camera, metres

void main() {
    vec2 p = vec2(a_grid);
    float h = level_height(p, morph_factor(p));
    vec4 off = u_lvl_offset[u_level];
    v_local = p;
    v_rel = vec3(off.x + p.x * off.z, h - u_cam_y, off.y + p.y * off.z);
    gl_Position = u_view_proj * vec4(v_rel, 1.0);
}
