#version 450 core
// The water plane at ocean_level: a quad around the camera (clipped to a bounded
// world), camera-relative like the terrain.
uniform mat4 u_view_proj;
uniform vec4 u_water_rect; // x0, z0, x1, z1 relative to the camera, metres
uniform float u_water_y;   // ocean level relative to the camera
out vec3 v_rel;
void main() {
    vec2 c = vec2((gl_VertexID & 1) != 0 ? u_water_rect.z : u_water_rect.x,
                  (gl_VertexID & 2) != 0 ? u_water_rect.w : u_water_rect.y);
    v_rel = vec3(c.x, u_water_y, c.y);
    gl_Position = u_view_proj * vec4(v_rel, 1.0);
}
