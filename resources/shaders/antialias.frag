#version 450 core
// Edge anti-aliasing of the finished terrain image (the idea of Lottes' FXAA, 2009):
// where the brightness jumps across a pixel, find the edge's direction (along rows or
// columns), follow the edge both ways to where it ends, and take the pixel's colour
// from across the edge in proportion to how far it lies from the nearer end: a long,
// nearly horizontal edge such as the horizon becomes a smooth ramp instead of steps.
// Inputs are sampled with linear filtering, so a sample half a pixel across an edge
// reads the mean of both sides. The loop has a fixed count: a software renderer runs
// every path anyway.
in vec2 v_ndc;
out vec4 o_colour;
uniform sampler2D u_image;
uniform vec2 u_texel; // 1 / the image's size

const float EDGE_MIN = 0.04;      // brightness range below which nothing is an edge
const float EDGE_RELATIVE = 0.12; // ... or below this share of the brightest neighbour
const int SEARCH_STEPS = 5;

float luma(vec3 c) {
    return dot(c, vec3(0.299, 0.587, 0.114));
}

float luma_at(vec2 uv) {
    return luma(textureLod(u_image, uv, 0.0).rgb);
}

void main() {
    vec2 uv = v_ndc * 0.5 + 0.5;
    vec3 centre = textureLod(u_image, uv, 0.0).rgb;
    float m = luma(centre);
    float n = luma_at(uv + vec2(0.0, u_texel.y)), s = luma_at(uv - vec2(0.0, u_texel.y));
    float e = luma_at(uv + vec2(u_texel.x, 0.0)), w = luma_at(uv - vec2(u_texel.x, 0.0));
    float lo = min(m, min(min(n, s), min(e, w))), hi = max(m, max(max(n, s), max(e, w)));
    float range = hi - lo;
    float ne = luma_at(uv + u_texel), sw = luma_at(uv - u_texel);
    float nw = luma_at(uv + vec2(-u_texel.x, u_texel.y)), se = luma_at(uv + vec2(u_texel.x, -u_texel.y));

    // Which way the edge runs: brightness changing across rows means a horizontal edge.
    float across_rows = 2.0 * abs(n + s - 2.0 * m) + abs(ne + se - 2.0 * e) + abs(nw + sw - 2.0 * w);
    float across_cols = 2.0 * abs(e + w - 2.0 * m) + abs(ne + nw - 2.0 * n) + abs(se + sw - 2.0 * s);
    bool horizontal = across_rows >= across_cols;
    float before = horizontal ? s : w, after = horizontal ? n : e;
    bool to_before = abs(before - m) >= abs(after - m); // the steeper side holds the edge
    float other = to_before ? before : after;
    float gradient = abs(other - m);
    vec2 normal = horizontal ? vec2(0.0, u_texel.y) : vec2(u_texel.x, 0.0);
    if (to_before) normal = -normal;
    vec2 along = horizontal ? vec2(u_texel.x, 0.0) : vec2(0.0, u_texel.y);

    // Along the edge (half a pixel over, between the two sides) until the mean there
    // leaves the edge's own: an end of the edge on each side.
    float edge_luma = 0.5 * (m + other);
    vec2 on_edge = uv + 0.5 * normal;
    vec2 p1 = on_edge - along, p2 = on_edge + along;
    float d1 = luma_at(p1) - edge_luma, d2 = luma_at(p2) - edge_luma;
    bool end1 = abs(d1) >= 0.25 * gradient, end2 = abs(d2) >= 0.25 * gradient;
    const float stride[SEARCH_STEPS] = float[](1.5, 2.0, 4.0, 8.0, 16.0);
    for (int i = 0; i < SEARCH_STEPS; i++) {
        if (!end1) {
            p1 -= along * stride[i];
            d1 = luma_at(p1) - edge_luma;
            end1 = abs(d1) >= 0.25 * gradient;
        }
        if (!end2) {
            p2 += along * stride[i];
            d2 = luma_at(p2) - edge_luma;
            end2 = abs(d2) >= 0.25 * gradient;
        }
    }
    float dist1 = horizontal ? uv.x - p1.x : uv.y - p1.y;
    float dist2 = horizontal ? p2.x - uv.x : p2.y - uv.y;
    bool nearer1 = dist1 < dist2;
    float nearest = min(dist1, dist2), span = dist1 + dist2;
    // Blend only on the side of the end where the edge turns toward this pixel's
    // brightness (else the pixel is already on the right side of the ramp).
    bool centre_darker = m < edge_luma;
    bool turns = ((nearer1 ? d1 : d2) < 0.0) != centre_darker;
    float offset = turns ? 0.5 - nearest / span : 0.0;
    // Sub-pixel: a lone bright or dark pixel blends toward its neighbours' mean.
    float mean = (2.0 * (n + s + e + w) + ne + nw + se + sw) / 12.0;
    float lone = clamp(abs(mean - m) / max(range, 1e-5), 0.0, 1.0);
    lone = smoothstep(0.0, 1.0, lone);
    offset = max(offset, lone * lone * 0.6);
    vec3 smoothed = textureLod(u_image, uv + offset * normal, 0.0).rgb;
    bool edge = range >= max(EDGE_MIN, hi * EDGE_RELATIVE);
    o_colour = vec4(edge ? smoothed : centre, 1.0);
}
