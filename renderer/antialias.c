// The anti-aliasing pass: the source image as a linearly filtered texture, one triangle
// over the target.
#include "renderer/antialias.h"

#include "renderer/gl_context.h"
#include "renderer/shader.h"

#include <stdlib.h>

struct antialias {
    GLuint prog, vao, sampler;
    GLint texel;
};

antialias *antialias_create(const char *shader_dir, og_error *err) {
    antialias *a = calloc(1, sizeof *a);
    if (!a) {
        og_error_set(err, "out of memory");
        return NULL;
    }
    if (!(a->prog = shader_program_load(shader_dir, "fullscreen.vert", "antialias.frag", err))) {
        free(a);
        return NULL;
    }
    a->texel = glGetUniformLocation(a->prog, "u_texel");
    glProgramUniform1i(a->prog, glGetUniformLocation(a->prog, "u_image"), 0);
    glCreateVertexArrays(1, &a->vao);
    // Linear, clamped: a sample half a pixel across an edge reads both sides' mean.
    glCreateSamplers(1, &a->sampler);
    glSamplerParameteri(a->sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(a->sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(a->sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(a->sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return a;
}

void antialias_destroy(antialias *a) {
    if (!a) return;
    glDeleteProgram(a->prog);
    glDeleteVertexArrays(1, &a->vao);
    glDeleteSamplers(1, &a->sampler);
    free(a);
}

int antialias_apply(antialias *a, const gl_target *src, const gl_target *dst, og_error *err) {
    if (!src->fbo || !dst->fbo || src->width != dst->width || src->height != dst->height)
        return og_error_set(err,
                            "anti-aliasing: the images must exist and be the same size "
                            "(%d x %d, %d x %d)",
                            src->width, src->height, dst->width, dst->height);
    GLint old_fbo = 0, old_prog = 0, old_view[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &old_fbo);
    glGetIntegerv(GL_CURRENT_PROGRAM, &old_prog);
    glGetIntegerv(GL_VIEWPORT, old_view);
    GLboolean old_depth = glIsEnabled(GL_DEPTH_TEST), old_blend = glIsEnabled(GL_BLEND);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, dst->fbo);
    glViewport(0, 0, dst->width, dst->height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(a->prog);
    glProgramUniform2f(a->prog, a->texel, 1.0f / (float)src->width, 1.0f / (float)src->height);
    glBindTextureUnit(0, src->colour);
    glBindSampler(0, a->sampler);
    glBindVertexArray(a->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glBindSampler(0, 0);
    glUseProgram((GLuint)old_prog);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)old_fbo);
    glViewport(old_view[0], old_view[1], old_view[2], old_view[3]);
    if (old_depth) glEnable(GL_DEPTH_TEST);
    if (old_blend) glEnable(GL_BLEND);
    return gl_check_error("anti-aliasing", err) < 0 ? -1 : 0;
}
