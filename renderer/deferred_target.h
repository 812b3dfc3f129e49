// The flat terrain's deferred shading target (renderer/terrain_renderer.c): llvmpipe runs
// a fragment shader on at least 8 pixels for every triangle that touches them, and the
// clipmap's far triangles cover a few pixels each, so shading them as they are drawn
// ran the whole material and lighting shader several times a pixel. Instead the
// triangles write only each pixel's depth (the G-buffer: the ground's place follows
// from it and the pixel) and the level drawn there (stencil), and a full-screen pass
// per level shades each pixel once. The result goes to the caller's framebuffer with its depth, so
// what is drawn after the terrain (water, volume meshes, cursors) meets it as before.
#ifndef OROGEN_RENDERER_DEFERRED_TARGET_H
#define OROGEN_RENDERER_DEFERRED_TARGET_H

#include "io/err.h"

#include <epoxy/gl.h>

typedef struct deferred_target {
    GLuint fbo;
    GLuint ground_depth;  // R32F: the depth drawn (0, the far plane: no ground), sampled
    GLuint shaded;        // RGBA8: the finished colour (terrain and sky)
    GLuint depth_stencil; // DEPTH32F_STENCIL8: the depth test, the level drawn
    int width, height;    // 0 until the first frame
    GLuint prog_copy;     // the shaded colour and depth into the caller's framebuffer
    GLint caller_fbo;
} deferred_target;

// Loads the copy program from shader_dir; no GL storage until the first frame.
int deferred_target_init(deferred_target *t, const char *shader_dir, og_error *err);
void deferred_target_free(deferred_target *t);

// Starts a frame of width x height pixels: remembers the caller's draw framebuffer,
// binds the target with only the ground's depth drawn, clears it (depth 0: the
// reversed-Z far plane, stencil 0) and leaves the stencil test on.
int deferred_target_begin(deferred_target *t, int width, int height, og_error *err);
// The stencil value a level's pieces write (still: drawn without morphing), 2 .. 255;
// a level's still and morphing parts differ only in the lowest bit.
int deferred_target_stencil(int level, int still);
// From the G-buffer to shading: the shaded colour drawn, the ground's depth on texture
// unit `unit`, no depth test.
void deferred_target_shade(deferred_target *t, int unit);
// Copies the shaded colour and the depth into the caller's framebuffer (every pixel),
// and leaves that framebuffer bound with the stencil test off and the depth test on.
void deferred_target_finish(deferred_target *t, GLuint empty_vao);

// The inverse of a view-projection matrix (column-major; camera-relative metres from
// clip space), computed in double. 0, or -1 when it has none.
int deferred_target_inverse(const float m[16], float out[16]);

#endif
