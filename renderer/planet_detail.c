#include "renderer/planet_detail.h"

#include "renderer/clip_window.h"
#include "renderer/clip_window_upload.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#define DETAIL_TEXELS 512 // window side, detail samples (as the flat viewport's)
#define DETAIL_SNAP 16    // the window moves in steps of this many samples
#define DETAIL_LEVELS 3   // chunks of levels 0-2 show it (coarser ones lie past the fade)
#define DETAIL_WINDOWS 3  // the camera's face and, near an edge or corner, its neighbours
#define DETAIL_BLOCKS (DETAIL_TEXELS / DETAIL_SNAP) // blocks per window side
#define DETAIL_MARGIN 8 // samples around a chunk the parallax (6) and the filters can reach

// One face's window: the detail samples around the camera (or, on a neighbouring face,
// around the camera's place extended onto it), kept inside the face.
typedef struct detail_window {
    GLuint tex_heights, tex_slopes;
    clip_window heights, slopes;
    int face;          // -1: unused
    int64_t origin[2]; // detail sample of the window's first texel
    int current;       // this frame: the window holds the samples around origin
    // The largest |offset| (metres) in each DETAIL_SNAP-square block of texels, laid out
    // toroidally as the texture (FLT_MIN for slopes without offsets). The detail layer is
    // zero until edited: chunks over blocks of zeros skip the detail's shading.
    float block_max[DETAIL_BLOCKS][DETAIL_BLOCKS];
} detail_window;

struct planet_detail {
    detail_window w[DETAIL_WINDOWS];
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

static int open_window(detail_window *w, int face) {
    clip_window_free(&w->heights);
    clip_window_free(&w->slopes);
    w->face = -1;
    w->current = 0;
    if (clip_window_init(&w->heights, TILE_LAYER_DETAIL, face, 0, DETAIL_TEXELS) != 0 ||
        clip_window_init(&w->slopes, TILE_LAYER_DETAIL_PD, face, 0, DETAIL_TEXELS) != 0)
        return -1;
    w->face = face;
    return 0;
}

planet_detail *planet_detail_create(og_error *err) {
    planet_detail *d = calloc(1, sizeof *d);
    if (!d) {
        og_error_set(err, "out of memory for the planet's detail window");
        return NULL;
    }
    for (int i = 0; i < DETAIL_WINDOWS; i++) {
        d->w[i].face = -1;
        d->w[i].tex_heights = make_texture(GL_R32F);
        d->w[i].tex_slopes = make_texture(GL_RG16_SNORM);
    }
    return d;
}

void planet_detail_destroy(planet_detail *d) {
    if (!d) return;
    for (int i = 0; i < DETAIL_WINDOWS; i++) {
        clip_window_free(&d->w[i].heights);
        clip_window_free(&d->w[i].slopes);
        glDeleteTextures(1, &d->w[i].tex_heights);
        glDeleteTextures(1, &d->w[i].tex_slopes);
    }
    free(d);
}

void planet_detail_forget(planet_detail *d) {
    for (int i = 0; i < DETAIL_WINDOWS; i++) {
        if (d->w[i].face < 0) continue;
        clip_window_invalidate(&d->w[i].heights);
        clip_window_invalidate(&d->w[i].slopes);
        d->w[i].current = 0;
    }
}

void planet_detail_touched(planet_detail *d, tile_cache *cache, int face, grid_rect rect) {
    for (int i = 0; i < DETAIL_WINDOWS; i++) {
        detail_window *w = &d->w[i];
        if (face != w->face) continue;
        // Slopes change one sample around the change.
        clip_window_refresh(&w->heights, cache, rect.x0 - 1, rect.z0 - 1, rect.x1 + 1, rect.z1 + 1);
        clip_window_refresh(&w->slopes, cache, rect.x0 - 1, rect.z0 - 1, rect.x1 + 1, rect.z1 + 1);
    }
}

// Re-measures the blocks that the rectangles (texels, not wrapping) touch.
static void measure_blocks(detail_window *w, const clip_window *changed) {
    texel_rect whole = {0, 0, changed->size, changed->size};
    const texel_rect *rects = changed->upload_all ? &whole : changed->uploads;
    int count = changed->upload_all ? 1 : changed->upload_count;
    const float *heights = (const float *)w->heights.mirror;
    const short *slopes = (const short *)w->slopes.mirror;
    for (int k = 0; k < count; k++)
        for (int bz = rects[k].z / DETAIL_SNAP; bz <= (rects[k].z + rects[k].h - 1) / DETAIL_SNAP;
             bz++)
            for (int bx = rects[k].x / DETAIL_SNAP;
                 bx <= (rects[k].x + rects[k].w - 1) / DETAIL_SNAP; bx++) {
                float most = 0.0f;
                int sloped = 0;
                for (int z = bz * DETAIL_SNAP; z < (bz + 1) * DETAIL_SNAP; z++)
                    for (int x = bx * DETAIL_SNAP; x < (bx + 1) * DETAIL_SNAP; x++) {
                        const size_t i = (size_t)z * DETAIL_TEXELS + x;
                        most = fmaxf(most, fabsf(heights[i]));
                        sloped |= slopes[2 * i] != 0 || slopes[2 * i + 1] != 0;
                    }
                w->block_max[bz][bx] = most > 0.0f ? most : sloped ? FLT_MIN : 0.0f;
            }
}

// Follows (s, t) on `face` (past [-1, 1] on a neighbouring face: the camera's place
// extended onto it), the window kept inside the face.
static int follow(planet_detail *d, detail_window *w, tile_cache *cache, const double st[2],
                  int64_t face_samples, int detail_ratio) {
    const int64_t last = face_samples * detail_ratio - DETAIL_TEXELS; // the last origin
    for (int a = 0; a < 2; a++) {
        double j = ((st[a] + 1.0) * 0.5 * (double)face_samples - 0.5) * detail_ratio;
        int64_t c = (int64_t)floor(j) - DETAIL_TEXELS / 2;
        c = c < 0 ? 0 : c > last ? last : c;
        w->origin[a] = c / DETAIL_SNAP * DETAIL_SNAP;
    }
    int a = clip_window_update(&w->heights, cache, w->origin);
    int b = clip_window_update(&w->slopes, cache, w->origin);
    if (a < 0 || b < 0) return -1;
    measure_blocks(w, &w->heights); // both mirrors, where either changed
    measure_blocks(w, &w->slopes);
    d->uploads += clip_window_upload(&w->heights, w->tex_heights, -1, GL_RED, GL_FLOAT);
    d->uploads += clip_window_upload(&w->slopes, w->tex_slopes, -1, GL_RG, GL_SHORT);
    w->current = a == 1 && b == 1;
    return w->current;
}

int planet_detail_update(planet_detail *d, tile_cache *cache, const double cam_pos[3],
                         double altitude_above_ground, int64_t face_samples, double cell_arc,
                         int detail_ratio, const render_settings *s) {
    for (int i = 0; i < DETAIL_WINDOWS; i++)
        d->w[i].current = 0;
    if (!(altitude_above_ground < s->detail_distance) || detail_ratio < 1) return 1;
    if (face_samples * detail_ratio < DETAIL_TEXELS) return 1; // a face smaller than a window
    // Detail sample j of a face sits at level-0 sample j / ratio, whose centre is half a
    // cell in from its cell's edge.
    d->samples_per_metre = detail_ratio / cell_arc;
    d->half_cell = 0.5 * detail_ratio;
    // The faces whose ground lies within the fade distance of the camera's place: its
    // own, and the neighbours whose edge is that near (two near a corner).
    int faces[DETAIL_WINDOWS], count = 0, own;
    double st[DETAIL_WINDOWS][2];
    world_grid_direction_face(cam_pos, &own, &st[0][0], &st[0][1]);
    faces[count++] = own;
    const double reach = s->detail_distance / (0.5 * (double)face_samples * cell_arc);
    for (int f = 0; f < 6 && count < DETAIL_WINDOWS; f++) {
        double fs, ft;
        if (f == own || !world_grid_face_coords_on(f, cam_pos, &fs, &ft)) continue;
        double past = fmax(fabs(fs), fabs(ft)) - 1.0; // how far past face f's edge, in s
        if (past > reach) continue;
        st[count][0] = fs, st[count][1] = ft;
        faces[count++] = f;
    }
    // Keep windows already on these faces; give the others to the faces without one.
    int used[DETAIL_WINDOWS] = {0}, slot_of[DETAIL_WINDOWS];
    for (int k = 0; k < count; k++) {
        slot_of[k] = -1;
        for (int i = 0; i < DETAIL_WINDOWS; i++)
            if (!used[i] && d->w[i].face == faces[k]) slot_of[k] = i, used[i] = 1;
    }
    int all = 1;
    for (int k = 0; k < count; k++) {
        if (slot_of[k] < 0) {
            int i = 0;
            while (used[i])
                i++;
            used[i] = 1, slot_of[k] = i;
            if (open_window(&d->w[i], faces[k]) != 0) return -1;
        }
        int rc = follow(d, &d->w[slot_of[k]], cache, st[k], face_samples, detail_ratio);
        if (rc < 0) return -1;
        all &= rc;
    }
    return all;
}

// The largest |offset| within DETAIL_MARGIN samples of samples [lo, hi] (from the
// window's origin, both axes), 0 outside the window.
static float window_max(const detail_window *w, const double lo[2], const double hi[2]) {
    int b0[2], b1[2];
    for (int a = 0; a < 2; a++) {
        double l = fmax(lo[a] - DETAIL_MARGIN, 0.0),
               h = fmin(hi[a] + DETAIL_MARGIN, DETAIL_TEXELS - 1);
        if (l > h) return 0.0f;
        b0[a] = (int)l / DETAIL_SNAP, b1[a] = (int)h / DETAIL_SNAP;
    }
    // The origin is a whole number of blocks: block b from it is texture block b + o.
    const int ox = (int)(w->origin[0] / DETAIL_SNAP), oz = (int)(w->origin[1] / DETAIL_SNAP);
    float most = 0.0f;
    for (int bz = b0[1]; bz <= b1[1]; bz++)
        for (int bx = b0[0]; bx <= b1[0]; bx++)
            most = fmaxf(most, w->block_max[(bz + oz) % DETAIL_BLOCKS][(bx + ox) % DETAIL_BLOCKS]);
    return most;
}

int planet_detail_chunk(const planet_detail *d, int face, int level, const double lo_m[2],
                        const double hi_m[2], double base_u, double base_v, float out[4],
                        float wrap[2]) {
    out[0] = out[1] = out[2] = out[3] = 0.0f;
    wrap[0] = wrap[1] = 0.0f;
    if (level >= DETAIL_LEVELS) return -1;
    for (int i = 0; i < DETAIL_WINDOWS; i++) {
        const detail_window *w = &d->w[i];
        if (!w->current || face != w->face) continue;
        // Detail sample index of face-local metres m: m x samples_per_metre - half a cell.
        double lo[2], hi[2];
        for (int a = 0; a < 2; a++) {
            lo[a] = lo_m[a] * d->samples_per_metre - d->half_cell - (double)w->origin[a];
            hi[a] = hi_m[a] * d->samples_per_metre - d->half_cell - (double)w->origin[a];
        }
        out[0] = (float)(base_u * d->samples_per_metre - d->half_cell - (double)w->origin[0]);
        out[1] = (float)(base_v * d->samples_per_metre - d->half_cell - (double)w->origin[1]);
        out[2] = (float)d->samples_per_metre;
        out[3] = window_max(w, lo, hi);
        wrap[0] = (float)(w->origin[0] & (DETAIL_TEXELS - 1));
        wrap[1] = (float)(w->origin[1] & (DETAIL_TEXELS - 1));
        return i;
    }
    return -1;
}

void planet_detail_bind(planet_detail *d, GLuint prog, const render_settings *s, int unit_heights,
                        int unit_slopes) {
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_detail_spacing"),
                       d->samples_per_metre > 0 ? (float)(1.0 / d->samples_per_metre) : 1.0f);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_detail_size"), DETAIL_TEXELS);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_parallax"), s->parallax);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_parallax_steps"), s->parallax_steps);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_parallax_fade"),
                       (float)s->detail_distance);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_detail"), unit_heights);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_detail_pd"), unit_slopes);
}

void planet_detail_use(const planet_detail *d, int window, int unit_heights, int unit_slopes) {
    if (window < 0 || window >= DETAIL_WINDOWS) return;
    glBindTextureUnit((GLuint)unit_heights, d->w[window].tex_heights);
    glBindTextureUnit((GLuint)unit_slopes, d->w[window].tex_slopes);
}

uint64_t planet_detail_take_uploads(planet_detail *d) {
    uint64_t n = d->uploads;
    d->uploads = 0;
    return n;
}
