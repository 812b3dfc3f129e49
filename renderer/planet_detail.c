#include "renderer/planet_detail.h"

#include "renderer/clip_window.h"

#include <math.h>
#include <stdlib.h>

#define DETAIL_TEXELS 512 // window side, detail samples (as the flat viewport's)
#define DETAIL_SNAP 16    // the window moves in steps of this many samples
#define DETAIL_LEVELS 3   // chunks of levels 0-2 show it (coarser ones lie past the fade)

struct planet_detail {
    GLuint tex_heights, tex_slopes;
    clip_window heights, slopes;
    int face;                            // the window's face (-1: none yet)
    int64_t origin[2];                   // detail sample of the window's first texel
    int current;                         // this frame: the window holds the samples around origin
    double samples_per_metre, half_cell; // detail samples per metre, 0.5 cell in samples
    uint64_t uploads;
};

static GLuint make_texture(GLenum internal) {
    GLuint t;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, internal, DETAIL_TEXELS, DETAIL_TEXELS);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_REPEAT);
    return t;
}

static int open_windows(planet_detail *d, int face) {
    clip_window_free(&d->heights);
    clip_window_free(&d->slopes);
    d->face = -1;
    if (clip_window_init(&d->heights, TILE_LAYER_DETAIL, face, 0, DETAIL_TEXELS) != 0 ||
        clip_window_init(&d->slopes, TILE_LAYER_DETAIL_PD, face, 0, DETAIL_TEXELS) != 0)
        return -1;
    d->face = face;
    return 0;
}

planet_detail *planet_detail_create(og_error *err) {
    planet_detail *d = calloc(1, sizeof *d);
    if (!d) {
        og_error_set(err, "out of memory for the planet's detail window");
        return NULL;
    }
    d->face = -1;
    d->tex_heights = make_texture(GL_R32F);
    d->tex_slopes = make_texture(GL_RG16_SNORM);
    return d;
}

void planet_detail_destroy(planet_detail *d) {
    if (!d) return;
    clip_window_free(&d->heights);
    clip_window_free(&d->slopes);
    glDeleteTextures(1, &d->tex_heights);
    glDeleteTextures(1, &d->tex_slopes);
    free(d);
}

void planet_detail_forget(planet_detail *d) {
    if (d->face < 0) return;
    clip_window_invalidate(&d->heights);
    clip_window_invalidate(&d->slopes);
    d->current = 0;
}

void planet_detail_touched(planet_detail *d, tile_cache *cache, int face, grid_rect rect) {
    if (face != d->face) return;
    // Slopes change one sample around the change.
    clip_window_refresh(&d->heights, cache, rect.x0 - 1, rect.z0 - 1, rect.x1 + 1, rect.z1 + 1);
    clip_window_refresh(&d->slopes, cache, rect.x0 - 1, rect.z0 - 1, rect.x1 + 1, rect.z1 + 1);
}

// Sends what changed in a window's mirror to its texture.
static void upload(planet_detail *d, clip_window *w, GLuint tex, GLenum format, GLenum type) {
    if (!w->upload_all && w->upload_count == 0) return;
    texel_rect whole = {0, 0, w->size, w->size};
    const texel_rect *rects = w->upload_all ? &whole : w->uploads;
    int count = w->upload_all ? 1 : w->upload_count;
    glPixelStorei(GL_UNPACK_ROW_LENGTH, w->size);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int k = 0; k < count; k++) {
        const texel_rect *t = &rects[k];
        const unsigned char *src = w->mirror + ((size_t)t->z * w->size + t->x) * w->texel_bytes;
        glTextureSubImage2D(tex, 0, t->x, t->z, t->w, t->h, format, type, src);
        d->uploads += (uint64_t)t->w * t->h;
    }
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    w->upload_all = 0;
    w->upload_count = 0;
}

int planet_detail_update(planet_detail *d, tile_cache *cache, const double cam_pos[3],
                         double altitude_above_ground, int64_t face_samples, double cell_arc,
                         int detail_ratio, const render_settings *s) {
    d->current = 0;
    if (!(altitude_above_ground < s->detail_distance) || detail_ratio < 1) return 1;
    int face;
    double st[2];
    world_grid_direction_face(cam_pos, &face, &st[0], &st[1]);
    if (face != d->face && open_windows(d, face) != 0) return -1;
    // Detail sample j of a face sits at level-0 sample j / ratio, whose centre is half a
    // cell in from its cell's edge.
    d->samples_per_metre = detail_ratio / cell_arc;
    d->half_cell = 0.5 * detail_ratio;
    for (int a = 0; a < 2; a++) {
        double j = ((st[a] + 1.0) * 0.5 * (double)face_samples - 0.5) * detail_ratio;
        int64_t c = (int64_t)floor(j) - DETAIL_TEXELS / 2;
        d->origin[a] = (c / DETAIL_SNAP - (c % DETAIL_SNAP < 0)) * DETAIL_SNAP;
    }
    int a = clip_window_update(&d->heights, cache, d->origin);
    int b = clip_window_update(&d->slopes, cache, d->origin);
    if (a < 0 || b < 0) return -1;
    upload(d, &d->heights, d->tex_heights, GL_RED, GL_FLOAT);
    upload(d, &d->slopes, d->tex_slopes, GL_RG, GL_SHORT);
    d->current = a == 1 && b == 1;
    return d->current;
}

void planet_detail_chunk(const planet_detail *d, int face, int level, double base_u, double base_v,
                         float out[4]) {
    out[0] = out[1] = out[2] = out[3] = 0.0f;
    if (!d->current || face != d->face || level >= DETAIL_LEVELS) return;
    // Detail sample index of face-local metres m: m x samples_per_metre - half a cell.
    out[0] = (float)(base_u * d->samples_per_metre - d->half_cell - (double)d->origin[0]);
    out[1] = (float)(base_v * d->samples_per_metre - d->half_cell - (double)d->origin[1]);
    out[2] = (float)d->samples_per_metre;
    out[3] = 1.0f;
}

void planet_detail_bind(planet_detail *d, GLuint prog, const render_settings *s, int unit_heights,
                        int unit_slopes) {
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_detail_wrap"),
                       (float)(d->origin[0] & (DETAIL_TEXELS - 1)),
                       (float)(d->origin[1] & (DETAIL_TEXELS - 1)));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_detail_spacing"),
                       d->samples_per_metre > 0 ? (float)(1.0 / d->samples_per_metre) : 1.0f);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_detail_size"), DETAIL_TEXELS);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_parallax"), s->parallax);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_parallax_steps"), s->parallax_steps);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_parallax_fade"),
                       (float)s->detail_distance);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_detail"), unit_heights);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_detail_pd"), unit_slopes);
    glBindTextureUnit((GLuint)unit_heights, d->tex_heights);
    glBindTextureUnit((GLuint)unit_slopes, d->tex_slopes);
}

uint64_t planet_detail_take_uploads(planet_detail *d) {
    uint64_t n = d->uploads;
    d->uploads = 0;
    return n;
}
