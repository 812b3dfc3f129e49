// The automatic material rules (materials.glsl automatic_varied) with a texture lookup
// only for the rules whose material shows in the pixel, the same colour to the bit:
// a software renderer runs all of a program's straight-line code for every pixel, but
// leaves a loop once no pixel of the group needs another turn, so the lookups are made
// in a loop, from the top rule down, and stop at a rule that hides all below it.
// A rule hides the ones below where its weight is 1 and its texture's height (alpha) at
// least 0.15 (blend2 then gives the lower colour no weight); a rule of weight 0 changes
// nothing (but its first-rule neighbour, whose alpha may be lower), so it needs no lookup.
// Only in the deferred shading pass: its lookups take explicit gradients, valid inside
// a loop whose pixels part ways.
#if defined(RESOLVE) && defined(RULE_CALLS)
vec3 automatic_sparse(float h, float slope, float curvature, vec2 uv, vec4 far0, vec4 far1) {
    // The live rules' weights, materials and variations, slot k for the kth of RULE_CALLS.
    float w[MAX_RULES];
    int mat[MAX_RULES];
    float var[MAX_RULES];
    vec4 got[MAX_RULES]; // the looked-up materials
    int n = 0;
#define R(i, terms) \
    w[n] = rule_weight(i, terms, h, slope, curvature, far0, far1, mat[n], var[n]); \
    got[n] = vec4(0.0); \
    n++;
    RULE_CALLS
#undef R
    uint pending = 0u; // the slots whose material may show
    for (int k = 0; k < n; k++)
        if (k < 2 || w[k] > 0.0) pending |= 1u << uint(k);
    int base = 0; // the lowest slot that shows
    if (n > 0) do { // (a while loop would run its body once more, with no pixel in it)
        int k = findMSB(pending);
        pending &= ~(1u << uint(k));
        int m = 0;
        float v = 0.0, wk = 0.0;
        for (int j = 0; j < n; j++)
            if (j == k) m = mat[j], v = var[j], wk = w[j];
        vec4 a = albedo_varied(m, uv, v);
        for (int j = 0; j < n; j++)
            if (j == k) got[j] = a;
        if (k == 0 || (wk >= 1.0 && max(0.0, a.a) - 0.15 >= 0.0)) base = k, pending = 0u;
    } while (pending != 0u);
    // Bottom up from there, as automatic_varied lays them (a slot of weight 0 above the
    // first blends with a material of no weight: its texture's value is not used).
    vec4 c = vec4(0.45, 0.42, 0.38, 0.5);
    for (int j = 0; j < n; j++)
        if (j >= base) {
            vec4 a = j < 2 || w[j] > 0.0 ? got[j] : vec4(0.0);
            c = j == 0 && w[0] >= 1.0 ? a : vec4(blend2(c, a, w[j]), 0.5);
        }
    return c.rgb;
}
#endif
