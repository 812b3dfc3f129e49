// The 3D viewport's renderer: GPU geometry clipmaps over the tile cache (Crause 2010),
// with material splatting, parallax detail, sky, water, fog, the brush cursor and the
// debug views. Needs a current OpenGL 4.5 core context (the window's or a headless
// one); everything it holds is the same size whatever the world's size.
#ifndef OROGEN_RENDERER_TERRAIN_RENDERER_H
#define OROGEN_RENDERER_TERRAIN_RENDERER_H

#include "editor/world/world.h"
#include "io/err.h"
#include "renderer/camera.h"
#include "renderer/render_settings.h"

#include <stdint.h>

typedef struct render_stats {
    uint64_t triangles;                          // drawn this frame (terrain)
    uint64_t level_triangles[RENDER_MAX_LEVELS]; // of those, each clipmap level's
    int draw_calls;
    int levels_drawn, levels_ready, finest_level;
    uint64_t texels_uploaded;       // this frame
    uint64_t slope_texels_uploaded; // this frame, to the shading slopes (clip_slopes.h)
    double cpu_ms; // CPU time of update + draw submission (the calling thread's, on flat
                   // worlds; planets: wall time)
} render_stats;

typedef struct terrain_renderer terrain_renderer;

// Loads the shaders from resource_dir/shaders and builds the fixed buffers.
terrain_renderer *terrain_renderer_create(const char *resource_dir, og_error *err);
void terrain_renderer_destroy(terrain_renderer *r);

// Brings the clipmaps up to date for this camera without waiting: edits since the
// last call are re-read, entering rows and columns are uploaded, tiles that are not
// resident yet are requested (the levels that need them show the coarser level).
// Returns 1 when every level is current, 0 while some still wait, -1 on error (a
// planet world, which this viewport does not draw yet, or a cache failure).
// A frame uploads at most about a tenth of the level textures: jumps and first fills
// are spread over frames (the next coarser level stands in meanwhile).
int terrain_renderer_update(terrain_renderer *r, world *w, const camera *cam,
                            const render_settings *s, og_error *err);
// Off: every update copies all it can (a headless render waiting for a finished
// picture has no frames to spread the uploads over). On by default.
void terrain_renderer_spread_uploads(terrain_renderer *r, int on);

// Draws into the current framebuffer (width x height pixels).
int terrain_renderer_draw(terrain_renderer *r, world *w, const camera *cam,
                          const render_settings *s, const brush_cursor *cursor, int width,
                          int height, og_error *err);

void terrain_renderer_stats(const terrain_renderer *r, render_stats *out);
// The size the next frame will have (each draw records its own): a planet's level of
// detail is chosen for it.
void terrain_renderer_set_view_size(terrain_renderer *r, int width, int height);
// The volume meshes (caves, overhangs) the renderer draws, for picking.
typedef struct volume_renderer volume_renderer;
volume_renderer *terrain_renderer_volume(terrain_renderer *r);

// The ground height at world x, z from the finest current level holding it (what the
// viewport shows, without morphing). 0 and *h, or -1 when no level holds it.
int terrain_renderer_height_at(void *renderer, double x, double z, double *h);

#endif
