// The material textures and the automatic material rules, shared by the terrain and
// the volume meshes (caves, overhangs) so both look the same.
uniform sampler2DArray u_albedo; // the 8 procedural material textures
uniform float u_ocean_level, u_max_height;

#ifdef MINIFIED
// Ground so far away that the near scale's texels are all smaller than a pixel: a
// lookup would return the texture's 1 x 1 level, its mean, read once on the CPU.
uniform vec4 u_albedo_mean[8];
#endif

// A material's colour (and height, a) at uv, varied by v: the green channel of its
// texture at a second, much larger scale, which breaks up the repetition.
#ifdef RESOLVE
// The near scale's uv derivatives across the screen, set by terrain.frag before the
// lookups (a deferred pass's neighbouring pixels may hold another level or no ground).
vec2 g_uv_dx, g_uv_dy;
#endif

vec4 albedo_varied(int layer, vec2 uv, float v) {
#ifdef MINIFIED
    vec4 near_c = u_albedo_mean[layer];
#elif defined(RESOLVE)
    vec4 near_c = textureGrad(u_albedo, vec3(uv, float(layer)), g_uv_dx, g_uv_dy);
#else
    vec4 near_c = texture(u_albedo, vec3(uv, float(layer)));
#endif
    return vec4(near_c.rgb * (0.82 + 0.36 * v), near_c.a);
}

// The far scale's value for material `layer` at uv_far.
float far_variation(int layer, vec2 uv_far) {
    return texture(u_albedo, vec3(uv_far, float(layer))).g;
}

vec4 albedo(int layer, vec2 uv, vec2 uv_far) {
    return albedo_varied(layer, uv, far_variation(layer, uv_far));
}

// Height-aware blend: the material whose texture stands higher wins at the border.
vec3 blend2(vec4 a, vec4 b, float t) {
    float ha = a.a * (1.0 - t), hb = b.a * t;
    float m = max(ha, hb) - 0.15;
    float wa = max(ha - m, 0.0) + (1.0 - t) * 0.01, wb = max(hb - m, 0.0) + t * 0.01;
    return (a.rgb * wa + b.rgb * wb) / (wa + wb);
}

// The automatic material rules (editor/layers/material_rules.h): bottom first, each
// lays its material over the rules below with the product of its terms' weights
// (1 inside a range, a smoothstep edge outside it), moved by its breakup times the
// material's far-scale variation. The default stack is Harris 2011's four materials:
// sand by the water, grass, rock on steep ground, cliff steeper, snow up high.
#define MAX_RULES 16
uniform int u_rule_count;
uniform int u_rule_material[MAX_RULES];
// Per rule and term, where its weight starts rising, reaches 1, starts falling, reaches
// 0 (editor/layers/material_rules.h): heights in metres, slopes as rise over run,
// curvature as -100 x the Laplacian (positive convex).
uniform vec4 u_rule_height[MAX_RULES], u_rule_slope[MAX_RULES], u_rule_curvature[MAX_RULES];
uniform float u_rule_breakup[MAX_RULES];

// Material m's far-scale variation from the eight in far0 (sand, grass, rock, cliff) and
// far1 (snow, dirt, gravel, moss): the flat terrain's far texture holds them so
// (renderer/material_rule_uniforms.h material_far_slot), and a level whose rules lay
// none of far1's reads only far0.
float far_of(int m, vec4 far0, vec4 far1) {
    return m == 7 ? far0.w : m < 3 ? far0[m] : far1[m - 3];
}

float rule_term(vec4 r, float v) {
    float up = r.y > r.x ? smoothstep(r.x, r.y, v) : float(v >= r.y);
    float down = r.w > r.z ? 1.0 - smoothstep(r.z, r.w, v) : float(v <= r.z);
    return up * down;
}

// Rule i's weight, and the material m it lays (v: m's far-scale variation). terms says
// which of its terms are set (1 height, 2 slope, 4 curvature, 8 breakup): a constant in
// RULE_CALLS, so what a rule lacks is not computed.
float rule_weight(int i, int terms, float h, float slope, float curvature, vec4 far0, vec4 far1,
                  out int m, out float v) {
    m = u_rule_material[i];
    v = far_of(m, far0, far1);
    float w = 1.0;
    if ((terms & 1) != 0) w *= rule_term(u_rule_height[i], h);
    if ((terms & 2) != 0) w *= rule_term(u_rule_slope[i], slope);
    if ((terms & 4) != 0) w *= rule_term(u_rule_curvature[i], curvature);
    if ((terms & 8) != 0) w = clamp(w + u_rule_breakup[i] * (2.0 * v - 1.0), 0.0, 1.0);
    return w;
}

// Rule i laid over c.
vec4 rule_over(vec4 c, inout bool bare, int i, int terms, float h, float slope, float curvature,
               vec2 uv, vec4 far0, vec4 far1) {
    int m;
    float v;
    float w = rule_weight(i, terms, h, slope, curvature, far0, far1, m, v);
    vec4 a = albedo_varied(m, uv, v);
    // A first rule covering everything is the ground itself, with its texture's heights.
    vec4 over = bare && w >= 1.0 ? a : vec4(blend2(c, a, w), 0.5);
    bare = false;
    return over;
}

// slope: rise over run; curvature as the rules read it. far0, far1: the far scale's
// values of materials 0-3 and 4-7. RULE_CALLS, when the renderer defines it, is the
// rules that can have weight where this program draws, as R(i, terms) in stack order:
// a software renderer runs every iteration of a loop and both sides of an `if`, so
// only those are in the program; without it every rule runs.
vec3 automatic_varied(float h, float slope, float curvature, vec2 uv, vec4 far0, vec4 far1) {
    vec4 c = vec4(0.45, 0.42, 0.38, 0.5); // no rule covers it: a neutral clay
    bool bare = true;
#ifdef RULE_CALLS
#define R(i, terms) c = rule_over(c, bare, i, terms, h, slope, curvature, uv, far0, far1);
    RULE_CALLS
#undef R
#else
    for (int i = 0; i < u_rule_count; i++)
        c = rule_over(c, bare, i, 15, h, slope, curvature, uv, far0, far1);
#endif
    return c.rgb;
}

vec3 automatic(float h, float slope, float curvature, vec2 uv, vec2 uv_far) {
    vec4 far0 = vec4(far_variation(0, uv_far), far_variation(1, uv_far), far_variation(2, uv_far),
                     far_variation(7, uv_far));
    vec4 far1 = vec4(far_variation(3, uv_far), far_variation(4, uv_far), far_variation(5, uv_far),
                     far_variation(6, uv_far));
    return automatic_varied(h, slope, curvature, uv, far0, far1);
}
