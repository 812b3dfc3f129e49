// Edge anti-aliasing of a finished terrain image (resources/shaders/antialias.frag): one
// full-screen pass that smooths the steps along edges (the horizon, ridges against the
// sky, a planet's limb) without rendering the terrain again.
#ifndef OROGEN_RENDERER_ANTIALIAS_H
#define OROGEN_RENDERER_ANTIALIAS_H

#include "io/err.h"
#include "renderer/gl_target.h"

typedef struct antialias antialias;

// shader_dir: resources/shaders. NULL with err when the program does not build.
antialias *antialias_create(const char *shader_dir, og_error *err);
void antialias_destroy(antialias *a);

// Draws src's colour with its edges smoothed over the whole of dst (the same size).
// Leaves the framebuffer binding, viewport and program as it found them.
int antialias_apply(antialias *a, const gl_target *src, const gl_target *dst, og_error *err);

#endif
