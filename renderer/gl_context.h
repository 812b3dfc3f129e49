// The OpenGL context the renderer runs on, and the checks around it: a headless
// GL 4.5 core context (EGL, surfaceless: no window, no display server) for batch
// rendering, tests and benchmarks; the feature check every context must pass; GL
// error draining and debug output.
#ifndef OROGEN_RENDERER_GL_CONTEXT_H
#define OROGEN_RENDERER_GL_CONTEXT_H

#include "io/err.h"

typedef struct gl_headless gl_headless;

// A headless OpenGL 4.5 core context on EGL's surfaceless platform
// (EGL_PLATFORM_SURFACELESS_MESA through EGL_EXT_platform_base), made current on
// the calling thread. Render into a gl_target: there is no default framebuffer.
// NULL with err saying what is missing (no EGL, no surfaceless platform, no GL 4.5 core).
gl_headless *gl_headless_create(og_error *err);
// Releases the context (made not current first if it is current on this thread). NULL is fine.
void gl_headless_destroy(gl_headless *ctx);

// With any context current (GLFW window or headless): checks for GL >= 4.5 core and
// the features the renderer needs. -1 with err naming what is missing and the GL_RENDERER.
int gl_require_features(og_error *err);

// Installs a KHR_debug callback that prints GL errors (type ERROR) to stderr, once
// per message id; a no-op where KHR_debug is unavailable.
void gl_debug_enable(void);

// Drains glGetError(). 0 if there was no error, else -1 with err
// "WHERE: GL_INVALID_OPERATION (0x502)" naming the first code (and counting the rest).
int gl_check_error(const char *where, og_error *err);

#endif
