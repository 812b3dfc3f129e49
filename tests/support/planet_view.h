// What the tests that look at a rendered planet share (test_planet_look, test_planet_rules,
// test_mask_overlay): a headless GL context, an offscreen target, a terrain renderer and
// the Earth-like preset's world, and a draw that waits for every tile it wants.
#ifndef OROGEN_TEST_PLANET_VIEW_H
#define OROGEN_TEST_PLANET_VIEW_H

#include "editor/world/world.h"
#include "renderer/camera.h"
#include "renderer/gl_context.h"
#include "renderer/gl_target.h"
#include "renderer/terrain_renderer.h"

typedef struct planet_view {
    gl_headless *ctx;
    gl_target target;
    terrain_renderer *renderer;
    world *earth; // the Earth-like preset, 1 GiB cache, 2 workers
    int w, h;
} planet_view;

// Opens the view at w x h pixels: 0, or -1 with the reason on stderr after the test's name.
int planet_view_open(planet_view *v, int w, int h, const char *test);
void planet_view_close(planet_view *v);
// Draws world from c with s (NULL: the defaults) once every tile it wants is there (or
// 60 s passed). rgb gets w x h x 3 bytes, top row first. When not NULL, pos gets the
// position each pixel shows and height its height above the planet's datum (NAN: sky).
void planet_view_draw(planet_view *v, world *world, const camera *c, const render_settings *s,
                      unsigned char *rgb, double (*pos)[3], double *height);

#endif
