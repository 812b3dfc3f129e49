// The UI's draw list: indexed triangles (rectangles, text, lines, triangles, images)
// in commands that share a texture and a clip rectangle. The renderer draws each
// command with one call; texture 0 is the font atlas (which also holds a solid
// texel for fills), other values are the renderer's own texture handles.
// Coordinates are pixels, origin at the top left, y down.
#ifndef OROGEN_UI_DRAW_H
#define OROGEN_UI_DRAW_H

#include "ui/ui_font.h"

#include <stddef.h>
#include <stdint.h>

typedef struct ui_rect {
    float x, y, w, h;
} ui_rect;

// RGBA bytes in memory order (little-endian 0xAABBGGRR).
typedef uint32_t ui_color;
#define UI_RGBA(r, g, b, a)                                                                        \
    ((ui_color)(r) | ((ui_color)(g) << 8) | ((ui_color)(b) << 16) | ((ui_color)(a) << 24))

typedef struct ui_vertex {
    float x, y, u, v;
    ui_color color;
} ui_vertex;

typedef struct ui_draw_cmd {
    uint32_t texture; // 0: the font atlas
    ui_rect clip;
    uint32_t first_index, index_count;
} ui_draw_cmd;

#define UI_CLIP_DEPTH 32

typedef struct ui_draw_list {
    ui_vertex *vtx;
    uint32_t vtx_count, vtx_cap;
    uint32_t *idx;
    uint32_t idx_count, idx_cap;
    ui_draw_cmd *cmds;
    uint32_t cmd_count, cmd_cap;
    ui_rect clip[UI_CLIP_DEPTH];
    int clip_depth;
    const ui_font *font;
    float white_u, white_v;
    int out_of_memory; // something could not be added (the frame draws what fitted)
} ui_draw_list;

// Empties the list for a new frame of width x height pixels (the first clip).
void ui_draw_reset(ui_draw_list *dl, const ui_font *font, float width, float height);
void ui_draw_free(ui_draw_list *dl);

// Clipping: r intersected with the current clip; pops restore the previous one.
void ui_draw_push_clip(ui_draw_list *dl, ui_rect r);
void ui_draw_pop_clip(ui_draw_list *dl);
ui_rect ui_draw_clip(const ui_draw_list *dl);

void ui_draw_rect(ui_draw_list *dl, ui_rect r, ui_color c);
void ui_draw_rect_outline(ui_draw_list *dl, ui_rect r, ui_color c, float thickness);
void ui_draw_line(ui_draw_list *dl, float x0, float y0, float x1, float y1, ui_color c,
                  float thickness);
void ui_draw_triangle(ui_draw_list *dl, float x0, float y0, float x1, float y1, float x2, float y2,
                      ui_color c);
// Text of n bytes (UTF-8) with its line's top at y; returns the width drawn.
float ui_draw_text(ui_draw_list *dl, ui_face face, float x, float y, const char *text, size_t n,
                   ui_color c);
// A texture of the renderer's (texture != 0) over r, uv from (u0, v0) to (u1, v1).
void ui_draw_image(ui_draw_list *dl, uint32_t texture, ui_rect r, float u0, float v0, float u1,
                   float v1, ui_color tint);

// Rectangle helpers shared by the library and its users.
ui_rect ui_rect_intersect(ui_rect a, ui_rect b);
int ui_rect_contains(ui_rect r, float x, float y);

#endif
