#version 450 core
// The benchmark's full-resolution reference mesh: one vertex per level-0 sample,
// positions relative to a fixed anchor, moved camera-relative by u_offset.
layout(location = 0) in vec3 a_pos;  // metres from the anchor; y is the height
layout(location = 1) in vec2 a_grad; // height gradient (d/dx, d/dz)

uniform mat4 u_view_proj; // camera-relative, as the clipmap's
uniform vec3 u_offset;    // anchor minus camera, metres

out vec3 v_rel;
out vec2 v_grad;
out float v_height;

void main() {
    v_rel = a_pos + u_offset;
    v_grad = a_grad;
    v_height = a_pos.y;
    gl_Position = u_view_proj * vec4(v_rel, 1.0);
}
