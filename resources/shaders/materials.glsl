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

vec4 albedo(int layer, vec2 uv, vec2 uv_far) {
    return albedo_varied(layer, uv, texture(u_albedo, vec3(uv_far, float(layer))).g);
}

// Height-aware blend: the material whose texture stands higher wins at the border.
vec3 blend2(vec4 a, vec4 b, float t) {
    float ha = a.a * (1.0 - t), hb = b.a * t;
    float m = max(ha, hb) - 0.15;
    float wa = max(ha - m, 0.0) + (1.0 - t) * 0.01, wb = max(hb - m, 0.0) + t * 0.01;
    return (a.rgb * wa + b.rgb * wb) / (wa + wb);
}

// Harris 2011's four materials by height and slope: sand by the water, grass, rock on
// steep ground, snow up high; cliff rock where it is steeper still.
vec3 automatic_of(float h, float slope, vec4 sand, vec4 grass, vec4 rock, vec4 snow, vec4 cliff) {
    float beach = u_ocean_level + max(u_max_height * 0.015, 2.0);
    float snow_line = u_ocean_level + (u_max_height - u_ocean_level) * 0.62;
    vec3 c = blend2(sand, grass, smoothstep(beach - 2.0, beach + 4.0, h));
    c = blend2(vec4(c, 0.5), rock, smoothstep(0.55, 0.85, slope));
    c = blend2(vec4(c, 0.5), cliff, smoothstep(1.1, 1.5, slope));
    float snowy = smoothstep(snow_line - 40.0, snow_line + 40.0, h) * (1.0 - smoothstep(0.55, 0.8, slope));
    return blend2(vec4(c, 0.5), snow, snowy);
}

vec3 automatic(float h, float slope, vec2 uv, vec2 uv_far) {
    return automatic_of(h, slope, albedo(0, uv, uv_far), albedo(1, uv, uv_far),
                        albedo(2, uv, uv_far), albedo(3, uv, uv_far), albedo(7, uv, uv_far));
}
