// Draws the UI's draw lists (ui/ui_draw.h) with OpenGL: one font atlas texture, one
// streaming vertex and index buffer, one draw call per command (texture and clip).
#ifndef OROGEN_RENDERER_UI_RENDERER_H
#define OROGEN_RENDERER_UI_RENDERER_H

#include "io/err.h"
#include "ui/ui_draw.h"
#include "ui/ui_font.h"

typedef struct ui_renderer ui_renderer;

// Needs a current GL 4.5 context; shaders come from resource_dir/shaders.
ui_renderer *ui_renderer_create(const char *resource_dir, og_error *err);
void ui_renderer_destroy(ui_renderer *r);

// Draws dl over whatever the current framebuffer holds (width x height pixels, the
// draw list's coordinates), uploading font's atlas when it changed. Commands with a
// texture other than 0 use that GL texture name. Leaves blending and scissor off.
int ui_renderer_draw(ui_renderer *r, const ui_draw_list *dl, const ui_font *font, int width,
                     int height, og_error *err);

// An RGBA8 texture for the UI's images (thumbnails); 0 on failure. Deleted with
// ui_renderer_delete_texture.
uint32_t ui_renderer_create_texture(int width, int height, const uint8_t *rgba);
void ui_renderer_delete_texture(uint32_t texture);

#endif
