#version 450 core
// Volume meshes: the terrain's materials and automatic rules, tri-planar (the surface
// may be steep, vertical or upside down), lit and fogged as the terrain is.
#include "lighting.glsl"
#include "colour_ramp.glsl"
#include "materials.glsl"

in vec3 v_rel;
in vec3 v_normal;
in vec3 v_near;
in vec3 v_far;
out vec4 o_colour;

uniform float u_cam_y;
uniform vec2 u_tex_period; // metres per repeat: near texture, far variation
uniform int u_view_mode;   // as terrain.frag
uniform vec3 u_wire_tint;

void main() {
    vec3 n = normalize(v_normal);
    float h = v_rel.y + u_cam_y;
    if (u_view_mode == 1) { // wireframe
        o_colour = vec4(u_wire_tint, 1.0);
        return;
    }
    if (u_view_mode == 3) { // height
        float t = (h + u_max_height) / (2.0 * u_max_height);
        o_colour = vec4(ramp(t) * (0.55 + 0.45 * max(dot(n, u_sun_dir), 0.0)), 1.0);
        return;
    }
    // Slope as rise over run; ceilings and undercuts count as cliffs.
    float slope = n.y > 0.05 ? sqrt(max(1.0 - n.y * n.y, 0.0)) / n.y : 10.0;
    if (u_view_mode == 4) {
        o_colour = vec4(ramp(degrees(atan(slope)) / 60.0) * (0.55 + 0.45 * max(dot(n, u_sun_dir), 0.0)), 1.0);
        return;
    }
    vec3 w = pow(abs(n), vec3(4.0));
    w /= w.x + w.y + w.z;
    vec3 a = v_near / u_tex_period.x, b = v_far / u_tex_period.y;
    vec3 c = vec3(0.0);
    // The rules' curvature terms read 0 here: a mesh has no height grid to take it from.
    if (w.x > 0.01) c += w.x * automatic(h, slope, 0.0, a.zy, b.zy);
    if (w.y > 0.01) c += w.y * automatic(h, slope, 0.0, a.xz, b.xz);
    if (w.z > 0.01) c += w.z * automatic(h, slope, 0.0, a.xy, b.xy);
    c /= max(w.x * float(w.x > 0.01) + w.y * float(w.y > 0.01) + w.z * float(w.z > 0.01), 1e-4);
    float dist = length(v_rel);
    vec3 lit = sunlit(c, n, v_rel / -max(dist, 1e-6), 24.0, 0.04);
    o_colour = vec4(apply_fog(lit, v_rel), 1.0);
}
