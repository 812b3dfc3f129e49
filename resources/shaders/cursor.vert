#version 450 core
// The volume tools' brush cursor: three great circles of a sphere (64 vertices each,
// drawn as line loops), camera-relative.
uniform mat4 u_view_proj;
uniform vec3 u_centre; // relative to the camera, metres
uniform float u_radius;

void main() {
    int circle = gl_VertexID / 64;
    float a = float(gl_VertexID % 64) / 64.0 * 6.28318531;
    vec3 p = circle == 0 ? vec3(cos(a), sin(a), 0.0)
           : circle == 1 ? vec3(0.0, cos(a), sin(a))
                         : vec3(cos(a), 0.0, sin(a));
    gl_Position = u_view_proj * vec4(u_centre + p * u_radius, 1.0);
}
