#include "ui/ui_draw.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

ui_rect ui_rect_intersect(ui_rect a, ui_rect b) {
    float x0 = fmaxf(a.x, b.x), y0 = fmaxf(a.y, b.y);
    float x1 = fminf(a.x + a.w, b.x + b.w), y1 = fminf(a.y + a.h, b.y + b.h);
    return (ui_rect){x0, y0, fmaxf(0.0f, x1 - x0), fmaxf(0.0f, y1 - y0)};
}

int ui_rect_contains(ui_rect r, float x, float y) {
    return x >= r.x && y >= r.y && x < r.x + r.w && y < r.y + r.h;
}

void ui_draw_reset(ui_draw_list *dl, const ui_font *font, float width, float height) {
    dl->vtx_count = dl->idx_count = dl->cmd_count = 0;
    dl->clip_depth = 1;
    dl->clip[0] = (ui_rect){0, 0, width, height};
    dl->font = font;
    dl->out_of_memory = 0;
    if (font) ui_font_white_uv(font, &dl->white_u, &dl->white_v);
}

void ui_draw_free(ui_draw_list *dl) {
    free(dl->vtx);
    free(dl->idx);
    free(dl->cmds);
    memset(dl, 0, sizeof *dl);
}

ui_rect ui_draw_clip(const ui_draw_list *dl) {
    return dl->clip[dl->clip_depth - 1];
}

void ui_draw_push_clip(ui_draw_list *dl, ui_rect r) {
    if (dl->clip_depth == UI_CLIP_DEPTH) { // too deep: keep clipping to the innermost
        dl->out_of_memory = 1;
        return;
    }
    dl->clip[dl->clip_depth] = ui_rect_intersect(ui_draw_clip(dl), r);
    dl->clip_depth++;
}

void ui_draw_pop_clip(ui_draw_list *dl) {
    if (dl->clip_depth > 1) dl->clip_depth--;
}

static int grow(void **p, uint32_t *cap, uint32_t need, size_t size) {
    if (need <= *cap) return 0;
    uint32_t n = *cap ? *cap : 256;
    while (n < need)
        n *= 2;
    void *q = realloc(*p, (size_t)n * size);
    if (!q) return -1;
    *p = q;
    *cap = n;
    return 0;
}

// Room for nv vertices and ni indices in a command of this texture and the current clip.
static int reserve(ui_draw_list *dl, uint32_t texture, uint32_t nv, uint32_t ni) {
    if (grow((void **)&dl->vtx, &dl->vtx_cap, dl->vtx_count + nv, sizeof *dl->vtx) != 0 ||
        grow((void **)&dl->idx, &dl->idx_cap, dl->idx_count + ni, sizeof *dl->idx) != 0) {
        dl->out_of_memory = 1;
        return -1;
    }
    ui_rect clip = ui_draw_clip(dl);
    ui_draw_cmd *last = dl->cmd_count ? &dl->cmds[dl->cmd_count - 1] : NULL;
    if (!last || last->texture != texture || memcmp(&last->clip, &clip, sizeof clip) != 0) {
        if (grow((void **)&dl->cmds, &dl->cmd_cap, dl->cmd_count + 1, sizeof *dl->cmds) != 0) {
            dl->out_of_memory = 1;
            return -1;
        }
        dl->cmds[dl->cmd_count++] = (ui_draw_cmd){texture, clip, dl->idx_count, 0};
    }
    dl->cmds[dl->cmd_count - 1].index_count += ni;
    return 0;
}

static int visible(const ui_draw_list *dl, float x0, float y0, float x1, float y1) {
    ui_rect c = ui_draw_clip(dl);
    return c.w > 0 && c.h > 0 && x1 > c.x && y1 > c.y && x0 < c.x + c.w && y0 < c.y + c.h;
}

static void quad(ui_draw_list *dl, uint32_t texture, float x0, float y0, float x1, float y1,
                 float u0, float v0, float u1, float v1, ui_color c) {
    if (!visible(dl, x0, y0, x1, y1) || reserve(dl, texture, 4, 6) != 0) return;
    uint32_t b = dl->vtx_count;
    ui_vertex *v = dl->vtx + b;
    v[0] = (ui_vertex){x0, y0, u0, v0, c};
    v[1] = (ui_vertex){x1, y0, u1, v0, c};
    v[2] = (ui_vertex){x1, y1, u1, v1, c};
    v[3] = (ui_vertex){x0, y1, u0, v1, c};
    dl->vtx_count += 4;
    uint32_t *i = dl->idx + dl->idx_count;
    i[0] = b, i[1] = b + 1, i[2] = b + 2, i[3] = b, i[4] = b + 2, i[5] = b + 3;
    dl->idx_count += 6;
}

void ui_draw_rect(ui_draw_list *dl, ui_rect r, ui_color c) {
    if (r.w <= 0 || r.h <= 0) return;
    quad(dl, 0, r.x, r.y, r.x + r.w, r.y + r.h, dl->white_u, dl->white_v, dl->white_u, dl->white_v,
         c);
}

void ui_draw_rect_outline(ui_draw_list *dl, ui_rect r, ui_color c, float t) {
    ui_draw_rect(dl, (ui_rect){r.x, r.y, r.w, t}, c);
    ui_draw_rect(dl, (ui_rect){r.x, r.y + r.h - t, r.w, t}, c);
    ui_draw_rect(dl, (ui_rect){r.x, r.y + t, t, r.h - 2 * t}, c);
    ui_draw_rect(dl, (ui_rect){r.x + r.w - t, r.y + t, t, r.h - 2 * t}, c);
}

void ui_draw_triangle(ui_draw_list *dl, float x0, float y0, float x1, float y1, float x2, float y2,
                      ui_color c) {
    if (!visible(dl, fminf(x0, fminf(x1, x2)), fminf(y0, fminf(y1, y2)), fmaxf(x0, fmaxf(x1, x2)),
                 fmaxf(y0, fmaxf(y1, y2))) ||
        reserve(dl, 0, 3, 3) != 0)
        return;
    uint32_t b = dl->vtx_count;
    float u = dl->white_u, v = dl->white_v;
    dl->vtx[b] = (ui_vertex){x0, y0, u, v, c};
    dl->vtx[b + 1] = (ui_vertex){x1, y1, u, v, c};
    dl->vtx[b + 2] = (ui_vertex){x2, y2, u, v, c};
    dl->vtx_count += 3;
    uint32_t *i = dl->idx + dl->idx_count;
    i[0] = b, i[1] = b + 1, i[2] = b + 2;
    dl->idx_count += 3;
}

void ui_draw_line(ui_draw_list *dl, float x0, float y0, float x1, float y1, ui_color c, float t) {
    float dx = x1 - x0, dy = y1 - y0, len = sqrtf(dx * dx + dy * dy);
    if (len <= 0) return;
    float nx = -dy / len * t * 0.5f, ny = dx / len * t * 0.5f;
    ui_draw_triangle(dl, x0 + nx, y0 + ny, x1 + nx, y1 + ny, x1 - nx, y1 - ny, c);
    ui_draw_triangle(dl, x0 + nx, y0 + ny, x1 - nx, y1 - ny, x0 - nx, y0 - ny, c);
}

float ui_draw_text(ui_draw_list *dl, ui_face face, float x, float y, const char *text, size_t n,
                   ui_color c) {
    if (!dl->font) return 0;
    float pen = roundf(x), base = roundf(y + ui_font_ascent(dl->font));
    size_t i = 0;
    uint32_t cp;
    int len;
    while (i < n && (len = ui_utf8_decode(text + i, n - i, &cp)) > 0) {
        const ui_glyph *g = ui_font_glyph(dl->font, face, cp);
        if (g->x1 > g->x0)
            quad(dl, 0, pen + g->x0, base + g->y0, pen + g->x1, base + g->y1, g->u0, g->v0, g->u1,
                 g->v1, c);
        pen += g->advance;
        i += (size_t)len;
    }
    return pen - roundf(x);
}

void ui_draw_image(ui_draw_list *dl, uint32_t texture, ui_rect r, float u0, float v0, float u1,
                   float v1, ui_color tint) {
    if (texture == 0 || r.w <= 0 || r.h <= 0) return;
    quad(dl, texture, r.x, r.y, r.x + r.w, r.y + r.h, u0, v0, u1, v1, tint);
}
