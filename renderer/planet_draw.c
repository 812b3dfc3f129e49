// Drawing the shown chunks: each with the ground program variant of what it can show
// (planet.frag), its detail window, morph and skirts, then the sky.
#include "renderer/planet_internal.h"
#include "renderer/planet_renderer.h"

#include "renderer/material_rule_uniforms.h"
#include "renderer/planet_camera.h"
#include "renderer/shader.h"

#include <stdlib.h>
#include <string.h>

// The ground program for a variant (V_* bits), built on first use.
ground_program *planet_ground_variant(planet_renderer *r, int variant, og_error *err) {
    ground_program *g = &r->ground[variant];
    if (g->prog) return g;
    static const char *const names[] = {"SHADED", "DETAIL",   "SEA",      "PAINTED", "BARE",
                                        "BRUSH",  "OVERLAYS", "MINIFIED", "SEAM",    "RULES"};
    g->prog = shader_program_load_flags(r->shader_dir, "planet.vert", "planet.frag", names, 10,
                                        (unsigned)variant, err);
    if (!g->prog) return NULL;
    g->offset = glGetUniformLocation(g->prog, "u_offset");
    g->level = glGetUniformLocation(g->prog, "u_level");
    g->morph = glGetUniformLocation(g->prog, "u_morph");
    g->detail = glGetUniformLocation(g->prog, "u_chunk_detail");
    g->wrap = glGetUniformLocation(g->prog, "u_detail_wrap");
    g->tile = glGetUniformLocation(g->prog, "u_chunk_tile");
    g->cell = glGetUniformLocation(g->prog, "u_chunk_cell");
    g->normal_map = glGetUniformLocation(g->prog, "u_normal_map");
    g->face_axis = glGetUniformLocation(g->prog, "u_face_axis");
    g->slope_scale = glGetUniformLocation(g->prog, "u_slope_scale");
    g->face_edges = glGetUniformLocation(g->prog, "u_face_edges");
    g->frame = 0;
    return g;
}

// Nearest chunks first: the depth test then rejects what they hide before it is shaded
// (a software renderer shades every fragment that passes).
typedef struct draw_key {
    double dist;
    int chunk;

} draw_key;
static int nearer(const void *a, const void *b) {
    double da = ((const draw_key *)a)->dist, db = ((const draw_key *)b)->dist;
    return (da > db) - (da < db);
}
static void sort_near_first(planet_renderer *r) {
    static draw_key keys[MAX_CHUNKS];
    for (int i = 0; i < r->draw_count; i++)
        keys[i] = (draw_key){r->chunks[r->draw_list[i]].near_dist, r->draw_list[i]};
    qsort(keys, (size_t)r->draw_count, sizeof keys[0], nearer);
    for (int i = 0; i < r->draw_count; i++)
        r->draw_list[i] = keys[i].chunk;
}

// What every ground program gets this frame.
typedef struct ground_frame {
    const camera *cam;
    const render_settings *s;
    float view_proj[16];
    float brush[4], brush_up[3]; // the cursor's centre relative to the camera, radius (0: none)
    float tint[4], ring[3];      // the tool's colours
} ground_frame;

// The brush cursor: its centre relative to the camera, the local up there, the falloff
// curve (uploaded once) and the tool's colours (as the flat viewport draws them).
static void cursor_frame(planet_renderer *r, const brush_cursor *cursor, ground_frame *f) {
    const camera *cam = f->cam;
    memset(f->brush, 0, sizeof f->brush);
    f->brush_up[0] = 0, f->brush_up[1] = 1, f->brush_up[2] = 0;
    if (cursor && cursor->visible && cursor->radius > 0 && !cursor->sphere) {
        const double c[3] = {cursor->x, cursor->y, cursor->z};
        double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        for (int k = 0; k < 3; k++) {
            f->brush[k] = (float)(c[k] - cam->pos[k]);
            f->brush_up[k] = len > 0 ? (float)(c[k] / len) : 0.0f;
        }
        f->brush[3] = (float)cursor->radius;
        glTextureSubImage2D(r->falloff, 0, 0, 0, BRUSH_FALLOFF_SAMPLES, 1, GL_RED, GL_FLOAT,
                            cursor->falloff);
    }
    const float tint[4] = {1.0f, 0.55f, 0.1f, 0.35f}, ring[3] = {1.0f, 0.9f, 0.3f}; // orange
    memcpy(f->tint, tint, sizeof tint);
    memcpy(f->ring, ring, sizeof ring);
    if (cursor && cursor->opacity > 0) {
        for (int i = 0; i < 3; i++)
            f->tint[i] = cursor->color[i], f->ring[i] = 0.65f * cursor->color[i] + 0.35f;
        f->tint[3] = cursor->opacity;
    }
}

// A ground program's uniforms for this frame, once per frame and program.
static void ground_frame_uniforms(planet_renderer *r, GLuint prog, const ground_frame *f) {
    const world_params *p = &r->params;
    const render_settings *s = f->s;
    planet_set_common(r, prog, f->cam, s);
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE,
                              f->view_proj);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_ocean_h"),
                       (float)world_params_ocean_height(p));
    // The material rules' sea level: a planet without a sea (its radius under all the
    // ground) keeps its beaches and snow line where the ground is.
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_ocean_level"),
                       (float)fmax(world_params_ocean_height(p), -p->max_height));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_max_height"), (float)p->max_height);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_palette"),
                       p->atmosphere < 0.05 ? 1 : 2); // used by the BARE variants
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_tex_period"), (float)TEX_PERIOD_NEAR,
                       (float)TEX_PERIOD_FAR);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_albedo"), 0);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_albedo_mean"), MATERIAL_TEXTURE_COUNT,
                        &r->albedo_mean[0][0]);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_brush"), 1, f->brush);
    glProgramUniform3fv(prog, glGetUniformLocation(prog, "u_brush_up"), 1, f->brush_up);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_brush_tint"), 1, f->tint);
    glProgramUniform3fv(prog, glGetUniformLocation(prog, "u_brush_ring"), 1, f->ring);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_falloff"), 1);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_normals"), 4);
    planet_detail_bind(r->detail, prog, s, 2, 3);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_overlays"),
                       (s->tile_grid ? 1 : 0) | (s->level_grid ? 2 : 0));
    glProgramUniform3i(prog, glGetUniformLocation(prog, "u_mask"), s->mask_terms != 0,
                       s->mask_invert, s->mask_terms);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_mask_height"), 1, s->mask_height);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_mask_slope"), 1, s->mask_slope);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_mask_curvature"), 1, s->mask_curvature);
    material_rule_uniforms(prog, &r->rules);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_rules_curvature"),
                       r->rules.uses_curvature);
}

// The variant a chunk is drawn with: only what it can show this frame.
static int chunk_variant(const planet_renderer *r, const chunk *c, const ground_frame *f,
                         const float detail[4]) {
    const render_settings *s = f->s;
    if (s->view == VIEW_WIREFRAME) return 0;
    const double ocean = world_params_ocean_height(&r->params);
    const int has_sea = ocean > -r->params.max_height;
    double to_chunk = 0; // metres from the camera to the chunk's origin
    for (int k = 0; k < 3; k++)
        to_chunk += (c->origin[k] - f->cam->pos[k]) * (c->origin[k] - f->cam->pos[k]);
    to_chunk = sqrt(to_chunk);
    // Detail where it shows: the detail window covers the chunk, holds some detail
    // there (it is zero until edited) and some of the chunk is nearer than the
    // detail's fade-out distance.
    int v = detail[3] > 0 && to_chunk - c->reach < s->detail_distance ? V_DETAIL : 0;
    if (s->tile_grid || s->level_grid || s->mask_terms) v |= V_OVERLAYS;
    if (f->brush[3] > 0) { // the cursor reaches the chunk (raised to the sea where under it)
        double d2 = 0;
        for (int k = 0; k < 3; k++) {
            double dk = c->origin[k] - f->cam->pos[k] - f->brush[k];
            d2 += dk * dk;
        }
        double reach = c->reach + fmax(ocean - c->lowest, 0.0) + 1.1 * f->brush[3];
        if (d2 < reach * reach) v |= V_BRUSH;
    }
    if (s->view != VIEW_SHADED) return v;
    v |= V_SHADED;
    // Far enough that the material textures' near scale is smaller than a pixel all
    // over the chunk: every lookup would return the texture's 1 x 1 level. A pixel's
    // footprint shrinks toward the screen's corners and filtering measures it roughly,
    // hence the factor 4.
    const double nearest =
        to_chunk - c->reach - skirt_depth(r, c->level) - fmax(ocean - c->lowest, 0.0);
    if (!(v & V_DETAIL) && r->has_albedo_mean &&
        nearest > 4.0 * TEX_PERIOD_NEAR * r->pixels_per_radian)
        v |= V_MINIFIED;
    if (!has_sea)
        v |= V_BARE;
    else if (c->lowest < ocean)
        v |= V_SEA;
    if (c->painted) v |= V_PAINTED;
    if (c->blended) v |= V_SEAM;
    if (material_rules_live(&r->rules, c->lowest - 1.0, c->hmax + 1.0, 1e30)) v |= V_RULES;
    return v;
}

// The index ranges to draw for a chunk: its grid, and the skirts the camera can see the
// front of. A skirt hangs straight down from its edge, which lies on a great circle,
// so the whole skirt lies in that circle's plane through the centre and shows its front
// (it faces away from its chunk) only to a camera on the outer side of that plane; the
// others would all be culled as back faces, after their vertices were shaded.
static int index_ranges(const chunk *c, const camera *cam, int all_skirts, GLsizei counts[5],
                        const void *offsets[5]) {
    enum { GRID = BLOCK * BLOCK * 6, EDGE = BLOCK * 6 };
    counts[0] = GRID, offsets[0] = NULL;
    int n = 1;
    const double(*dir)[3] = c->corner_dir;
    // Edges 0-3 (make_indices): t = t0, t = t1, s = s0, s = s1; their corners and a
    // corner across the chunk from them.
    static const int ends[4][3] = {{0, 1, 2}, {2, 3, 0}, {0, 2, 1}, {1, 3, 0}};
    for (int e = 0; e < 4; e++) {
        const double *a = dir[ends[e][0]], *b = dir[ends[e][1]], *across = dir[ends[e][2]];
        double plane[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                           a[0] * b[1] - a[1] * b[0]};
        const double inward = plane[0] * across[0] + plane[1] * across[1] + plane[2] * across[2];
        const double camera_side =
            plane[0] * cam->pos[0] + plane[1] * cam->pos[1] + plane[2] * cam->pos[2];
        if (all_skirts || (inward > 0 ? camera_side <= 0 : camera_side >= 0)) {
            counts[n] = EDGE;
            offsets[n] = (const void *)(uintptr_t)((GRID + e * EDGE) * sizeof(uint16_t));
            n++;
        }
    }
    return n;
}

// What stays bound from one chunk's draw to the next.
typedef struct chunk_pass {
    ground_frame *f;
    int all_skirts;
    ground_program *g;
    int variant, window; // bound (-1: none yet)
} chunk_pass;

// Draws shown chunk i, switching the program where the variant changes.
static int draw_chunk(planet_renderer *r, int i, chunk_pass *p, og_error *err) {
    const chunk_look *l = &r->looks[i];
    const int v = l->variant;
    const camera *cam = p->f->cam;
    const render_settings *s = p->f->s;
    if (v != p->variant) {
        p->variant = v;
        if (!(p->g = planet_ground_variant(r, v, err))) return -1;
        if (p->g->frame != r->frame) {
            ground_frame_uniforms(r, p->g->prog, p->f);
            p->g->frame = r->frame;
        }
        glUseProgram(p->g->prog);
    }
    ground_program *g = p->g;
    const chunk *c = &r->chunks[r->shown[i]];
    glProgramUniform3f(g->prog, g->offset, (float)(c->origin[0] - cam->pos[0]),
                       (float)(c->origin[1] - cam->pos[1]), (float)(c->origin[2] - cam->pos[2]));
    glProgramUniform1i(g->prog, g->level, c->level);
    { // its normal texture: its metres at the atlas's texel 0, texels a metre, its layer
        const int from = c->normal_level < 0 ? c->level : c->normal_level;
        const double texel = ldexp(r->cell_arc, from);
        glProgramUniform1f(g->prog, g->slope_scale, (float)exp2(SLOPE_SCALE_EXPONENT * from));
        int layer, x, y;
        planet_normals_place(r->shown[i], &layer, &x, &y);
        glProgramUniform4f(g->prog, g->normal_map,
                           (float)(c->metres_lo[0] - c->metres_base[0] - (x + 1) * texel),
                           (float)(c->metres_lo[1] - c->metres_base[1] - (y + 1) * texel),
                           (float)(1.0 / texel), (float)layer);
        const double *axis = r->face_axis[chunk_face(c)];
        glProgramUniform3f(g->prog, g->face_axis, (float)axis[0], (float)axis[1], (float)axis[2]);
        const double extent = (double)r->face_samples * r->cell_arc; // face-local metres
        glProgramUniform4f(g->prog, g->face_edges, (float)-c->metres_base[0],
                           (float)(extent - c->metres_base[0]), (float)-c->metres_base[1],
                           (float)(extent - c->metres_base[1]));
    }
    glProgramUniform4fv(g->prog, g->detail, 1, l->detail);
    if (v & V_DETAIL) { // the window of the chunk's face
        if (l->window != p->window) planet_detail_use(r->detail, p->window = l->window, 2, 3);
        glProgramUniform2fv(g->prog, g->wrap, 1, l->wrap);
    }
    if (v & V_OVERLAYS) { // where the chunk's metres meet the grids
        const double tile = TILE_SIZE * r->cell_arc, cell = ldexp(r->cell_arc, c->level);
        glProgramUniform3f(g->prog, g->tile, (float)fmod(c->metres_base[0], tile),
                           (float)fmod(c->metres_base[1], tile), (float)tile);
        glProgramUniform3f(g->prog, g->cell, (float)fmod(c->metres_base[0], cell),
                           (float)fmod(c->metres_base[1], cell), (float)cell);
    }
    // Fully the parent's mesh where the parent would be drawn instead: at the
    // distance its samples shrink to split_pixels. (The haze is measured to the
    // sphere through each fragment's height, not along the morphed chords, so
    // coarse quads do not show in it.)
    const int morph = s->morph && c->level < r->root_level;
    glProgramUniform1f(g->prog, g->morph, morph ? (float)(1.0 / c->morph_reach) : 0.0f);
    glFrontFace(r->front[chunk_face(c)]);
    glVertexArrayVertexBuffer(r->vao, 0, c->vbo, 0, VERTEX_FLOATS * sizeof(float));
    GLsizei counts[5];
    const void *offsets[5];
    const int ranges = index_ranges(c, cam, p->all_skirts, counts, offsets);
    glMultiDrawElements(GL_TRIANGLES, counts, GL_UNSIGNED_SHORT, offsets, ranges);
    for (int k = 0; k < ranges; k++)
        r->stats.triangles += (uint64_t)counts[k] / 3;
    r->stats.draw_calls++;
    return 0;
}

int planet_renderer_draw(planet_renderer *r, const camera *cam, const render_settings *s,
                         const brush_cursor *cursor, int width, int height, og_error *err) {
    double t0 = now_ms();
    double aspect = (double)width / (double)(height > 0 ? height : 1);
    ground_frame f = {.cam = cam, .s = s};
    // The world's material rules over the planet's look, resolved as the shaders read
    // them (their sea level as u_ocean_level's).
    const world_params *p = &r->params;
    material_rules_resolve(&p->material_rules, fmax(world_params_ocean_height(p), -p->max_height),
                           p->max_height, &r->rules);
    planet_camera_view_projection(cam, aspect, f.view_proj);
    glViewport(0, 0, width, height);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glClearDepth(0.0);
    const int wire = s->view == VIEW_WIREFRAME;
    // Back faces cost llvmpipe as much as the ground: the skirts seen from inside their
    // chunks, slopes facing away, the ground past the horizon. The wireframe shows all,
    // and under the sea its surface is seen from below.
    const int under_sea = r->camera_altitude < world_params_ocean_height(&r->params);
    if (wire || under_sea)
        glDisable(GL_CULL_FACE);
    else
        glEnable(GL_CULL_FACE), glCullFace(GL_BACK);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    r->stats.triangles = 0;
    r->stats.draw_calls = 0;
    cursor_frame(r, cursor, &f);
    glBindTextureUnit(0, r->albedo);
    glBindTextureUnit(1, r->falloff);
    glBindTextureUnit(4, r->normals);
    sort_near_first(r);
    planet_choose_shown(r, cam, s, aspect);
    // Each chunk's variant and detail window, the nearest chunk first.
    for (int i = 0; i < r->shown_count; i++) {
        const chunk *c = &r->chunks[r->shown[i]];
        chunk_look *l = &r->looks[i];
        l->window = (signed char)planet_detail_chunk(r->detail, chunk_face(c), c->level,
                                                     c->metres_lo, c->metres_hi, c->metres_base[0],
                                                     c->metres_base[1], l->detail, l->wrap);
        l->variant = (unsigned short)chunk_variant(r, c, &f, l->detail);
    }
    glBindVertexArray(r->vao);
    if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    chunk_pass pass = {.f = &f, .all_skirts = wire || under_sea, .variant = -1, .window = -1};
    int rc = 0;
    for (int i = 0; i < r->shown_count && rc == 0; i++)
        rc = draw_chunk(r, i, &pass, err);
    if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    if (!wire && rc == 0) planet_draw_sky(r, cam, s, aspect);
    r->stats.chunks_drawn = r->shown_count;
    r->stats.chunks_occluded = r->draw_count - r->shown_count;
    glBindVertexArray(0);
    glUseProgram(0);
    r->stats.cpu_ms += now_ms() - t0;
    if (rc < 0) return -1;
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return og_error_set(err, "planet_renderer_draw: GL error 0x%x", e);
    return 0;
}
