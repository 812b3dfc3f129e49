#include "bench/naive_mesh.h"

#include "io/tile.h"
#include "io/tile_cache.h"
#include "renderer/lighting.h"
#include "renderer/shader.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// One vertex: position relative to the anchor (x, height, z metres) and the height's
// gradient (d/dx, d/dz) from central differences, as the clipmap's fragment shader
// takes it from its level texture.
typedef struct naive_vertex {
    float pos[3];
    float grad[2];
} naive_vertex;

// The level-0 heights of the whole world, row-major, size x size.
static float *read_heights(world *w, int64_t size, og_error *err) {
    float *h = malloc((size_t)(size * size) * sizeof *h);
    if (!h) {
        og_error_set(err, "out of memory for %lld^2 heights", (long long)size);
        return NULL;
    }
    tile_cache *cache = world_cache(w);
    int64_t tiles = (size + TILE_SIZE - 1) / TILE_SIZE;
    for (int64_t ty = 0; ty < tiles; ty++)
        for (int64_t tx = 0; tx < tiles; tx++) {
            tile_key key = {TILE_LAYER_COARSE, 0, 0, (int32_t)tx, (int32_t)ty};
            tile_view v;
            if (tile_cache_acquire(cache, key, &v, err) != 0) {
                free(h);
                return NULL;
            }
            const float *src = v.data;
            for (int j = 0; j < TILE_SIZE && ty * TILE_SIZE + j < size; j++) {
                int64_t z = ty * TILE_SIZE + j, x0 = tx * TILE_SIZE;
                int64_t n = size - x0 < TILE_SIZE ? size - x0 : TILE_SIZE;
                memcpy(h + z * size + x0, src + (size_t)j * TILE_SIZE, (size_t)n * sizeof *h);
            }
            tile_cache_release(cache, &v);
        }
    return h;
}

int naive_mesh_create(naive_mesh *m, world *w, const char *shader_dir, const char *resource_dir,
                      og_error *err) {
    memset(m, 0, sizeof *m);
    const world_params *p = world_get_params(w);
    if (p->kind != WORLD_FLAT || p->size < 2 || p->size > 8192)
        return og_error_set(err,
                            "naive mesh: needs a bounded flat world of 2 .. 8192 samples "
                            "per side (size = %lld)",
                            (long long)p->size);
    int64_t n = p->size;
    double sp = p->spacing;
    m->size = n;
    m->max_height = p->max_height;
    m->anchor[0] = m->anchor[2] = 0.5 * (double)(n - 1) * sp;
    m->anchor[1] = 0;

    char sky_dir[4200];
    snprintf(sky_dir, sizeof sky_dir, "%s/shaders", resource_dir);
    if (!(m->prog = shader_program_load(shader_dir, "naive.vert", "naive.frag", err)) ||
        !(m->prog_sky = shader_program_load(sky_dir, "fullscreen.vert", "sky.frag", err))) {
        naive_mesh_destroy(m);
        return -1;
    }

    float *h = read_heights(w, n, err);
    if (!h) {
        naive_mesh_destroy(m);
        return -1;
    }
    size_t vcount = (size_t)(n * n);
    uint64_t quads = (uint64_t)(n - 1) * (uint64_t)(n - 1);
    naive_vertex *v = malloc(vcount * sizeof *v);
    uint32_t *idx = malloc((size_t)quads * 6 * sizeof *idx);
    if (!v || !idx) {
        free(h), free(v), free(idx);
        naive_mesh_destroy(m);
        return og_error_set(err, "out of memory for the naive mesh");
    }
    for (int64_t z = 0; z < n; z++)
        for (int64_t x = 0; x < n; x++) {
            naive_vertex *o = &v[z * n + x];
            o->pos[0] = (float)((double)x * sp - m->anchor[0]);
            o->pos[1] = h[z * n + x];
            o->pos[2] = (float)((double)z * sp - m->anchor[2]);
            // Central differences, one-sided at the world's edge.
            int64_t xl = x > 0 ? x - 1 : x, xr = x < n - 1 ? x + 1 : x;
            int64_t zd = z > 0 ? z - 1 : z, zu = z < n - 1 ? z + 1 : z;
            o->grad[0] = (float)((h[z * n + xr] - h[z * n + xl]) / ((double)(xr - xl) * sp));
            o->grad[1] = (float)((h[zu * n + x] - h[zd * n + x]) / ((double)(zu - zd) * sp));
        }
    free(h);
    // The clipmap's quad split (renderer/clipmap_mesh.c), so both cut the same diagonal.
    uint32_t *o = idx;
    for (int64_t z = 0; z + 1 < n; z++)
        for (int64_t x = 0; x + 1 < n; x++) {
            uint32_t a = (uint32_t)(z * n + x), b = a + 1, c = a + (uint32_t)n, d = c + 1;
            *o++ = a, *o++ = c, *o++ = b;
            *o++ = b, *o++ = c, *o++ = d;
        }
    m->triangles = quads * 2;

    glCreateVertexArrays(1, &m->vao);
    glCreateVertexArrays(1, &m->empty_vao);
    glCreateBuffers(1, &m->vbo);
    glCreateBuffers(1, &m->ibo);
    size_t vbytes = vcount * sizeof *v, ibytes = (size_t)quads * 6 * sizeof *idx;
    glNamedBufferStorage(m->vbo, (GLsizeiptr)vbytes, v, 0);
    glNamedBufferStorage(m->ibo, (GLsizeiptr)ibytes, idx, 0);
    free(v), free(idx);
    m->gpu_bytes = vbytes + ibytes;
    glVertexArrayVertexBuffer(m->vao, 0, m->vbo, 0, sizeof(naive_vertex));
    glVertexArrayElementBuffer(m->vao, m->ibo);
    glEnableVertexArrayAttrib(m->vao, 0);
    glVertexArrayAttribFormat(m->vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(naive_vertex, pos));
    glVertexArrayAttribBinding(m->vao, 0, 0);
    glEnableVertexArrayAttrib(m->vao, 1);
    glVertexArrayAttribFormat(m->vao, 1, 2, GL_FLOAT, GL_FALSE, offsetof(naive_vertex, grad));
    glVertexArrayAttribBinding(m->vao, 1, 0);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        naive_mesh_destroy(m);
        return og_error_set(err, "naive mesh: GL error 0x%x uploading %zu MB", e,
                            (vbytes + ibytes) >> 20);
    }
    return 0;
}

void naive_mesh_destroy(naive_mesh *m) {
    glDeleteProgram(m->prog);
    glDeleteProgram(m->prog_sky);
    glDeleteVertexArrays(1, &m->vao);
    glDeleteVertexArrays(1, &m->empty_vao);
    glDeleteBuffers(1, &m->vbo);
    glDeleteBuffers(1, &m->ibo);
    memset(m, 0, sizeof *m);
}

int naive_mesh_draw(naive_mesh *m, const camera *cam, const render_settings *s, int width,
                    int height, og_error *err) {
    double aspect = (double)width / (double)(height > 0 ? height : 1);
    // The fog density must be explicit: the renderer's automatic one depends on its reach.
    double fog = s->fog_density;
    float view_proj[16];
    camera_view_projection(cam, aspect, view_proj);
    glViewport(0, 0, width, height);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glClearDepth(0.0);
    glDisable(GL_CULL_FACE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    render_sky(m->prog_sky, m->empty_vao, cam, s, aspect, fog);

    GLuint prog = m->prog;
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE,
                              view_proj);
    // Camera-relative, as the clipmap: the offset is taken in double, then rounded.
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_offset"),
                       (float)(m->anchor[0] - cam->pos[0]), (float)(m->anchor[1] - cam->pos[1]),
                       (float)(m->anchor[2] - cam->pos[2]));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_max_height"), (float)m->max_height);
    render_lighting_uniforms(prog, s, fog);
    glUseProgram(prog);
    glBindVertexArray(m->vao);
    glDrawElements(GL_TRIANGLES, (GLsizei)(m->triangles * 3), GL_UNSIGNED_INT, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return og_error_set(err, "naive_mesh_draw: GL error 0x%x", e);
    return 0;
}
