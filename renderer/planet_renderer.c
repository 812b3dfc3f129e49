#include "renderer/planet_renderer.h"

// Creating and destroying the planet renderer: its index buffer, vertex layout and
// first program; change notifications and figures.
#include "renderer/planet_internal.h"

#include "renderer/shader.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// A chunk vertex's place in the block's own frame: across (i), along (j) and up (h;
// -1 for a skirt's lowered copy). Used to wind every triangle alike.
static void block_coords(uint16_t index, double out[3]) {
    if (index < GRID_VERTS) {
        out[0] = index % (BLOCK + 1), out[1] = index / (BLOCK + 1), out[2] = 0;
        return;
    }
    int e = (index - GRID_VERTS) / (BLOCK + 1), g = (index - GRID_VERTS) % (BLOCK + 1);
    out[0] = e < 2 ? g : (e == 2 ? 0 : BLOCK);
    out[1] = e < 2 ? (e == 0 ? 0 : BLOCK) : g;
    out[2] = -1;
}

// Winds the triangle counter-clockwise seen from `outward` (in the block's frame), so
// back faces can be culled: the ground from below, a skirt from inside its chunk.
static void wind(uint16_t tri[3], const double outward[3]) {
    double p[3][3];
    for (int v = 0; v < 3; v++)
        block_coords(tri[v], p[v]);
    double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    if (n[0] * outward[0] + n[1] * outward[1] + n[2] * outward[2] < 0) {
        uint16_t t = tri[1];
        tri[1] = tri[2], tri[2] = t;
    }
}

// The winding a face's chunks show from outside the planet: counter-clockwise where the
// face's s, t and the outward direction make a right-handed frame.
static GLenum face_front(int face) {
    double o[3], ds[3], dt[3];
    world_grid_face_direction_warped(face, 0, 0, o);
    world_grid_face_direction_warped(face, 0.01, 0, ds);
    world_grid_face_direction_warped(face, 0, 0.01, dt);
    for (int a = 0; a < 3; a++)
        ds[a] -= o[a], dt[a] -= o[a];
    double n[3] = {ds[1] * dt[2] - ds[2] * dt[1], ds[2] * dt[0] - ds[0] * dt[2],
                   ds[0] * dt[1] - ds[1] * dt[0]};
    return n[0] * o[0] + n[1] * o[1] + n[2] * o[2] > 0 ? GL_CCW : GL_CW;
}

static GLuint make_indices(void) {
    static uint16_t idx[CHUNK_INDICES];
    const double up[3] = {0, 0, 1};
    const double skirt_out[4][3] = {{0, -1, 0}, {0, 1, 0}, {-1, 0, 0}, {1, 0, 0}}; // edges 0-3
    int k = 0;
    for (int j = 0; j < BLOCK; j++)
        for (int i = 0; i < BLOCK; i++) {
            uint16_t a = (uint16_t)(j * (BLOCK + 1) + i), b = a + 1, c = a + BLOCK + 1, d = c + 1;
            uint16_t quad[6] = {a, c, b, b, c, d};
            wind(quad, up), wind(quad + 3, up);
            memcpy(idx + k, quad, sizeof quad);
            k += 6;
        }
    for (int e = 0; e < 4; e++)
        for (int g = 0; g < BLOCK; g++) {
            int gi0 = e < 2 ? g : (e == 2 ? 0 : BLOCK), gj0 = e < 2 ? (e == 0 ? 0 : BLOCK) : g;
            int gi1 = e < 2 ? g + 1 : gi0, gj1 = e < 2 ? gj0 : g + 1;
            uint16_t t0 = (uint16_t)(gj0 * (BLOCK + 1) + gi0),
                     t1 = (uint16_t)(gj1 * (BLOCK + 1) + gi1);
            uint16_t b0 = (uint16_t)(GRID_VERTS + e * (BLOCK + 1) + g), b1 = b0 + 1;
            uint16_t quad[6] = {t0, b0, t1, t1, b0, b1};
            wind(quad, skirt_out[e]), wind(quad + 3, skirt_out[e]);
            memcpy(idx + k, quad, sizeof quad);
            k += 6;
        }
    GLuint ibo;
    glCreateBuffers(1, &ibo);
    glNamedBufferStorage(ibo, sizeof idx, idx, 0);
    return ibo;
}

// Each material texture's 1 x 1 level: what a fully minified lookup returns (the
// MINIFIED variant's albedo, materials.glsl).
static void albedo_means(planet_renderer *r) {
    GLint levels = 0;
    glGetTextureParameteriv(r->albedo, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
    if (levels < 1) return; // not an immutable texture: the MINIFIED variant is never chosen
    glGetTextureImage(r->albedo, levels - 1, GL_RGBA, GL_FLOAT, sizeof r->albedo_mean,
                      r->albedo_mean);
    r->has_albedo_mean = 1;
}

planet_renderer *planet_renderer_create(const char *resource_dir, GLuint albedo, GLuint falloff,
                                        og_error *err) {
    planet_renderer *r = calloc(1, sizeof *r);
    if (!r) {
        og_error_set(err, "out of memory for the planet renderer");
        return NULL;
    }
    snprintf(r->shader_dir, sizeof r->shader_dir, "%s/shaders", resource_dir);
    // The plain shaded ground now, so a broken shader shows at once; other variants
    // when a chunk first needs them.
    if (planet_ground_variant(r, V_SHADED, err))
        r->prog_sky = shader_program_load(r->shader_dir, "fullscreen.vert", "planet_sky.frag", err);
    if (!r->prog_sky) {
        planet_renderer_destroy(r);
        return NULL;
    }
    r->albedo = albedo;
    r->falloff = falloff;
    albedo_means(r);
    if (!(r->detail = planet_detail_create(err))) {
        planet_renderer_destroy(r);
        return NULL;
    }
    if (planet_normals_create(r, err) != 0) {
        planet_renderer_destroy(r);
        return NULL;
    }
    r->ibo = make_indices();
    for (int f = 0; f < 6; f++)
        r->front[f] = face_front(f);
    glCreateVertexArrays(1, &r->vao);
    glCreateVertexArrays(1, &r->empty_vao);
    glVertexArrayElementBuffer(r->vao, r->ibo);
    const int sizes[6] = {3, 3, 3, 1, 2, 4}, offsets[6] = {0, 3, 6, 9, 10, 12};
    for (int a = 0; a < 6; a++) {
        glEnableVertexArrayAttrib(r->vao, a);
        glVertexArrayAttribFormat(r->vao, a, sizes[a], GL_FLOAT, GL_FALSE,
                                  (GLuint)(offsets[a] * sizeof(float)));
        glVertexArrayAttribBinding(r->vao, a, 0);
    }
    glEnableVertexArrayAttrib(r->vao, 6); // the painted weights, as integers
    glVertexArrayAttribIFormat(r->vao, 6, 2, GL_UNSIGNED_INT, (GLuint)(16 * sizeof(float)));
    glVertexArrayAttribBinding(r->vao, 6, 0);
    for (int a = 7; a <= 8; a++) { // the neighbouring faces' texture metres and weights
        glEnableVertexArrayAttrib(r->vao, a);
        glVertexArrayAttribFormat(r->vao, a, 3, GL_FLOAT, GL_FALSE,
                                  (GLuint)((BLEND_FLOAT0 + 3 * (a - 7)) * sizeof(float)));
        glVertexArrayAttribBinding(r->vao, a, 0);
    }
    planet_drop_all(r);
    return r;
}

void planet_renderer_destroy(planet_renderer *r) {
    if (!r) return;
    for (int i = 0; i < MAX_CHUNKS; i++)
        if (r->chunks[i].vbo) glDeleteBuffers(1, &r->chunks[i].vbo);
    if (r->ibo) glDeleteBuffers(1, &r->ibo);
    if (r->normals) glDeleteTextures(1, &r->normals);
    if (r->vao) glDeleteVertexArrays(1, &r->vao);
    if (r->empty_vao) glDeleteVertexArrays(1, &r->empty_vao);
    for (int v = 0; v < VARIANTS; v++)
        if (r->ground[v].prog) glDeleteProgram(r->ground[v].prog);
    if (r->prog_sky) glDeleteProgram(r->prog_sky);
    planet_detail_destroy(r->detail);
    free(r);
}

void planet_renderer_forget(planet_renderer *r) {
    planet_drop_all(r);
    planet_detail_forget(r->detail);
}

void planet_renderer_detail_touched(planet_renderer *r, tile_cache *cache, int face,
                                    grid_rect rect) {
    planet_detail_touched(r->detail, cache, face, rect);
}

void planet_renderer_touched(planet_renderer *r, int face, grid_rect rect) {
    for (int i = 0; i < MAX_CHUNKS; i++) {
        chunk *c = &r->chunks[i];
        if (!c->key) continue;
        uint64_t k = c->key - 1;
        int cf = (int)(k & 7), level = (int)((k >> 3) & 31);
        int64_t bx = (int64_t)((k >> 8) & ((1u << 28) - 1)), by = (int64_t)(k >> 36);
        if (cf != face) continue;
        // The level-0 cells the chunk's vertices interpolate from, a sample's margin
        // around (mips are box filtered; vertices blend neighbouring samples).
        const int64_t cell = (int64_t)1 << level;
        const int64_t x0 = (bx * BLOCK - 1) * cell, x1 = ((bx + 1) * BLOCK + 1) * cell;
        const int64_t z0 = (by * BLOCK - 1) * cell, z1 = ((by + 1) * BLOCK + 1) * cell;
        if (rect.x1 <= x0 || rect.x0 >= x1 || rect.z1 <= z0 || rect.z0 >= z1) continue;
        planet_table_remove(r, c->key);
        c->key = 0;
        r->resident--;
    }
}

void planet_renderer_stats(const planet_renderer *r, planet_stats *out) {
    *out = r->stats;
}
