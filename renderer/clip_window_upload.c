#include "renderer/clip_window_upload.h"

uint64_t clip_window_upload(clip_window *w, GLuint tex, int layer, GLenum format, GLenum type) {
    if (!w->upload_all && w->upload_count == 0) return 0;
    texel_rect whole = {0, 0, w->size, w->size};
    const texel_rect *rects = w->upload_all ? &whole : w->uploads;
    int count = w->upload_all ? 1 : w->upload_count;
    uint64_t texels = 0;
    glPixelStorei(GL_UNPACK_ROW_LENGTH, w->size);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int k = 0; k < count; k++) {
        const texel_rect *t = &rects[k];
        const unsigned char *src = w->mirror + ((size_t)t->z * w->size + t->x) * w->texel_bytes;
        if (layer >= 0)
            glTextureSubImage3D(tex, 0, t->x, t->z, layer, t->w, t->h, 1, format, type, src);
        else
            glTextureSubImage2D(tex, 0, t->x, t->z, t->w, t->h, format, type, src);
        texels += (uint64_t)t->w * t->h;
    }
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    w->upload_all = 0;
    w->upload_count = 0;
    return texels;
}
