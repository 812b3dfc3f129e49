#include "renderer/deferred_target.h"

#include "renderer/shader.h"

#include <math.h>
#include <string.h>

int deferred_target_init(deferred_target *t, const char *shader_dir, og_error *err) {
    memset(t, 0, sizeof *t);
    t->prog_copy = shader_program_load(shader_dir, "fullscreen.vert", "deferred_copy.frag", err);
    return t->prog_copy ? 0 : -1;
}

static void free_storage(deferred_target *t) {
    if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
    GLuint tex[3] = {t->ground_depth, t->shaded, t->depth_stencil};
    glDeleteTextures(3, tex);
    t->fbo = t->ground_depth = t->shaded = t->depth_stencil = 0;
    t->width = t->height = 0;
}

void deferred_target_free(deferred_target *t) {
    free_storage(t);
    if (t->prog_copy) glDeleteProgram(t->prog_copy);
    t->prog_copy = 0;
}

static GLuint texture_2d(GLenum format, int width, int height) {
    GLuint tex;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, format, width, height);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return tex;
}

static int make_storage(deferred_target *t, int width, int height, og_error *err) {
    free_storage(t);
    // The depth is copied to a colour attachment: a texture attached to the framebuffer
    // as its depth-stencil may not be sampled while the stencil test runs.
    t->ground_depth = texture_2d(GL_R32F, width, height);
    t->shaded = texture_2d(GL_RGBA8, width, height);
    t->depth_stencil = texture_2d(GL_DEPTH32F_STENCIL8, width, height);
    glCreateFramebuffers(1, &t->fbo);
    glNamedFramebufferTexture(t->fbo, GL_COLOR_ATTACHMENT0, t->ground_depth, 0);
    glNamedFramebufferTexture(t->fbo, GL_COLOR_ATTACHMENT1, t->shaded, 0);
    glNamedFramebufferTexture(t->fbo, GL_DEPTH_STENCIL_ATTACHMENT, t->depth_stencil, 0);
    GLenum status = glCheckNamedFramebufferStatus(t->fbo, GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        free_storage(t);
        return og_error_set(err, "deferred terrain target %dx%d incomplete (0x%x)", width, height,
                            status);
    }
    t->width = width, t->height = height;
    return 0;
}

int deferred_target_begin(deferred_target *t, int width, int height, og_error *err) {
    if ((t->width != width || t->height != height) && make_storage(t, width, height, err) != 0)
        return -1;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &t->caller_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t->fbo);
    glNamedFramebufferDrawBuffer(t->fbo, GL_COLOR_ATTACHMENT0);
    const float none[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(t->fbo, GL_COLOR, 0, none);
    glClearNamedFramebufferfi(t->fbo, GL_DEPTH_STENCIL, 0, 0.0f, 0);
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    return 0;
}

int deferred_target_stencil(int level, int still) {
    return 2 + 2 * level + (still ? 1 : 0); // a level's two differ in the lowest bit only
}

void deferred_target_shade(deferred_target *t, int unit) {
    glNamedFramebufferDrawBuffer(t->fbo, GL_COLOR_ATTACHMENT1);
    glDisable(GL_DEPTH_TEST);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glBindTextureUnit((GLuint)unit, t->ground_depth);
}

void deferred_target_finish(deferred_target *t, GLuint empty_vao) {
    glDisable(GL_STENCIL_TEST);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)t->caller_fbo);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glProgramUniform1i(t->prog_copy, glGetUniformLocation(t->prog_copy, "u_shaded"), 0);
    glProgramUniform1i(t->prog_copy, glGetUniformLocation(t->prog_copy, "u_depth"), 1);
    glBindTextureUnit(0, t->shaded);
    glBindTextureUnit(1, t->ground_depth);
    glUseProgram(t->prog_copy);
    glBindVertexArray(empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthFunc(GL_GREATER);
}

int deferred_target_inverse(const float m[16], float out[16]) {
    double a[4][8]; // [m | I], row-major rows of the matrix (m is column-major)
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 8; c++)
            a[r][c] = c < 4 ? (double)m[c * 4 + r] : (double)(c - 4 == r);
    for (int c = 0; c < 4; c++) { // Gauss-Jordan with partial pivoting
        int pivot = c;
        for (int r = c + 1; r < 4; r++)
            if (fabs(a[r][c]) > fabs(a[pivot][c])) pivot = r;
        if (!(fabs(a[pivot][c]) > 0)) return -1;
        for (int k = 0; k < 8; k++) {
            double t = a[c][k];
            a[c][k] = a[pivot][k], a[pivot][k] = t;
        }
        const double inv = 1.0 / a[c][c];
        for (int k = 0; k < 8; k++)
            a[c][k] *= inv;
        for (int r = 0; r < 4; r++)
            if (r != c) {
                const double f = a[r][c];
                for (int k = 0; k < 8; k++)
                    a[r][k] -= f * a[c][k];
            }
    }
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            out[c * 4 + r] = (float)a[r][c + 4];
    return 0;
}
