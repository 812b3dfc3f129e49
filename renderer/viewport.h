// The viewport's state shared by the window and the batch commands: the camera, the
// render settings, the brush cursor, and the renderer with the GL context it lives in
// (the window's, or a headless EGL one made on first use in batch mode).
#ifndef OROGEN_RENDERER_VIEWPORT_H
#define OROGEN_RENDERER_VIEWPORT_H

#include "editor/world/world.h"
#include "io/err.h"
#include "renderer/antialias.h"
#include "renderer/camera.h"
#include "renderer/gl_context.h"
#include "renderer/gl_target.h"
#include "renderer/terrain_renderer.h"

#include <stdint.h>

typedef struct viewport {
    camera cam;
    int cam_set; // the camera was placed (else the first render places it)
    // The world (cmd_context world_serial) a command placed the camera for: a window
    // that sees the world replaced keeps a camera placed after the replacement.
    uint64_t cam_world_serial;
    render_settings settings;
    brush_cursor cursor;
    gl_headless *headless; // owned; NULL when a window's context is used
    int window_context;    // a window made its context current: never make a headless one
    terrain_renderer *renderer;
    antialias *aa; // made when first used
    char resource_dir[4096];
    double wait_seconds; // how long a screenshot waits for tiles (default 600)
    double aspect;       // width over height of the view shown (0: not known, taken as 1)
} viewport;

viewport *viewport_create(const char *resource_dir);
void viewport_destroy(viewport *v);

// A view over the world's centre (or the origin of an unbounded world), a few hundred
// metres above the ground, looking out over the terrain. Planets: the whole disc from
// orbit, north up, seen from the day side with the sun behind the camera's right
// shoulder (the visible hemisphere lit), inside the view whatever its aspect.
int viewport_default_camera(viewport *v, world *w, og_error *err);
// The editor's first view of a flat world: the default camera turned to face the nearest
// land well above the sea (searched in rings out to 3 km from the centre, then in a bounded
// world over all of it; above the plain a heightmap's relief stands on, when that lies
// above the sea: renderer/land_scan.h), from a distance that shows it whole (a bounded
// world smaller than that view: all of it); the whole of a small bounded world with no
// such land; else the default camera. Planets: as viewport_default_camera.
int viewport_camera_on_land(viewport *v, world *w, og_error *err);

// Makes sure a GL context is current and the renderer exists.
int viewport_prepare(viewport *v, og_error *err);

// Updates the clipmaps until every level is current (at most wait_seconds).
int viewport_settle(viewport *v, world *w, og_error *err);

// Draws src with its edges smoothed into dst (the same size; renderer/antialias.h).
int viewport_antialias(viewport *v, const gl_target *src, const gl_target *dst, og_error *err);

// Renders width x height pixels offscreen and writes them to path as an RGB PNG (edges
// smoothed when the settings' antialias is on, as the window shows them).
int viewport_screenshot(viewport *v, world *w, const char *path, int width, int height,
                        og_error *err);

// The terrain point under pixel (px, py) of a width x height image, by marching the
// ray against the heights the viewport holds. 0 and hit, or -1 (err) when the ray
// meets no terrain.
// The same without waiting, against whatever the levels hold now (the window's
// brushes): sx, sy in [0, 1] from the top-left. 0 and hit, or -1 on no terrain.
int viewport_pick_loaded(viewport *v, world *w, double sx, double sy, double aspect, double hit[3]);
// Flat worlds' picking reads only what the renderer holds (its levels and volume
// meshes) and the parameters given, never the world's tiles: the window may use it
// while a job owns the world. -1 on planets (their picking reads the world).
int viewport_pick_shown(viewport *v, const world_params *p, double sx, double sy, double aspect,
                        double hit[3]);
int viewport_pick(viewport *v, world *w, double px, double py, int width, int height, double hit[3],
                  og_error *err);
// As viewport_pick, but on a planet the sea floor under the sea (the ground, not the
// surface).
int viewport_pick_floor(viewport *v, world *w, double px, double py, int width, int height,
                        double hit[3], og_error *err);

#endif
