// Fine relief near the camera on a planet: the detail layer's offsets and slopes in a
// window around the camera (as the flat viewport's detail window) on the face under it
// and, when a face edge or corner is within the fade distance, on the neighbouring
// faces too (a window each), for the parallax and the normals of the finest chunks.
#ifndef OROGEN_RENDERER_PLANET_DETAIL_H
#define OROGEN_RENDERER_PLANET_DETAIL_H

#include "editor/params/world_grid.h"
#include "io/err.h"
#include "io/tile_cache.h"
#include "renderer/render_settings.h"

#include <epoxy/gl.h>
#include <stdint.h>

typedef struct planet_detail planet_detail;

planet_detail *planet_detail_create(og_error *err);
void planet_detail_destroy(planet_detail *d);
// Forgets the contents (another world, new parameters).
void planet_detail_forget(planet_detail *d);
// A detail edit on a face (detail-sample rectangle): re-read it if the window shows it.
void planet_detail_touched(planet_detail *d, tile_cache *cache, int face, grid_rect rect);

// Follows the camera (planet coordinates) when it is within the fade distance of the
// ground (altitude_above_ground metres); face_samples and cell_arc: the face's level-0
// grid (samples per side, metres per cell on the datum). Returns 1 when the window is
// current or not wanted, 0 while its tiles are pending, -1 on error.
int planet_detail_update(planet_detail *d, tile_cache *cache, const double cam_pos[3],
                         double altitude_above_ground, int64_t face_samples, double cell_arc,
                         int detail_ratio, const render_settings *s);

// The chunk's mapping from its vertices' metres (face-local, less base_u, base_v) to
// detail samples from its face's window's origin: (offset u, offset v, samples per
// metre, the largest |offset| in metres around the chunk's face-local metres [lo_m,
// hi_m]: 0 where the detail is zero, as it is until edited), and the window's
// u_detail_wrap. Returns the window (for planet_detail_use), or -1 when no current
// window covers the chunk's face (all 0).
int planet_detail_chunk(const planet_detail *d, int face, int level, const double lo_m[2],
                        const double hi_m[2], double base_u, double base_v, float out[4],
                        float wrap[2]);

// Sets the detail uniforms of detail_parallax.glsl but u_detail_wrap (per chunk).
void planet_detail_bind(planet_detail *d, GLuint prog, const render_settings *s, int unit_heights,
                        int unit_slopes);
// Binds a window's two textures to the units planet_detail_bind named.
void planet_detail_use(const planet_detail *d, int window, int unit_heights, int unit_slopes);

// Detail texels uploaded since the last call.
uint64_t planet_detail_take_uploads(planet_detail *d);

#endif
