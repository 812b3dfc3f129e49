// An offscreen render target (framebuffer with a colour texture and a depth renderbuffer):
// what screenshots, golden-image tests and benchmarks render into, with or without a window.
#ifndef OROGEN_RENDERER_GL_TARGET_H
#define OROGEN_RENDERER_GL_TARGET_H

#include <epoxy/gl.h>

#include "io/err.h"

typedef struct gl_target {
    GLuint fbo, colour, depth;
    int width, height;
} gl_target;

// RGBA8 colour and DEPTH_COMPONENT32F depth (the renderer uses reversed-Z, which
// wants float depth). Sizes 1..16384 (and within GL_MAX_RENDERBUFFER_SIZE).
// -1 with err on a bad size, an incomplete framebuffer or a GL error; t is then zeroed.
int gl_target_create(gl_target *t, int width, int height, og_error *err);
// Deletes the GL objects and zeroes t. A zeroed t is fine.
void gl_target_destroy(gl_target *t);

// Reads the colour buffer into rgb (width*height*3 bytes), rows top first (GL's
// are bottom first). Leaves the caller's framebuffer and pack state as they were.
int gl_target_read_rgb(const gl_target *t, unsigned char *rgb, og_error *err);

#endif
