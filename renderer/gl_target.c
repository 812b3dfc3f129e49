// Offscreen framebuffers through GL 4.5 direct state access, and reading them back.
#include "renderer/gl_target.h"

#include "renderer/gl_context.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { TARGET_SIZE_MAX = 16384 };

static const char *status_name(GLenum status) {
    switch (status) {
    case GL_FRAMEBUFFER_UNDEFINED:
        return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
        return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
        return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_UNSUPPORTED:
        return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
        return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case 0:
        return "error while checking";
    default:
        return "incomplete";
    }
}

int gl_target_create(gl_target *t, int width, int height, og_error *err) {
    memset(t, 0, sizeof *t);
    GLint max_size = 0;
    GLint max_texture = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
    if (max_texture < max_size) max_size = max_texture;
    if (max_size > TARGET_SIZE_MAX) max_size = TARGET_SIZE_MAX;
    if (width < 1 || height < 1 || width > max_size || height > max_size)
        return og_error_set(err, "render target %dx%d: sizes must be 1..%d", width, height,
                            max_size);
    // Errors from before are not ours to report.
    while (glGetError() != GL_NO_ERROR) {
    }

    glCreateFramebuffers(1, &t->fbo);
    glCreateTextures(GL_TEXTURE_2D, 1, &t->colour); // a texture: a later pass may read it
    glCreateRenderbuffers(1, &t->depth);
    glTextureStorage2D(t->colour, 1, GL_RGBA8, width, height);
    glNamedRenderbufferStorage(t->depth, GL_DEPTH_COMPONENT32F, width, height);
    glNamedFramebufferTexture(t->fbo, GL_COLOR_ATTACHMENT0, t->colour, 0);
    glNamedFramebufferRenderbuffer(t->fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->depth);
    glNamedFramebufferDrawBuffer(t->fbo, GL_COLOR_ATTACHMENT0);
    glNamedFramebufferReadBuffer(t->fbo, GL_COLOR_ATTACHMENT0);

    char where[64];
    snprintf(where, sizeof where, "render target %dx%d", width, height);
    if (gl_check_error(where, err) < 0) { // GL_OUT_OF_MEMORY for a big one
        gl_target_destroy(t);
        return -1;
    }
    GLenum status = glCheckNamedFramebufferStatus(t->fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        og_error_set(err, "%s: framebuffer incomplete: %s (0x%x)", where, status_name(status),
                     (unsigned)status);
        gl_target_destroy(t);
        return -1;
    }
    t->width = width;
    t->height = height;
    return 0;
}

void gl_target_destroy(gl_target *t) {
    if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
    if (t->colour) glDeleteTextures(1, &t->colour);
    if (t->depth) glDeleteRenderbuffers(1, &t->depth);
    memset(t, 0, sizeof *t);
}

int gl_target_read_rgb(const gl_target *t, unsigned char *rgb, og_error *err) {
    if (!t->fbo || t->width < 1 || t->height < 1)
        return og_error_set(err, "render target: read from a target that was not created");
    while (glGetError() != GL_NO_ERROR) {
    }

    // The caller's state, restored below: the read framebuffer, a bound pixel pack
    // buffer (which would turn rgb into an offset) and the row packing.
    GLint old_fbo = 0, old_pack_buffer = 0, old_alignment = 4, old_row_length = 0;
    GLint old_skip_rows = 0, old_skip_pixels = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &old_fbo);
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &old_pack_buffer);
    glGetIntegerv(GL_PACK_ALIGNMENT, &old_alignment);
    glGetIntegerv(GL_PACK_ROW_LENGTH, &old_row_length);
    glGetIntegerv(GL_PACK_SKIP_ROWS, &old_skip_rows);
    glGetIntegerv(GL_PACK_SKIP_PIXELS, &old_skip_pixels);

    glBindFramebuffer(GL_READ_FRAMEBUFFER, t->fbo);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1); // rows of width*3 bytes, no padding
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_PACK_SKIP_ROWS, 0);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
    size_t row = (size_t)t->width * 3, size = row * (size_t)t->height;
    glReadnPixels(0, 0, t->width, t->height, GL_RGB, GL_UNSIGNED_BYTE, (GLsizei)size, rgb);

    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)old_fbo);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, (GLuint)old_pack_buffer);
    glPixelStorei(GL_PACK_ALIGNMENT, old_alignment);
    glPixelStorei(GL_PACK_ROW_LENGTH, old_row_length);
    glPixelStorei(GL_PACK_SKIP_ROWS, old_skip_rows);
    glPixelStorei(GL_PACK_SKIP_PIXELS, old_skip_pixels);
    if (gl_check_error("render target: glReadnPixels", err) < 0) return -1;

    // GL's first row is the bottom one: swap rows pairwise.
    unsigned char *swap = malloc(row);
    if (!swap) return og_error_set(err, "render target: out of memory");
    for (int top = 0, bottom = t->height - 1; top < bottom; top++, bottom--) {
        unsigned char *a = rgb + (size_t)top * row, *b = rgb + (size_t)bottom * row;
        memcpy(swap, a, row);
        memcpy(a, b, row);
        memcpy(b, swap, row);
    }
    free(swap);
    return 0;
}
