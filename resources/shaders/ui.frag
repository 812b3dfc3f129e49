#version 450 core
// The font atlas holds coverage in its red channel; user textures are colour images.
in vec2 v_uv;
in vec4 v_colour;
uniform sampler2D u_texture;
uniform int u_coverage; // 1: the font atlas (coverage), 0: an RGBA image
out vec4 o_colour;
void main() {
    vec4 t = texture(u_texture, v_uv);
    o_colour = u_coverage == 1 ? vec4(v_colour.rgb, v_colour.a * t.r) : v_colour * t;
}
