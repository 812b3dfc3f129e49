#version 450 core
// Terrain shading: normals from the heights' partial derivatives (Crause 2010's PD
// normals), 8-layer material splatting over the automatic material rules
// (materials.glsl), parallax-mapped detail near the camera (detail_parallax.glsl), sun,
// fog, the brush cursor and the debug views.
// Built in variants (renderer/terrain_renderer.c picks one per clipmap level): SHADED
// (else the debug views), DETAIL (the level has detail), PAINTED (the level's
// material window holds paint), BRUSH (the cursor shows), OVERLAYS (a View menu grid), CONTOURS. A software
// renderer runs every branch of an `if` for every fragment, so what a level cannot show
// is left out of its program rather than skipped at run time.
// Deferred (renderer/deferred_target.h): GBUFFER draws the clipmap's triangles writing
// only their depth; RESOLVE shades every pixel once, the ground's place found from
// that depth, in a full-screen pass per level (llvmpipe shades at least 8 pixels a
// triangle touches, and the far levels' triangles cover only a few each).
#include "terrain_common.glsl"
#include "lighting.glsl"
#include "colour_ramp.glsl"
#include "materials.glsl"
#include "rules_sparse.glsl"
#include "volume_mask.glsl"
#include "detail_parallax.glsl"
#include "grid_lines.glsl"

#ifdef RESOLVE
vec2 v_local; // the ground seen in this pixel, from the depth drawn there
vec3 v_rel;
uniform sampler2D u_ground_depth; // the G-buffer: the depth drawn (0: no ground)
uniform mat4 u_inv_view_proj;     // clip space to camera-relative metres
// The ground's step (camera-relative metres) to the next pixel right and up, standing in
// for screen derivatives: a neighbouring pixel may hold another level or no ground.
vec3 g_step_x, g_step_y;

// Where the ground seen in pixel p is (camera-relative metres); false where none is.
bool ground_at_pixel(ivec2 p, out vec3 rel) {
    ivec2 size = textureSize(u_ground_depth, 0);
    float d = texelFetch(u_ground_depth, clamp(p, ivec2(0), size - 1), 0).r;
    vec4 q = u_inv_view_proj * vec4((vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0, d, 1.0);
    rel = q.xyz / q.w;
    return d > 0.0 && all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, size));
}
#else
in vec2 v_local_vs; // as the vertex shader placed them: on the level's surface
in vec3 v_rel_vs;
vec2 v_local;       // the ground shaded (toward_finer_ground moves it)
vec3 v_rel;
#endif
out vec4 o_colour;

// Views (renderer/terrain_renderer.h view_mode).
#define VIEW_SHADED 0
#define VIEW_WIREFRAME 1
#define VIEW_LEVELS 2
#define VIEW_HEIGHT 3
#define VIEW_SLOPE 4
uniform int u_view_mode;

uniform vec4 u_lvl_bounds[MAX_LEVELS]; // the world's extent in local units (x0, z0, x1, z1)
uniform vec4 u_lvl_uv[MAX_LEVELS];     // local (0,0) in metres modulo the texture periods
uniform vec4 u_lvl_mat[MAX_LEVELS];    // painted weights: window texel of local (0,0), texels per unit, layer (-1: none)
uniform vec4 u_lvl_mat_b[MAX_LEVELS];  // the same from the next coarser level (morph target)
uniform ivec4 u_lvl_mat_wrap[MAX_LEVELS]; // toroidal texel of those windows' origins (xy, zw)
uniform vec4 u_lvl_grid[MAX_LEVELS];   // tile grid: local (0,0) modulo a tile (xy), a tile in units (z; 0: none)
uniform int u_overlays;                // 1: the tile grid, 2: the clipmap level grids
uniform int u_auto_materials;          // 0: unpainted ground in a neutral clay
uniform vec4 u_lvl_detail[MAX_LEVELS]; // detail: sample of local (0,0), samples per unit, valid
uniform vec2 u_tex_period;             // metres per repeat: near texture, far variation
uniform sampler2DArray u_albedo_far;   // the materials' green channels, 4 a layer (materials.glsl far_of)

uniform usampler2DArray u_material;    // 8 x uint8 weights per texel (RG32UI), a layer per level, toroidal
uniform vec4 u_brush;                  // centre relative to the camera (xz), radius, visible
uniform sampler2D u_falloff;           // the brush's falloff curve over 0..1 of the radius (64x1)
uniform vec4 u_brush_tint;              // the tool's colour, and its opacity (follows strength)
uniform vec3 u_brush_ring;              // the colour of its edge and centre
uniform vec3 u_level_tint[MAX_LEVELS];
uniform float u_contour;               // metres between contour lines; 0: none
// The mask editor's overlay (render_settings.h mask_*): x on, y invert, z the terms drawn
// (1 height, 2 slope, 4 curvature, 8 flow); each term's corners as rule_term reads them.
uniform ivec3 u_mask;
uniform vec4 u_mask_height, u_mask_slope, u_mask_curvature; // metres, degrees, -100 x Laplacian
uniform vec4 u_mask_flow;              // m2 of upstream area
uniform vec4 u_mask_flow_area;         // the flow field's first sample relative to the camera
                                       // (xy), samples a metre (z), 1 when there is one (w)
uniform sampler2D u_mask_flow_field;   // m2 a sample (renderer/mask_flow_texture.h)

// Contour lines every u_contour metres of height, one pixel or so wide; faded out where
// they would crowd (a steep slope seen from afar).
vec3 with_contours(vec3 c, float h) {
#ifndef CONTOURS
    return c;
#endif
    if (u_contour <= 0.0) return c;
    float k = h / u_contour;
#ifdef RESOLVE
    float fw = max((abs(g_step_x.y) + abs(g_step_y.y)) / u_contour, 1e-5);
#else
    float fw = max(fwidth(k), 1e-5);
#endif
    float line = 1.0 - smoothstep(0.0, 1.2 * fw, abs(fract(k + 0.5) - 0.5));
    float crowd = 1.0 - smoothstep(0.15, 0.35, fw);
    return mix(c, vec3(0.06, 0.05, 0.04), 0.65 * line * crowd);
}

// The View menu's overlays: the world's tile edges in white, each clipmap level's vertex
// grid in its level's colour (Terrain3D's region and vertex grids), so the rings where
// the level (and the vertex spacing) changes show.
vec3 with_grids(vec3 c) {
#ifndef OVERLAYS
    return c;
#endif
#ifdef RESOLVE
    vec2 fw = (abs(g_step_x.xz) + abs(g_step_y.xz)) / u_lvl_offset[u_level].z;
#else
    vec2 fw = fwidth(v_local);
#endif
    if ((u_overlays & 2) != 0) // every vertex close up, every eighth farther out
        c = mix(c, u_level_tint[u_level], 0.7 * max(grid_lines_across(v_local, fw), grid_lines_across(v_local / 8.0, fw / 8.0)));
    vec4 g = u_lvl_grid[u_level];
    if ((u_overlays & 1) != 0 && g.z > 0.0)
        c = mix(c, vec3(1.0), 0.8 * grid_lines_across((v_local + g.xy) / g.z, fw / g.z));
    return c;
}

// The flow term from the field read around the view; -1 beyond it (not known there).
float flow_term() {
    if (u_mask_flow_area.w == 0.0) return -1.0;
    vec2 size = vec2(textureSize(u_mask_flow_field, 0));
    vec2 st = ((v_rel.xz - u_mask_flow_area.xy) * u_mask_flow_area.z + 0.5) / size;
    if (any(lessThan(st, vec2(0.0))) || any(greaterThan(st, vec2(1.0)))) return -1.0;
    return rule_term(u_mask_flow, texture(u_mask_flow_field, st).r);
}

// Where the edited mask lets its layer apply: tinted there, dimmed elsewhere (the
// terms of editor/layers/layer_mask.h over the drawn surface; flow from its field, and
// where the field does not reach the ground is left as it is).
vec3 with_mask(vec3 c, float h, float slope, float curvature) {
    float w = 1.0;
    if ((u_mask.z & 1) != 0) w *= rule_term(u_mask_height, h);
    if ((u_mask.z & 2) != 0) w *= rule_term(u_mask_slope, degrees(atan(slope)));
    if ((u_mask.z & 4) != 0) w *= rule_term(u_mask_curvature, curvature);
    if ((u_mask.z & 8) != 0) {
        float f = flow_term();
        if (f < 0.0) return c; // beyond the flow read: neither tinted nor dimmed
        w *= f;
    }
    if (u_mask.y != 0) w = 1.0 - w;
    return mix(c * 0.4, mix(c, vec3(1.0, 0.2, 0.55), 0.45), w);
}

// Central differences clamped to the level's window (past its edge the toroidal texture
// holds samples from the far side): a source texel apart on level 0, as the
// full-resolution mesh's vertex normals; half a texel apart on the coarser levels, the
// mean slope under one of their texels (a texel apart blurred it over two, which cost
// RMSE against the full-resolution mesh).
// fine: from the finer heights (SLOPES_A, SLOPES_B: the renderer knows which levels
// have them). Levels 1 and 2's hold level 0's samples (fine.w, the source level, up to
// CLIP_SLOPES_SHIFT: clip_slopes.h): a sample apart. The others hold a mip's: seen from
// above, where the pixel's place on them (toward_finer_ground) is near enough, half a
// texel apart (the mean slope under a texel); at grazing views, where one step leaves
// it further off, a texel apart (the smoother slope); in between, in between (rays 6 to
// 17 degrees down). bench_render 7's distant view 2.70 -> 2.47; half a texel at every
// angle made low views worse (2.19 -> 2.24 from 30 m up).
vec2 gradient_at(vec4 src, vec4 fine, vec2 p, float spacing_here, bool from_fine) {
    if (from_fine) {
        vec2 t = fine.xy + p * fine.z + 0.5;
        float SLOPES_SIZE = float(textureSize(u_slopes, 0).x);
        float down = -normalize(v_rel).y; // the sine of the view ray's angle below level
        float a = fine.w > 2.0 ? mix(1.0, 0.5, smoothstep(0.1, 0.3, down)) : 1.0; // texels either side
        float l = texture(u_slopes, vec3((t - vec2(a, 0.0)) / SLOPES_SIZE, fine.w)).r;
        float r = texture(u_slopes, vec3((t + vec2(a, 0.0)) / SLOPES_SIZE, fine.w)).r;
        float d = texture(u_slopes, vec3((t - vec2(0.0, a)) / SLOPES_SIZE, fine.w)).r;
        float u = texture(u_slopes, vec3((t + vec2(0.0, a)) / SLOPES_SIZE, fine.w)).r;
        return vec2(r - l, u - d) * (fine.z / (2.0 * a * spacing_here));
    }
    float texel = (src.w == 0.0 ? 1.0 : 0.5) / src.z; // in local units
    vec2 lo = max(p - texel, vec2(0.0)), hi = min(p + texel, vec2(CLIP_SIZE - 1.0));
    float l = sample_height(src, vec2(lo.x, p.y)), r = sample_height(src, vec2(hi.x, p.y));
    float d = sample_height(src, vec2(p.x, lo.y)), u = sample_height(src, vec2(p.x, hi.y));
    return vec2(r - l, u - d) / ((hi - lo) * spacing_here);
}

// A coarse level's surface stands off the full-resolution ground (its samples are 2^L
// apart), so at a grazing view the place a pixel shows on it lies metres to tens of
// metres along the view ray from the ground the full-resolution mesh shows there, and
// the finer slopes and height read at that place belong to other ground (finer slopes
// on the coarse surface moved the error more than they removed it). One Newton step of
// the ray against the finer heights (parallax mapping over the level's own surface)
// finds where it meets them: the distance to move along the ray, metres, at most 3/4 of
// the level's spacing (the slopes window's margin: clip_slopes.h). 0 on ground turned
// away or seen edge-on, where the step would not converge.
float toward_finer_ground(vec4 src, vec4 fine, vec2 p, vec3 rel, float spacing_here) {
    vec3 dir = normalize(rel);
    vec2 t = (fine.xy + p * fine.z + 0.5) / float(textureSize(u_slopes, 0).x);
    float above = rel.y + u_cam_y - texture(u_slopes, vec3(t, fine.w)).r;
    vec2 g = gradient_at(src, fine, p, spacing_here, true);
    float rate = dir.y - dot(g, dir.xz); // d(above) per metre along the ray
    float along = rate < -0.05 ? -above / rate : 0.0;
    return clamp(along, -0.75 * spacing_here, 0.75 * spacing_here);
}

// The rules' curvature: -100 x the Laplacian (1/m) over the level's samples, positive on
// convex ground; coarser levels see broader shapes.
float curvature_at(vec4 src, vec2 p, float spacing_here) {
    float texel = 1.0 / src.z;
    vec2 lo = max(p - texel, vec2(0.0)), hi = min(p + texel, vec2(CLIP_SIZE - 1.0));
    float c = sample_height(src, p);
    float l = sample_height(src, vec2(lo.x, p.y)), r = sample_height(src, vec2(hi.x, p.y));
    float d = sample_height(src, vec2(p.x, lo.y)), u = sample_height(src, vec2(p.x, hi.y));
    float step_m = texel * spacing_here;
    return -100.0 * (l + r + d + u - 4.0 * c) / (step_m * step_m);
}

#ifdef RESOLVE
// The step in camera-relative metres (xz) to the next pixel along `axis`: the smaller of
// the steps to either side that holds ground, as the triangle's own plane would give
// (a step across a silhouette or into the sky is not the surface's).
// A neighbour's step is taken where it agrees with the step on the plane through this
// pixel's ground along its normal n; where neither does (across a silhouette, a ridge a
// pixel thin, or a slope seen edge-on, whose plane the smooth normal misses), the
// shortest of the three.
vec3 ground_step(ivec2 px, ivec2 axis, vec3 n) {
    vec3 a, b;
    bool use_a = ground_at_pixel(px + axis, a), use_b = ground_at_pixel(px - axis, b);
    vec3 da = a - v_rel, db = v_rel - b;
    ivec2 size = textureSize(u_ground_depth, 0);
    vec4 q = u_inv_view_proj * vec4((vec2(px + axis) + 0.5) / vec2(size) * 2.0 - 1.0, 1.0, 1.0);
    vec3 ray = q.xyz / q.w;
    float t = dot(v_rel, n) / dot(ray, n);
    if (t > 0.0) { // the neighbour's ray meets the plane
        vec3 plane = ray * t - v_rel;
        float near2 = 0.5 * dot(plane, plane);
        bool agree_a = use_a && dot(da - plane, da - plane) < near2;
        bool agree_b = use_b && dot(db - plane, db - plane) < near2;
        if (!agree_a && !agree_b) {
            vec3 best = plane;
            if (use_a && dot(da, da) < dot(best, best)) best = da;
            if (use_b && dot(db, db) < dot(best, best)) best = db;
            return best;
        }
        use_a = agree_a, use_b = agree_b;
    }
    if (use_a && use_b) return dot(da, da) <= dot(db, db) ? da : db;
    return use_a ? da : use_b ? db : vec3(0.0);
}
#endif

vec4 unpack4(uint v) {
    return vec4(float(v & 255u), float((v >> 8) & 255u), float((v >> 16) & 255u), float(v >> 24));
}

// The 8 painted weights (sum 1) at local point p, bilinear between the samples of a
// level's material window (lm, wrap: u_lvl_mat*). False, with the weights of unpainted
// ground, where the window has none (no paint there, or p outside it).
bool painted_weights(vec4 lm, ivec2 wrap, vec2 p, out vec4 w0, out vec4 w1) {
    w0 = vec4(1.0, 0.0, 0.0, 0.0), w1 = vec4(0.0);
    vec2 t = lm.xy + p * lm.z;
    if (lm.w < 0.0 || any(lessThan(t, vec2(0.0))) || any(greaterThanEqual(t, vec2(CLIP_SIZE - 1.0))))
        return false;
    ivec2 i = ivec2(floor(t));
    vec2 a = t - vec2(i);
    w0 = vec4(0.0);
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        float wt = (o.x == 1 ? a.x : 1.0 - a.x) * (o.y == 1 ? a.y : 1.0 - a.y);
        uvec2 v = texelFetch(u_material, ivec3((i + o + wrap) & 255, int(lm.w)), 0).rg;
        w0 += unpack4(v.x) * wt;
        w1 += unpack4(v.y) * wt;
    }
    w0 /= 255.0, w1 /= 255.0;
    return true;
}

void main() {
    vec4 off = u_lvl_offset[u_level];
#ifdef RESOLVE
    ivec2 px = ivec2(gl_FragCoord.xy);
    ground_at_pixel(px, v_rel);
    v_local = (v_rel.xz - off.xy) / off.z;
#else
    v_local = v_local_vs, v_rel = v_rel_vs;
#ifndef INSIDE
    vec4 bounds = u_lvl_bounds[u_level];
    if (v_local.x < bounds.x || v_local.y < bounds.y || v_local.x > bounds.z || v_local.y > bounds.w)
        discard; // outside a bounded world
#endif
#ifdef VOLUME
    if (replaced_by_volume(v_rel)) discard; // the volume mesh draws the ground here
#endif
#endif
#ifdef GBUFFER
    o_colour = vec4(gl_FragCoord.z);
    return;
#endif
    float spacing = off.z;
    float alpha = morph_factor(v_local);
    const vec3 rel_drawn = v_rel;
    { // onto the finer ground, as far as the morph toward the coarser level's has gone
        float along = 0.0;
#ifdef SLOPES_A
        along = toward_finer_ground(u_lvl_src_a[u_level], u_lvl_slopes_a[u_level], v_local, v_rel, spacing);
#endif
#ifdef SLOPES_B
        if (alpha > 0.0)
            along = mix(along, toward_finer_ground(u_lvl_src_b[u_level], u_lvl_slopes_b[u_level], v_local, v_rel, spacing), alpha);
#else
        along *= 1.0 - alpha;
#endif
        vec3 dir = normalize(v_rel);
        v_rel += along * dir, v_local += along * dir.xz / spacing;
    }
#ifdef SLOPES_A
    const bool fine_a = true;
#else
    const bool fine_a = false;
#endif
#ifdef SLOPES_B
    const bool fine_b = true;
#else
    const bool fine_b = false;
#endif
    vec2 g = gradient_at(u_lvl_src_a[u_level], u_lvl_slopes_a[u_level], v_local, spacing, fine_a);
    if (alpha > 0.0)
        g = mix(g, gradient_at(u_lvl_src_b[u_level], u_lvl_slopes_b[u_level], v_local, spacing, fine_b), alpha);
#ifdef RESOLVE
    vec3 n_plane = normalize(vec3(-g.x, 1.0, -g.y));
    vec3 rel_shaded = v_rel;
    v_rel = rel_drawn; // the steps to the neighbours' ground as drawn, as theirs are
    g_step_x = ground_step(px, ivec2(1, 0), n_plane), g_step_y = ground_step(px, ivec2(0, 1), n_plane);
    v_rel = rel_shaded;
#endif
    float h = v_rel.y + u_cam_y;
    float dist = length(v_rel);
    vec3 view_dir = v_rel / -max(dist, 1e-6);

#ifndef SHADED
    if (u_view_mode == VIEW_WIREFRAME) {
        o_colour = vec4(u_level_tint[u_level], 1.0);
        return;
    }
#endif

    // Detail: parallax over the detail window, faded out with distance.
    vec2 detail_slope = vec2(0.0);
    vec2 shift_m = vec2(0.0); // parallax shift of the texture lookups, metres
#ifdef DETAIL
    vec4 ld = u_lvl_detail[u_level];
    float fade = detail_fade(dist);
    if (ld.w > 0.0 && fade > 0.0) {
        vec2 dt = ld.xy + v_local * ld.z; // detail samples from the window's origin
        if (in_detail_window(dt)) {
            vec3 n0 = normalize(vec3(-g.x, 1.0, -g.y));
            vec3 t_axis = normalize(vec3(1.0, 0.0, 0.0) - n0 * n0.x);
            vec3 b_axis = cross(t_axis, n0);
            vec3 v = vec3(dot(view_dir, t_axis), dot(view_dir, b_axis), dot(view_dir, n0));
            vec2 tc = detail_parallax(dt, v, fade);
            shift_m = (tc - dt) * u_detail_spacing;
            detail_slope = detail_slopes(tc, fade);
        }
    }
#endif
    vec3 n = normalize(vec3(-(g.x + detail_slope.x), 1.0, -(g.y + detail_slope.y)));
    float slope = sqrt(dot(g, g)); // rise over run of the coarse surface

#ifndef SHADED
    if (u_view_mode == VIEW_LEVELS) {
        vec3 c = u_level_tint[u_level] * (0.35 + 0.65 * max(dot(n, u_sun_dir), 0.0));
        o_colour = vec4(with_grids(c), 1.0);
        return;
    }
    if (u_view_mode == VIEW_HEIGHT) {
        float t = (h + u_max_height) / (2.0 * u_max_height);
        o_colour = vec4(with_grids(with_contours(ramp(t) * (0.55 + 0.45 * max(dot(n, u_sun_dir), 0.0)), h)), 1.0);
        return;
    }
    { // VIEW_SLOPE
        float degrees_ = degrees(atan(slope));
        o_colour = vec4(with_grids(with_contours(ramp(degrees_ / 60.0) * (0.55 + 0.45 * max(dot(n, u_sun_dir), 0.0)), h)), 1.0);
        return;
    }
#else

    vec4 luv = u_lvl_uv[u_level];
    vec2 metres_near = luv.xy + v_local * spacing + shift_m;
    vec2 metres_far = luv.zw + v_local * spacing;
    vec2 uv = metres_near / u_tex_period.x, uv_far = metres_far / u_tex_period.y;

    // The far scale of all eight materials in two lookups (the same values as one
    // lookup of each texture's green channel: renderer/terrain_renderer.c packs them).
#ifdef RESOLVE
    g_uv_dx = (g_step_x.xz + dFdx(shift_m)) / u_tex_period.x;
    g_uv_dy = (g_step_y.xz + dFdy(shift_m)) / u_tex_period.x;
    vec2 far_dx = g_step_x.xz / u_tex_period.y, far_dy = g_step_y.xz / u_tex_period.y;
    vec4 far[2] = vec4[2](textureGrad(u_albedo_far, vec3(uv_far, 0.0), far_dx, far_dy), vec4(0.0));
#ifdef FAR_B // (else no rule here lays a material of the second layer)
    far[1] = textureGrad(u_albedo_far, vec3(uv_far, 1.0), far_dx, far_dy);
#endif
#else
    vec4 far[2] = vec4[2](texture(u_albedo_far, vec3(uv_far, 0.0)), vec4(0.0));
#ifdef FAR_B
    far[1] = texture(u_albedo_far, vec3(uv_far, 1.0));
#endif
#endif
    // Unpainted ground: the automatic rules, or a neutral clay when they are hidden.
    float curvature = 0.0;
#ifdef CURVATURE
    curvature = curvature_at(u_lvl_src_a[u_level], v_local, spacing);
    if (alpha > 0.0)
        curvature = mix(curvature, curvature_at(u_lvl_src_b[u_level], v_local, spacing), alpha);
#endif
#if defined(RESOLVE) && defined(RULE_CALLS)
    vec3 auto_c = u_auto_materials != 0 ? automatic_sparse(h, slope, curvature, uv, far[0], far[1])
                                        : vec3(0.45, 0.42, 0.38);
#else
    vec3 auto_c = u_auto_materials != 0 ? automatic_varied(h, slope, curvature, uv, far[0], far[1])
                                        : vec3(0.45, 0.42, 0.38);
#endif
    vec3 c = auto_c;
#ifdef PAINTED
    {
        vec4 w0, w1;
        ivec4 wrap = u_lvl_mat_wrap[u_level];
        if (painted_weights(u_lvl_mat[u_level], wrap.xy, v_local, w0, w1)) {
            if (alpha > 0.0) { // toward the coarser level's weights, as the heights morph
                vec4 b0, b1;
                painted_weights(u_lvl_mat_b[u_level], wrap.zw, v_local, b0, b1);
                w0 = mix(w0, b0, alpha), w1 = mix(w1, b1, alpha);
            }
            // Weight 0 is "automatic"; 1..7 paint sand, grass, rock, snow, dirt, gravel, moss.
            c = auto_c * w0.x;
            c += albedo_varied(0, uv, far[0].x).rgb * w0.y + albedo_varied(1, uv, far[0].y).rgb * w0.z
               + albedo_varied(2, uv, far[0].z).rgb * w0.w + albedo_varied(3, uv, far[1].x).rgb * w1.x
               + albedo_varied(4, uv, far[1].y).rgb * w1.y + albedo_varied(5, uv, far[1].z).rgb * w1.z
               + albedo_varied(6, uv, far[1].w).rgb * w1.w;
        }
    }
#endif
    vec3 lit = sunlit(c, n, view_dir, 24.0, 0.04);
#ifdef OVERLAYS
    if (u_mask.x != 0) {
        float k = curvature;
#ifndef CURVATURE
        if ((u_mask.z & 4) != 0) {
            k = curvature_at(u_lvl_src_a[u_level], v_local, spacing);
            if (alpha > 0.0) k = mix(k, curvature_at(u_lvl_src_b[u_level], v_local, spacing), alpha);
        }
#endif
        lit = with_mask(lit, h, slope, k);
    }
#endif

#ifdef BRUSH
    {
        float d = length(v_rel.xz - u_brush.xy) / u_brush.z;
#ifdef RESOLVE
        vec2 toward = (v_rel.xz - u_brush.xy) / max(length(v_rel.xz - u_brush.xy), 1e-6);
        float fw = max((abs(dot(toward, g_step_x.xz)) + abs(dot(toward, g_step_y.xz))) / u_brush.z, 1e-4);
#else
        float fw = max(fwidth(d), 1e-4);
#endif
        if (d < 1.0) {
            float f = texture(u_falloff, vec2(d, 0.5)).r;
            lit = mix(lit, u_brush_tint.rgb, u_brush_tint.a * f);
        }
        float ring = 1.0 - smoothstep(0.0, 1.5 * fw, abs(d - 1.0));
        float centre = 1.0 - smoothstep(0.0, 1.5 * fw, d - 0.02);
        lit = mix(lit, u_brush_ring, max(ring, centre));
    }
#endif
    o_colour = vec4(apply_fog(with_grids(with_contours(lit, h)), v_rel), 1.0);
#endif
}
