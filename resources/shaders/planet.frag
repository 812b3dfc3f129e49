#version 450 core
// A planet's ground and sea with the flat worlds' shading: the automatic material
// rules by height above the datum and slope, parallax-mapped detail near the camera,
// the sun, the sea by Fresnel, and the atmosphere between the camera and the ground.
// Built in variants (renderer/planet_renderer.c picks one per chunk): SHADED (else the
// debug view modes), DETAIL (the detail window covers the chunk), SEA (some of it is
// under the sea), PAINTED (painted weights), BARE (a planet without a sea: bare
// ground), BRUSH (the cursor reaches it), OVERLAYS (a View menu grid is on), MINIFIED
// (so far that the material textures' near scale is below a pixel), SEAM (near a face's
// edge: the neighbouring faces' textures blend in), RULES (the world's material rules lay
// over the planet's look: planet_rules.glsl). A software
// renderer runs every branch of an `if` for every fragment, so what a chunk cannot show
// is left out of its program rather than skipped at run time.
#include "materials.glsl"
#include "planet_atmosphere.glsl"
#include "detail_parallax.glsl"
#include "grid_lines.glsl"
in vec3 v_rel, v_normal, v_up;
in float v_height, v_depth;
in vec2 v_metres;
in vec4 v_paint0, v_paint1; // painted weights: 0 automatic, 1-7 sand, grass, rock, snow, dirt,
                            // gravel, moss
in vec3 v_air, v_transmittance, v_sky_reflected; // the atmosphere, per vertex (planet.vert)
#ifdef SEAM
in vec3 v_other0, v_other1; // other faces' texture metres (xy) and weights (z)
#endif
out vec4 o_colour;
uniform int u_view_mode; // VIEW_SHADED 0, WIREFRAME 1, LEVELS 2, HEIGHT 3, SLOPE 4
uniform int u_level;
uniform float u_ocean_h; // the sea's height above the datum
uniform vec2 u_tex_period; // metres per repeat: near, far
uniform vec4 u_brush;      // the cursor's centre relative to the camera, radius (0: none)
uniform vec3 u_brush_up;   // the local vertical at the cursor
uniform sampler2D u_falloff;
uniform vec4 u_brush_tint; // the tool's colour and opacity
uniform vec3 u_brush_ring;
uniform vec4 u_chunk_detail; // this chunk's detail samples at v_metres (0, 0), samples per
                             // metre, the largest |offset| around it (metres)
uniform int u_overlays;    // 1: the tile grid, 2: the chunks' vertex grids
uniform vec3 u_chunk_tile;  // the face's tiles: v_metres (0, 0) modulo a tile (xy), a tile (z)
uniform vec3 u_chunk_cell;  // the chunk's vertex cells: the same for a cell of its level
uniform sampler2DArray u_normals; // the chunks' normals (renderer/planet_normals.c)
uniform vec4 u_normal_map; // this chunk's: v_metres at its atlas layer's texel 0, texels a
                           // metre, the layer
uniform vec3 u_face_axis;  // its face's s axis (the normals' tangent frame)
uniform vec4 u_face_edges; // its face's edges in v_metres: s = -1, s = 1, t = -1, t = 1
uniform float u_slope_scale; // the slopes the level-0 samples would show over those the
                             // normal texture's coarser ones do (renderer/planet_draw.c)
uniform int u_palette;     // 0: the automatic rules; 1 airless and dry (rock, gravel); 2 dry
                           // with air (sand, dirt, rock)
// The mask editor's overlay, as on flat worlds (render_settings.h mask_*): x on, y invert,
// z the terms drawn (1 height, 2 slope, 4 curvature); each term's corners.
uniform ivec3 u_mask;
uniform vec4 u_mask_height, u_mask_slope, u_mask_curvature; // metres, degrees, -100 x Laplacian

vec3 level_colour(int l) {
    const vec3 c[6] = vec3[6](vec3(0.9, 0.3, 0.3), vec3(0.9, 0.7, 0.2), vec3(0.4, 0.8, 0.3),
                              vec3(0.2, 0.7, 0.8), vec3(0.4, 0.4, 0.9), vec3(0.8, 0.4, 0.8));
    return c[l % 6];
}

// The surface's unit directions of growing face-local metres u and v, perpendicular to
// n, from the screen-space derivatives of the position and the metres (a cotangent
// frame): no per-vertex tangents are stored.
void metre_axes(vec3 n, out vec3 t_axis, out vec3 b_axis) {
    vec3 dp1 = dFdx(v_rel), dp2 = dFdy(v_rel);
    vec2 duv1 = dFdx(v_metres), duv2 = dFdy(v_metres);
    vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
    vec3 t = dp2perp * duv1.x + dp1perp * duv2.x;
    vec3 b = dp2perp * duv1.y + dp1perp * duv2.y;
    t = t - n * dot(n, t);
    t_axis = t * inversesqrt(max(dot(t, t), 1e-30));
    b = b - n * dot(n, b) - t_axis * dot(t_axis, b);
    b_axis = b * inversesqrt(max(dot(b, b), 1e-30));
}

// The View menu's overlays, as on flat worlds: the face's tile edges in white, the
// chunk's vertex grid in its level's colour (every cell close up, every eighth farther).
vec3 with_grids(vec3 c) {
    if ((u_overlays & 2) != 0) {
        vec2 k = (v_metres + u_chunk_cell.xy) / u_chunk_cell.z;
        c = mix(c, level_colour(u_level), 0.7 * max(grid_lines(k), grid_lines(k / 8.0)));
    }
    if ((u_overlays & 1) != 0)
        c = mix(c, vec3(1.0), 0.8 * grid_lines((v_metres + u_chunk_tile.xy) / u_chunk_tile.z));
    return c;
}

#include "planet_curvature.glsl"
#include "planet_rules.glsl"

#if defined(SHADED) && !defined(BARE)
in vec3 v_climate; // planet_climate's moisture, breakup and patches (planet.vert)

// A planet's automatic rules, fit for its scale (the flat worlds' are for a valley) and
// its climate, so that no border follows a contour: warmth falls with latitude and
// height (a lapse rate: the relief's top is as cold as the poles' lowlands), moisture
// from planet_climate (deserts in the subtropics, forest where wet and warm, tundra where
// cold), a beach a few metres wide, bare rock and cliffs on slopes (measured at the
// normal texture's resolution, scaled to what the samples' slopes would be: u_slope_scale),
// alpine ground above the tree line, snow where it is cold enough and not too steep. The
// breakup noise moves every border by region.
vec3 planet_automatic(float h, float slope, float lat_sin, vec2 uv, vec2 uv_far) {
    float range = max(u_max_height - u_ocean_level, 1.0), above = h - u_ocean_level;
    float beach = max(0.002 * range, 2.0), rel = above / range;
    float patches = v_climate.z, wet = v_climate.x + 0.2 * patches, breakup = v_climate.y;
    float warmth = 1.0 - asin(clamp(abs(lat_sin), 0.0, 1.0)) / 1.5708 - 1.35 * max(rel, 0.0) +
                   0.08 * breakup;
    vec4 grass = albedo(1, uv, uv_far), sand = albedo(0, uv, uv_far), dirt = albedo(4, uv, uv_far);
    vec4 gravel = albedo(5, uv, uv_far), moss = albedo(6, uv, uv_far);
    // The lowlands: desert, steppe, grassland, forest by moisture; tundra where cold.
    vec3 desert = sand.rgb * mix(vec3(1.0), vec3(0.86, 0.74, 0.6), 0.5 + 0.5 * breakup);
    // A plain mix over a width of moisture (the texture-height blend drew a hard line),
    // its border broken into patches by the moisture's fine octaves.
    vec3 c = mix(desert, grass.rgb, smoothstep(0.14, 0.5, wet + 0.1 * breakup));
    vec3 forest = grass.rgb * vec3(0.5, 0.62, 0.45);
    c = mix(c, forest, smoothstep(0.5, 0.75, wet) * smoothstep(0.25, 0.45, warmth) * 0.85);
    vec3 tundra = blend2(moss, gravel, clamp(0.5 - breakup, 0.0, 1.0)) * vec3(0.85, 0.82, 0.78);
    c = mix(tundra, c, smoothstep(0.12, 0.3, warmth));
    // Alpine ground above the tree line, then the beach by the sea.
    c = blend2(vec4(c, 0.5), vec4(blend2(dirt, gravel, 0.5), 0.5),
               smoothstep(0.22, 0.1, warmth) * smoothstep(0.08, 0.2, rel));
    c = blend2(vec4(c, 0.5), sand, 1.0 - smoothstep(0.5 * beach, 1.5 * beach, above));
    // Rock on steep ground and on the heights' slopes, cliffs steeper.
    float s = slope * u_slope_scale;
    vec4 rock = albedo(2, uv, uv_far);
    float rocky = max(smoothstep(0.32, 0.6, s + 0.12 * breakup),
                      smoothstep(0.3, 0.55, rel + 0.1 * breakup) * smoothstep(0.08, 0.25, s));
    c = blend2(vec4(c, 0.5), rock, rocky);
    c = blend2(vec4(c, 0.5), albedo(7, uv, uv_far), smoothstep(0.9, 1.3, s));
    // Snow where it is cold enough and the ground flat enough to hold it, both limits
    // broken into patches; a little below white so the light on its slopes is not lost
    // in the exposure's shoulder (flat white fields from orbit).
    // Dry heights get less of it (bare high plateaus, as Tibet's).
    float cold = smoothstep(0.16, 0.05, warmth + 0.07 * patches + 0.08 * (0.5 - wet));
    float holds = 1.0 - smoothstep(0.3, 0.6, s + 0.2 * patches);
    vec4 snow = albedo(3, uv, uv_far);
    snow.rgb *= 0.8 + 0.12 * patches; // wind-packed and drifted
    return blend2(vec4(c, 0.5), snow, cold * holds);
}
#endif

#ifdef SHADED
// The ground's colour before lighting, its textures looked up at uv and uv_far.
vec3 ground_albedo(vec2 uv, vec2 uv_far, float slope, vec3 up) {
    vec3 base;
#ifdef BARE // no sea: bare ground by slope (and height, for dust in the lowlands)
    vec4 low = albedo(u_palette == 1 ? 5 : 0, uv, uv_far), mid = albedo(u_palette == 1 ? 2 : 4, uv, uv_far);
    vec4 steep = albedo(7, uv, uv_far);
    float lowland = 1.0 - smoothstep(-0.4, 0.2, v_height / max(u_max_height, 1e-6));
    vec3 c0 = blend2(mid, low, lowland);
    base = blend2(vec4(c0, 0.5), steep, smoothstep(0.5, 1.0, slope * u_slope_scale));
    if (u_palette == 2) base *= vec3(1.15, 0.78, 0.58); // iron-red dust
    else base = vec3(dot(base, vec3(0.3, 0.5, 0.2))) * 0.9; // grey regolith
    if (u_palette == 2) { // Mars-like: ice caps at the poles
        float cap = smoothstep(0.93, 0.97, abs(up.y)) * (1.0 - smoothstep(0.6, 0.9, slope));
        base = blend2(vec4(base, 0.5), vec4(vec3(0.92, 0.9, 0.88), 0.5), cap);
    }
#else
    base = planet_automatic(v_height, slope, up.y, uv, uv_far);
#endif
#ifdef RULES
    base = planet_rules(base, v_height, slope * u_slope_scale, up, uv, uv_far);
#endif
#ifdef PAINTED // as the flat viewport blends the weights
    base = base * v_paint0.x + albedo(0, uv, uv_far).rgb * v_paint0.y +
           albedo(1, uv, uv_far).rgb * v_paint0.z + albedo(2, uv, uv_far).rgb * v_paint0.w +
           albedo(3, uv, uv_far).rgb * v_paint1.x + albedo(4, uv, uv_far).rgb * v_paint1.y +
           albedo(5, uv, uv_far).rgb * v_paint1.z + albedo(6, uv, uv_far).rgb * v_paint1.w;
#endif
    return base;
}
#endif

// The ground's normal from the chunk's normal texture (heights finer than its vertices):
// its components along the face's s axis and across it in the tangent plane. Within a
// texel of the face's edge it turns into the vertices' normal, which is the same from
// every face there: the faces' texels do not line up across an edge near a cube corner,
// and on ground rough at the samples' scale the two sides' normals differed (a step in
// the light along the edge).
vec3 fine_normal(vec3 up) {
    vec2 st = (v_metres - u_normal_map.xy) * u_normal_map.z / vec2(textureSize(u_normals, 0).xy);
    vec2 g = texture(u_normals, vec3(st, u_normal_map.w)).rg;
    vec3 t = normalize(u_face_axis - up * dot(up, u_face_axis)), b = cross(up, t);
    vec3 fine = g.x * t + g.y * b + sqrt(max(1.0 - dot(g, g), 0.0)) * up;
    vec2 lo = v_metres - u_face_edges.xz, hi = u_face_edges.yw - v_metres;
    float edge = min(min(lo.x, lo.y), min(hi.x, hi.y)) * u_normal_map.z;
    return normalize(mix(normalize(v_normal), fine, clamp(edge, 0.0, 1.0)));
}

#ifdef OVERLAYS
// Where the edited mask lets its layer apply: tinted there, dimmed elsewhere (the terms
// of editor/layers/layer_mask.h over the drawn surface; slopes scaled to the samples').
vec3 with_mask(vec3 c, float slope, vec3 up) {
    float w = 1.0;
    if ((u_mask.z & 1) != 0) w *= rule_term(u_mask_height, v_height);
    if ((u_mask.z & 2) != 0) w *= rule_term(u_mask_slope, degrees(atan(slope * u_slope_scale)));
    if ((u_mask.z & 4) != 0) w *= rule_term(u_mask_curvature, curvature_here(up));
    if (u_mask.y != 0) w = 1.0 - w;
    return mix(c * 0.4, mix(c, vec3(1.0, 0.2, 0.55), 0.45), w);
}
#endif

void main() {
    vec3 up = normalize(v_up), n = fine_normal(up);
    float dist = length(v_rel);
    vec3 view_dir = v_rel / max(dist, 1e-6);
    float cos_slope = clamp(dot(n, up), 0.05, 1.0);
    float slope = sqrt(max(1.0 - cos_slope * cos_slope, 0.0)) / cos_slope; // rise over run
    // Detail near the camera: parallax shifts the texture lookups, the detail's slopes
    // tilt the normal (the slope rules keep the coarse surface's, as on flat worlds).
    vec2 shift_m = vec2(0.0);
#ifdef DETAIL
    {
        vec3 t_axis, b_axis;
        metre_axes(n, t_axis, b_axis);
        float fade = detail_fade(dist);
        vec2 dt = u_chunk_detail.xy + v_metres * u_chunk_detail.z;
        if (fade > 0.0 && in_detail_window(dt)) {
            vec3 to_eye = -view_dir;
            vec3 v = vec3(dot(to_eye, t_axis), dot(to_eye, b_axis), dot(to_eye, n));
            vec2 tc = detail_parallax(dt, v, fade);
            shift_m = (tc - dt) / u_chunk_detail.z;
            vec2 ds = detail_slopes(tc, fade);
            n = normalize(n - t_axis * ds.x - b_axis * ds.y);
        }
    }
#endif
    // The light on ground whose normal texture is coarse: its slopes steepened part of the
    // way back to the samples' (u_slope_scale), so ranges seen from far off keep the
    // relief their finer ground has instead of reading as smooth domes.
    vec3 lit_n = normalize(up + (n - up * dot(n, up)) * clamp(sqrt(u_slope_scale), 1.0, 2.5) /
                                    max(dot(n, up), 0.05));
    float diffuse = max(dot(lit_n, u_sun_dir), 0.0);
    float day = smoothstep(-0.1, 0.2, dot(up, u_sun_dir));
    vec3 ambient = vec3(0.10, 0.13, 0.18) * (0.25 + 0.75 * day);
#ifndef SHADED
    if (u_view_mode == 1) {
        o_colour = vec4(0.75, 0.85, 0.95, 1.0);
        return;
    }
    vec3 base = u_view_mode == 3 ? vec3(clamp(v_height / (2.0 * u_max_height) + 0.5, 0.0, 1.0))
              : u_view_mode == 4
                  ? mix(vec3(0.2, 0.6, 0.3), vec3(0.8, 0.2, 0.1), clamp(slope, 0.0, 1.5) / 1.5)
                  : level_colour(u_level);
    vec3 c = base * (ambient + u_sun_colour * diffuse);
#else
    vec2 uv = (v_metres + shift_m) / u_tex_period.x, uv_far = v_metres / u_tex_period.y;
vec3 base = ground_albedo(uv, uv_far, slope, up);
#ifdef SEAM // weights that depend on the point alone: both sides of an edge mix alike
    base *= 1.0 - v_other0.z - v_other1.z;
    if (v_other0.z > 0.0)
        base += v_other0.z * ground_albedo(v_other0.xy / u_tex_period.x,
                                           v_other0.xy / u_tex_period.y, slope, up);
    if (v_other1.z > 0.0)
        base += v_other1.z * ground_albedo(v_other1.xy / u_tex_period.x,
                                           v_other1.xy / u_tex_period.y, slope, up);
#endif
    vec3 c = base * (ambient + u_sun_colour * diffuse);
#ifdef SEA
    if (v_depth > 0.0) {
        vec3 to_eye = -view_dir;
        float fresnel = 0.02 + 0.98 * pow(1.0 - max(dot(up, to_eye), 0.0), 5.0);
        vec3 deep = mix(vec3(0.03, 0.16, 0.22), vec3(0.01, 0.05, 0.10),
                        clamp(v_depth / max(u_max_height * 0.3, 1e-3), 0.0, 1.0));
        vec3 sky = v_sky_reflected + vec3(0.02, 0.03, 0.05) * day;
        c = mix(deep * (0.3 + 0.7 * day), sky, fresnel);
        vec3 h = normalize(u_sun_dir + to_eye);
        c += u_sun_colour * pow(max(dot(up, h), 0.0), 800.0) * 0.8 * day;
    }
#endif
#endif
#ifdef BRUSH // the brush, draped: distance on the local level
    {
        vec3 d = v_rel - u_brush.xyz;
        d -= u_brush_up * dot(d, u_brush_up);
        float r = length(d) / u_brush.w, fw = max(fwidth(r), 1e-4);
        if (r < 1.0) c = mix(c, u_brush_tint.rgb, u_brush_tint.a * texture(u_falloff, vec2(r, 0.5)).r);
        float ring = 1.0 - smoothstep(0.0, 1.5 * fw, abs(r - 1.0));
        float centre = 1.0 - smoothstep(0.0, 1.5 * fw, r - 0.02);
        c = mix(c, u_brush_ring, max(ring, centre));
    }
#endif
#ifdef OVERLAYS
    c = with_grids(c);
    if (u_mask.x != 0) c = with_mask(c, slope, up);
#endif
#ifdef SHADED // the air between the camera and the ground
    {
        c = c * v_transmittance + v_air * 0.6; // the sky's light, less bright over ground
        c = 1.0 - exp(-c * 1.8); // exposure (the sky uses the same curve)
    }
#endif
    o_colour = vec4(c, 1.0);
}
