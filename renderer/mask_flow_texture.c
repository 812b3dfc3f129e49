#include "renderer/mask_flow_texture.h"

void mask_flow_texture_destroy(mask_flow_texture *t) {
    if (t->tex) glDeleteTextures(1, &t->tex);
    *t = (mask_flow_texture){0};
}

void mask_flow_texture_bind(mask_flow_texture *t, GLuint prog, const render_settings *s,
                            const camera *cam, int unit) {
    const int have = (s->mask_terms & 8) && s->mask_flow_area && s->mask_flow_w > 0 &&
                     s->mask_flow_h > 0 && s->mask_flow_spacing > 0;
    if (have && (!t->tex || t->serial != s->mask_flow_serial)) {
        if (t->tex && (t->w != s->mask_flow_w || t->h != s->mask_flow_h)) {
            glDeleteTextures(1, &t->tex);
            t->tex = 0;
        }
        if (!t->tex) {
            glCreateTextures(GL_TEXTURE_2D, 1, &t->tex);
            glTextureStorage2D(t->tex, 1, GL_R32F, s->mask_flow_w, s->mask_flow_h);
            glTextureParameteri(t->tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTextureParameteri(t->tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glTextureParameteri(t->tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTextureParameteri(t->tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            t->w = s->mask_flow_w, t->h = s->mask_flow_h;
        }
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTextureSubImage2D(t->tex, 0, 0, 0, t->w, t->h, GL_RED, GL_FLOAT, s->mask_flow_area);
        t->serial = s->mask_flow_serial;
    }
    // x, z of the first sample relative to the camera, samples a metre, 1: a field.
    float area[4] = {0, 0, 0, 0};
    if (have) {
        area[0] = (float)(s->mask_flow_x0 - cam->pos[0]);
        area[1] = (float)(s->mask_flow_z0 - cam->pos[2]);
        area[2] = (float)(1.0 / s->mask_flow_spacing), area[3] = 1;
    }
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_mask_flow_area"), 1, area);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_mask_flow"), 1, s->mask_flow);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_mask_flow_field"), unit);
    if (t->tex) glBindTextureUnit((GLuint)unit, t->tex);
}
