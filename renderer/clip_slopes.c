#include "renderer/clip_slopes.h"

#include "renderer/clip_window_upload.h"

#include <math.h>

int clip_slopes_mip(int l) {
    return l > CLIP_SLOPES_SHIFT ? l - CLIP_SLOPES_SHIFT : 0;
}

// The window origin for level l at `origin` (level-l sample indices): the level's
// samples scaled to the window's mip, centred (the margin holds the neighbours the
// central differences at the level's edge read).
static void window_origin(int l, const int64_t origin[2], int64_t out[2]) {
    const int shift = l - clip_slopes_mip(l);
    const int64_t span = (int64_t)254 << shift; // the level's 255 samples
    for (int a = 0; a < 2; a++)
        out[a] = origin[a] * ((int64_t)1 << shift) - (CLIP_SLOPES_TEXELS - span) / 2;
}

int clip_slopes_init(clip_slopes *s) {
    for (int l = 1; l < RENDER_MAX_LEVELS; l++)
        if (clip_window_init(&s->windows[l], TILE_LAYER_COARSE, 0, clip_slopes_mip(l),
                             CLIP_SLOPES_TEXELS) != 0)
            return -1;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &s->tex);
    glTextureStorage3D(s->tex, 1, GL_R32F, CLIP_SLOPES_TEXELS, CLIP_SLOPES_TEXELS,
                       RENDER_MAX_LEVELS);
    glTextureParameteri(s->tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(s->tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(s->tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(s->tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
    return 0;
}

void clip_slopes_free(clip_slopes *s) {
    for (int l = 1; l < RENDER_MAX_LEVELS; l++)
        clip_window_free(&s->windows[l]);
    glDeleteTextures(1, &s->tex);
    s->tex = 0;
}

void clip_slopes_invalidate(clip_slopes *s) {
    for (int l = 1; l < RENDER_MAX_LEVELS; l++)
        clip_window_invalidate(&s->windows[l]);
}

int clip_slopes_update(clip_slopes *s, tile_cache *cache, const int64_t (*origin)[2], int finest,
                       int levels, int64_t *budget) {
    int all = 1;
    for (int l = finest > 1 ? finest : 1; l < levels; l++) {
        window_origin(l, origin[l], s->want[l]);
        int ok = clip_window_update_within(&s->windows[l], cache, s->want[l], budget);
        if (ok < 0) return -1;
        if (!ok) all = 0;
    }
    return all;
}

void clip_slopes_refresh(clip_slopes *s, tile_cache *cache, int64_t x0, int64_t z0, int64_t x1,
                         int64_t z1) {
    for (int l = 1; l < RENDER_MAX_LEVELS; l++) {
        int m = clip_slopes_mip(l);
        clip_window_refresh(&s->windows[l], cache, (x0 >> m) - 1, (z0 >> m) - 1,
                            ((x1 - 1) >> m) + 2, ((z1 - 1) >> m) + 2);
    }
}

void clip_slopes_upload(clip_slopes *s, int finest, int levels) {
    s->frame_texels = 0;
    for (int l = finest > 1 ? finest : 1; l < levels; l++)
        s->frame_texels += clip_window_upload(&s->windows[l], s->tex, l, GL_RED, GL_FLOAT);
}

void clip_slopes_uniform(const clip_slopes *s, int l, int src, const int64_t local_origin[2],
                         float out[4]) {
    out[0] = out[1] = 0, out[2] = 1, out[3] = -1;
    if (src < 1 || src >= RENDER_MAX_LEVELS || !clip_window_current(&s->windows[src], s->want[src]))
        return;
    // Window texels per level-l local unit, and where local (0, 0) falls in the window.
    const int m = clip_slopes_mip(src);
    const double scale = ldexp(1.0, l - m);
    for (int a = 0; a < 2; a++) {
        double rel = (double)local_origin[a] * scale - (double)s->want[src][a];
        out[a] = (float)((double)(s->want[src][a] & (CLIP_SLOPES_TEXELS - 1)) + rel);
    }
    out[2] = (float)scale;
    out[3] = (float)src;
}
