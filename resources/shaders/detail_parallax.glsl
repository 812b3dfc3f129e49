// Detail near the camera, shared by the flat and the planet viewports: the detail
// layer's heights and slopes in a toroidal window, and iterative parallax with offset
// limiting over them (Crause 2010 4.4.3), faded out with distance.
uniform sampler2D u_detail;     // detail heights (metres), toroidal
uniform sampler2D u_detail_pd;  // detail slopes (RG16 snorm, x 8)
uniform vec2 u_detail_wrap;     // texel of the detail window's origin sample
uniform float u_detail_spacing; // metres between detail samples
uniform int u_detail_size;
uniform int u_parallax;         // on/off
uniform int u_parallax_steps;   // iterations (the quality setting)
uniform float u_parallax_fade;  // metres: detail fades out by this distance

// How much of the detail shows at this distance from the camera.
float detail_fade(float dist) {
    return 1.0 - smoothstep(u_parallax_fade * 0.6, u_parallax_fade, dist);
}

// dt: detail samples from the window's origin; inside the window with a sample's margin.
bool in_detail_window(vec2 dt) {
    float size = float(u_detail_size);
    return all(greaterThanEqual(dt, vec2(1.0))) && all(lessThan(dt, vec2(size - 2.0)));
}

// Where the eye meets the detail relief seen at dt. v: the direction to the eye in the
// tangent frame (x, y along the detail grid's axes, z along the normal). Offset
// limiting: at most a few detail samples from dt.
vec2 detail_parallax(vec2 dt, vec3 v, float fade) {
    if (u_parallax == 0) return dt;
    float size = float(u_detail_size);
    vec3 p = vec3(dt, 0.0);
    float limit = 6.0;
    for (int i = 0; i < u_parallax_steps; i++) {
        float dh = texture(u_detail, (p.xy + u_detail_wrap + 0.5) / size).r * fade;
        vec3 step_v = (dh - p.z) * vec3(v.xy / u_detail_spacing, v.z);
        p += step_v;
        vec2 o = p.xy - dt;
        float len = length(o);
        if (len > limit) p.xy = dt + o * (limit / len);
    }
    return p.xy;
}

// The detail's slopes at tc (rise over run along the grid's axes), faded.
vec2 detail_slopes(vec2 tc, float fade) {
    float size = float(u_detail_size);
    return texture(u_detail_pd, (tc + u_detail_wrap + 0.5) / size).rg * 8.0 * fade;
}
