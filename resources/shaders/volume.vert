#version 450 core
// Volume meshes (caves, overhangs, arches): one brick's surface, positions in metres
// from the brick's corner, drawn camera-relative like the terrain.
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_view_proj;
uniform vec3 u_offset;     // the brick's corner relative to the camera, metres
uniform vec4 u_uv_origin;  // the brick's corner x, z modulo the near (xy) and far (zw) texture periods
uniform vec2 u_uv_y;       // its height modulo the near (x) and far (y) periods

out vec3 v_rel;
out vec3 v_normal;
out vec3 v_near; // metres, modulo the near texture period at the brick's corner
out vec3 v_far;  // the same for the far period

void main() {
    v_rel = u_offset + a_pos;
    v_normal = a_normal;
    v_near = vec3(u_uv_origin.x, u_uv_y.x, u_uv_origin.y) + a_pos;
    v_far = vec3(u_uv_origin.z, u_uv_y.y, u_uv_origin.w) + a_pos;
    gl_Position = u_view_proj * vec4(v_rel, 1.0);
}
