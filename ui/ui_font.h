// Fonts for the UI: TrueType files rasterised with stb_truetype into one alpha
// atlas at start-up (the renderer uploads it as one texture). Covers Basic Latin,
// Latin-1 and the symbols the editor draws (arrows, triangles, check mark, ellipsis);
// other code points show as '?'. Text is UTF-8.
#ifndef OROGEN_UI_FONT_H
#define OROGEN_UI_FONT_H

#include <stddef.h>
#include <stdint.h>

typedef enum ui_face { UI_FACE_SANS, UI_FACE_MONO, UI_FACE_COUNT } ui_face;

typedef struct ui_glyph {
    float x0, y0, x1, y1; // quad relative to the pen on the baseline, pixels
    float u0, v0, u1, v1; // atlas coordinates, 0-1
    float advance;        // pixels
} ui_glyph;

typedef struct ui_font ui_font;

// Loads the two faces (paths to .ttf files) at pixel_size (already multiplied by the
// UI scale). NULL with a message in why when a file cannot be read or is not a font.
ui_font *ui_font_create(const char *sans_path, const char *mono_path, float pixel_size, char *why,
                        size_t why_size);
void ui_font_destroy(ui_font *f);

// The atlas: width x height bytes of coverage (0-255), row-major. The texel at
// ui_font_white_uv is fully covered, for solid fills from the same texture.
const uint8_t *ui_font_atlas(const ui_font *f, int *width, int *height);
void ui_font_white_uv(const ui_font *f, float *u, float *v);
// Bumped whenever the atlas bytes change (the renderer re-uploads then).
uint32_t ui_font_atlas_version(const ui_font *f);

float ui_font_size(const ui_font *f);        // pixel size
float ui_font_line_height(const ui_font *f); // ascent - descent + line gap, pixels
float ui_font_ascent(const ui_font *f);      // baseline below the line's top, pixels

// The glyph of a code point ('?' when the atlas lacks it).
const ui_glyph *ui_font_glyph(const ui_font *f, ui_face face, uint32_t codepoint);

// Decodes one UTF-8 code point at s (at most n bytes); returns the bytes used (1 for
// a malformed sequence, which decodes as U+FFFD) and 0 at the end (n == 0 or NUL).
int ui_utf8_decode(const char *s, size_t n, uint32_t *codepoint);
// Width in pixels of the first n bytes of text.
float ui_font_text_width(const ui_font *f, ui_face face, const char *text, size_t n);
// The byte offset in text (of n bytes) whose glyph boundary is nearest to x pixels.
size_t ui_font_offset_at(const ui_font *f, ui_face face, const char *text, size_t n, float x);

#endif
