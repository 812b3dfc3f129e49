#version 450 core
// The deferred terrain's colour and depth into the caller's framebuffer
// (renderer/deferred_target.c), pixel for pixel.
uniform sampler2D u_shaded;
uniform sampler2D u_depth; // the depth the terrain drew (R32F)
out vec4 o_colour;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    o_colour = texelFetch(u_shaded, p, 0);
    gl_FragDepth = texelFetch(u_depth, p, 0).r;
}
