#include "renderer/terrain_renderer.h"

#include "editor/world/world_events.h"
#include "renderer/clip_cells.h"
#include "renderer/clip_refine.h"
#include "renderer/clip_refine_mesh.h"
#include "renderer/clip_skyline.h"
#include "renderer/clip_slopes.h"
#include "renderer/clip_window.h"
#include "renderer/clip_window_upload.h"
#include "renderer/clipmap_mesh.h"
#include "renderer/deferred_target.h"
#include "renderer/driver_heap.h"
#include "renderer/frustum.h"
#include "renderer/ground_occlusion.h"
#include "renderer/lighting.h"
#include "renderer/mask_flow_texture.h"
#include "renderer/material_rule_uniforms.h"
#include "renderer/material_textures.h"
#include "renderer/shader.h"
#include "renderer/planet_renderer.h"
#include "renderer/volume_renderer.h"
#include "renderer/water_ripples.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define CLIP_N 255          // vertices per level side (2^8 - 1)
#define CLIP_TEXELS 256     // level texture side: the window plus one spare column
#define DETAIL_TEXELS 512   // detail window side, detail samples
#define DETAIL_SNAP 16      // the detail window moves in steps of this many samples
#define TEX_PERIOD_NEAR 6.0 // metres per repeat of the material textures
#define TEX_PERIOD_FAR 97.0 // metres per repeat of the variation layer
#define UNBOUNDED 1e9f
// The transition band, ending one unit inside the edge: n/40 level units. Hoppe's n/10
// blended the outer fifth of each ring's radius into the coarser level's heights and
// normals; against the full-resolution mesh (bench_render 7, default/low/distant) n/40
// took the RMSE from 4.07/3.01/3.28 to 3.90/2.79/3.17 (n/80: 3.88/2.78/3.16, no
// morphing 3.91/2.78/3.15), its vertices still meeting the coarser level's at the edge.
#define MORPH_BAND ((float)(CLIP_N / 40))
#define MORPH_START ((CLIP_N - 1) / 2.0f - MORPH_BAND - 1.0f)
#define UPLOAD_BUDGET_PERCENT 6 // of the level textures, for refills (moves come on top)

// The terrain program's variants (see terrain.frag): what a level can show.
enum {
    TV_SHADED = 1,
    TV_DETAIL = 2,
    TV_PAINTED = 4,
    TV_BRUSH = 8,
    TV_OVERLAYS = 16,
    TV_CONTOURS = 32,
    TV_MINIFIED = 64,
    TV_NO_MORPH = 128, // the parts of a level inside its morph band's inner edge
    TV_GBUFFER = 256,  // deferred: where the ground is, nothing shaded
    TV_RESOLVE = 512,  // deferred: the shading, one full-screen pass
    // Set per level from what is known on the CPU (a software renderer runs both sides
    // of an `if` on a uniform):
    TV_CURVATURE = 1024, // some material rule reads curvature
    TV_SLOPES_A = 2048,  // the level's shading slopes come from finer heights
    TV_SLOPES_B = 4096,  // the same for the coarser level it morphs into
    TV_VOLUME = 8192,    // volume meshes replace the ground somewhere
    TV_REFINED = 16384,  // parts drawn at twice the density (renderer/clip_refine.h)
    TV_INSIDE = 32768,   // every part drawn lies inside the world: no bounds test (which
                         // keeps llvmpipe from testing depth before the fragment shader)
    TV_FAR_B = 65536,    // a rule or the paint reads the far texture's second layer
    TV_SEAM = 131072,    // the refined parts' zero-area seams (renderer/clip_refine_mesh.h)
    TERRAIN_VARIANTS = 262144
};
#define GBUFFER_UNIT 10 // the texture unit the resolve passes read the G-buffer from
#define REFINE_UNIT 11  // the refined parts' vertex weights (renderer/clip_refine.h)
#define TERRAIN_PROGRAMS 48
#define PIECES_MAX 512 // drawable parts of a level (clipmap_mesh.h pieces)
// A level's draws per group: every refinable piece may come in its refined parts.
#define DRAWS_MAX (PIECES_MAX * CLIP_REFINE_PARTS_MAX)
enum { DRAW_BASE, DRAW_FINE, DRAW_SEAMS }; // base program, refined, refined seams

struct terrain_renderer {
    char shader_dir[4200];
    // Terrain programs built when first needed: a variant (TV_* bits) with the material
    // rules it runs (RULE_CALLS, materials.glsl); the least recently used goes when full.
    struct terrain_prog {
        int variant;
        char calls[MATERIAL_RULES_MAX * 12];
        GLuint prog;
        uint64_t used;     // the frame it last drew in
        uint64_t uniforms; // the frame its uniforms were set for
    } progs[TERRAIN_PROGRAMS];
    uint64_t frame;
    GLuint prog_sky, prog_water, prog_cursor;
    GLuint vao, vbo, ebo, empty_vao;
    deferred_target deferred; // the shaded view's G-buffer (renderer/deferred_target.h)
    clipmap_mesh mesh;
    GLuint tex_heights, tex_material, tex_albedo, tex_detail, tex_detail_pd, tex_falloff;
    GLuint tex_albedo_far;       // the material textures' green channels, 4 to a layer
    mask_flow_texture mask_flow; // the mask editor's flow field
    float albedo_mean[MATERIAL_TEXTURE_COUNT][4]; // each material texture's 1 x 1 level
    material_rules_resolved rules; // the world's material rules this frame, in metres
    clip_window heights[RENDER_MAX_LEVELS];
    // Painted weights per level, from the material layer's mip levels, so paint shows at
    // every distance. Kept only once the world has paint (paint_seen), and uploaded
    // only while a window holds paint (mat_painted: set when paint enters it, cleared
    // when a whole refill finds none), so unpainted ground costs nothing.
    clip_window material[RENDER_MAX_LEVELS];
    int mat_painted[RENDER_MAX_LEVELS];
    int paint_seen;
    clip_window detail, detail_pd;
    clip_slopes slopes; // the levels' shading slopes from finer mip levels
    // Parts of levels drawn at twice the density where their error shows (the refined
    // mesh's own buffers; the error and bounds per cell, rebuilt when the level's or its
    // shading window changed: refine_stale; the weights the vertex shader reads).
    clip_refine_mesh refine_mesh;
    GLuint refine_vao, refine_vbo, refine_ebo;
    clip_refine_cells refine_cells[RENDER_MAX_LEVELS];
    int refine_stale[RENDER_MAX_LEVELS];
    clip_refine_map refine_map;
    float hmin[RENDER_MAX_LEVELS], hmax[RENDER_MAX_LEVELS];
    // The same per cell of each window, for culling blocks (rebuilt once a changed
    // window is whole: cells_stale).
    clip_cells cells[RENDER_MAX_LEVELS];
    int cells_stale[RENDER_MAX_LEVELS];
    ground_occlusion occlusion; // this frame's ground hiding farther blocks
    clip_skyline skyline;       // this frame's skyline, when only parts near it refine
    // The steepest slope (rise over run) between neighbouring samples of each level's
    // window, re-measured when it changed and is whole (slope_stale).
    double slope_max[RENDER_MAX_LEVELS];
    int slope_stale[RENDER_MAX_LEVELS];

    // What the levels show: the world they were filled from, and its change
    // notifications (edits, new parameters, another world).
    world *world;
    world_subscription *changes;
    world_params params; // the world's, as of this frame's update

    // This frame's layout (terrain_renderer_update).
    int levels, finest;
    int64_t origin[RENDER_MAX_LEVELS][2]; // level sample index of local vertex (0, 0)
    int src[RENDER_MAX_LEVELS];           // level whose texture draws level l (-1: none)
    int mat_src[RENDER_MAX_LEVELS];       // level whose material window paints level l (-1: none)
    int detail_current;
    int64_t detail_origin[2];

    volume_renderer *volume; // caves, overhangs and arches near the camera
    planet_renderer *planet; // planets' cube-sphere, made on the first planet
    char resource_dir[4096];
    int width, height; // of the last frame drawn (the planet's level of detail uses it)

    render_stats stats;
    uint64_t frame_texels;
    int whole_uploads; // terrain_renderer_spread_uploads off
};

// CPU time of the calling thread: a software renderer's vertex work runs in it, and
// waiting for its rasteriser threads (the deferred pass reads what they drew) does not
// count.
static double thread_cpu_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static GLuint make_texture(GLenum target) {
    GLuint t = 0;
    glCreateTextures(target, 1, &t);
    return t;
}

static void set_filter_wrap(GLuint t, GLenum filter, GLenum wrap) {
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER,
                        filter == GL_LINEAR_MIPMAP_LINEAR ? GL_LINEAR : filter);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, wrap);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, wrap);
}

// The far scale reads only the green channel of each material texture, at the same
// coordinates for all of them: packed 4 to a texel (level by level from the textures'
// own mips, so filtering gives the same values), the automatic rules' five lookups
// become two. Also keeps each texture's 1 x 1 level (the MINIFIED variant's albedo).
static int pack_far_variation(terrain_renderer *r, int mips) {
    const int n = MATERIAL_TEXTURE_COUNT, layers = (n + 3) / 4;
    r->tex_albedo_far = make_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(r->tex_albedo_far, mips, GL_RGBA8, MATERIAL_TEXTURE_SIZE,
                       MATERIAL_TEXTURE_SIZE, layers);
    size_t texels = (size_t)MATERIAL_TEXTURE_SIZE * MATERIAL_TEXTURE_SIZE;
    unsigned char *src = malloc(texels * 4 * n), *dst = malloc(texels * 4 * layers);
    if (!src || !dst) {
        free(src);
        free(dst);
        return -1;
    }
    for (int lv = 0; lv < mips; lv++) {
        int side = MATERIAL_TEXTURE_SIZE >> lv;
        size_t count = (size_t)side * side;
        glGetTextureImage(r->tex_albedo, lv, GL_RGBA, GL_UNSIGNED_BYTE, (GLsizei)(count * 4 * n),
                          src);
        for (int m = 0; m < n; m++)
            for (size_t i = 0; i < count; i++)
                dst[((size_t)(material_far_slot(m) / 4) * count + i) * 4 +
                    material_far_slot(m) % 4] = src[((size_t)m * count + i) * 4 + 1];
        if (lv == mips - 1) // as the sampler reads it
            glGetTextureImage(r->tex_albedo, lv, GL_RGBA, GL_FLOAT, sizeof r->albedo_mean,
                              r->albedo_mean);
        glTextureSubImage3D(r->tex_albedo_far, lv, 0, 0, 0, side, side, layers, GL_RGBA,
                            GL_UNSIGNED_BYTE, dst);
    }
    free(src);
    free(dst);
    set_filter_wrap(r->tex_albedo_far, GL_LINEAR_MIPMAP_LINEAR, GL_REPEAT);
    return 0;
}

static int create_textures(terrain_renderer *r, og_error *err) {
    r->tex_heights = make_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(r->tex_heights, 1, GL_R32F, CLIP_TEXELS, CLIP_TEXELS, RENDER_MAX_LEVELS);
    set_filter_wrap(r->tex_heights, GL_LINEAR, GL_REPEAT);

    r->tex_material = make_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(r->tex_material, 1, GL_RG32UI, CLIP_TEXELS, CLIP_TEXELS, RENDER_MAX_LEVELS);
    set_filter_wrap(r->tex_material, GL_NEAREST, GL_REPEAT);

    r->tex_detail = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(r->tex_detail, 1, GL_R32F, DETAIL_TEXELS, DETAIL_TEXELS);
    set_filter_wrap(r->tex_detail, GL_LINEAR, GL_REPEAT);
    r->tex_detail_pd = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(r->tex_detail_pd, 1, GL_RG16_SNORM, DETAIL_TEXELS, DETAIL_TEXELS);
    set_filter_wrap(r->tex_detail_pd, GL_LINEAR, GL_REPEAT);

    r->tex_falloff = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(r->tex_falloff, 1, GL_R32F, BRUSH_FALLOFF_SAMPLES, 1);
    set_filter_wrap(r->tex_falloff, GL_LINEAR, GL_CLAMP_TO_EDGE);

    // The material textures the program makes itself (renderer/material_textures.c).
    int mips = 1;
    while ((MATERIAL_TEXTURE_SIZE >> mips) > 0)
        mips++;
    r->tex_albedo = make_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(r->tex_albedo, mips, GL_RGBA8, MATERIAL_TEXTURE_SIZE, MATERIAL_TEXTURE_SIZE,
                       MATERIAL_TEXTURE_COUNT);
    unsigned char *rgba = malloc((size_t)MATERIAL_TEXTURE_SIZE * MATERIAL_TEXTURE_SIZE * 4);
    if (!rgba) return og_error_set(err, "out of memory for the material textures");
    for (int i = 0; i < MATERIAL_TEXTURE_COUNT; i++) {
        material_texture_generate(i, rgba);
        glTextureSubImage3D(r->tex_albedo, 0, 0, 0, i, MATERIAL_TEXTURE_SIZE, MATERIAL_TEXTURE_SIZE,
                            1, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    }
    free(rgba);
    glGenerateTextureMipmap(r->tex_albedo);
    set_filter_wrap(r->tex_albedo, GL_LINEAR_MIPMAP_LINEAR, GL_REPEAT);
    if (pack_far_variation(r, mips) != 0)
        return og_error_set(err, "out of memory for the material textures");
    // Anisotropic filtering sharpens grazing views on GPUs; on llvmpipe (Mesa 22.3) it
    // made a 320x180 frame take minutes instead of a second, so software renderers skip it.
    const char *renderer_name = (const char *)glGetString(GL_RENDERER);
    int software =
        renderer_name && (strstr(renderer_name, "llvmpipe") || strstr(renderer_name, "softpipe"));
    if (!software && (epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic") ||
                      epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic"))) {
        glTextureParameterf(r->tex_albedo, GL_TEXTURE_MAX_ANISOTROPY_EXT, 8.0f);
        glTextureParameterf(r->tex_albedo_far, GL_TEXTURE_MAX_ANISOTROPY_EXT, 8.0f);
    }
    return 0;
}

static int create_windows(terrain_renderer *r, og_error *err) {
    for (int l = 0; l < RENDER_MAX_LEVELS; l++)
        r->slope_max[l] = INFINITY, r->slope_stale[l] = 1;
    for (int l = 0; l < RENDER_MAX_LEVELS; l++)
        if ((l == 0 ? clip_window_init(&r->heights[l], TILE_LAYER_COARSE, 0, l, CLIP_TEXELS)
                    : clip_window_init_ridges(&r->heights[l], 0, l, CLIP_TEXELS,
                                              l - clip_slopes_mip(l))) != 0 ||
            clip_window_init(&r->material[l], TILE_LAYER_MATERIAL, 0, l, CLIP_TEXELS) != 0 ||
            (l == 0 && clip_slopes_init(&r->slopes) != 0))
            return og_error_set(err, "out of memory for the clipmap levels");
    if (clip_window_init(&r->detail, TILE_LAYER_DETAIL, 0, 0, DETAIL_TEXELS) != 0 ||
        clip_window_init(&r->detail_pd, TILE_LAYER_DETAIL_PD, 0, 0, DETAIL_TEXELS) != 0)
        return og_error_set(err, "out of memory for the clipmap windows");
    return 0;
}

// The terrain program for a variant (TV_* bits) running the rules `calls` (shaded
// variants only), built on first use. *fresh: its uniforms are not set this frame.
static GLuint terrain_program(terrain_renderer *r, int variant, const char *calls, int *fresh,
                              og_error *err) {
    if (!(variant & TV_SHADED)) calls = ""; // only the shaded view runs the rules
    struct terrain_prog *slot = NULL;
    for (int i = 0; i < TERRAIN_PROGRAMS; i++) {
        struct terrain_prog *p = &r->progs[i];
        if (p->prog && p->variant == variant && !strcmp(p->calls, calls)) {
            p->used = r->frame;
            if (fresh) *fresh = p->uniforms != r->frame, p->uniforms = r->frame;
            return p->prog;
        }
        if (!p->prog ? !slot || slot->prog : !slot || (slot->prog && p->used < slot->used))
            slot = p; // an empty slot, else the least recently used
    }
    static const char *const names[] = {"SHADED",    "DETAIL",   "PAINTED",  "BRUSH",   "OVERLAYS",
                                        "CONTOURS",  "MINIFIED", "NO_MORPH", "GBUFFER", "RESOLVE",
                                        "CURVATURE", "SLOPES_A", "SLOPES_B", "VOLUME",  "REFINED",
                                        "INSIDE",    "FAR_B",    "SEAM"};
    char defines[512 + sizeof slot->calls] = "";
    size_t n = 0;
    for (int b = 0; b < (int)(sizeof names / sizeof *names); b++)
        if (variant & (1 << b))
            n += (size_t)snprintf(defines + n, sizeof defines - n, "#define %s\n", names[b]);
    if (variant & TV_SHADED)
        snprintf(defines + n, sizeof defines - n, "#define RULE_CALLS %s\n", calls);
    const char *vs = variant & TV_RESOLVE ? "fullscreen.vert" : "terrain.vert";
    GLuint prog = shader_program_load_variant(r->shader_dir, vs, "terrain.frag", defines, err);
    if (!prog) return 0;
    if (slot->prog) glDeleteProgram(slot->prog);
    slot->variant = variant;
    snprintf(slot->calls, sizeof slot->calls, "%s", calls);
    slot->prog = prog;
    slot->used = r->frame;
    slot->uniforms = fresh ? r->frame : 0;
    if (fresh) *fresh = 1;
    return prog;
}

terrain_renderer *terrain_renderer_create(const char *resource_dir, og_error *err) {
    terrain_renderer *r = calloc(1, sizeof *r);
    if (!r) {
        og_error_set(err, "out of memory");
        return NULL;
    }
    char *dir = r->shader_dir;
    snprintf(dir, sizeof r->shader_dir, "%s/shaders", resource_dir);
    snprintf(r->resource_dir, sizeof r->resource_dir, "%s", resource_dir);
    r->width = 1280, r->height = 720;
    driver_heap_keep_freed(); // the driver's per-frame scene memory stays mapped
    // The plain shaded terrain now, so a broken shader shows at once; other variants
    // when a level first needs them.
    if (!terrain_program(r, TV_SHADED, "", NULL, err) ||
        !(r->prog_sky = shader_program_load(dir, "fullscreen.vert", "sky.frag", err)) ||
        !(r->prog_water = shader_program_load(dir, "water.vert", "water.frag", err)) ||
        !(r->prog_cursor = shader_program_load(dir, "cursor.vert", "cursor.frag", err)) ||
        !(r->volume = volume_renderer_create(dir, err)) ||
        deferred_target_init(&r->deferred, dir, err) != 0)
        goto fail;
    if (clipmap_mesh_build(&r->mesh, CLIP_N) != 0) {
        og_error_set(err, "out of memory for the clipmap mesh");
        goto fail;
    }
    glCreateVertexArrays(1, &r->vao);
    glCreateVertexArrays(1, &r->empty_vao);
    glCreateBuffers(1, &r->vbo);
    glCreateBuffers(1, &r->ebo);
    glNamedBufferStorage(r->vbo, (GLsizeiptr)(r->mesh.vertex_count * 2 * sizeof(uint16_t)),
                         r->mesh.vertices, 0);
    glVertexArrayVertexBuffer(r->vao, 0, r->vbo, 0, 2 * sizeof(uint16_t));
    glVertexArrayElementBuffer(r->vao, r->ebo);
    glEnableVertexArrayAttrib(r->vao, 0);
    glVertexArrayAttribIFormat(r->vao, 0, 2, GL_UNSIGNED_SHORT, 0);
    glVertexArrayAttribBinding(r->vao, 0, 0);
    if (clip_refine_mesh_build(&r->refine_mesh, &r->mesh) != 0 ||
        clip_refine_map_init(&r->refine_map) != 0) {
        og_error_set(err, "out of memory for the clipmap's refined mesh");
        goto fail;
    }
    // The base mesh's indices, then its refinable parts' at the level's density.
    const size_t base_bytes = r->mesh.index_count * sizeof(uint16_t),
                 parts_bytes = r->refine_mesh.coarse_count * sizeof(uint16_t);
    glNamedBufferStorage(r->ebo, (GLsizeiptr)(base_bytes + parts_bytes), NULL,
                         GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferSubData(r->ebo, 0, (GLsizeiptr)base_bytes, r->mesh.indices);
    glNamedBufferSubData(r->ebo, (GLintptr)base_bytes, (GLsizeiptr)parts_bytes,
                         r->refine_mesh.coarse);
    glCreateVertexArrays(1, &r->refine_vao);
    glCreateBuffers(1, &r->refine_vbo);
    glCreateBuffers(1, &r->refine_ebo);
    glNamedBufferStorage(r->refine_vbo,
                         (GLsizeiptr)(r->refine_mesh.vertex_count * 2 * sizeof(uint16_t)),
                         r->refine_mesh.vertices, 0);
    glNamedBufferStorage(r->refine_ebo, (GLsizeiptr)(r->refine_mesh.index_count * sizeof(uint32_t)),
                         r->refine_mesh.indices, 0);
    glVertexArrayVertexBuffer(r->refine_vao, 0, r->refine_vbo, 0, 2 * sizeof(uint16_t));
    glVertexArrayElementBuffer(r->refine_vao, r->refine_ebo);
    glEnableVertexArrayAttrib(r->refine_vao, 0);
    glVertexArrayAttribIFormat(r->refine_vao, 0, 2, GL_UNSIGNED_SHORT, 0);
    glVertexArrayAttribBinding(r->refine_vao, 0, 0);
    if (create_textures(r, err) != 0 || create_windows(r, err) != 0) goto fail;
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        og_error_set(err, "renderer set-up failed: GL error 0x%x", e);
        goto fail;
    }
    return r;
fail:
    terrain_renderer_destroy(r);
    return NULL;
}

void terrain_renderer_destroy(terrain_renderer *r) {
    if (!r) return;
    world_events_unsubscribe(r->changes);
    volume_renderer_destroy(r->volume);
    planet_renderer_destroy(r->planet);
    for (int i = 0; i < TERRAIN_PROGRAMS; i++)
        if (r->progs[i].prog) glDeleteProgram(r->progs[i].prog);
    mask_flow_texture_destroy(&r->mask_flow);
    glDeleteProgram(r->prog_sky);
    deferred_target_free(&r->deferred);
    glDeleteProgram(r->prog_water);
    glDeleteProgram(r->prog_cursor);
    glDeleteVertexArrays(1, &r->vao);
    glDeleteVertexArrays(1, &r->empty_vao);
    glDeleteBuffers(1, &r->vbo);
    glDeleteBuffers(1, &r->ebo);
    glDeleteVertexArrays(1, &r->refine_vao);
    glDeleteBuffers(1, &r->refine_vbo);
    glDeleteBuffers(1, &r->refine_ebo);
    clip_refine_mesh_free(&r->refine_mesh);
    clip_refine_map_free(&r->refine_map);
    GLuint tex[] = {r->tex_heights,   r->tex_material, r->tex_albedo,    r->tex_detail,
                    r->tex_detail_pd, r->tex_falloff,  r->tex_albedo_far};
    glDeleteTextures(7, tex);
    clipmap_mesh_free(&r->mesh);
    for (int l = 0; l < RENDER_MAX_LEVELS; l++) {
        clip_window_free(&r->heights[l]);
        clip_window_free(&r->material[l]);
    }
    clip_window_free(&r->detail);
    clip_window_free(&r->detail_pd);
    clip_slopes_free(&r->slopes);
    free(r);
}

static int64_t floor_to_i64(double v) {
    return (int64_t)floor(v);
}

// The level layout for this camera (Asirvatham & Hoppe's nesting): level l's local
// vertex (0,0) sits at an even sample index so the next coarser level's samples land
// on its vertices, and the finer level sits m-1 or m quads inside it.
static void layout_levels(terrain_renderer *r, const world_params *p, const camera *cam,
                          const render_settings *s) {
    int m = (CLIP_N + 1) / 4;
    r->levels = s->levels < RENDER_MIN_LEVELS   ? RENDER_MIN_LEVELS
                : s->levels > RENDER_MAX_LEVELS ? RENDER_MAX_LEVELS
                                                : s->levels;
    // Skip levels too fine to matter from high up (their whole extent is far below).
    double ground;
    double above = terrain_renderer_height_at(r, cam->pos[0], cam->pos[2], &ground) == 0
                       ? fabs(cam->pos[1] - ground)
                       : 0.0;
    r->finest = 0;
    // A level is drawn while its extent exceeds the camera's height above the ground
    // (Hoppe uses 2.5x the height; that dropped 2 m samples still 3-5 pixels wide at
    // 960x540 and cost RMSE against a full-resolution render). At least three levels
    // are always drawn.
    while (r->finest < r->levels - 3 &&
           (CLIP_N - 1) * p->spacing * (double)(1 << r->finest) < above)
        r->finest++;
    for (int l = 0; l < r->levels; l++) {
        double level_spacing = p->spacing * (double)((int64_t)1 << l);
        for (int a = 0; a < 2; a++) {
            double c = cam->pos[a == 0 ? 0 : 2] / level_spacing;
            r->origin[l][a] = 2 * floor_to_i64(c / 2.0) - (2 * m - 2);
        }
    }
}

// Widens level l's height bounds by the texels of rects (all: the whole window), after
// forgetting them (reset, or all).
static void scan_bounds(terrain_renderer *r, int l, const texel_rect *rects, int count, int all,
                        int reset) {
    const clip_window *w = &r->heights[l];
    const float *h = (const float *)w->mirror;
    texel_rect whole = {0, 0, w->size, w->size};
    if (all) rects = &whole, count = 1, reset = 1;
    if (reset) r->hmin[l] = INFINITY, r->hmax[l] = -INFINITY;
    for (int k = 0; k < count; k++)
        for (int z = rects[k].z; z < rects[k].z + rects[k].h; z++)
            for (int x = rects[k].x; x < rects[k].x + rects[k].w; x++) {
                float v = h[(size_t)z * w->size + x];
                if (v < r->hmin[l]) r->hmin[l] = v;
                if (v > r->hmax[l]) r->hmax[l] = v;
            }
}

// Sends what changed in a window's mirror to its texture (layer for array textures),
// the coarse heights' bounds re-measured over it first.
static void upload_window(terrain_renderer *r, clip_window *w, GLuint tex, int layer, GLenum format,
                          GLenum type) {
    // A whole upload or the first band of a fill from nothing starts the bounds afresh.
    if (layer >= 0 && w->layer == TILE_LAYER_COARSE && (w->upload_all || w->upload_count > 0)) {
        r->cells_stale[layer] = 1;
        r->refine_stale[layer] = 1;
        scan_bounds(r, layer, w->uploads, w->upload_count, w->upload_all, w->refill_started);
        w->refill_started = 0;
    }
    r->frame_texels += clip_window_upload(w, tex, layer, format, type);
}

// Level l's steepest step between neighbouring samples of its window (in sample order:
// the toroidal mirror's wrap seam is not a step), in metres per metre.
static void measure_slopes(terrain_renderer *r, int l, int i0, int j0, int i1, int j1) {
    const clip_window *w = &r->heights[l];
    const float *h = (const float *)w->mirror;
    int n = w->size, mask = n - 1, x0 = (int)(w->have[0] & mask), z0 = (int)(w->have[1] & mask);
    float steepest = 0.0f;
    for (int j = j0; j < j1; j++) {
        const float *row = h + (size_t)((z0 + j) & mask) * n;
        const float *next = h + (size_t)((z0 + j + 1) & mask) * n;
        for (int i = i0; i < i1; i++) {
            int x = (x0 + i) & mask;
            float a = row[x];
            if (i + 1 < n) steepest = fmaxf(steepest, fabsf(row[(x + 1) & mask] - a));
            if (j + 1 < n) steepest = fmaxf(steepest, fabsf(next[x] - a));
        }
    }
    double slope = steepest / (r->params.spacing * (double)((int64_t)1 << l));
    if (i0 == 0 && j0 == 0 && i1 == n && j1 == n)
        r->slope_max[l] = slope;
    else
        r->slope_max[l] = fmax(r->slope_max[l], slope);
}

// What a whole window's changes do to its slope bound: a move or an edit widens it by
// the steps into and inside the texels that changed (a sample before each, as the
// steps run forward); a refill or a fill under way measures it again once whole.
static void slopes_changed(terrain_renderer *r, int l) {
    const clip_window *w = &r->heights[l];
    if (!(w->upload_all || w->upload_count > 0)) return;
    if (w->upload_all || w->refill_started || !w->has_data || r->slope_stale[l]) {
        r->slope_stale[l] = 1;
        return;
    }
    int n = w->size, mask = n - 1;
    for (int k = 0; k < w->upload_count; k++) {
        const texel_rect *t = &w->uploads[k]; // never across the window's own seam
        int i = (int)((t->x - w->have[0]) & mask), j = (int)((t->z - w->have[1]) & mask);
        measure_slopes(r, l, i > 0 ? i - 1 : 0, j > 0 ? j - 1 : 0, i + t->w, j + t->h);
    }
}

// Whether any texel of rect t of a material window holds paint (weight 0, "automatic",
// under 255).
static int rect_has_paint(const clip_window *w, texel_rect t) {
    for (int z = t.z; z < t.z + t.h; z++) {
        const unsigned char *row = w->mirror + ((size_t)z * w->size + t.x) * w->texel_bytes;
        for (int x = 0; x < t.w; x++)
            if (row[(size_t)x * w->texel_bytes] != 255) return 1;
    }
    return 0;
}

// Uploads what changed in level l's material window while it holds paint. A window
// without paint is not uploaded (its level draws without the painted variant); once
// paint enters it, all of it is.
static void upload_material(terrain_renderer *r, int l) {
    clip_window *w = &r->material[l];
    if (!w->upload_all && w->upload_count == 0) return;
    int was = r->mat_painted[l], painted = was;
    if (w->upload_all || w->refill_started) {
        painted = rect_has_paint(w, (texel_rect){0, 0, w->size, w->size});
        w->refill_started = 0;
    }
    for (int k = 0; k < w->upload_count && !painted && !w->upload_all; k++)
        painted = rect_has_paint(w, w->uploads[k]);
    r->mat_painted[l] = painted;
    if (!painted) {
        w->upload_all = 0, w->upload_count = 0;
        return;
    }
    if (!was) w->upload_all = 1; // what was skipped while it had none
    upload_window(r, w, r->tex_material, l, GL_RG_INTEGER, GL_UNSIGNED_INT);
}

// Whether the world has paint anywhere: saved, in the journal of unsaved edits, or
// edited in the cache (later paint changes reach the renderer as change notifications).
static int world_has_paint(world *w) {
    if (tile_cache_edited_keys(world_cache(w), TILE_LAYER_MATERIAL, NULL, 0) > 0) return 1;
    tile_store *s[2] = {world_store(w), world_journal(w)};
    for (int i = 0; i < 2; i++)
        if (s[i] && tile_store_count(s[i], TILE_LAYER_MATERIAL) > 0) return 1;
    return 0;
}

static void invalidate_all(terrain_renderer *r) {
    for (int l = 0; l < RENDER_MAX_LEVELS; l++) {
        clip_window_invalidate(&r->heights[l]);
        r->slope_max[l] = INFINITY, r->slope_stale[l] = 1;
        r->cells[l].cells = 0, r->cells_stale[l] = 1;
        r->refine_cells[l].cells = 0, r->refine_stale[l] = 1;
        clip_window_invalidate(&r->material[l]);
    }
    clip_window_invalidate(&r->detail);
    clip_window_invalidate(&r->detail_pd);
    clip_slopes_invalidate(&r->slopes);
    if (r->volume) volume_renderer_reset(r->volume);
}

// Re-reads just the changed samples of every window.
static void refresh_area(terrain_renderer *r, tile_cache *cache, const world_event *e) {
    grid_rect g = e->rect;
    if (e->face != 0 || e->level != 0) return;
    switch (e->layer) {
    case TILE_LAYER_COARSE: {
        // Mips are tent-filtered: a change reaches one sample further per level.
        for (int l = 0; l < RENDER_MAX_LEVELS; l++)
            clip_window_refresh(&r->heights[l], cache, (g.x0 >> l) - 1, (g.z0 >> l) - 1,
                                ((g.x1 - 1) >> l) + 2, ((g.z1 - 1) >> l) + 2);
        clip_slopes_refresh(&r->slopes, cache, g.x0, g.z0, g.x1, g.z1);
        // Volume meshes include the ground inside their bricks (and its slope).
        int64_t k = r->params.volume_ratio > 0 ? r->params.volume_ratio : 1;
        volume_renderer_touched(
            r->volume, (grid_rect){(g.x0 - 1) * k, (g.z0 - 1) * k, (g.x1 + 1) * k, (g.z1 + 1) * k},
            0);
        break;
    }
    case TILE_LAYER_VOLUME:
        volume_renderer_touched(r->volume, g, 1);
        break;
    case TILE_LAYER_MATERIAL: // tent-filtered mips too (editor/edit/material_mips.h)
        r->paint_seen = 1;
        for (int l = 0; l < RENDER_MAX_LEVELS; l++)
            clip_window_refresh(&r->material[l], cache, (g.x0 >> l) - 1, (g.z0 >> l) - 1,
                                ((g.x1 - 1) >> l) + 2, ((g.z1 - 1) >> l) + 2);
        break;
    case TILE_LAYER_DETAIL:
    case TILE_LAYER_DETAIL_PD: // slopes change one sample around the change
        clip_window_refresh(&r->detail, cache, g.x0 - 1, g.z0 - 1, g.x1 + 1, g.z1 + 1);
        clip_window_refresh(&r->detail_pd, cache, g.x0 - 1, g.z0 - 1, g.x1 + 1, g.z1 + 1);
        break;
    default:
        break;
    }
}

// What changed since the last frame, from the world's change notifications: edited
// areas are re-read, new parameters or another world refill everything.
static int apply_changes(terrain_renderer *r, world *w, og_error *err) {
    world_events *hub = world_event_hub(w);
    int fresh = r->world != w;
    if (!r->changes || world_subscription_hub(r->changes) != hub) {
        world_events_unsubscribe(r->changes);
        r->changes = world_events_subscribe(hub, NULL, NULL);
        if (!r->changes) return og_error_set(err, "out of memory");
        fresh = 1;
    }
    r->world = w;
    if (fresh) {
        invalidate_all(r);
        r->paint_seen = world_has_paint(w);
    }
    if (fresh && r->planet) planet_renderer_forget(r->planet);
    tile_cache *cache = world_cache(w);
    world_event events[64];
    size_t n;
    while ((n = world_subscription_take(r->changes, events, 64)) > 0) {
        for (size_t i = 0; i < n; i++) {
            const world_event *e = &events[i];
            if (r->planet && (e->kind == WORLD_EVENT_PARAMS || e->kind == WORLD_EVENT_REPLACED))
                planet_renderer_forget(r->planet);
            else if (r->planet && e->kind == WORLD_EVENT_AREA && e->level == 0 &&
                     (e->layer == TILE_LAYER_COARSE || e->layer == TILE_LAYER_MATERIAL))
                planet_renderer_touched(r->planet, e->face, e->rect);
            else if (r->planet && e->kind == WORLD_EVENT_AREA && e->level == 0 &&
                     (e->layer == TILE_LAYER_DETAIL || e->layer == TILE_LAYER_DETAIL_PD))
                planet_renderer_detail_touched(r->planet, cache, e->face, e->rect);
            if (events[i].kind == WORLD_EVENT_PARAMS || events[i].kind == WORLD_EVENT_REPLACED)
                invalidate_all(r);
            else if (events[i].kind == WORLD_EVENT_AREA)
                refresh_area(r, cache, &events[i]);
        }
        if (n < 64) break;
    }
    return 0;
}

// The planet's figures in the viewport's terms (texels: chunk vertices uploaded).
static void copy_planet_stats(terrain_renderer *r) {
    planet_stats ps;
    planet_renderer_stats(r->planet, &ps);
    r->stats.triangles = ps.triangles;
    r->stats.draw_calls = ps.draw_calls;
    r->stats.levels_drawn = ps.chunks_drawn;
    r->stats.levels_ready = ps.chunks_resident;
    r->stats.finest_level = ps.finest_level;
    r->stats.texels_uploaded = ps.vertices_uploaded;
    r->stats.cpu_ms = ps.cpu_ms;
}

int terrain_renderer_update(terrain_renderer *r, world *w, const camera *cam,
                            const render_settings *s, og_error *err) {
    double t0 = thread_cpu_ms();
    const world_params *p = world_get_params(w);
    if (p->kind == WORLD_PLANET) {
        if (!r->planet && !(r->planet = planet_renderer_create(r->resource_dir, r->tex_albedo,
                                                               r->tex_falloff, err)))
            return -1;
        if (apply_changes(r, w, err) != 0) return -1;
        r->params = *p;
        int rc = planet_renderer_update(r->planet, w, cam, s, (double)r->width / r->height,
                                        r->height, err);
        copy_planet_stats(r);
        return rc;
    }
    // Tile coordinates are int32: keep the window's samples addressable (with margin).
    double limit = 0.25 * 2147483647.0 * TILE_SIZE * p->spacing;
    if (!(fabs(cam->pos[0]) < limit && fabs(cam->pos[2]) < limit && fabs(cam->pos[1]) < 1e12))
        return og_error_set(err,
                            "the camera (%g, %g, %g) m is outside the world's addressable "
                            "range (|x|, |z| < %g m at %g m spacing)",
                            cam->pos[0], cam->pos[1], cam->pos[2], limit, p->spacing);
    r->frame_texels = 0;
    if (apply_changes(r, w, err) != 0) return -1;
    r->params = *p;
    material_rules_resolve(&p->material_rules, world_params_ocean_height(p), p->max_height,
                           &r->rules);
    layout_levels(r, p, cam, s);
    // Meshing waits for nothing but takes CPU: a few milliseconds a frame while moving.
    int volume_ok = volume_renderer_update(r->volume, w, cam, 12.0, err);
    if (volume_ok < 0) return -1;
    tile_cache *cache = world_cache(w);
    int all = 1;
    // Texels this frame may copy beyond small moves: a jump or a level the camera comes
    // down to refills over a few frames (the next coarser level stands in meanwhile), so
    // no frame uploads more than a tenth of the level textures. Only the coarsest
    // level's first fill, which nothing can stand in for, is made at once.
    int64_t budget = r->whole_uploads ? INT64_MAX / 2
                                      : (int64_t)r->levels * CLIP_TEXELS * CLIP_TEXELS *
                                            UPLOAD_BUDGET_PERCENT / 100;
    // Finest first: the cache serves the last request first, so the coarsest level,
    // which stands in for all the others, arrives first.
    for (int l = r->finest; l < r->levels; l++) {
        clip_window *hw = &r->heights[l];
        int first_fill = l == r->levels - 1 && !hw->has_data && !hw->partial;
        int ok = first_fill ? clip_window_update(hw, cache, r->origin[l])
                            : clip_window_update_within(hw, cache, r->origin[l], &budget);
        if (ok < 0) return og_error_set(err, "the clipmap could not read level %d", l);
        if (!ok) all = 0;
    }
    int mat_current[RENDER_MAX_LEVELS] = {0};
    for (int l = r->finest; l < r->levels && r->paint_seen; l++) {
        int ok = clip_window_update_within(&r->material[l], cache, r->origin[l], &budget);
        if (ok < 0) return og_error_set(err, "the clipmap could not read the paint of level %d", l);
        mat_current[l] = ok == 1;
        if (!ok) all = 0;
    }
    r->detail_current = 0;
    { // detail heights and slopes near the camera (slopes shade even without parallax)
        double ds = p->spacing / p->detail_ratio;
        for (int a = 0; a < 2; a++) {
            int64_t c = floor_to_i64(cam->pos[a == 0 ? 0 : 2] / ds) - DETAIL_TEXELS / 2;
            r->detail_origin[a] = (c / DETAIL_SNAP - (c % DETAIL_SNAP < 0)) * DETAIL_SNAP;
        }
        double ground;
        int near_ground = terrain_renderer_height_at(r, cam->pos[0], cam->pos[2], &ground) == 0 &&
                          fabs(cam->pos[1] - ground) < s->detail_distance;
        if (near_ground) {
            int a = clip_window_update_within(&r->detail, cache, r->detail_origin, &budget);
            int b = clip_window_update_within(&r->detail_pd, cache, r->detail_origin, &budget);
            r->detail_current = a == 1 && b == 1;
            if (!r->detail_current) all = 0;
        }
    }
    { // the shading slopes, within a budget of the same share of their textures
        int64_t fine_budget = r->whole_uploads
                                  ? INT64_MAX / 2
                                  : (int64_t)r->levels * CLIP_SLOPES_TEXELS * CLIP_SLOPES_TEXELS *
                                        UPLOAD_BUDGET_PERCENT / 100;
        int ok = clip_slopes_update(&r->slopes, cache, (const int64_t(*)[2])r->origin, r->finest,
                                    r->levels, &fine_budget);
        if (ok < 0) return og_error_set(err, "the clipmap could not read its shading slopes");
        if (!ok) all = 0;
    }
    // Uploads, and which level each level draws from while its own is not current.
    for (int l = r->finest; l < r->levels; l++) {
        clip_window *hw = &r->heights[l];
        slopes_changed(r, l);
        upload_window(r, hw, r->tex_heights, l, GL_RED, GL_FLOAT);
        if (r->slope_stale[l] && clip_window_current(hw, r->origin[l])) {
            measure_slopes(r, l, 0, 0, hw->size, hw->size);
            r->slope_stale[l] = 0;
        }
        if (r->cells_stale[l] && clip_window_current(hw, r->origin[l])) {
            clip_cells_build(&r->cells[l], hw);
            r->cells_stale[l] = 0;
        }
    }
    for (int l = r->finest; l < r->levels && r->paint_seen; l++)
        upload_material(r, l);
    upload_window(r, &r->detail, r->tex_detail, -1, GL_RED, GL_FLOAT);
    upload_window(r, &r->detail_pd, r->tex_detail_pd, -1, GL_RG, GL_SHORT);
    for (int l = r->finest > 1 ? r->finest : 1; l < r->levels; l++) {
        const clip_window *fw = &r->slopes.windows[l];
        if (fw->upload_all || fw->upload_count > 0) r->refine_stale[l] = 1;
    }
    clip_slopes_upload(&r->slopes, r->finest, r->levels);
    // Only a refined view reads the cells (draw_terrain): building them for every level
    // whose shading window moved cost 5-8 ms of the calling thread a frame in flight.
    for (int l = r->finest > 1 ? r->finest : 1;
         l < r->levels && (s->refine_pixels > 0 || s->skyline_pixels > 0); l++)
        if (r->refine_stale[l] && clip_window_current(&r->heights[l], r->origin[l]) &&
            clip_window_current(&r->slopes.windows[l], r->slopes.want[l])) {
            clip_refine_cells_build(&r->refine_cells[l], &r->heights[l], &r->slopes.windows[l],
                                    1 << (l - clip_slopes_mip(l)));
            r->refine_stale[l] = 0;
        }
    int below = -1, paint_below = -1;
    for (int l = r->levels - 1; l >= 0; l--) {
        if (l >= r->finest && clip_window_current(&r->heights[l], r->origin[l])) below = l;
        r->src[l] = l >= r->finest ? below : -1;
        if (l >= r->finest && mat_current[l]) paint_below = l;
        r->mat_src[l] = l >= r->finest ? paint_below : -1;
    }
    r->stats.texels_uploaded = r->frame_texels;
    r->stats.slope_texels_uploaded = r->slopes.frame_texels;
    r->stats.levels_ready = 0;
    for (int l = r->finest; l < r->levels; l++)
        r->stats.levels_ready += r->src[l] == l;
    r->stats.finest_level = r->finest;
    r->stats.cpu_ms = thread_cpu_ms() - t0;
    return all && volume_ok;
}

int terrain_renderer_height_at(void *renderer, double x, double z, double *h) {
    terrain_renderer *r = renderer;
    if (!r->world || r->params.kind == WORLD_PLANET) return -1; // planets: no flat heights
    double spacing = r->params.spacing;
    for (int l = r->finest; l < r->levels; l++) {
        const clip_window *w = &r->heights[l];
        if (!clip_window_current(w, r->origin[l])) continue;
        double ls = spacing * (double)((int64_t)1 << l);
        double fx = x / ls - (double)w->have[0], fz = z / ls - (double)w->have[1];
        if (fx < 0 || fz < 0 || fx >= CLIP_N - 1 || fz >= CLIP_N - 1) continue;
        int ix = (int)fx, iz = (int)fz;
        double ax = fx - ix, az = fz - iz;
        const float *m = (const float *)w->mirror;
        int mask = w->size - 1;
        int64_t gx = w->have[0] + ix, gz = w->have[1] + iz;
#define AT(dx, dz) m[(size_t)((gz + (dz)) & mask) * w->size + (size_t)((gx + (dx)) & mask)]
        *h = (AT(0, 0) * (1 - ax) + AT(1, 0) * ax) * (1 - az) +
             (AT(0, 1) * (1 - ax) + AT(1, 1) * ax) * az;
#undef AT
        return 0;
    }
    return -1;
}

static void uniform_vec4s(GLuint prog, const char *name, const float (*v)[4], int count) {
    glProgramUniform4fv(prog, glGetUniformLocation(prog, name), count, &v[0][0]);
}

static double positive_fmod(double a, double b) {
    double m = fmod(a, b);
    return m < 0 ? m + b : m;
}

// Where level-s texels are for level l's local coordinates: texel of local (0,0) and
// texels per local unit, plus the texture layer.
static void source_uniform(const terrain_renderer *r, int l, int s, float out[4]) {
    double scale = 1.0 / (double)((int64_t)1 << (s - l));
    for (int a = 0; a < 2; a++) {
        double rel = (double)r->origin[l][a] * scale - (double)r->origin[s][a];
        out[a] = (float)((double)(r->origin[s][a] & (CLIP_TEXELS - 1)) + rel);
    }
    out[2] = (float)scale;
    out[3] = (float)s;
}

// Where level s's painted weights are for level l's local coordinates: the window
// texel (from its origin) of local (0,0), texels per local unit, and the texture layer
// (-1: no paint to read there, "automatic"); wrap: the toroidal texel of its origin.
static void paint_uniform(const terrain_renderer *r, int l, int s, float out[4], int wrap[2]) {
    out[0] = out[1] = 0, out[2] = 1, out[3] = -1;
    if (s < 0 || !r->mat_painted[s]) return;
    double scale = 1.0 / (double)((int64_t)1 << (s - l));
    for (int a = 0; a < 2; a++) {
        out[a] = (float)((double)r->origin[l][a] * scale - (double)r->origin[s][a]);
        wrap[a] = (int)(r->origin[s][a] & (CLIP_TEXELS - 1));
    }
    out[2] = (float)scale;
    out[3] = (float)s;
}

static double reach_metres(const terrain_renderer *r) {
    return 0.5 * (CLIP_N - 1) * r->params.spacing * (double)((int64_t)1 << (r->levels - 1));
}

static double fog_density(const terrain_renderer *r, const render_settings *s) {
    return s->fog_density > 0 ? s->fog_density : 2.5 / reach_metres(r);
}

static void set_lighting(GLuint prog, const terrain_renderer *r, const render_settings *s) {
    render_lighting_uniforms(prog, s, fog_density(r, s));
}

static const float level_tints[RENDER_MAX_LEVELS][3] = {
    {0.95f, 0.30f, 0.25f}, {0.95f, 0.65f, 0.20f}, {0.90f, 0.90f, 0.25f}, {0.45f, 0.85f, 0.30f},
    {0.25f, 0.80f, 0.70f}, {0.30f, 0.55f, 0.95f}, {0.55f, 0.35f, 0.90f}, {0.90f, 0.40f, 0.80f},
    {0.75f, 0.75f, 0.75f}, {0.60f, 0.45f, 0.30f}, {0.35f, 0.60f, 0.45f}, {0.40f, 0.40f, 0.65f}};

static void set_terrain_uniforms(terrain_renderer *r, GLuint prog, const camera *cam,
                                 const render_settings *s, const brush_cursor *cursor,
                                 const float view_proj[16]) {
    const world_params *p = &r->params;
    float offset[RENDER_MAX_LEVELS][4] = {{0}}, view[RENDER_MAX_LEVELS][4] = {{0}};
    float src_a[RENDER_MAX_LEVELS][4] = {{0}}, src_b[RENDER_MAX_LEVELS][4] = {{0}};
    float slopes_a[RENDER_MAX_LEVELS][4] = {{0}}, slopes_b[RENDER_MAX_LEVELS][4] = {{0}};
    float bounds[RENDER_MAX_LEVELS][4] = {{0}}, uv[RENDER_MAX_LEVELS][4] = {{0}};
    float mat[RENDER_MAX_LEVELS][4] = {{0}}, detail[RENDER_MAX_LEVELS][4] = {{0}};
    float grid[RENDER_MAX_LEVELS][4] = {{0}}, mat_b[RENDER_MAX_LEVELS][4] = {{0}};
    int mat_wrap[RENDER_MAX_LEVELS][4] = {{0}};
    double ratio = p->detail_ratio;
    for (int l = r->finest; l < r->levels; l++) {
        if (r->src[l] < 0) continue;
        double mult = (double)((int64_t)1 << l), ls = p->spacing * mult;
        double x0 = (double)r->origin[l][0] * ls, z0 = (double)r->origin[l][1] * ls;
        offset[l][0] = (float)(x0 - cam->pos[0]);
        offset[l][1] = (float)(z0 - cam->pos[2]);
        offset[l][2] = (float)ls;
        view[l][0] = (float)(cam->pos[0] / ls - (double)r->origin[l][0]);
        view[l][1] = (float)(cam->pos[2] / ls - (double)r->origin[l][1]);
        int coarser = l + 1 < r->levels ? r->src[l + 1] : -1;
        view[l][2] = s->morph && coarser >= 0 ? 1.0f : 0.0f;
        source_uniform(r, l, r->src[l], src_a[l]);
        source_uniform(r, l, coarser >= 0 ? coarser : r->src[l], src_b[l]);
        clip_slopes_uniform(&r->slopes, l, r->src[l], r->origin[l], slopes_a[l]);
        clip_slopes_uniform(&r->slopes, l, coarser >= 0 ? coarser : r->src[l], r->origin[l],
                            slopes_b[l]);
        if (p->size > 0) {
            double last = (double)(p->size - 1) / mult;
            double last_z = (double)(world_params_size_z(p) - 1) / mult;
            bounds[l][0] = (float)(-(double)r->origin[l][0]);
            bounds[l][1] = (float)(-(double)r->origin[l][1]);
            bounds[l][2] = (float)(last - (double)r->origin[l][0]);
            bounds[l][3] = (float)(last_z - (double)r->origin[l][1]);
        } else {
            bounds[l][0] = bounds[l][1] = -UNBOUNDED;
            bounds[l][2] = bounds[l][3] = UNBOUNDED;
        }
        // The tile grid: tiles are TILE_SIZE level-0 samples across, TILE_SIZE >> l here
        // (finer than one level sample from level 8 on: not drawn there).
        int64_t period = TILE_SIZE >> l;
        if (period >= 1) {
            grid[l][0] = (float)(((r->origin[l][0] % period) + period) % period);
            grid[l][1] = (float)(((r->origin[l][1] % period) + period) % period);
            grid[l][2] = (float)period;
        }
        uv[l][0] = (float)positive_fmod(x0, TEX_PERIOD_NEAR);
        uv[l][1] = (float)positive_fmod(z0, TEX_PERIOD_NEAR);
        uv[l][2] = (float)positive_fmod(x0, TEX_PERIOD_FAR);
        uv[l][3] = (float)positive_fmod(z0, TEX_PERIOD_FAR);
        paint_uniform(r, l, r->mat_src[l], mat[l], &mat_wrap[l][0]);
        paint_uniform(r, l, l + 1 < r->levels ? r->mat_src[l + 1] : -1, mat_b[l], &mat_wrap[l][2]);
        if (r->detail_current && l <= 3) {
            detail[l][0] =
                (float)((double)r->origin[l][0] * mult * ratio - (double)r->detail_origin[0]);
            detail[l][1] =
                (float)((double)r->origin[l][1] * mult * ratio - (double)r->detail_origin[1]);
            detail[l][2] = (float)(mult * ratio);
            detail[l][3] = 1;
        }
    }
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE,
                              view_proj);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_cam_y"), (float)cam->pos[1]);
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_morph"), MORPH_START, MORPH_BAND);
    uniform_vec4s(prog, "u_lvl_offset", offset, RENDER_MAX_LEVELS);
    uniform_vec4s(prog, "u_lvl_view", view, RENDER_MAX_LEVELS);
    uniform_vec4s(prog, "u_lvl_src_a", src_a, RENDER_MAX_LEVELS);
    uniform_vec4s(prog, "u_lvl_src_b", src_b, RENDER_MAX_LEVELS);
    uniform_vec4s(prog, "u_lvl_slopes_a", slopes_a, RENDER_MAX_LEVELS);
    uniform_vec4s(prog, "u_lvl_slopes_b", slopes_b, RENDER_MAX_LEVELS);
    uniform_vec4s(prog, "u_lvl_bounds", bounds, RENDER_MAX_LEVELS);
    uniform_vec4s(prog, "u_lvl_uv", uv, RENDER_MAX_LEVELS);
    uniform_vec4s(prog, "u_lvl_mat", mat, RENDER_MAX_LEVELS);
    uniform_vec4s(prog, "u_lvl_detail", detail, RENDER_MAX_LEVELS);
    uniform_vec4s(prog, "u_lvl_grid", grid, RENDER_MAX_LEVELS);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_overlays"),
                       (s->tile_grid ? 1 : 0) | (s->level_grid ? 2 : 0));
    glProgramUniform3i(prog, glGetUniformLocation(prog, "u_mask"), s->mask_terms != 0,
                       s->mask_invert, s->mask_terms);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_mask_height"), 1, s->mask_height);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_mask_slope"), 1, s->mask_slope);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_mask_curvature"), 1, s->mask_curvature);
    glProgramUniform3fv(prog, glGetUniformLocation(prog, "u_level_tint"), RENDER_MAX_LEVELS,
                        &level_tints[0][0]);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_view_mode"), s->view);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_contour"), (float)s->contours);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_auto_materials"), s->auto_materials);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_ocean_level"),
                       (float)world_params_ocean_height(p));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_max_height"), (float)p->max_height);
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_tex_period"), (float)TEX_PERIOD_NEAR,
                       (float)TEX_PERIOD_FAR);
    uniform_vec4s(prog, "u_lvl_mat_b", mat_b, RENDER_MAX_LEVELS);
    glProgramUniform4iv(prog, glGetUniformLocation(prog, "u_lvl_mat_wrap"), RENDER_MAX_LEVELS,
                        &mat_wrap[0][0]);
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_detail_wrap"),
                       (float)(r->detail_origin[0] & (DETAIL_TEXELS - 1)),
                       (float)(r->detail_origin[1] & (DETAIL_TEXELS - 1)));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_detail_spacing"),
                       (float)(p->spacing / ratio));
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_detail_size"), DETAIL_TEXELS);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_parallax"), s->parallax);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_parallax_steps"), s->parallax_steps);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_parallax_fade"),
                       (float)s->detail_distance);
    float brush[4] = {0, 0, 1, 0};
    if (cursor && cursor->visible && cursor->radius > 0 && !cursor->sphere) {
        brush[0] = (float)(cursor->x - cam->pos[0]);
        brush[1] = (float)(cursor->z - cam->pos[2]);
        brush[2] = (float)cursor->radius;
        brush[3] = 1;
    }
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_brush"), 1, brush);
    float tint[4] = {1.0f, 0.55f, 0.1f, 0.35f}, ring[3] = {1.0f, 0.9f, 0.3f}; // default: orange
    if (cursor && cursor->opacity > 0) { // the tool's colour, the ring a lighter shade of it
        for (int i = 0; i < 3; i++)
            tint[i] = cursor->color[i], ring[i] = 0.65f * cursor->color[i] + 0.35f;
        tint[3] = cursor->opacity;
    }
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_brush_tint"), 1, tint);
    glProgramUniform3fv(prog, glGetUniformLocation(prog, "u_brush_ring"), 1, ring);
    set_lighting(prog, r, s);
    const char *samplers[] = {"u_heights", "u_material",  "u_albedo",
                              "u_detail",  "u_detail_pd", "u_falloff"};
    for (int i = 0; i < 6; i++)
        glProgramUniform1i(prog, glGetUniformLocation(prog, samplers[i]), i);
    GLuint tex[] = {r->tex_heights, r->tex_material,  r->tex_albedo,
                    r->tex_detail,  r->tex_detail_pd, r->tex_falloff};
    glBindTextures(0, 6, tex);
    volume_renderer_mask_uniforms(r->volume, prog, cam, 6);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_albedo_far"), 7);
    glBindTextureUnit(7, r->tex_albedo_far);
    mask_flow_texture_bind(&r->mask_flow, prog, s, cam, 8);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_slopes"), 9);
    glBindTextureUnit(9, r->slopes.tex);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_refine"), REFINE_UNIT);
    glBindTextureUnit(REFINE_UNIT, r->refine_map.tex);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_albedo_mean"), MATERIAL_TEXTURE_COUNT,
                        &r->albedo_mean[0][0]);
}

// The heights a piece of level l can take: its source's samples under it and, where
// it morphs, the coarser source's (bilinear between the samples around it); the
// sources' whole bounds where their cells are not built.
static void piece_heights(const terrain_renderer *r, int l, const clip_piece *pc, int morphs,
                          float *lo, float *hi) {
    int s = r->src[l], c = morphs && l + 1 < r->levels && r->src[l + 1] >= 0 ? r->src[l + 1] : s;
    *lo = INFINITY, *hi = -INFINITY;
    for (int k = 0; k < (c != s ? 2 : 1); k++) {
        int src = k == 0 ? s : c, shift = src - l;
        double i0 = (double)(r->origin[l][0] + pc->x0), i1 = (double)(r->origin[l][0] + pc->x1);
        double j0 = (double)(r->origin[l][1] + pc->z0), j1 = (double)(r->origin[l][1] + pc->z1);
        // In src's samples: the floor at the low end, the ceiling at the high end.
        float a, b;
        if (r->cells_stale[src] ||
            !clip_cells_range(&r->cells[src], floor_to_i64(ldexp(i0, -shift)),
                              floor_to_i64(ldexp(j0, -shift)), -floor_to_i64(-ldexp(i1, -shift)),
                              -floor_to_i64(-ldexp(j1, -shift)), &a, &b))
            a = r->hmin[src], b = r->hmax[src];
        *lo = fminf(*lo, a), *hi = fmaxf(*hi, b);
    }
}

// The camera-relative bounding box of a piece of level l between heights lo and hi.
static void piece_box(const terrain_renderer *r, int l, const clip_piece *pc, const camera *cam,
                      float lo, float hi, float mn[3], float mx[3]) {
    double ls = r->params.spacing * (double)((int64_t)1 << l);
    double x0 = (double)r->origin[l][0] * ls - cam->pos[0],
           z0 = (double)r->origin[l][1] * ls - cam->pos[2];
    mn[0] = (float)(x0 + pc->x0 * ls), mx[0] = (float)(x0 + pc->x1 * ls);
    mn[1] = (float)(lo - cam->pos[1]), mx[1] = (float)(hi - cam->pos[1]);
    mn[2] = (float)(z0 + pc->z0 * ls), mx[2] = (float)(z0 + pc->z1 * ls);
}

static int cursor_drapes(const brush_cursor *cursor) {
    return cursor && cursor->visible && cursor->radius > 0 && !cursor->sphere;
}

// Horizontal metres from the camera to the nearest ground level l draws: the edge of
// the finer level's square, which the camera stands in (0 for the finest level).
static double level_nearest(const terrain_renderer *r, const camera *cam, int l) {
    if (l <= r->finest) return 0.0;
    double ls = r->params.spacing * (double)((int64_t)1 << (l - 1)), nearest = INFINITY;
    for (int a = 0; a < 2; a++) {
        double lo = (double)r->origin[l - 1][a] * ls, hi = lo + (CLIP_N - 1) * ls;
        double c = cam->pos[a == 0 ? 0 : 2];
        nearest = fmin(nearest, fmin(c - lo, hi - c));
    }
    return fmax(nearest, 0.0);
}

// The variant level l is drawn with: only what it can show this frame.
static int level_variant(const terrain_renderer *r, const camera *cam, const render_settings *s,
                         const brush_cursor *cursor, int l) {
    int v = (s->tile_grid || s->level_grid || s->mask_terms ? TV_OVERLAYS : 0) |
            (s->contours > 0 ? TV_CONTOURS : 0);
    // Detail where set_terrain_uniforms places it and the level comes within the distance
    // it fades out by (beyond, the shader's fade is 0: the same colour without it).
    if (r->detail_current && l <= 3 && level_nearest(r, cam, l) < s->detail_distance * 1.01 + 1.0)
        v |= TV_DETAIL;
    if (volume_renderer_active(r->volume)) v |= TV_VOLUME;
    // Where the slopes come from, as set_terrain_uniforms says.
    float fine[4];
    int coarser = l + 1 < r->levels ? r->src[l + 1] : -1;
    clip_slopes_uniform(&r->slopes, l, r->src[l], r->origin[l], fine);
    if (fine[3] >= 0) v |= TV_SLOPES_A;
    clip_slopes_uniform(&r->slopes, l, coarser >= 0 ? coarser : r->src[l], r->origin[l], fine);
    if (fine[3] >= 0) v |= TV_SLOPES_B;
    if (s->view != VIEW_SHADED) return v;
    v |= TV_SHADED;
    if (r->rules.uses_curvature) v |= TV_CURVATURE;
    if (r->mat_src[l] >= 0 && r->mat_painted[r->mat_src[l]]) v |= TV_PAINTED;
    if (cursor_drapes(cursor)) v |= TV_BRUSH;
    // So far that the material textures' near scale is smaller than a pixel all over
    // the level: every lookup would return the texture's 1 x 1 level (as the planet's
    // chunks; the factor 4 for the screen's corners and filtering's rough measure).
    double pixels_per_radian =
        (r->height > 0 ? r->height : 720) / (2.0 * tan(cam->fov_y * M_PI / 360.0));
    if (!(v & TV_DETAIL) && level_nearest(r, cam, l) > 4.0 * TEX_PERIOD_NEAR * pixels_per_radian)
        v |= TV_MINIFIED;
    return v;
}

// The material rules that can have weight on level l: those whose height and slope
// ranges meet the level's (and the coarser one it morphs into), with a margin for the
// shader's rounding. The others are skipped: two texture lookups a fragment fewer each.
static unsigned level_rules_live(const terrain_renderer *r, const material_rules_resolved *rules,
                                 int l) {
    int a = r->src[l], b = l + 1 < r->levels && r->src[l + 1] >= 0 ? r->src[l + 1] : a;
    double slope = fmax(r->slope_max[a], r->slope_max[b]) * 1.01 + 1e-4;
    return material_rules_live(rules, fmin(r->hmin[a], r->hmin[b]) - 1.0,
                               fmax(r->hmax[a], r->hmax[b]) + 1.0, slope);
}

// A level's drawable part and its squared distance from the camera (level units).
typedef struct piece_order {
    float distance2;
    int piece;
} piece_order;

static int nearer_first(const void *a, const void *b) {
    const piece_order *p = a, *q = b;
    return (p->distance2 > q->distance2) - (p->distance2 < q->distance2);
}

// Whether the camera is above the ground drawn under it (ground_occlusion.h's argument
// needs it): the highest sample around it in the finest level drawn and the one it
// morphs into.
static int camera_above_ground(const terrain_renderer *r, const camera *cam) {
    int l = r->finest;
    if (l >= r->levels || r->src[l] < 0) return 0;
    double ls = r->params.spacing * (double)((int64_t)1 << l);
    int64_t x = floor_to_i64(cam->pos[0] / ls) - r->origin[l][0];
    int64_t z = floor_to_i64(cam->pos[2] / ls) - r->origin[l][1];
    if (x < 0 || z < 0 || x + 1 >= CLIP_N || z + 1 >= CLIP_N) return 0;
    clip_piece under = {
        .x0 = (uint16_t)x, .z0 = (uint16_t)z, .x1 = (uint16_t)(x + 1), .z1 = (uint16_t)(z + 1)};
    float lo, hi;
    piece_heights(r, l, &under, 1, &lo, &hi);
    return cam->pos[1] > hi + 0.01 + 1e-6 * fabs(hi);
}

// Whether a camera-relative box is hidden by the ground added so far.
static int box_hidden(const terrain_renderer *r, const float mn[3], const float mx[3]) {
    double pts[8][3];
    for (int k = 0; k < 8; k++)
        pts[k][0] = (k & 1) ? mx[0] : mn[0], pts[k][1] = (k & 2) ? mx[1] : mn[1],
        pts[k][2] = (k & 4) ? mx[2] : mn[2];
    return ground_occlusion_hidden(&r->occlusion, (const double(*)[3])pts, 8);
}

// The solid under a drawn piece's ground (its box from its lowest point less a margin
// for float rounding, as deep again as the piece is wide), cut to a bounded world's
// extent (lo, hi: level l's local units), outside which the ground is not drawn.
static void add_solid_under(terrain_renderer *r, int l, const float mn[3], const float mx[3],
                            const double lo[2], const double hi[2], const camera *cam) {
    double ls = r->params.spacing * (double)((int64_t)1 << l);
    double x0 = mn[0], x1 = mx[0], z0 = mn[2], z1 = mx[2];
    double ox = (double)r->origin[l][0] * ls - cam->pos[0],
           oz = (double)r->origin[l][1] * ls - cam->pos[2];
    x0 = fmax(x0, ox + lo[0] * ls), x1 = fmin(x1, ox + hi[0] * ls);
    z0 = fmax(z0, oz + lo[1] * ls), z1 = fmin(z1, oz + hi[1] * ls);
    if (!(x0 < x1 && z0 < z1)) return;
    double top = mn[1] - 0.01 - 1e-6 * fabs(mn[1] + cam->pos[1]);
    double bottom = top - fmax(x1 - x0, z1 - z0);
    double pts[8][3];
    for (int k = 0; k < 8; k++)
        pts[k][0] = (k & 1) ? x1 : x0, pts[k][1] = (k & 2) ? top : bottom,
        pts[k][2] = (k & 4) ? z1 : z0;
    ground_occlusion_add_solid(&r->occlusion, (const double(*)[3])pts, 8);
}

// Widens the pixel rectangle rect (x0, y0, x1, y1) by a camera-relative box's
// projection: its corners in front of the camera and, where an edge crosses the
// camera's plane, the edge's point just in front of it (far off the screen, so the
// rectangle reaches the screen's edge that way).
static void widen_screen_rect(const float view_proj[16], const float mn[3], const float mx[3],
                              int width, int height, int rect[4]) {
    const double near_w = 1e-3;
    double c[8][4];
    for (int k = 0; k < 8; k++) {
        const double p[3] = {(k & 1) ? mx[0] : mn[0], (k & 2) ? mx[1] : mn[1],
                             (k & 4) ? mx[2] : mn[2]};
        for (int i = 0; i < 4; i++)
            c[k][i] = view_proj[i] * p[0] + view_proj[4 + i] * p[1] + view_proj[8 + i] * p[2] +
                      view_proj[12 + i];
    }
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int a = 0; a < 8; a++)
        for (int e = -1; e < 3; e++) { // the corner itself, then its edges to higher corners
            const int b = e < 0 ? a : a | (1 << e);
            if (e >= 0 && b == a) continue;
            double q[4];
            if (e < 0) {
                if (!(c[a][3] > near_w)) continue;
                memcpy(q, c[a], sizeof q);
            } else {
                if ((c[a][3] > near_w) == (c[b][3] > near_w)) continue;
                const double t = (near_w - c[a][3]) / (c[b][3] - c[a][3]);
                for (int i = 0; i < 4; i++)
                    q[i] = c[a][i] + t * (c[b][i] - c[a][i]);
            }
            for (int i = 0; i < 2; i++)
                lo[i] = fmin(lo[i], q[i] / q[3]), hi[i] = fmax(hi[i], q[i] / q[3]);
        }
    if (!(lo[0] <= hi[0])) return; // wholly behind the camera
    const int size[2] = {width, height};
    for (int i = 0; i < 2; i++) {
        const double a = fmax((lo[i] * 0.5 + 0.5) * size[i] - 1.0, 0.0);
        const double b = fmin((hi[i] * 0.5 + 0.5) * size[i] + 1.0, (double)size[i]);
        if (a < b)
            rect[i] = (int)fmin(rect[i], floor(a)), rect[2 + i] = (int)fmax(rect[2 + i], ceil(b));
    }
}

// A deferred shading pass: the pixels a level's pieces (still or morphing) won.
typedef struct resolve_pass {
    int level, still, variant, rect[4];
    int stencil_mask; // 0xFE: the level's still and morphing parts in one pass
    char calls[MATERIAL_RULES_MAX * 12];
} resolve_pass;

// The deferred shading: each pass drawn won, then the sky where no ground was drawn.
static int resolve_terrain(terrain_renderer *r, const camera *cam, const render_settings *s,
                           const brush_cursor *cursor, const float view_proj[16],
                           const resolve_pass *passes, int count, og_error *err) {
    float inverse[16];
    if (deferred_target_inverse(view_proj, inverse) != 0)
        return og_error_set(err, "terrain: the view has no inverse");
    deferred_target_shade(&r->deferred, GBUFFER_UNIT);
    glBindVertexArray(r->empty_vao);
    glEnable(GL_SCISSOR_TEST);
    for (int i = 0; i < count; i++) {
        const resolve_pass *p = &passes[i];
        if (p->rect[2] <= p->rect[0] || p->rect[3] <= p->rect[1]) continue;
        int fresh = 0;
        GLuint prog = terrain_program(r, p->variant, p->calls, &fresh, err);
        if (!prog) return -1;
        if (fresh) {
            set_terrain_uniforms(r, prog, cam, s, cursor, view_proj);
            material_rule_uniforms(prog, &r->rules);
            glProgramUniform1i(prog, glGetUniformLocation(prog, "u_ground_depth"), GBUFFER_UNIT);
            glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_inv_view_proj"), 1,
                                      GL_FALSE, inverse);
        }
        glUseProgram(prog);
        glProgramUniform1i(prog, glGetUniformLocation(prog, "u_level"), p->level);
        glStencilFunc(GL_EQUAL, deferred_target_stencil(p->level, p->still) & p->stencil_mask,
                      (GLuint)p->stencil_mask);
        glScissor(p->rect[0], p->rect[1], p->rect[2] - p->rect[0], p->rect[3] - p->rect[1]);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        r->stats.draw_calls++;
    }
    glDisable(GL_SCISSOR_TEST);
    return 0;
}

// The skyline of the levels drawn (renderer/clip_skyline.h): each level's cells over
// what it draws (its square less the finer level's, cut to a bounded world), in the
// units of the level it draws from.
static void build_skyline(terrain_renderer *r, const camera *cam) {
    double forward[3], right[3], up[3];
    camera_forward(cam, forward), camera_right(cam, right), camera_up(cam, up);
    const double ty = tan((cam->fov_y >= 1 && cam->fov_y <= 170 ? cam->fov_y : 60) * M_PI / 360.0);
    clip_skyline_begin(&r->skyline, cam->pos, forward, right, up,
                       ty * r->width / (r->height > 0 ? r->height : 1), ty);
    for (int l = r->finest; l < r->levels; l++) {
        const int src = r->src[l];
        if (src < 0 || r->cells[src].cells == 0) continue;
        const int d = src - l; // src is l or coarser
        int64_t a[2], b[2], ha[2] = {1, 1}, hb[2] = {0, 0};
        for (int k = 0; k < 2; k++) {
            a[k] = r->origin[l][k], b[k] = a[k] + CLIP_N - 1;
            if (l > r->finest) // the finer level's square, in this level's samples
                ha[k] = r->origin[l - 1][k] / 2, hb[k] = (r->origin[l - 1][k] + CLIP_N - 1) / 2;
            if (r->params.size > 0) {
                const int64_t size = k == 0 ? r->params.size : world_params_size_z(&r->params);
                const int64_t last = (size - 1) >> l;
                a[k] = a[k] < 0 ? 0 : a[k], b[k] = b[k] > last ? last : b[k];
            }
            a[k] >>= d, b[k] = (b[k] + (1 << d) - 1) >> d; // floor and ceiling
            ha[k] = (ha[k] + (1 << d) - 1) >> d, hb[k] >>= d;
        }
        if (a[0] > b[0] || a[1] > b[1]) continue;
        clip_skyline_add_level(&r->skyline, &r->cells[src],
                               r->params.spacing * (double)((int64_t)1 << src), a[0], a[1], b[0],
                               b[1], ha[0], ha[1], hb[0], hb[1]);
    }
}

static double level_spacing(const terrain_renderer *r, int l) {
    return r->params.spacing * (double)((int64_t)1 << l);
}

// The band under the skyline whose parts refine at `pixels` of error, in screen units.
static double skyline_band(const terrain_renderer *r, double pixels) {
    return CLIP_SKYLINE_BAND * pixels * 2.0 / (r->height > 0 ? r->height : 720);
}

// A refinable piece's parts' weights near the skyline (renderer/clip_skyline.h), set in
// the level's weight map; returns the most of them.
static float skyline_parts(terrain_renderer *r, int l, size_t piece, double pixels_per_radian,
                           double pixels, float part_w[CLIP_REFINE_PARTS_MAX]) {
    const double band = skyline_band(r, pixels), spacing = level_spacing(r, l);
    float most = 0.0f;
    for (uint32_t k = 0; k < r->refine_mesh.part_count[piece]; k++) {
        const clip_refine_part *q = &r->refine_mesh.parts[r->refine_mesh.part_first[piece] + k];
        const int64_t x = r->origin[l][0], z = r->origin[l][1];
        part_w[k] =
            clip_skyline_weight(&r->skyline, &r->cells[l], &r->refine_cells[l], spacing, x + q->x0,
                                z + q->z0, x + q->x1, z + q->z1, band, pixels_per_radian, pixels);
        clip_refine_map_limit(&r->refine_map, l, q->x0, q->z0, q->x1, q->z1, part_w[k]);
        most = most > part_w[k] ? most : part_w[k];
    }
    return most;
}

// Adds index range [first, first + count) to group g of level l's draws (indices into
// the base mesh's buffer for DRAW_BASE, the refined grid's for the others), joined to
// the group's last draw where it follows it (each sub-draw costs llvmpipe's draw module
// a pass of its own).
static void add_draw(terrain_renderer *r, int l, int n[6], int g, uint32_t first, uint32_t count,
                     GLsizei counts[][DRAWS_MAX], const void *offsets[][DRAWS_MAX]) {
    const size_t size = g < 2 ? sizeof(uint16_t) : sizeof(uint32_t);
    r->stats.triangles += count / 3;
    r->stats.level_triangles[l] += count / 3;
    if (n[g] > 0 &&
        (uintptr_t)offsets[g][n[g] - 1] + (size_t)counts[g][n[g] - 1] * size == first * size) {
        counts[g][n[g] - 1] += (GLsizei)count;
        return;
    }
    if (n[g] == DRAWS_MAX) return;
    counts[g][n[g]] = (GLsizei)count;
    offsets[g][n[g]++] = (const void *)(uintptr_t)(first * size);
}

static int draw_terrain(terrain_renderer *r, const camera *cam, const render_settings *s,
                        const brush_cursor *cursor, const float view_proj[16], int deferred,
                        og_error *err) {
    static resolve_pass passes[2 * RENDER_MAX_LEVELS];
    int pass_count = 0;
    frustum f;
    frustum_from_matrix(&f, view_proj);
    int m = r->mesh.m;
    // Per group of a level's parts (DRAW_BASE, DRAW_FINE or DRAW_SEAMS x may morph or
    // never does).
    static GLsizei counts[6][DRAWS_MAX];
    static const void *offsets[6][DRAWS_MAX];
    const double pixels_per_radian =
        (r->height > 0 ? r->height : 720) /
        (2.0 * tan((cam->fov_y >= 1 && cam->fov_y <= 170 ? cam->fov_y : 60) * M_PI / 360.0));
    const int occlude = s->culling && s->view != VIEW_WIREFRAME &&
                        !volume_renderer_active(r->volume) && camera_above_ground(r, cam);
    if (occlude) {
        double eye[3] = {0, 0, 0}, forward[3], right[3], up[3];
        camera_forward(cam, forward), camera_right(cam, right), camera_up(cam, up);
        const double ty =
            tan((cam->fov_y >= 1 && cam->fov_y <= 170 ? cam->fov_y : 60) * M_PI / 360.0);
        ground_occlusion_begin(&r->occlusion, eye, forward, right, up,
                               ty * r->width / (r->height > 0 ? r->height : 1), ty);
    }
    // Coarse parts refined where their error shows (render refine=P), or only those
    // near the skyline (render skyline=P).
    const int skyline_only = !(s->refine_pixels > 0) && s->skyline_pixels > 0;
    const double refine_pixels = skyline_only ? s->skyline_pixels : s->refine_pixels;
    if (skyline_only) build_skyline(r, cam);
    glBindVertexArray(r->vao);
    r->frame++;
    if (cursor_drapes(cursor)) // the falloff curve, once a frame
        glTextureSubImage2D(r->tex_falloff, 0, 0, 0, BRUSH_FALLOFF_SAMPLES, 1, GL_RED, GL_FLOAT,
                            cursor->falloff);
    GLuint current = 0;
    for (int l = r->finest; l < r->levels; l++) {
        if (r->src[l] < 0) continue;
        clip_trim trims[2] = {CLIP_TRIM_COUNT, CLIP_TRIM_COUNT};
        if (l > r->finest) {
            int off_x = (int)(r->origin[l - 1][0] / 2 - r->origin[l][0]);
            int off_z = (int)(r->origin[l - 1][1] / 2 - r->origin[l][1]);
            clipmap_trims_for_offset(m, off_x, off_z, trims);
        }
        // A bounded world's extent in this level's local units: pieces wholly outside
        // it are not drawn (the fragment shader discards the rest of the outside).
        double lo[2] = {-1e18, -1e18}, hi[2] = {1e18, 1e18};
        if (r->params.size > 0) {
            const double last[2] = {(double)(r->params.size - 1) / (double)((int64_t)1 << l),
                                    (double)(world_params_size_z(&r->params) - 1) /
                                        (double)((int64_t)1 << l)};
            for (int a = 0; a < 2; a++)
                lo[a] = -(double)r->origin[l][a], hi[a] = last[a] - (double)r->origin[l][a];
        }
        // Parts wholly inside the morph band's inner edge (the camera's square of side
        // 2 x MORPH_START, less a hundredth for the varyings' rounding) never morph: they
        // are drawn without the coarser level's lookups (the same values: alpha is 0).
        int morphs = s->morph && l + 1 < r->levels && r->src[l + 1] >= 0;
        double ls = r->params.spacing * (double)((int64_t)1 << l);
        float view[2] = {(float)(cam->pos[0] / ls - (double)r->origin[l][0]),
                         (float)(cam->pos[2] / ls - (double)r->origin[l][1])};
        float reach = MORPH_START - 0.01f;
        // The parts this level may draw, nearest first (so that nearer ground hides
        // what lies behind it, and the depth test rejects more fragments early).
        piece_order order[PIECES_MAX];
        int candidates = 0;
        for (size_t i = 0; i < r->mesh.piece_count && candidates < PIECES_MAX; i++) {
            const clip_piece *pc = &r->mesh.pieces[i];
            if (pc->x1 < lo[0] || pc->x0 > hi[0] || pc->z1 < lo[1] || pc->z0 > hi[1]) continue;
            if (pc->kind == CLIP_PIECE_INTERIOR && l != r->finest) continue;
            if (pc->kind == CLIP_PIECE_TRIM &&
                (l == r->finest || (pc->trim != (int)trims[0] && pc->trim != (int)trims[1])))
                continue;
            float dx = fmaxf(fmaxf(pc->x0 - view[0], view[0] - pc->x1), 0.0f);
            float dz = fmaxf(fmaxf(pc->z0 - view[1], view[1] - pc->z1), 0.0f);
            order[candidates++] = (piece_order){dx * dx + dz * dz, (int)i};
        }
        qsort(order, (size_t)candidates, sizeof order[0], nearer_first);
        // Its parts may be refined where its error shows: its own window and its shading
        // window current, their cells built for this layout.
        const int refinable = refine_pixels > 0 && l >= CLIP_REFINE_MIN_LEVEL && r->src[l] == l &&
                              !r->refine_stale[l] && r->refine_cells[l].cells > 0 &&
                              r->refine_cells[l].have[0] == r->origin[l][0] &&
                              r->refine_cells[l].have[1] == r->origin[l][1] &&
                              clip_window_current(&r->slopes.windows[l], r->slopes.want[l]);
        if (refinable) clip_refine_map_begin(&r->refine_map, l, m - 1, 3 * m - 1);
        int n[6] = {0, 0, 0, 0, 0, 0}; // [DRAW_* * 2 + still]: still parts never morph
        int inside = 1;                // no part drawn reaches the world's edge (a unit's margin)
        int rect[2][4] = {{r->width, r->height, 0, 0}, {r->width, r->height, 0, 0}};
        for (int o = 0; o < candidates; o++) {
            const int i = order[o].piece;
            const clip_piece *pc = &r->mesh.pieces[i];
            int still = !morphs || (pc->x0 >= view[0] - reach && pc->x1 <= view[0] + reach &&
                                    pc->z0 >= view[1] - reach && pc->z1 <= view[1] + reach);
            const int culled_kind = pc->kind == CLIP_PIECE_BLOCK || pc->kind == CLIP_PIECE_FIXUP ||
                                    pc->kind == CLIP_PIECE_INTERIOR;
            float mn[3], mx[3], h0 = 0, h1 = 0, r0, r1, error = 0.0f;
            const int boxed = deferred && pc->kind != CLIP_PIECE_DEGENERATE;
            if (refinable || (s->culling && culled_kind) || boxed)
                piece_heights(r, l, pc, !still, &h0, &h1);
            int refined = 0; // some of its parts drawn at twice the density
            float part_w[CLIP_REFINE_PARTS_MAX];
            if (refinable && clip_refine_piece_refinable(pc) &&
                (!skyline_only ||
                 clip_skyline_near(&r->skyline, &r->cells[l], level_spacing(r, l),
                                   r->origin[l][0] + pc->x0, r->origin[l][1] + pc->z0,
                                   r->origin[l][0] + pc->x1, r->origin[l][1] + pc->z1,
                                   skyline_band(r, refine_pixels))) &&
                clip_refine_cells_range(&r->refine_cells[l], r->origin[l][0] + pc->x0,
                                        r->origin[l][1] + pc->z0, r->origin[l][0] + pc->x1,
                                        r->origin[l][1] + pc->z1, &r0, &r1, &error)) {
                // Its error as seen from its nearest point.
                piece_box(r, l, pc, cam, fminf(h0, r0), fmaxf(h1, r1), mn, mx);
                double d[3];
                for (int a = 0; a < 3; a++)
                    d[a] = fmax(fmax((double)mn[a], -(double)mx[a]), 0.0);
                float w = clip_refine_weight(error, hypot(d[0], d[2]),
                                             sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]),
                                             pixels_per_radian, refine_pixels);
                if (w > 0.0f && skyline_only) { // only its parts near the sky
                    w = skyline_parts(r, l, i, pixels_per_radian, refine_pixels, part_w);
                } else {
                    clip_refine_map_limit(&r->refine_map, l, pc->x0, pc->z0, pc->x1, pc->z1, w);
                    for (uint32_t k = 0; k < r->refine_mesh.part_count[i]; k++)
                        part_w[k] = w;
                }
                if (w > 0.0f) refined = 1, h0 = fminf(h0, r0), h1 = fmaxf(h1, r1);
            } else if (refinable && culled_kind) { // never refined: its vertices stay
                clip_refine_map_limit(&r->refine_map, l, pc->x0, pc->z0, pc->x1, pc->z1, 0.0f);
            }
            if (s->culling && culled_kind) {
                piece_box(r, l, pc, cam, h0, h1, mn, mx);
                if (!frustum_test_aabb(&f, mn, mx)) continue;
                if (occlude) {
                    if (box_hidden(r, mn, mx)) continue;
                    add_solid_under(r, l, mn, mx, lo, hi, cam);
                }
            }
            if (boxed) { // where its pixels can be
                piece_box(r, l, pc, cam, h0, h1, mn, mx);
                widen_screen_rect(view_proj, mn, mx, r->width, r->height, rect[still]);
            }
            if (!(pc->x0 > lo[0] + 1 && pc->x1 < hi[0] - 1 && pc->z0 > lo[1] + 1 &&
                  pc->z1 < hi[1] - 1))
                inside = 0;
            if (!refined) {
                add_draw(r, l, n, DRAW_BASE * 2 + still, pc->first, pc->count, counts, offsets);
                continue;
            }
            // Its refined parts at twice the density, with their seams; the others at
            // the level's density (their vertices have weight 0) by the base program.
            for (uint32_t k = 0; k < r->refine_mesh.part_count[i]; k++) {
                const clip_refine_part *q = &r->refine_mesh.parts[r->refine_mesh.part_first[i] + k];
                if (part_w[k] > 0.0f) {
                    add_draw(r, l, n, DRAW_FINE * 2 + still, q->fine_first, q->fine_count, counts,
                             offsets);
                    add_draw(r, l, n, DRAW_SEAMS * 2 + still, q->seam_first, q->seam_count, counts,
                             offsets);
                } else {
                    add_draw(r, l, n, DRAW_BASE * 2 + still, q->coarse_first, q->coarse_count,
                             counts, offsets);
                }
            }
        }
        if (n[0] + n[1] + n[2] + n[3] + n[4] + n[5] == 0) continue;
        if (n[2] + n[3] > 0) clip_refine_map_upload(&r->refine_map, l);
        int base = level_variant(r, cam, s, cursor, l) | (inside ? TV_INSIDE : 0);
        char calls[sizeof r->progs[0].calls];
        const unsigned live = level_rules_live(r, &r->rules, l);
        material_rule_calls(&r->rules, live, calls, sizeof calls);
        // The far texture's second layer only where a rule or the paint may read it.
        if ((base & TV_SHADED) &&
            ((base & TV_PAINTED) || material_rules_read_far_b(&r->rules, live)))
            base |= TV_FAR_B;
        for (int still = 0; still < 2; still++) {
            if (n[still] + n[2 + still] == 0) continue;
            int v = base | (still ? TV_NO_MORPH : 0);
            if (deferred) { // shaded later (resolve_terrain); now where the ground is
                resolve_pass *p = &passes[pass_count];
                if (still && pass_count > 0 && p[-1].level == l) {
                    // One pass with the morphing part: alpha is 0 on the still part, so
                    // its pixels shade as the still variant would, and the pixels on the
                    // parts' border are shaded once, not by two passes.
                    p = &p[-1];
                    p->stencil_mask = 0xFE;
                    for (int i = 0; i < 2; i++)
                        p->rect[i] = p->rect[i] < rect[1][i] ? p->rect[i] : rect[1][i],
                        p->rect[2 + i] =
                            p->rect[2 + i] > rect[1][2 + i] ? p->rect[2 + i] : rect[1][2 + i];
                } else {
                    pass_count++;
                    p->level = l, p->still = still, p->variant = (v & ~TV_INSIDE) | TV_RESOLVE;
                    p->stencil_mask = 0xFF;
                    memcpy(p->rect, rect[still], sizeof p->rect);
                    snprintf(p->calls, sizeof p->calls, "%s", calls);
                }
                v = TV_GBUFFER | (v & (TV_NO_MORPH | TV_VOLUME | TV_INSIDE));
                glStencilFunc(GL_ALWAYS, deferred_target_stencil(l, still), 0xFF);
            }
            for (int kind = DRAW_BASE; kind <= DRAW_SEAMS; kind++) {
                const int g = kind * 2 + still, refined = kind != DRAW_BASE;
                if (n[g] == 0) continue;
                int fresh = 0;
                GLuint prog = terrain_program(
                    r, v | (refined ? TV_REFINED : 0) | (kind == DRAW_SEAMS ? TV_SEAM : 0), calls,
                    &fresh, err);
                if (!prog) return -1;
                if (fresh) {
                    set_terrain_uniforms(r, prog, cam, s, cursor, view_proj);
                    material_rule_uniforms(prog, &r->rules);
                }
                if (prog != current) glUseProgram(current = prog);
                glProgramUniform1i(prog, glGetUniformLocation(prog, "u_level"), l);
                glBindVertexArray(refined ? r->refine_vao : r->vao);
                glMultiDrawElements(GL_TRIANGLES, counts[g],
                                    refined ? GL_UNSIGNED_INT : GL_UNSIGNED_SHORT, offsets[g],
                                    n[g]);
                r->stats.draw_calls++;
            }
        }
        r->stats.levels_drawn++;
    }
    if (deferred) return resolve_terrain(r, cam, s, cursor, view_proj, passes, pass_count, err);
    return 0;
}

// A volume tool's cursor: a sphere's three great circles, faint where the ground hides
// them and solid where seen.
static void draw_sphere_cursor(terrain_renderer *r, const camera *cam, const brush_cursor *c,
                               const float view_proj[16]) {
    GLuint prog = r->prog_cursor;
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE,
                              view_proj);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_centre"), (float)(c->x - cam->pos[0]),
                       (float)(c->y - cam->pos[1]), (float)(c->z - cam->pos[2]));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_radius"), (float)c->radius);
    GLint colour = glGetUniformLocation(prog, "u_colour");
    float rgb[3] = {1.0f, 0.55f, 0.1f};
    if (c->opacity > 0) memcpy(rgb, c->color, sizeof rgb);
    glUseProgram(prog);
    glBindVertexArray(r->empty_vao);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    GLint first[3] = {0, 64, 128};
    GLsizei count[3] = {64, 64, 64};
    glDisable(GL_DEPTH_TEST);
    glProgramUniform4f(prog, colour, rgb[0], rgb[1], rgb[2], 0.3f);
    glMultiDrawArrays(GL_LINE_LOOP, first, count, 3);
    glEnable(GL_DEPTH_TEST);
    glProgramUniform4f(prog, colour, rgb[0], rgb[1], rgb[2], 1.0f);
    glMultiDrawArrays(GL_LINE_LOOP, first, count, 3);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    r->stats.draw_calls += 2;
}

static void draw_water(terrain_renderer *r, const camera *cam, const render_settings *s,
                       const float view_proj[16]) {
    const world_params *p = &r->params;
    double reach = reach_metres(r);
    double x0 = cam->pos[0] - reach, x1 = cam->pos[0] + reach;
    double z0 = cam->pos[2] - reach, z1 = cam->pos[2] + reach;
    if (p->size > 0) {
        double last = (double)(p->size - 1) * p->spacing;
        double last_z = (double)(world_params_size_z(p) - 1) * p->spacing;
        x0 = fmax(x0, 0), z0 = fmax(z0, 0), x1 = fmin(x1, last), z1 = fmin(z1, last_z);
        if (x0 >= x1 || z0 >= z1) return;
    }
    GLuint prog = r->prog_water;
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE,
                              view_proj);
    glProgramUniform4f(prog, glGetUniformLocation(prog, "u_water_rect"), (float)(x0 - cam->pos[0]),
                       (float)(z0 - cam->pos[2]), (float)(x1 - cam->pos[0]),
                       (float)(z1 - cam->pos[2]));
    // Ground exactly at the level (a DEM's sea, stored as 0 m, under ocean_level 0) is
    // under water: the plane is lifted a centimetre, or the ground's equal depth would win.
    const double lift = 0.01;
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_water_y"),
                       (float)(world_params_ocean_height(p) + lift - cam->pos[1]));
    water_ripple_uniforms(prog, cam->pos);
    set_lighting(prog, r, s);
    glUseProgram(prog);
    glBindVertexArray(r->empty_vao);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    r->stats.draw_calls++;
}

int terrain_renderer_draw(terrain_renderer *r, world *w, const camera *cam,
                          const render_settings *s, const brush_cursor *cursor, int width,
                          int height, og_error *err) {
    double t0 = thread_cpu_ms();
    if (r->world != w) return og_error_set(err, "terrain_renderer_draw: update first");
    r->width = width, r->height = height;
    if (r->params.kind == WORLD_PLANET && r->planet) {
        int rc = planet_renderer_draw(r->planet, cam, s, cursor, width, height, err);
        copy_planet_stats(r);
        return rc;
    }
    r->stats.triangles = 0;
    memset(r->stats.level_triangles, 0, sizeof r->stats.level_triangles);
    r->stats.draw_calls = 0;
    r->stats.levels_drawn = 0;
    double aspect = (double)width / (double)(height > 0 ? height : 1);
    float view_proj[16];
    camera_view_projection(cam, aspect, view_proj);
    glViewport(0, 0, width, height);
    // Reversed Z: depth 1 at the near plane, 0 at infinity, in a float buffer.
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glClearDepth(0.0);
    glDisable(GL_CULL_FACE);
    int wire = s->view == VIEW_WIREFRAME;
    if (wire) glClearColor(0.06f, 0.07f, 0.09f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    int terrain = r->levels > 0 && r->src[r->levels - 1] >= 0;
    // The shaded view shades each pixel once (renderer/deferred_target.h); its sky goes
    // where no ground was drawn.
    int deferred = terrain && s->view == VIEW_SHADED;
    if (deferred && deferred_target_begin(&r->deferred, width, height, err) != 0) return -1;
    if (!wire && !deferred) {
        render_sky(r->prog_sky, r->empty_vao, cam, s, aspect, fog_density(r, s));
        r->stats.draw_calls++;
    }
    if (terrain) {
        if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        // The clipmap's triangles face up (counter-clockwise from above): slopes turned
        // away and the fix-up strips' backs are not rasterised (5-8% a frame from 7
        // levels up on llvmpipe). The wireframe shows every triangle.
        if (!wire) glEnable(GL_CULL_FACE), glCullFace(GL_BACK), glFrontFace(GL_CCW);
        int drawn = draw_terrain(r, cam, s, cursor, view_proj, deferred, err);
        glDisable(GL_CULL_FACE);
        if (deferred && drawn == 0) {
            glStencilFunc(GL_EQUAL, 0, 0xFF);
            render_sky(r->prog_sky, r->empty_vao, cam, s, aspect, fog_density(r, s));
            deferred_target_finish(&r->deferred, r->empty_vao);
            r->stats.draw_calls += 2;
        }
        if (drawn != 0) {
            if (deferred) deferred_target_finish(&r->deferred, r->empty_vao);
            glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
            glBindVertexArray(0);
            glUseProgram(0);
            return -1;
        }
        if (s->view != VIEW_LEVELS) {
            float period[2] = {(float)TEX_PERIOD_NEAR, (float)TEX_PERIOD_FAR};
            uint64_t t = volume_renderer_draw(
                r->volume, cam, view_proj, s, r->tex_albedo, fog_density(r, s),
                world_params_ocean_height(&r->params), r->params.max_height, period, &r->rules);
            r->stats.triangles += t;
            r->stats.draw_calls += t > 0;
        }
        if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        if (!wire && s->view == VIEW_SHADED) draw_water(r, cam, s, view_proj);
        if (cursor && cursor->visible && cursor->sphere && cursor->radius > 0)
            draw_sphere_cursor(r, cam, cursor, view_proj);
    }
    glBindVertexArray(0);
    glUseProgram(0);
    GLenum e = glGetError();
    r->stats.cpu_ms += thread_cpu_ms() - t0;
    if (e != GL_NO_ERROR) return og_error_set(err, "terrain_renderer_draw: GL error 0x%x", e);
    return 0;
}

void terrain_renderer_spread_uploads(terrain_renderer *r, int on) {
    r->whole_uploads = !on;
}

void terrain_renderer_set_view_size(terrain_renderer *r, int width, int height) {
    if (width > 0 && height > 0) r->width = width, r->height = height;
}

void terrain_renderer_stats(const terrain_renderer *r, render_stats *out) {
    *out = r->stats;
}

volume_renderer *terrain_renderer_volume(terrain_renderer *r) {
    return r->volume;
}
