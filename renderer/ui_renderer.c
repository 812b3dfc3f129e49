#include "renderer/ui_renderer.h"

#include "renderer/shader.h"

#include <epoxy/gl.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

struct ui_renderer {
    GLuint prog, vao, vbo, ebo, atlas;
    GLint u_screen, u_texture, u_coverage;
    const ui_font *atlas_font;
    uint32_t atlas_version;
    size_t vbo_bytes, ebo_bytes;
};

ui_renderer *ui_renderer_create(const char *resource_dir, og_error *err) {
    ui_renderer *r = calloc(1, sizeof *r);
    if (!r) return og_error_set(err, "out of memory"), NULL;
    char dir[4200];
    snprintf(dir, sizeof dir, "%s/shaders", resource_dir);
    if (!(r->prog = shader_program_load(dir, "ui.vert", "ui.frag", err))) {
        free(r);
        return NULL;
    }
    r->u_screen = glGetUniformLocation(r->prog, "u_screen");
    r->u_texture = glGetUniformLocation(r->prog, "u_texture");
    r->u_coverage = glGetUniformLocation(r->prog, "u_coverage");
    glCreateVertexArrays(1, &r->vao);
    glCreateBuffers(1, &r->vbo);
    glCreateBuffers(1, &r->ebo);
    glVertexArrayVertexBuffer(r->vao, 0, r->vbo, 0, sizeof(ui_vertex));
    glVertexArrayElementBuffer(r->vao, r->ebo);
    glEnableVertexArrayAttrib(r->vao, 0);
    glEnableVertexArrayAttrib(r->vao, 1);
    glEnableVertexArrayAttrib(r->vao, 2);
    glVertexArrayAttribFormat(r->vao, 0, 2, GL_FLOAT, GL_FALSE, offsetof(ui_vertex, x));
    glVertexArrayAttribFormat(r->vao, 1, 2, GL_FLOAT, GL_FALSE, offsetof(ui_vertex, u));
    glVertexArrayAttribFormat(r->vao, 2, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(ui_vertex, color));
    for (int a = 0; a < 3; a++)
        glVertexArrayAttribBinding(r->vao, a, 0);
    return r;
}

void ui_renderer_destroy(ui_renderer *r) {
    if (!r) return;
    glDeleteProgram(r->prog);
    glDeleteVertexArrays(1, &r->vao);
    glDeleteBuffers(1, &r->vbo);
    glDeleteBuffers(1, &r->ebo);
    glDeleteTextures(1, &r->atlas);
    free(r);
}

static void upload_atlas(ui_renderer *r, const ui_font *font) {
    if (r->atlas && r->atlas_font == font && r->atlas_version == ui_font_atlas_version(font))
        return;
    int w, h;
    const uint8_t *pixels = ui_font_atlas(font, &w, &h);
    glDeleteTextures(1, &r->atlas);
    glCreateTextures(GL_TEXTURE_2D, 1, &r->atlas);
    glTextureStorage2D(r->atlas, 1, GL_R8, w, h);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(r->atlas, 0, 0, 0, w, h, GL_RED, GL_UNSIGNED_BYTE, pixels);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    // Glyphs are rasterised at the pixel size they are drawn at: nearest is exact.
    glTextureParameteri(r->atlas, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(r->atlas, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(r->atlas, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(r->atlas, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    r->atlas_font = font;
    r->atlas_version = ui_font_atlas_version(font);
}

// Streams data into a buffer, growing it (orphaning the old storage) when needed.
static void stream(GLuint buffer, size_t *capacity, const void *data, size_t bytes) {
    if (bytes > *capacity) {
        size_t cap = *capacity ? *capacity : 65536;
        while (cap < bytes)
            cap *= 2;
        glNamedBufferData(buffer, (GLsizeiptr)cap, NULL, GL_STREAM_DRAW);
        *capacity = cap;
    } else {
        glInvalidateBufferData(buffer);
    }
    glNamedBufferSubData(buffer, 0, (GLsizeiptr)bytes, data);
}

int ui_renderer_draw(ui_renderer *r, const ui_draw_list *dl, const ui_font *font, int width,
                     int height, og_error *err) {
    if (!dl->cmd_count) return 0;
    upload_atlas(r, font);
    stream(r->vbo, &r->vbo_bytes, dl->vtx, dl->vtx_count * sizeof(ui_vertex));
    stream(r->ebo, &r->ebo_bytes, dl->idx, dl->idx_count * sizeof(uint32_t));
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glEnable(GL_SCISSOR_TEST);
    glUseProgram(r->prog);
    glUniform2f(r->u_screen, (float)width, (float)height);
    glUniform1i(r->u_texture, 0);
    glBindVertexArray(r->vao);
    for (uint32_t i = 0; i < dl->cmd_count; i++) {
        const ui_draw_cmd *c = &dl->cmds[i];
        if (!c->index_count || c->clip.w <= 0 || c->clip.h <= 0) continue;
        // GL's scissor origin is the bottom left.
        int x = (int)c->clip.x, y = (int)c->clip.y, w = (int)(c->clip.x + c->clip.w) - x,
            h = (int)(c->clip.y + c->clip.h) - y;
        glScissor(x, height - (y + h), w, h);
        glBindTextureUnit(0, c->texture ? c->texture : r->atlas);
        glUniform1i(r->u_coverage, c->texture ? 0 : 1);
        glDrawElements(GL_TRIANGLES, (GLsizei)c->index_count, GL_UNSIGNED_INT,
                       (const void *)(uintptr_t)(c->first_index * sizeof(uint32_t)));
    }
    glBindVertexArray(0);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return og_error_set(err, "OpenGL error 0x%x drawing the UI", e);
    return 0;
}

uint32_t ui_renderer_create_texture(int width, int height, const uint8_t *rgba) {
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    if (!t) return 0;
    glTextureStorage2D(t, 1, GL_RGBA8, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(t, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

void ui_renderer_delete_texture(uint32_t texture) {
    GLuint t = texture;
    if (t) glDeleteTextures(1, &t);
}
