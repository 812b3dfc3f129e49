#include "renderer/material_rule_uniforms.h"
#include "renderer/volume_renderer.h"

#include "editor/world/volume_grid.h"
#include "renderer/frustum.h"
#include "renderer/lighting.h"
#include "renderer/shader.h"
#include "editor/world/volume_mesh.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define MASK_LEVELS 32 // bits per mask texel: brick levels above the column's lowest
#define MESH_BATCH 8   // bricks meshed together (on every core) between budget checks

typedef struct vbrick {
    tile_key key;
    GLuint vao, vbo, ebo;
    volume_mesh mesh;   // CPU copy for picking (positions and indices)
    float lo[3], hi[3]; // bounds of the mesh, metres from mesh.origin
    int dirty;
    int listed; // seen in the last listing
} vbrick;

struct volume_renderer {
    GLuint prog, tex_mask;
    vbrick *bricks;
    size_t count, cap;
    world *world;
    volume_grid grid;
    int enabled;
    int need_list, need_relist;
    grid_rect *touched;
    size_t touched_count, touched_cap;
    int64_t mask_origin[2]; // brick column of mask texel (0, 0)
    int mask_valid;
    int32_t *mask;   // VOLUME_VIEW_BRICKS^2 x (lowest level, bits)
    int last_meshed; // bricks meshed by the current update
};

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

volume_renderer *volume_renderer_create(const char *shader_dir, og_error *err) {
    volume_renderer *vr = calloc(1, sizeof *vr);
    if (!vr) {
        og_error_set(err, "out of memory");
        return NULL;
    }
    vr->mask = calloc((size_t)VOLUME_VIEW_BRICKS * VOLUME_VIEW_BRICKS * 2, sizeof *vr->mask);
    vr->prog = shader_program_load(shader_dir, "volume.vert", "volume.frag", err);
    // Unit 6 stays bound to the mask: the terrain shader reads it even with no bricks.
    if (!vr->mask || !vr->prog) {
        if (!vr->mask) og_error_set(err, "out of memory");
        volume_renderer_destroy(vr);
        return NULL;
    }
    glCreateTextures(GL_TEXTURE_2D, 1, &vr->tex_mask);
    glTextureStorage2D(vr->tex_mask, 1, GL_RG32I, VOLUME_VIEW_BRICKS, VOLUME_VIEW_BRICKS);
    glTextureParameteri(vr->tex_mask, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(vr->tex_mask, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    vr->need_list = 1;
    return vr;
}

static void free_gl(vbrick *b) {
    if (b->vao) glDeleteVertexArrays(1, &b->vao);
    if (b->vbo) glDeleteBuffers(1, &b->vbo);
    if (b->ebo) glDeleteBuffers(1, &b->ebo);
    b->vao = b->vbo = b->ebo = 0;
}

static void drop_all(volume_renderer *vr) {
    for (size_t i = 0; i < vr->count; i++) {
        free_gl(&vr->bricks[i]);
        volume_mesh_free(&vr->bricks[i].mesh);
    }
    vr->count = 0;
    vr->mask_valid = 0;
}

void volume_renderer_destroy(volume_renderer *vr) {
    if (!vr) return;
    drop_all(vr);
    free(vr->bricks);
    free(vr->touched);
    free(vr->mask);
    if (vr->prog) glDeleteProgram(vr->prog);
    if (vr->tex_mask) glDeleteTextures(1, &vr->tex_mask);
    free(vr);
}

void volume_renderer_reset(volume_renderer *vr) {
    vr->need_list = 1;
}

void volume_renderer_touched(volume_renderer *vr, grid_rect r, int new_bricks) {
    if (vr->touched_count == vr->touched_cap) {
        size_t cap = vr->touched_cap ? vr->touched_cap * 2 : 16;
        grid_rect *grown = realloc(vr->touched, cap * sizeof *grown);
        if (!grown) { // remember that something changed, if not where
            vr->need_list = 1;
            return;
        }
        vr->touched = grown;
        vr->touched_cap = cap;
    }
    vr->touched[vr->touched_count++] = r;
    vr->need_relist |= new_bricks;
}

static vbrick *find_brick(const volume_renderer *vr, tile_key key) {
    for (size_t i = 0; i < vr->count; i++)
        if (tile_key_equal(vr->bricks[i].key, key)) return &vr->bricks[i];
    return NULL;
}

// Brings the brick list up to the world's (new bricks are dirty).
static int relist(volume_renderer *vr, world *w, int full, og_error *err) {
    tile_key *keys;
    size_t n;
    if (volume_list_bricks(w, &keys, &n, err) != 0) return -1;
    for (size_t i = 0; i < vr->count; i++)
        vr->bricks[i].listed = 0;
    for (size_t k = 0; k < n; k++) {
        vbrick *b = find_brick(vr, keys[k]);
        if (!b) {
            if (vr->count == vr->cap) {
                size_t cap = vr->cap ? vr->cap * 2 : 64;
                vbrick *grown = realloc(vr->bricks, cap * sizeof *grown);
                if (!grown) {
                    free(keys);
                    return og_error_set(err, "out of memory");
                }
                vr->bricks = grown;
                vr->cap = cap;
            }
            b = &vr->bricks[vr->count++];
            memset(b, 0, sizeof *b);
            b->key = keys[k];
            b->dirty = 1;
            vr->mask_valid = 0;
        }
        if (full) b->dirty = 1;
        b->listed = 1;
    }
    free(keys);
    // Bricks no store holds any more (the world was replaced) go.
    size_t kept = 0;
    for (size_t i = 0; i < vr->count; i++) {
        if (vr->bricks[i].listed) {
            vr->bricks[kept++] = vr->bricks[i];
        } else {
            free_gl(&vr->bricks[i]);
            volume_mesh_free(&vr->bricks[i].mesh);
            vr->mask_valid = 0;
        }
    }
    vr->count = kept;
    return 0;
}

// Bricks whose mesh reads the touched columns (one voxel of border) are dirty.
static void mark_touched(volume_renderer *vr) {
    for (size_t t = 0; t < vr->touched_count; t++) {
        grid_rect r = vr->touched[t];
        int64_t bx0 = volume_floor_div(r.x0 - 1, VOLUME_BRICK_X),
                bx1 = volume_floor_div(r.x1, VOLUME_BRICK_X);
        int64_t bz0 = volume_floor_div(r.z0 - 1, VOLUME_BRICK_Z),
                bz1 = volume_floor_div(r.z1, VOLUME_BRICK_Z);
        for (size_t i = 0; i < vr->count; i++) {
            vbrick *b = &vr->bricks[i];
            if (b->key.tx >= bx0 && b->key.tx <= bx1 && b->key.ty >= bz0 && b->key.ty <= bz1)
                b->dirty = 1;
        }
    }
    vr->touched_count = 0;
}

static void camera_column(const volume_renderer *vr, const camera *cam, int64_t col[2]) {
    col[0] = (int64_t)floor(cam->pos[0] / vr->grid.voxel / VOLUME_BRICK_X);
    col[1] = (int64_t)floor(cam->pos[2] / vr->grid.voxel / VOLUME_BRICK_Z);
}

static int in_view(const volume_renderer *vr, const vbrick *b) {
    int64_t x = b->key.tx - vr->mask_origin[0], z = b->key.ty - vr->mask_origin[1];
    return x >= 0 && z >= 0 && x < VOLUME_VIEW_BRICKS && z < VOLUME_VIEW_BRICKS;
}

static void upload(vbrick *b) {
    free_gl(b);
    volume_mesh *m = &b->mesh;
    for (int a = 0; a < 3; a++)
        b->lo[a] = INFINITY, b->hi[a] = -INFINITY;
    for (size_t v = 0; v < m->vertex_count; v++)
        for (int a = 0; a < 3; a++) {
            b->lo[a] = fminf(b->lo[a], m->pos[3 * v + a]);
            b->hi[a] = fmaxf(b->hi[a], m->pos[3 * v + a]);
        }
    if (m->index_count == 0) return;
    float *inter = malloc(m->vertex_count * 6 * sizeof *inter);
    if (!inter) return; // drawn again after the next edit; picking still works
    for (size_t v = 0; v < m->vertex_count; v++) {
        memcpy(inter + 6 * v, m->pos + 3 * v, 3 * sizeof *inter);
        memcpy(inter + 6 * v + 3, m->normal + 3 * v, 3 * sizeof *inter);
    }
    glCreateBuffers(1, &b->vbo);
    glNamedBufferStorage(b->vbo, (GLsizeiptr)(m->vertex_count * 6 * sizeof *inter), inter, 0);
    free(inter);
    glCreateBuffers(1, &b->ebo);
    glNamedBufferStorage(b->ebo, (GLsizeiptr)(m->index_count * sizeof *m->index), m->index, 0);
    glCreateVertexArrays(1, &b->vao);
    glVertexArrayVertexBuffer(b->vao, 0, b->vbo, 0, 6 * sizeof(float));
    glVertexArrayElementBuffer(b->vao, b->ebo);
    for (GLuint a = 0; a < 2; a++) {
        glEnableVertexArrayAttrib(b->vao, a);
        glVertexArrayAttribFormat(b->vao, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
        glVertexArrayAttribBinding(b->vao, a, 0);
    }
}

static void build_mask(volume_renderer *vr) {
    size_t texels = (size_t)VOLUME_VIEW_BRICKS * VOLUME_VIEW_BRICKS;
    for (size_t t = 0; t < texels; t++)
        vr->mask[2 * t] = INT32_MAX, vr->mask[2 * t + 1] = 0;
    for (size_t i = 0; i < vr->count; i++) {
        const vbrick *b = &vr->bricks[i];
        if (!in_view(vr, b)) continue;
        size_t t = (size_t)((b->key.ty - vr->mask_origin[1]) * VOLUME_VIEW_BRICKS +
                            (b->key.tx - vr->mask_origin[0]));
        if (b->key.level < vr->mask[2 * t]) vr->mask[2 * t] = b->key.level;
    }
    for (size_t i = 0; i < vr->count; i++) {
        const vbrick *b = &vr->bricks[i];
        if (!in_view(vr, b)) continue;
        size_t t = (size_t)((b->key.ty - vr->mask_origin[1]) * VOLUME_VIEW_BRICKS +
                            (b->key.tx - vr->mask_origin[0]));
        int64_t bit = (int64_t)b->key.level - vr->mask[2 * t];
        // Beyond 32 levels above the lowest (2048 voxels) the heightfield stays drawn.
        if (bit < MASK_LEVELS) vr->mask[2 * t + 1] |= (int32_t)(1u << bit);
    }
    glTextureSubImage2D(vr->tex_mask, 0, 0, 0, VOLUME_VIEW_BRICKS, VOLUME_VIEW_BRICKS,
                        GL_RG_INTEGER, GL_INT, vr->mask);
    vr->mask_valid = 1;
}

// Up to max dirty bricks in view, nearest the camera's column first.
static int nearest_dirty(volume_renderer *vr, const int64_t col[2], vbrick **out, int max) {
    int n = 0;
    for (size_t i = 0; i < vr->count; i++) {
        vbrick *b = &vr->bricks[i];
        if (!b->dirty || !in_view(vr, b)) continue;
        int64_t dx = b->key.tx - col[0], dz = b->key.ty - col[1], d = dx * dx + dz * dz;
        int at = n < max ? n++ : max;
        // Insertion into the sorted list (a brick farther than all kept ones drops out).
        while (at > 0) {
            const vbrick *o = out[at - 1];
            int64_t ox = o->key.tx - col[0], oz = o->key.ty - col[1];
            if (ox * ox + oz * oz <= d) break;
            if (at < max) out[at] = out[at - 1];
            at--;
        }
        if (at < max) out[at] = b;
    }
    return n;
}

typedef struct mesh_job {
    world *w;
    const volume_grid *g;
    vbrick **bricks;
    int count;
    atomic_int next;
    atomic_int failed;
    og_error err;
} mesh_job;

static void *mesh_worker(void *arg) {
    mesh_job *j = arg;
    for (;;) {
        int i = atomic_fetch_add(&j->next, 1);
        if (i >= j->count) break;
        vbrick *b = j->bricks[i];
        volume_mesh_free(&b->mesh);
        og_error err;
        if (volume_mesh_brick(j->w, j->g, b->key, &b->mesh, &err) != 0 &&
            atomic_exchange(&j->failed, 1) == 0)
            j->err = err;
    }
    return NULL;
}

// Meshes the bricks on every core (the cache and the world's reads are thread-safe).
static int mesh_batch(world *w, const volume_grid *g, vbrick **bricks, int count, og_error *err) {
    mesh_job j = {.w = w, .g = g, .bricks = bricks, .count = count};
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    int helpers = (int)(cores > 1 ? cores - 1 : 0);
    if (helpers > count - 1) helpers = count - 1;
    if (helpers > MESH_BATCH) helpers = MESH_BATCH;
    pthread_t threads[MESH_BATCH];
    int started = 0;
    for (; started < helpers; started++)
        if (pthread_create(&threads[started], NULL, mesh_worker, &j) != 0) break;
    mesh_worker(&j);
    for (int t = 0; t < started; t++)
        pthread_join(threads[t], NULL);
    if (atomic_load(&j.failed)) return og_error_set(err, "%s", j.err.msg);
    return 0;
}

int volume_renderer_update(volume_renderer *vr, world *w, const camera *cam, double budget_ms,
                           og_error *err) {
    vr->last_meshed = 0;
    if (vr->world != w) vr->need_list = 1;
    vr->world = w;
    volume_grid g;
    og_error ignored;
    if (volume_grid_init(&g, world_get_params(w), &ignored) != 0) { // planets: no volume
        drop_all(vr);
        vr->enabled = 0;
        return 1;
    }
    if (!vr->enabled || g.voxel != vr->grid.voxel) vr->need_list = 1;
    vr->grid = g;
    vr->enabled = 1;
    if (vr->need_list || vr->need_relist) {
        if (relist(vr, w, vr->need_list, err) != 0) return -1;
        vr->need_list = vr->need_relist = 0;
    }
    mark_touched(vr);
    int64_t col[2];
    camera_column(vr, cam, col);
    int64_t origin[2] = {col[0] - VOLUME_VIEW_BRICKS / 2, col[1] - VOLUME_VIEW_BRICKS / 2};
    if (origin[0] != vr->mask_origin[0] || origin[1] != vr->mask_origin[1]) {
        vr->mask_origin[0] = origin[0];
        vr->mask_origin[1] = origin[1];
        vr->mask_valid = 0;
    }
    if (!vr->mask_valid) build_mask(vr);
    // Nearest dirty bricks first, a batch at a time on every core, until the budget is spent.
    double t0 = now_ms();
    int all = 1;
    for (;;) {
        vbrick *batch[MESH_BATCH];
        int n = nearest_dirty(vr, col, batch, MESH_BATCH);
        if (n == 0) break;
        if (budget_ms > 0 && vr->last_meshed > 0 && now_ms() - t0 > budget_ms) {
            all = 0;
            break;
        }
        if (mesh_batch(w, &vr->grid, batch, n, err) != 0) return -1;
        for (int i = 0; i < n; i++) {
            upload(batch[i]);
            batch[i]->dirty = 0;
        }
        vr->last_meshed += n;
    }
    return all;
}

void volume_renderer_mask_uniforms(volume_renderer *vr, GLuint prog, const camera *cam, int unit) {
    int on = vr->enabled && vr->count > 0;
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_vol_on"), on);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_vol_mask"), unit);
    glBindTextureUnit((GLuint)unit, vr->tex_mask);
    if (!on) return;
    double v = vr->grid.voxel;
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_vol_cam"),
                       (float)(cam->pos[0] / v - (double)vr->mask_origin[0] * VOLUME_BRICK_X),
                       (float)(cam->pos[1] / v),
                       (float)(cam->pos[2] / v - (double)vr->mask_origin[1] * VOLUME_BRICK_Z));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_vol_voxel"), (float)v);
}

static double positive_fmod(double a, double b) {
    double m = fmod(a, b);
    return m < 0 ? m + b : m;
}

uint64_t volume_renderer_draw(volume_renderer *vr, const camera *cam, const float view_proj[16],
                              const render_settings *s, GLuint albedo, double fog_density,
                              double ocean_level, double max_height, const float tex_period[2],
                              const material_rules_resolved *rules) {
    if (!vr->enabled || vr->count == 0) return 0;
    GLuint prog = vr->prog;
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE,
                              view_proj);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_cam_y"), (float)cam->pos[1]);
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_tex_period"), tex_period[0],
                       tex_period[1]);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_view_mode"), s->view);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_wire_tint"), 0.95f, 0.95f, 0.95f);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_ocean_level"), (float)ocean_level);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_max_height"), (float)max_height);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_albedo"), 0);
    material_rule_uniforms(prog, rules);
    render_lighting_uniforms(prog, s, fog_density);
    glBindTextureUnit(0, albedo);
    glUseProgram(prog);
    frustum f;
    frustum_from_matrix(&f, view_proj);
    GLint offset_loc = glGetUniformLocation(prog, "u_offset");
    GLint uv_loc = glGetUniformLocation(prog, "u_uv_origin");
    GLint uvy_loc = glGetUniformLocation(prog, "u_uv_y");
    uint64_t triangles = 0;
    for (size_t i = 0; i < vr->count; i++) {
        const vbrick *b = &vr->bricks[i];
        if (!b->vao || !in_view(vr, b)) continue;
        const double *o = b->mesh.origin;
        float rel[3] = {(float)(o[0] - cam->pos[0]), (float)(o[1] - cam->pos[1]),
                        (float)(o[2] - cam->pos[2])};
        float mn[3], mx[3];
        for (int a = 0; a < 3; a++)
            mn[a] = rel[a] + b->lo[a], mx[a] = rel[a] + b->hi[a];
        if (s->culling && !frustum_test_aabb(&f, mn, mx)) continue;
        glProgramUniform3fv(prog, offset_loc, 1, rel);
        glProgramUniform4f(prog, uv_loc, (float)positive_fmod(o[0], tex_period[0]),
                           (float)positive_fmod(o[2], tex_period[0]),
                           (float)positive_fmod(o[0], tex_period[1]),
                           (float)positive_fmod(o[2], tex_period[1]));
        glProgramUniform2f(prog, uvy_loc, (float)positive_fmod(o[1], tex_period[0]),
                           (float)positive_fmod(o[1], tex_period[1]));
        glBindVertexArray(b->vao);
        glDrawElements(GL_TRIANGLES, (GLsizei)b->mesh.index_count, GL_UNSIGNED_INT, NULL);
        triangles += b->mesh.index_count / 3;
    }
    glBindVertexArray(0);
    return triangles;
}

// Ray against box [lo, hi]: the entry distance, or -1 when it misses within max.
static double ray_box(const double o[3], const double d[3], const double lo[3], const double hi[3],
                      double max) {
    double t0 = 0, t1 = max;
    for (int a = 0; a < 3; a++) {
        if (fabs(d[a]) < 1e-15) {
            if (o[a] < lo[a] || o[a] > hi[a]) return -1;
            continue;
        }
        double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) {
            double s = ta;
            ta = tb, tb = s;
        }
        t0 = fmax(t0, ta), t1 = fmin(t1, tb);
        if (t0 > t1) return -1;
    }
    return t0;
}

int volume_renderer_pick(const volume_renderer *vr, const double origin[3], const double dir[3],
                         double max, double *t_hit) {
    if (!vr->enabled) return -1;
    double best = max;
    int found = 0;
    for (size_t i = 0; i < vr->count; i++) {
        const vbrick *b = &vr->bricks[i];
        const volume_mesh *m = &b->mesh;
        if (m->index_count == 0) continue;
        double lo[3], hi[3], o[3];
        for (int a = 0; a < 3; a++) {
            lo[a] = m->origin[a] + b->lo[a] - 1e-3, hi[a] = m->origin[a] + b->hi[a] + 1e-3;
            o[a] = origin[a] - m->origin[a]; // brick-local: small numbers
        }
        if (ray_box(origin, dir, lo, hi, best) < 0) continue;
        for (size_t k = 0; k + 2 < m->index_count; k += 3) {
            const float *p0 = m->pos + 3 * m->index[k], *p1 = m->pos + 3 * m->index[k + 1],
                        *p2 = m->pos + 3 * m->index[k + 2];
            // Moeller-Trumbore.
            double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
            double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
            double pv[3] = {dir[1] * e2[2] - dir[2] * e2[1], dir[2] * e2[0] - dir[0] * e2[2],
                            dir[0] * e2[1] - dir[1] * e2[0]};
            double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
            if (fabs(det) < 1e-12) continue;
            double inv = 1.0 / det;
            double tv[3] = {o[0] - p0[0], o[1] - p0[1], o[2] - p0[2]};
            double u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) * inv;
            if (u < 0 || u > 1) continue;
            double qv[3] = {tv[1] * e1[2] - tv[2] * e1[1], tv[2] * e1[0] - tv[0] * e1[2],
                            tv[0] * e1[1] - tv[1] * e1[0]};
            double vv = (dir[0] * qv[0] + dir[1] * qv[1] + dir[2] * qv[2]) * inv;
            if (vv < 0 || u + vv > 1) continue;
            double t = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) * inv;
            if (t > 0 && t < best) best = t, found = 1;
        }
    }
    if (!found) return -1;
    *t_hit = best;
    return 0;
}

int volume_renderer_active(const volume_renderer *vr) {
    return vr->enabled && vr->count > 0;
}

int volume_renderer_replaces(const volume_renderer *vr, double x, double y, double z) {
    if (!vr->enabled || vr->count == 0) return 0;
    double v = vr->grid.voxel;
    // As volume_mask.glsl: the brick whose mesh holds the ground at this point.
    tile_key key = volume_brick_key((int64_t)floor(x / v), (int64_t)floor(y / v - 1e-3),
                                    (int64_t)floor(z / v));
    const vbrick *b = find_brick(vr, key);
    return b && in_view(vr, b);
}
