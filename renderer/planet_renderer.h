// The planet viewport: a chunked quadtree per cube face over the same tile cache the
// editor writes (Ulrich 2002's chunked LOD, with the world's own mip tiles as the
// levels). A chunk is a 16 x 16-sample block of one face at one mip level, meshed on
// the CPU in double precision around its own origin and drawn camera-relative, so an
// Earth-sized planet holds still from 40,000 km out down to metres above the ground.
// Chunks split where a sample would cover more than a few pixels; those behind the
// horizon or outside the view are never built nor drawn; skirts close the cracks
// between levels and along face edges. The ocean is the surface raised to the sea's
// radius (seed 004's way) with Fresnel; a single-scattering atmosphere draws the sky,
// the rim and the haze over distant ground.
#ifndef OROGEN_RENDERER_PLANET_RENDERER_H
#define OROGEN_RENDERER_PLANET_RENDERER_H

#include "editor/params/world_grid.h"
#include "editor/world/world.h"
#include "io/err.h"
#include "renderer/camera.h"
#include "renderer/planet_stats.h"
#include "renderer/render_settings.h"

#include <epoxy/gl.h>
#include <stdint.h>

typedef struct planet_renderer planet_renderer;

// albedo: the terrain renderer's material texture array; falloff: its brush falloff
// texture (64 x 1 R32F), both shared, not owned.
planet_renderer *planet_renderer_create(const char *resource_dir, GLuint albedo, GLuint falloff,
                                        og_error *err);
void planet_renderer_destroy(planet_renderer *r);

// Chooses the chunks for this camera and builds those whose tiles are resident (a
// few milliseconds' worth a frame; the rest are requested and their parents stand in).
// 1 when every chunk wanted is drawn at its own level, 0 while some wait, -1 on error.
int planet_renderer_update(planet_renderer *r, world *w, const camera *cam,
                           const render_settings *s, double aspect, int height_px, og_error *err);
// cursor (may be NULL): the brush draped on the ground around (x, y, z), planet
// coordinates, the disc measured on the local level.
int planet_renderer_draw(planet_renderer *r, const camera *cam, const render_settings *s,
                         const brush_cursor *cursor, int width, int height, og_error *err);
void planet_renderer_stats(const planet_renderer *r, planet_stats *out);

// Change notifications: a coarse edit on a face (level-0 sample rectangle) rebuilds the
// chunks over it; forget drops every chunk (new parameters, another world).
void planet_renderer_touched(planet_renderer *r, int face, grid_rect rect);
void planet_renderer_forget(planet_renderer *r);
// A detail-layer edit on a face (detail-sample rectangle): the parallax window re-reads it.
void planet_renderer_detail_touched(planet_renderer *r, tile_cache *cache, int face,
                                    grid_rect rect);

// The sun: render_sun_direction's vector read in planet coordinates (sun_yaw turns it
// around the +Y axis; the light's rotation, seed 004's omega, turns sun_yaw).

#endif
