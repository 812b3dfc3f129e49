// The slopes each clipmap level is shaded with, from heights CLIP_SLOPES_SHIFT mip levels
// finer than its own (its vertices' heights stay the level's, raised to these at their
// own places: renderer/clip_window.h clip_window_init_ridges): a level's sample is 4 to
// 8 pixels wide on the screen (a ring reaches 64 to 127 of them from the camera), so
// slopes from its own samples blur the ridges and gullies a full-resolution mesh
// shows. One toroidal window per level over the level's whole extent (level 0 has
// none: it is the full resolution), filled within an upload budget of its own; until a
// window is current its level shades from its own heights.
#ifndef OROGEN_RENDERER_CLIP_SLOPES_H
#define OROGEN_RENDERER_CLIP_SLOPES_H

#include "io/tile_cache.h"
#include "renderer/clip_window.h"
#include "renderer/render_settings.h"

#include <epoxy/gl.h>
#include <stdint.h>

#define CLIP_SLOPES_SHIFT 2     // mip levels finer than the level's own (at most)
#define CLIP_SLOPES_TEXELS 1024 // window side: a level's 255 samples, 4 finer each, a margin

typedef struct clip_slopes {
    clip_window windows[RENDER_MAX_LEVELS]; // [l] at mip level clip_slopes_mip(l)
    int64_t want[RENDER_MAX_LEVELS][2];     // this frame's origin of each window
    GLuint tex;                             // R32F, a layer per level
    uint64_t frame_texels;                  // uploaded by the last clip_slopes_upload
} clip_slopes;

// The mip level level l's slopes come from.
int clip_slopes_mip(int l);

int clip_slopes_init(clip_slopes *s);
void clip_slopes_free(clip_slopes *s);
void clip_slopes_invalidate(clip_slopes *s);

// Moves the windows of levels [finest, levels) to cover those levels (origin: each
// level's local vertex (0, 0), level sample indices), copying about *budget texels at
// most beyond small moves (taken off it; INT64_MAX / 2: no limit). 1 when all are
// current, 0 while some are pending, -1 when a tile cannot be had.
int clip_slopes_update(clip_slopes *s, tile_cache *cache, const int64_t (*origin)[2], int finest,
                       int levels, int64_t *budget);

// Re-reads level-0 samples [x0, x1) x [z0, z1) after an edit (tent-filtered mips: a
// sample further per level).
void clip_slopes_refresh(clip_slopes *s, tile_cache *cache, int64_t x0, int64_t z0, int64_t x1,
                         int64_t z1);

// Sends what changed to the texture; the texels sent are in frame_texels.
void clip_slopes_upload(clip_slopes *s, int finest, int levels);

// For shading level l from source level src's window (src >= l), in level l's local
// coordinates (local_origin: level l's vertex (0, 0), level-l sample indices): the texel
// of local (0, 0), texels per local unit, and the layer; layer -1 when src has no
// current window (shade from the level's own heights).
void clip_slopes_uniform(const clip_slopes *s, int l, int src, const int64_t local_origin[2],
                         float out[4]);

#endif
