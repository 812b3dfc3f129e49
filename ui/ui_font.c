#include "ui/ui_font.h"

#include <stb_rect_pack.h>
#include <stb_truetype.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// The code point ranges in the atlas: Basic Latin + Latin-1, then symbols.
static const struct {
    uint32_t first, count;
} ranges[] = {
    {0x20, 0x60}, // space .. '~'
    {0xA0, 0x60}, // Latin-1
    {0x2026, 1},  // ellipsis
    {0x2190, 4},  // arrows left, up, right, down
    {0x25B2, 1},  // up triangle
    {0x25B6, 1},  // right triangle
    {0x25B8, 1},  // small right triangle (a closed tree node)
    {0x25BC, 1},  // down triangle
    {0x25BE, 1},  // small down triangle (an open tree node)
    {0x25C0, 1},  // left triangle
    {0x2713, 1},  // check mark
};
#define RANGE_COUNT (sizeof ranges / sizeof ranges[0])
#define MAX_GLYPHS 256

typedef struct face_data {
    uint32_t codepoints[MAX_GLYPHS];
    ui_glyph glyphs[MAX_GLYPHS];
    int count;
    int question; // index of '?'
} face_data;

struct ui_font {
    float size, ascent, line_height;
    int width, height;
    uint8_t *atlas;
    float white_u, white_v;
    uint32_t version;
    face_data faces[UI_FACE_COUNT];
};

static unsigned char *read_all(const char *path, char *why, size_t why_size) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(why, why_size, "%s: %s", path, strerror(errno));
        return NULL;
    }
    unsigned char *data = NULL;
    long n = -1;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) > 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (data = malloc((size_t)n)) && fread(data, 1, (size_t)n, f) != (size_t)n) {
        free(data);
        data = NULL;
    }
    fclose(f);
    if (!data) snprintf(why, why_size, "%s: cannot read the font file", path);
    return data;
}

static int pack_face(stbtt_pack_context *pc, const unsigned char *ttf, float size, face_data *fd,
                     const char *path, char *why, size_t why_size) {
    stbtt_fontinfo info;
    int offset = stbtt_GetFontOffsetForIndex(ttf, 0); // -1: no font header (stb reads at it)
    if (offset < 0 || !stbtt_InitFont(&info, ttf, offset)) {
        snprintf(why, why_size, "%s: not a TrueType font", path);
        return -1;
    }
    stbtt_packedchar packed[MAX_GLYPHS];
    stbtt_pack_range pr[RANGE_COUNT];
    int n = 0, used = 0;
    for (size_t r = 0; r < RANGE_COUNT; r++) {
        if (!ranges[r].count) continue;
        memset(&pr[used], 0, sizeof pr[used]);
        pr[used].font_size = size;
        pr[used].first_unicode_codepoint_in_range = (int)ranges[r].first;
        pr[used].num_chars = (int)ranges[r].count;
        pr[used].chardata_for_range = packed + n;
        for (uint32_t k = 0; k < ranges[r].count; k++)
            fd->codepoints[n + (int)k] = ranges[r].first + k;
        n += (int)ranges[r].count;
        used++;
    }
    if (!stbtt_PackFontRanges(pc, ttf, 0, pr, used)) {
        snprintf(why, why_size, "%s: the glyphs do not fit the atlas", path);
        return -1;
    }
    fd->count = n;
    fd->question = 0;
    for (int i = 0; i < n; i++) {
        stbtt_aligned_quad q;
        float x = 0, y = 0;
        stbtt_GetPackedQuad(packed, pc->width, pc->height, i, &x, &y, &q, 0);
        fd->glyphs[i] = (ui_glyph){q.x0, q.y0, q.x1, q.y1, q.s0, q.t0, q.s1, q.t1, x};
        if (fd->codepoints[i] == '?') fd->question = i;
    }
    return 0;
}

ui_font *ui_font_create(const char *sans_path, const char *mono_path, float pixel_size, char *why,
                        size_t why_size) {
    if (!(pixel_size >= 4 && pixel_size <= 256)) {
        snprintf(why, why_size, "font size %g px is outside 4-256", pixel_size);
        return NULL;
    }
    ui_font *f = calloc(1, sizeof *f);
    if (!f) {
        snprintf(why, why_size, "out of memory");
        return NULL;
    }
    const char *paths[UI_FACE_COUNT] = {sans_path, mono_path};
    unsigned char *ttf[UI_FACE_COUNT] = {0};
    for (int i = 0; i < UI_FACE_COUNT; i++)
        if (!(ttf[i] = read_all(paths[i], why, why_size))) goto fail;
    // Square atlas, doubled until both faces fit.
    for (int side = 256; side <= 4096; side *= 2) {
        free(f->atlas);
        f->atlas = calloc((size_t)side * side, 1);
        if (!f->atlas) {
            snprintf(why, why_size, "out of memory");
            goto fail;
        }
        stbtt_pack_context pc;
        // Glyphs go in the top side - 4 rows; the bottom rows hold a solid block for
        // fills, so rectangles and text share one texture.
        if (!stbtt_PackBegin(&pc, f->atlas, side, side - 4, side, 1, NULL)) continue;
        stbtt_PackSetOversampling(&pc, 1, 1);
        int ok = 1;
        char inner[256];
        for (int i = 0; i < UI_FACE_COUNT && ok; i++)
            ok = pack_face(&pc, ttf[i], pixel_size, &f->faces[i], paths[i], inner, sizeof inner) ==
                 0;
        stbtt_PackEnd(&pc);
        if (!ok) {
            if (strstr(inner, "not a TrueType")) {
                snprintf(why, why_size, "%s", inner);
                goto fail;
            }
            continue;
        }
        f->width = f->height = side;
        // The solid texels: a 2x2 block in the reserved bottom rows.
        for (int y = side - 3; y < side - 1; y++)
            for (int x = 1; x < 3; x++)
                f->atlas[(size_t)y * side + x] = 255;
        f->white_u = 2.0f / side;
        f->white_v = (side - 2.0f) / side;
        // Glyph quads were computed for the packed height; rescale their v to the atlas.
        float vs = (float)(side - 4) / side;
        for (int i = 0; i < UI_FACE_COUNT; i++)
            for (int g = 0; g < f->faces[i].count; g++) {
                f->faces[i].glyphs[g].v0 *= vs;
                f->faces[i].glyphs[g].v1 *= vs;
            }
        break;
    }
    if (!f->width) {
        snprintf(why, why_size, "the glyphs at %g px do not fit a 4096 x 4096 atlas", pixel_size);
        goto fail;
    }
    stbtt_fontinfo info;
    stbtt_InitFont(&info, ttf[UI_FACE_SANS], stbtt_GetFontOffsetForIndex(ttf[UI_FACE_SANS], 0));
    int ascent, descent, gap;
    stbtt_GetFontVMetrics(&info, &ascent, &descent, &gap);
    float scale = stbtt_ScaleForPixelHeight(&info, pixel_size);
    f->size = pixel_size;
    f->ascent = roundf(ascent * scale);
    f->line_height = roundf((ascent - descent + gap) * scale);
    f->version = 1;
    for (int i = 0; i < UI_FACE_COUNT; i++)
        free(ttf[i]);
    return f;
fail:
    for (int i = 0; i < UI_FACE_COUNT; i++)
        free(ttf[i]);
    ui_font_destroy(f);
    return NULL;
}

void ui_font_destroy(ui_font *f) {
    if (!f) return;
    free(f->atlas);
    free(f);
}

const uint8_t *ui_font_atlas(const ui_font *f, int *width, int *height) {
    *width = f->width;
    *height = f->height;
    return f->atlas;
}

void ui_font_white_uv(const ui_font *f, float *u, float *v) {
    *u = f->white_u;
    *v = f->white_v;
}

uint32_t ui_font_atlas_version(const ui_font *f) {
    return f->version;
}
float ui_font_size(const ui_font *f) {
    return f->size;
}
float ui_font_line_height(const ui_font *f) {
    return f->line_height;
}
float ui_font_ascent(const ui_font *f) {
    return f->ascent;
}

const ui_glyph *ui_font_glyph(const ui_font *f, ui_face face, uint32_t cp) {
    const face_data *fd = &f->faces[face];
    // Ranges are sorted: a binary search over the code point table.
    int lo = 0, hi = fd->count - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (fd->codepoints[mid] == cp) return &fd->glyphs[mid];
        if (fd->codepoints[mid] < cp)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return &fd->glyphs[fd->question];
}

int ui_utf8_decode(const char *s, size_t n, uint32_t *cp) {
    if (n == 0 || !*s) return 0;
    const unsigned char *u = (const unsigned char *)s;
    int len = u[0] < 0x80         ? 1
              : (u[0] >> 5) == 6  ? 2
              : (u[0] >> 4) == 14 ? 3
              : (u[0] >> 3) == 30 ? 4
                                  : 0;
    if (len == 1) {
        *cp = u[0];
        return 1;
    }
    if (len == 0 || (size_t)len > n) {
        *cp = 0xFFFD;
        return 1;
    }
    uint32_t c = u[0] & (0x7F >> len);
    for (int i = 1; i < len; i++) {
        if ((u[i] & 0xC0) != 0x80) {
            *cp = 0xFFFD;
            return 1;
        }
        c = (c << 6) | (u[i] & 0x3F);
    }
    static const uint32_t min[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (c < min[len] || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) c = 0xFFFD, len = 1;
    *cp = c;
    return len;
}

float ui_font_text_width(const ui_font *f, ui_face face, const char *text, size_t n) {
    float w = 0;
    size_t i = 0;
    uint32_t cp;
    int len;
    while (i < n && (len = ui_utf8_decode(text + i, n - i, &cp)) > 0) {
        w += ui_font_glyph(f, face, cp)->advance;
        i += (size_t)len;
    }
    return w;
}

size_t ui_font_offset_at(const ui_font *f, ui_face face, const char *text, size_t n, float x) {
    float pen = 0;
    size_t i = 0;
    uint32_t cp;
    int len;
    while (i < n && (len = ui_utf8_decode(text + i, n - i, &cp)) > 0) {
        float adv = ui_font_glyph(f, face, cp)->advance;
        if (x < pen + adv * 0.5f) return i;
        pen += adv;
        i += (size_t)len;
    }
    return i;
}
