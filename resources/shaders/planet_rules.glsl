// A planet's material rules (the Materials panel, editor/layers/material_rules.h) laid
// over its own look (planet.frag's climate, or bare ground), bottom first, as
// materials.glsl lays a flat world's: each with the product of its terms' weights, moved
// by its breakup. Where a rule weighs nothing the look is left as it was, so a rule
// changes the ground only where it applies. Included by planet.frag in its RULES variant
// (the world has rules) after materials.glsl and planet_curvature.glsl.
uniform int u_rules_curvature; // some rule reads curvature

// h: metres above the datum; slope: rise over run as the samples show it.
vec3 planet_rules(vec3 look, float h, float slope, vec3 up, vec2 uv, vec2 uv_far) {
    float curvature = u_rules_curvature != 0 ? curvature_here(up) : 0.0;
    vec4 c = vec4(look, 0.5);
    for (int i = 0; i < u_rule_count; i++) {
        int m = u_rule_material[i];
        float v = far_variation(m, uv_far);
        float w = rule_term(u_rule_height[i], h) * rule_term(u_rule_slope[i], slope) *
                  rule_term(u_rule_curvature[i], curvature);
        if (u_rule_breakup[i] != 0.0)
            w = clamp(w + u_rule_breakup[i] * (2.0 * v - 1.0), 0.0, 1.0);
        if (w > 0.0) c = vec4(blend2(c, albedo_varied(m, uv, v), w), 0.5);
    }
    return c.rgb;
}
