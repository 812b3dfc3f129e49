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
vec4 albedo_varied(int layer, vec2 uv, float v) {
#ifdef MINIFIED
    vec4 near_c = u_albedo_mean[layer];
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

// Harris 2011's four materials by height and slope: sand by the water, grass, rock on
// steep ground, snow up high; cliff rock where it is steeper still. far0, far1: the far
// scale's values of materials 0-3 and 4-7. A caller that knows rock, cliff or snow has
// no weight anywhere it draws leaves it out (NO_ROCK, NO_CLIFF, NO_SNOW: the rest blends
// as before, up to rounding).
vec3 automatic_varied(float h, float slope, vec2 uv, vec4 far0, vec4 far1) {
    float beach = u_ocean_level + max(u_max_height * 0.015, 2.0);
    vec3 c = blend2(albedo_varied(0, uv, far0.x), albedo_varied(1, uv, far0.y),
                    smoothstep(beach - 2.0, beach + 4.0, h));
#ifndef NO_ROCK
    c = blend2(vec4(c, 0.5), albedo_varied(2, uv, far0.z), smoothstep(0.55, 0.85, slope));
#endif
#ifndef NO_CLIFF
    c = blend2(vec4(c, 0.5), albedo_varied(7, uv, far1.w), smoothstep(1.1, 1.5, slope));
#endif
#ifndef NO_SNOW
    float snow_line = u_ocean_level + (u_max_height - u_ocean_level) * 0.62;
    float snowy = smoothstep(snow_line - 40.0, snow_line + 40.0, h) * (1.0 - smoothstep(0.55, 0.8, slope));
    c = blend2(vec4(c, 0.5), albedo_varied(3, uv, far0.w), snowy);
#endif
    return c;
}

vec3 automatic(float h, float slope, vec2 uv, vec2 uv_far) {
    vec4 far0 = vec4(far_variation(0, uv_far), far_variation(1, uv_far), far_variation(2, uv_far),
                     far_variation(3, uv_far));
    return automatic_varied(h, slope, uv, far0, vec4(0.0, 0.0, 0.0, far_variation(7, uv_far)));
}
