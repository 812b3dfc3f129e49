// A toroidal window onto one tile layer at one mip level: a size x size CPU mirror of
// the samples around a moving origin, laid out exactly as its GPU texture (sample
// (i, j) lives at texel (i mod size, j mod size)), so that moving the window only
// rewrites the rows and columns that entered it (Losasso & Hoppe's toroidal update).
//
// Filling never blocks: the tiles a change needs are requested from the cache, and
// only when every one of them is resident is anything copied. Until then the window
// keeps its old, consistent contents and reports itself not current, and the renderer
// draws the next coarser level in its place.
#ifndef OROGEN_RENDERER_CLIP_WINDOW_H
#define OROGEN_RENDERER_CLIP_WINDOW_H

#include "io/tile_cache.h"

#include <stddef.h>
#include <stdint.h>

#define CLIP_WINDOW_MAX_RECTS 32

// A rectangle of texels (toroidal coordinates, never wrapping) to upload.
typedef struct texel_rect {
    int x, z, w, h;
} texel_rect;

typedef struct clip_window {
    tile_layer layer;
    int face, level;
    // Heights only (a float layer): 0, or each sample the higher of the level's own and
    // the sample at the same place 2^ridge_shift finer (clip_window_init_ridges).
    int ridge_shift;
    int size; // texels per side, a power of two
    size_t texel_bytes;
    unsigned char *mirror; // size * size * texel_bytes
    int64_t have[2];       // origin (sample indices at this level) the mirror holds
    int has_data;          // the mirror holds the whole window at `have`
    // Texels changed since the owner last uploaded (cleared by the owner).
    texel_rect uploads[CLIP_WINDOW_MAX_RECTS];
    int upload_count;
    int upload_all;         // the whole texture must be uploaded
    uint64_t texels_copied; // running total (benchmarks: texels uploaded while flying)
    // Budgeted updates (clip_window_update_within) fill a window over several calls:
    // meanwhile the samples [valid[0], valid[2]) x [valid[1], valid[3]) of the wanted
    // window are in the mirror (partial = 1, has_data = 0).
    int64_t valid[4];
    int partial;
    int refill_started; // a fill from nothing began since the owner last looked (owner clears)
} clip_window;

int clip_window_init(clip_window *w, tile_layer layer, int face, int level, int size);
// A window of heights (TILE_LAYER_COARSE) whose samples are each the higher of the
// level's own (tent-filtered mips: lower than the ground on ridges and peaks) and the
// point sample of mip level `level - shift` at the same place (shift > 0), so that the
// coarse levels' ridges and skylines come nearer the full resolution's.
int clip_window_init_ridges(clip_window *w, int face, int level, int size, int shift);
void clip_window_free(clip_window *w);
// Forgets the contents (new world, new parameters): the next update refills it all.
void clip_window_invalidate(clip_window *w);

// Moves the window to origin `want` (sample indices at this level). Returns 1 when the
// mirror holds the window at `want` (current), 0 while tiles are still pending, -1 when a
// tile cannot be had (err set).
int clip_window_update(clip_window *w, tile_cache *cache, const int64_t want[2]);
// The same, copying about *budget texels at most (taken off it): a move that needs more
// (a jump, a first fill, a level the camera comes down to) is spread over calls, the
// window growing from what it already holds of the wanted one, not current until it
// holds all of it (its owner draws something else meanwhile), so that no frame uploads
// a whole texture. A move needing at most 32 rows or columns is always made at once.
int clip_window_update_within(clip_window *w, tile_cache *cache, const int64_t want[2],
                              int64_t *budget);

// Re-reads the samples of rect [x0, x1) x [z0, z1) (sample indices at this level) that
// lie inside the window, after an edit. If their tiles are not resident the window
// is marked empty and refills on the next update.
void clip_window_refresh(clip_window *w, tile_cache *cache, int64_t x0, int64_t z0, int64_t x1,
                         int64_t z1);

int clip_window_current(const clip_window *w, const int64_t want[2]);

#endif
