// The immediate-mode UI library (ui/) without GL: the font atlas and UTF-8, ids and
// scopes, layout, every widget driven by synthetic input one frame at a time (a press
// and its release on separate frames, the button held in between), the draw list's
// clipping, scrolling, menus, combos and tooltips. Every check reads something the
// library exposes: return values, the caller's variables, named widget rectangles,
// ui_wants_mouse/keyboard and the draw list.
#include "ui/ui.h"
#include "support/test_support.h"

#include <math.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#define SANS_TTF "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#define MONO_TTF "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf"
#define WIN_W 800.0f
#define WIN_H 600.0f

static ui_font *font;

static int load_font(void **state) {
    (void)state;
    char why[512] = "";
    font = ui_font_create(SANS_TTF, MONO_TTF, 16, why, sizeof why);
    if (!font) fprintf(stderr, "cannot load the test font: %s\n", why);
    return font ? 0 : -1;
}

static int free_font(void **state) {
    (void)state;
    ui_font_destroy(font);
    font = NULL;
    return 0;
}

// ---- a driver: one context, its input and the widgets it builds each frame ------------

typedef struct drv drv;
typedef void (*build_fn)(drv *d);
struct drv {
    ui_context *ui;
    ui_input in;
    build_fn build;
    void *user;
    const ui_draw_list *dl; // the last frame's
};

// The draw list is well formed: commands cover the indices in order, every index
// names a vertex, and nothing was dropped.
static void check_draw_list(const ui_draw_list *dl) {
    uint32_t at = 0;
    for (uint32_t c = 0; c < dl->cmd_count; c++) {
        assert_int_equal(dl->cmds[c].first_index, at);
        at += dl->cmds[c].index_count;
    }
    assert_int_equal(at, dl->idx_count);
    for (uint32_t i = 0; i < dl->idx_count; i++)
        if (dl->idx[i] >= dl->vtx_count)
            fail_msg("index %u names vertex %u of %u", i, dl->idx[i], dl->vtx_count);
    assert_int_equal(dl->out_of_memory, 0);
}

// One frame: begin, the widgets, end. Then this frame's events are spent; the pointer,
// held buttons, modifiers and the time stay.
static const ui_draw_list *frame(drv *d) {
    ui_begin(d->ui, &d->in, WIN_W, WIN_H);
    if (d->build) d->build(d);
    d->dl = ui_end(d->ui);
    check_draw_list(d->dl);
    memset(d->in.mouse_pressed, 0, sizeof d->in.mouse_pressed);
    memset(d->in.mouse_released, 0, sizeof d->in.mouse_released);
    memset(d->in.key_pressed, 0, sizeof d->in.key_pressed);
    d->in.double_click = 0;
    d->in.wheel = 0;
    d->in.text[0] = 0;
    return d->dl;
}

// Contexts still alive when a test fails (cmocka jumps out of it) are freed after it.
static ui_context *live[8];

static ui_context *context_new(void) {
    ui_context *ui = ui_create(font);
    assert_non_null(ui);
    for (int i = 0; i < 8; i++)
        if (!live[i]) return live[i] = ui;
    fail_msg("more than 8 contexts alive");
    return NULL;
}

static void context_free(ui_context *ui) {
    for (int i = 0; i < 8; i++)
        if (live[i] == ui) live[i] = NULL;
    ui_destroy(ui);
}

static ui_draw_list scratch_list; // a draw list used on its own

static int free_contexts(void **state) {
    (void)state;
    ui_draw_free(&scratch_list);
    for (int i = 0; i < 8; i++) {
        ui_destroy(live[i]);
        live[i] = NULL;
    }
    return 0;
}

static void drv_init(drv *d, build_fn build, void *user) {
    memset(d, 0, sizeof *d);
    d->ui = context_new();
    d->build = build;
    d->user = user;
    d->in.mouse_x = d->in.mouse_y = -100; // off the window
    frame(d);                             // the first frame records the widgets
}

static void drv_free(drv *d) {
    context_free(d->ui);
}

static void move_to(drv *d, float x, float y) {
    d->in.mouse_x = x;
    d->in.mouse_y = y;
    frame(d);
}

static void press(drv *d, float x, float y) {
    d->in.mouse_x = x;
    d->in.mouse_y = y;
    d->in.mouse_pressed[0] = 1;
    d->in.mouse_down[0] = 1;
    frame(d);
}

static void drag_to(drv *d, float x, float y) {
    d->in.mouse_x = x;
    d->in.mouse_y = y;
    frame(d); // mouse_down[0] still held
}

static void release(drv *d, float x, float y) {
    d->in.mouse_x = x;
    d->in.mouse_y = y;
    d->in.mouse_down[0] = 0;
    d->in.mouse_released[0] = 1;
    frame(d);
}

static void click(drv *d, float x, float y) {
    press(d, x, y);
    release(d, x, y);
}

static void key(drv *d, ui_key k, int mods) {
    d->in.key_pressed[k] = 1;
    d->in.mods = mods;
    frame(d);
    d->in.mods = 0;
}

static void type(drv *d, const char *text) {
    snprintf(d->in.text, sizeof d->in.text, "%s", text);
    frame(d);
}

// A widget's rectangle in the last frame, by its scope path.
static ui_rect rect_of(drv *d, const char *name) {
    const ui_widget_info *w = ui_widget_find(d->ui, name);
    if (!w) fail_msg("no widget '%s' in the last frame", name);
    return w->rect;
}

static void click_widget(drv *d, const char *name) {
    ui_rect r = rect_of(d, name);
    click(d, r.x + r.w * 0.5f, r.y + r.h * 0.5f);
}

static int rect_within(ui_rect in, ui_rect out) {
    const float e = 1e-3f;
    return in.x >= out.x - e && in.y >= out.y - e && in.x + in.w <= out.x + out.w + e &&
           in.y + in.h <= out.y + out.h + e;
}

static void assert_rect(ui_rect r, float x, float y, float w, float h) {
    if (fabsf(r.x - x) > 1e-3f || fabsf(r.y - y) > 1e-3f || fabsf(r.w - w) > 1e-3f ||
        fabsf(r.h - h) > 1e-3f)
        fail_msg("rect {%g, %g, %g, %g}, wanted {%g, %g, %g, %g}", r.x, r.y, r.w, r.h, x, y, w, h);
}

// Valid UTF-8 with no replacement characters in it.
static int valid_utf8(const char *s) {
    size_t n = strlen(s), i = 0;
    while (i < n) {
        uint32_t cp;
        int k = ui_utf8_decode(s + i, n - i, &cp);
        if (k <= 0 || cp == 0xFFFD) return 0;
        i += (size_t)k;
    }
    return 1;
}

// ---- font ---------------------------------------------------------------------------

static void test_font_atlas(void **state) {
    (void)state;
    int w = 0, h = 0;
    const uint8_t *atlas = ui_font_atlas(font, &w, &h);
    assert_non_null(atlas);
    assert_true(w >= 256 && h >= 256);
    size_t covered = 0;
    for (size_t i = 0; i < (size_t)w * h; i++)
        covered += atlas[i] != 0;
    assert_true(covered > 2000); // two faces of ~200 glyphs each
    // The solid texel, and every texel a bilinear fetch at its coordinates reads.
    float u, v;
    ui_font_white_uv(font, &u, &v);
    assert_true(u > 0 && u < 1 && v > 0 && v < 1);
    int tx = (int)floorf(u * w - 0.5f), ty = (int)floorf(v * h - 0.5f);
    for (int y = ty; y <= ty + 1; y++)
        for (int x = tx; x <= tx + 1; x++)
            if (atlas[(size_t)y * w + x] != 255)
                fail_msg("texel (%d, %d) by the white uv is %d", x, y, atlas[(size_t)y * w + x]);
    assert_true(ui_font_atlas_version(font) > 0);
    assert_true(ui_font_size(font) == 16.0f);
    assert_true(ui_font_line_height(font) >= 16 && ui_font_line_height(font) <= 24);
    assert_true(ui_font_ascent(font) > 8 && ui_font_ascent(font) < ui_font_line_height(font));
    // 'A' has a quad whose atlas region holds coverage.
    const ui_glyph *a = ui_font_glyph(font, UI_FACE_SANS, 'A');
    assert_true(a->advance > 0);
    assert_true(a->x1 > a->x0 && a->y1 > a->y0);
    assert_true(a->u1 > a->u0 && a->v1 > a->v0);
    size_t inside = 0;
    for (int y = (int)(a->v0 * h); y < (int)(a->v1 * h); y++)
        for (int x = (int)(a->u0 * w); x < (int)(a->u1 * w); x++)
            inside += atlas[(size_t)y * w + x] > 128;
    assert_true(inside > 10);
    // A space advances and has no quad.
    const ui_glyph *sp = ui_font_glyph(font, UI_FACE_SANS, ' ');
    assert_true(sp->advance > 0);
}

static void test_font_widths_and_fallback(void **state) {
    (void)state;
    float a = ui_font_glyph(font, UI_FACE_SANS, 'A')->advance;
    float b = ui_font_glyph(font, UI_FACE_SANS, 'B')->advance;
    assert_true(a > 0 && b > 0);
    assert_true(ui_font_text_width(font, UI_FACE_SANS, "AB", 2) == a + b);
    assert_true(ui_font_text_width(font, UI_FACE_SANS, "AB", 1) == a); // n bytes only
    assert_true(ui_font_text_width(font, UI_FACE_SANS, "", 0) == 0);
    // A code point the atlas lacks shows as '?'.
    const ui_glyph *q = ui_font_glyph(font, UI_FACE_SANS, '?');
    assert_ptr_equal(ui_font_glyph(font, UI_FACE_SANS, 0x4E00), q);
    assert_ptr_equal(ui_font_glyph(font, UI_FACE_MONO, 0x4E00),
                     ui_font_glyph(font, UI_FACE_MONO, '?'));
    assert_true(ui_font_text_width(font, UI_FACE_SANS, "\xE4\xB8\x80", 3) == q->advance);
    // What the atlas has is not '?': Latin-1, the arrows, the check mark.
    assert_ptr_not_equal(ui_font_glyph(font, UI_FACE_SANS, 0xE9), q);
    assert_ptr_not_equal(ui_font_glyph(font, UI_FACE_SANS, 0x2192), q);
    assert_ptr_not_equal(ui_font_glyph(font, UI_FACE_SANS, 0x2713), q);
    // Every triangle the library draws (combo, section and tree arrows: a tree's showed
    // as '?' in the Layers panel).
    const uint32_t triangles[] = {0x25B2, 0x25B6, 0x25B8, 0x25BC, 0x25BE, 0x25C0};
    for (size_t i = 0; i < sizeof triangles / sizeof triangles[0]; i++)
        if (ui_font_glyph(font, UI_FACE_SANS, triangles[i]) == q)
            fail_msg("U+%04X is not in the atlas", (unsigned)triangles[i]);
    // "é" is one glyph of two bytes.
    assert_true(ui_font_text_width(font, UI_FACE_SANS, "\xC3\xA9", 2) ==
                ui_font_glyph(font, UI_FACE_SANS, 0xE9)->advance);
    // The mono face is monospaced; the sans face is not.
    assert_true(ui_font_glyph(font, UI_FACE_MONO, 'i')->advance ==
                ui_font_glyph(font, UI_FACE_MONO, 'W')->advance);
    assert_true(ui_font_glyph(font, UI_FACE_SANS, 'i')->advance <
                ui_font_glyph(font, UI_FACE_SANS, 'W')->advance);
}

static void expect_decode(const char *s, size_t n, uint32_t want_cp, int want_used) {
    uint32_t cp = 0x12345678;
    int used = ui_utf8_decode(s, n, &cp);
    if (used != want_used || (want_used > 0 && cp != want_cp)) {
        char hex[64] = "";
        for (size_t i = 0; i < n && i < 8; i++)
            snprintf(hex + strlen(hex), sizeof hex - strlen(hex), "%02X ",
                     (unsigned)(unsigned char)s[i]);
        fail_msg("decoding [%s] (n=%zu) gave U+%04X in %d bytes, wanted U+%04X in %d", hex, n,
                 (unsigned)cp, used, (unsigned)want_cp, want_used);
    }
}

static void test_utf8_decode(void **state) {
    (void)state;
    // Valid sequences of every length.
    expect_decode("A", 1, 'A', 1);
    expect_decode("\x7F", 1, 0x7F, 1);
    expect_decode("\xC2\x80", 2, 0x80, 2);
    expect_decode("\xC3\xA9", 2, 0xE9, 2);
    expect_decode("\xDF\xBF", 2, 0x7FF, 2);
    expect_decode("\xE0\xA0\x80", 3, 0x800, 3);
    expect_decode("\xE2\x82\xAC", 3, 0x20AC, 3);
    expect_decode("\xEF\xBF\xBD", 3, 0xFFFD, 3); // a real U+FFFD
    expect_decode("\xED\x9F\xBF", 3, 0xD7FF, 3); // just below the surrogates
    expect_decode("\xEE\x80\x80", 3, 0xE000, 3); // just above
    expect_decode("\xF0\x90\x80\x80", 4, 0x10000, 4);
    expect_decode("\xF0\x9F\x98\x80", 4, 0x1F600, 4);
    expect_decode("\xF4\x8F\xBF\xBF", 4, 0x10FFFF, 4);
    expect_decode("\xC3\xA9xyz", 5, 0xE9, 2); // stops after one code point
    // The end.
    expect_decode("", 1, 0, 0);
    expect_decode("A", 0, 0, 0);
    // Truncated: by n, or by the string's end.
    expect_decode("\xC3\xA9", 1, 0xFFFD, 1);
    expect_decode("\xE2\x82\xAC", 2, 0xFFFD, 1);
    expect_decode("\xE2\x82", 3, 0xFFFD, 1); // NUL where the third byte should be
    expect_decode("\xF0\x9F\x98", 3, 0xFFFD, 1);
    expect_decode("\xF0\x9F\x98\x80", 3, 0xFFFD, 1);
    // Not a lead byte, or a lead byte without its continuation.
    expect_decode("\x80", 1, 0xFFFD, 1);
    expect_decode("\xBF\xBF", 2, 0xFFFD, 1);
    expect_decode("\xFF", 1, 0xFFFD, 1);
    expect_decode("\xF8\x88\x80\x80\x80", 5, 0xFFFD, 1);
    expect_decode("\xC3(", 2, 0xFFFD, 1);
    expect_decode("\xE2\x82(", 3, 0xFFFD, 1);
    // Overlong encodings: U+FFFD and only the first byte used.
    expect_decode("\xC0\xAF", 2, 0xFFFD, 1);
    expect_decode("\xC1\xBF", 2, 0xFFFD, 1);
    expect_decode("\xE0\x80\xAF", 3, 0xFFFD, 1);
    expect_decode("\xE0\x9F\xBF", 3, 0xFFFD, 1);
    expect_decode("\xF0\x80\x80\xAF", 4, 0xFFFD, 1);
    expect_decode("\xF0\x8F\xBF\xBF", 4, 0xFFFD, 1);
    expect_decode("\xF0\x8F\xBF\xBD", 4, 0xFFFD, 1); // U+FFFD itself, overlong
    // UTF-16 surrogates and code points past U+10FFFF are malformed too.
    expect_decode("\xED\xA0\x80", 3, 0xFFFD, 1);
    expect_decode("\xED\xBF\xBF", 3, 0xFFFD, 1);
    expect_decode("\xF4\x90\x80\x80", 4, 0xFFFD, 1);
    // Walking a string with a malformed sequence in it: one U+FFFD per byte of it.
    const char *s = "a\xC0\xAF"
                    "b";
    uint32_t want[] = {'a', 0xFFFD, 0xFFFD, 'b'}, cp;
    size_t i = 0, k = 0, n = strlen(s);
    int used;
    while ((used = ui_utf8_decode(s + i, n - i, &cp)) > 0) {
        assert_true(k < 4);
        assert_int_equal(cp, want[k++]);
        i += (size_t)used;
    }
    assert_int_equal(k, 4);
}

static void test_font_offset_at(void **state) {
    (void)state;
    float a = ui_font_glyph(font, UI_FACE_SANS, 'A')->advance;
    float b = ui_font_glyph(font, UI_FACE_SANS, 'B')->advance;
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS, "AB", 2, 0), 0);
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS, "AB", 2, -50), 0);
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS, "AB", 2, a * 0.4f), 0);
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS, "AB", 2, a * 0.6f), 1);
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS, "AB", 2, a), 1); // the middle
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS, "AB", 2, a + b * 0.4f), 1);
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS, "AB", 2, a + b * 0.6f), 2);
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS, "AB", 2, 1000), 2); // past the end
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS, "", 0, 10), 0);
    // Offsets fall on code point boundaries: "aéb" has é at bytes 1-2.
    float wa = ui_font_glyph(font, UI_FACE_SANS, 'a')->advance;
    float we = ui_font_glyph(font, UI_FACE_SANS, 0xE9)->advance;
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS,
                                       "a\xC3\xA9"
                                       "b",
                                       4, wa + we * 0.4f),
                     1);
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS,
                                       "a\xC3\xA9"
                                       "b",
                                       4, wa + we * 0.6f),
                     3);
    assert_int_equal(ui_font_offset_at(font, UI_FACE_SANS,
                                       "a\xC3\xA9"
                                       "b",
                                       4, 1000),
                     4);
}

static void expect_font_error(const char *sans, const char *mono, float size, const char *want) {
    char why[512] = "";
    ui_font *f = ui_font_create(sans, mono, size, why, sizeof why);
    if (f) {
        ui_font_destroy(f);
        fail_msg("ui_font_create(%s, %s, %g) succeeded", sans, mono, size);
    }
    if (!strstr(why, want)) fail_msg("the message '%s' does not name '%s'", why, want);
}

static void test_font_errors(void **state) {
    (void)state;
    expect_font_error("/nonexistent/orogen/Sans.ttf", MONO_TTF, 16, "/nonexistent/orogen/Sans.ttf");
    expect_font_error(SANS_TTF, "/nonexistent/orogen/Mono.ttf", 16, "/nonexistent/orogen/Mono.ttf");
    const char *dir = test_tmpdir("ui-font");
    char text[512], empty[512];
    snprintf(text, sizeof text, "%s/not-a-font.ttf", dir);
    snprintf(empty, sizeof empty, "%s/empty.ttf", dir);
    const char *words = "This is a text file, not a TrueType font.\n";
    test_write_file(text, words, strlen(words));
    test_write_file(empty, "", 0);
    expect_font_error(text, MONO_TTF, 16, text);
    expect_font_error(SANS_TTF, text, 16, text);
    expect_font_error(empty, MONO_TTF, 16, empty);
    expect_font_error(SANS_TTF, MONO_TTF, 1, "font size");
    test_rmtree(dir);
}

// ---- ids and scopes -------------------------------------------------------------------

typedef struct id_run {
    ui_id top, tools, view, view_inner, a, b;
} id_run;

static void ids_frame(drv *d, id_run *r) {
    ui_begin(d->ui, &d->in, WIN_W, WIN_H);
    r->top = ui_get_id(d->ui, "Apply");
    ui_push_scope(d->ui, "Tools");
    r->tools = ui_get_id(d->ui, "Apply");
    ui_pop_scope(d->ui);
    ui_push_scope(d->ui, "View");
    r->view = ui_get_id(d->ui, "Apply");
    ui_push_scope(d->ui, "Inner");
    r->view_inner = ui_get_id(d->ui, "Apply");
    ui_pop_scope(d->ui);
    ui_pop_scope(d->ui);
    r->a = ui_get_id(d->ui, "Save##a");
    r->b = ui_get_id(d->ui, "Save##b");
    ui_end(d->ui);
}

static void test_ids(void **state) {
    (void)state;
    drv d;
    drv_init(&d, NULL, NULL);
    id_run one, two;
    ids_frame(&d, &one);
    ids_frame(&d, &two);
    assert_memory_equal(&one, &two, sizeof one); // the same across frames
    assert_int_not_equal(one.top, 0);
    assert_int_not_equal(one.top, one.tools);
    assert_int_not_equal(one.tools, one.view);
    assert_int_not_equal(one.top, one.view);
    assert_int_not_equal(one.view, one.view_inner);
    assert_int_not_equal(one.a, one.b);
    drv_free(&d);
}

// A scope and a label are not one string: "X" in scope "A" is not the top level's "AX".
static void test_ids_scope_is_not_a_label_prefix(void **state) {
    (void)state;
    drv d;
    drv_init(&d, NULL, NULL);
    ui_begin(d.ui, &d.in, WIN_W, WIN_H);
    ui_push_scope(d.ui, "Menu");
    ui_id scoped = ui_get_id(d.ui, "File");
    ui_pop_scope(d.ui);
    ui_id flat = ui_get_id(d.ui, "MenuFile");
    ui_end(d.ui);
    assert_int_not_equal(scoped, flat);
    drv_free(&d);
}

typedef struct two_saves {
    int a, b;
} two_saves;

static void build_two_saves(drv *d) {
    two_saves *s = d->user;
    ui_row(d->ui, 2, NULL, 0);
    s->a += ui_button(d->ui, "Save##a");
    s->b += ui_button(d->ui, "Save##b");
}

static void build_one_button(drv *d) {
    ui_button(d->ui, (const char *)d->user);
}

static void test_ids_hash_suffix(void **state) {
    (void)state;
    two_saves s = {0};
    drv d;
    drv_init(&d, build_two_saves, &s);
    // Both are shown and named "Save", side by side.
    assert_int_equal(ui_widget_count(d.ui), 2);
    assert_string_equal(ui_widget_at(d.ui, 0)->name, "Save");
    assert_string_equal(ui_widget_at(d.ui, 1)->name, "Save");
    assert_null(ui_widget_at(d.ui, 2));
    ui_rect ra = ui_widget_at(d.ui, 0)->rect, rb = ui_widget_at(d.ui, 1)->rect;
    assert_true(rb.x > ra.x + ra.w - 1);
    // Different ids: clicking the second triggers only it.
    click(&d, rb.x + rb.w / 2, rb.y + rb.h / 2);
    assert_int_equal(s.a, 0);
    assert_int_equal(s.b, 1);
    click(&d, ra.x + ra.w / 2, ra.y + ra.h / 2);
    assert_int_equal(s.a, 1);
    assert_int_equal(s.b, 1);
    drv_free(&d);
    // The suffix draws nothing: "Save##a" draws what "Save" does, "Saves" more.
    uint32_t counts[3];
    const char *labels[3] = {"Save##a", "Save", "Saves"};
    for (int i = 0; i < 3; i++) {
        drv_init(&d, build_one_button, (void *)labels[i]);
        counts[i] = frame(&d)->vtx_count;
        drv_free(&d);
    }
    assert_int_equal(counts[0], counts[1]);
    assert_true(counts[2] > counts[1]);
}

typedef struct panel_button {
    int clicks;
} panel_button;

static const ui_rect button_panel = {100, 100, 300, 200};

static void build_panel_button(drv *d) {
    panel_button *s = d->user;
    ui_panel_begin(d->ui, "Panel", button_panel);
    s->clicks += ui_button(d->ui, "Button");
    ui_push_scope(d->ui, "Group");
    ui_label(d->ui, "Label");
    ui_pop_scope(d->ui);
    ui_panel_end(d->ui);
    ui_label(d->ui, "Outside");
}

static void test_widget_find_by_path(void **state) {
    (void)state;
    panel_button s = {0};
    drv d;
    memset(&d, 0, sizeof d);
    d.ui = context_new();
    assert_null(ui_widget_find(d.ui, "Panel/Button")); // no frame yet
    assert_int_equal(ui_widget_count(d.ui), 0);
    d.build = build_panel_button;
    d.user = &s;
    frame(&d);
    const ui_widget_info *w = ui_widget_find(d.ui, "Panel/Button");
    assert_non_null(w);
    assert_true(rect_within(w->rect, button_panel));
    assert_true(w->rect.w > 0 && w->rect.h > 0);
    assert_non_null(ui_widget_find(d.ui, "Panel/Group/Label"));
    assert_non_null(ui_widget_find(d.ui, "Outside"));
    assert_null(ui_widget_find(d.ui, "Button")); // only by its full path
    assert_null(ui_widget_find(d.ui, "Panel/Label"));
    assert_null(ui_widget_find(d.ui, "Panel/Outside"));
    // While a frame is being built, the last finished one is what is found.
    ui_begin(d.ui, &d.in, WIN_W, WIN_H);
    assert_non_null(ui_widget_find(d.ui, "Panel/Button"));
    assert_int_equal(ui_widget_count(d.ui), 4); // the panel, Button, Label, Outside
    ui_label(d.ui, "Alone");
    assert_non_null(ui_widget_find(d.ui, "Panel/Button"));
    assert_null(ui_widget_find(d.ui, "Alone"));
    ui_end(d.ui);
    // After it, that frame's: only "Alone".
    assert_int_equal(ui_widget_count(d.ui), 1);
    assert_non_null(ui_widget_find(d.ui, "Alone"));
    assert_null(ui_widget_find(d.ui, "Panel/Button"));
    drv_free(&d);
}

// ---- layout -------------------------------------------------------------------------

static void test_split(void **state) {
    (void)state;
    drv d;
    drv_init(&d, NULL, NULL);
    ui_rect out[4];
    // Fixed 50, a quarter, two fills sharing the rest.
    ui_split(d.ui, (ui_rect){10, 20, 400, 30}, 1, 4, (const float[]){50, -0.25f, 0, 0}, out);
    assert_rect(out[0], 10, 20, 50, 30);
    assert_rect(out[1], 60, 20, 100, 30);
    assert_rect(out[2], 160, 20, 125, 30);
    assert_rect(out[3], 285, 20, 125, 30);
    assert_true(out[0].w + out[1].w + out[2].w + out[3].w == 400);
    // Vertically: half, a fill, fixed 60.
    ui_split(d.ui, (ui_rect){5, 0, 100, 300}, 0, 3, (const float[]){-0.5f, 0, 60}, out);
    assert_rect(out[0], 5, 0, 100, 150);
    assert_rect(out[1], 5, 150, 100, 90);
    assert_rect(out[2], 5, 240, 100, 60);
    // NULL sizes: all fill equally.
    ui_split(d.ui, (ui_rect){0, 0, 400, 10}, 1, 4, NULL, out);
    for (int i = 0; i < 4; i++)
        assert_rect(out[i], 100.0f * i, 0, 100, 10);
    // More fixed than there is: fills get nothing, not a negative size.
    ui_split(d.ui, (ui_rect){0, 0, 100, 10}, 1, 2, (const float[]){150, 0}, out);
    assert_true(out[1].w == 0);
    drv_free(&d);
}

// Cells tile the rectangle whatever its width: no gap, no overhang after rounding.
static void test_split_rounding_tiles_exactly(void **state) {
    (void)state;
    drv d;
    drv_init(&d, NULL, NULL);
    const float widths[] = {800, 100, 301};
    for (int k = 0; k < 3; k++) {
        ui_rect out[3];
        ui_split(d.ui, (ui_rect){0, 0, widths[k], 10}, 1, 3, NULL, out);
        for (int i = 1; i < 3; i++)
            assert_true(out[i].x == out[i - 1].x + out[i - 1].w);
        float end = out[2].x + out[2].w;
        if (end != widths[k])
            fail_msg("3 fills over %g px end at %g (%g + %g + %g)", widths[k], end, out[0].w,
                     out[1].w, out[2].w);
    }
    drv_free(&d);
}

typedef struct row_cells {
    ui_rect cells[5];
    ui_rect panel_cells[4];
} row_cells;

static const ui_rect row_panel = {50, 60, 400, 300};

static void build_rows(drv *d) {
    row_cells *s = d->user;
    ui_row(d->ui, 3, (const float[]){100, -0.25f, 0}, 30);
    for (int i = 0; i < 5; i++)
        s->cells[i] = ui_next_cell(d->ui);
    ui_panel_begin(d->ui, "Rows", row_panel);
    ui_row(d->ui, 3, NULL, 0);
    ui_button(d->ui, "A");
    ui_button(d->ui, "B");
    ui_button(d->ui, "C");
    ui_button(d->ui, "D");
    ui_panel_end(d->ui);
}

static void test_rows(void **state) {
    (void)state;
    row_cells s;
    drv d;
    drv_init(&d, build_rows, &s);
    float gap = ui_em(d.ui, 0.2f);
    assert_true(gap > 0);
    // Left to right, a gap after all but the last cell; the fourth wraps.
    assert_rect(s.cells[0], 0, 0, 100 - gap, 30);
    assert_rect(s.cells[1], 100, 0, 200 - gap, 30);
    assert_rect(s.cells[2], 300, 0, 500, 30);
    assert_rect(s.cells[3], 0, 30 + gap, 100 - gap, 30);
    assert_rect(s.cells[4], 100, 30 + gap, 200 - gap, 30);
    // In a panel: the same flow inside its padding, the default row height.
    ui_rect a = rect_of(&d, "Rows/A"), b = rect_of(&d, "Rows/B"), c = rect_of(&d, "Rows/C"),
            dd = rect_of(&d, "Rows/D");
    assert_true(rect_within(a, row_panel) && rect_within(c, row_panel));
    assert_true(a.x > row_panel.x && a.y > row_panel.y);
    assert_true(a.y == b.y && b.y == c.y);
    assert_true(a.x < b.x && b.x < c.x);
    assert_true(b.x >= a.x + a.w && c.x >= b.x + b.w);
    assert_true(a.h == ui_em(d.ui, 1.4f));
    assert_true(dd.x == a.x && dd.y == a.y + a.h + gap);
    drv_free(&d);
}

// ---- buttons, checkboxes, radios ---------------------------------------------------------

static void test_button(void **state) {
    (void)state;
    panel_button s = {0};
    drv d;
    drv_init(&d, build_panel_button, &s);
    ui_rect r = rect_of(&d, "Panel/Button");
    float cx = r.x + r.w / 2, cy = r.y + r.h / 2;
    // 1 on the release frame, exactly once.
    press(&d, cx, cy);
    assert_int_equal(s.clicks, 0);
    drag_to(&d, cx + 1, cy);
    assert_int_equal(s.clicks, 0);
    assert_int_equal(ui_wants_mouse(d.ui), 1); // held
    release(&d, cx + 1, cy);
    assert_int_equal(s.clicks, 1);
    for (int i = 0; i < 3; i++)
        frame(&d);
    assert_int_equal(s.clicks, 1);
    // Pressed over it, released outside: no click; nor does a release over it count
    // when the press was elsewhere.
    press(&d, cx, cy);
    drag_to(&d, 700, 500);
    release(&d, 700, 500);
    assert_int_equal(s.clicks, 1);
    press(&d, 700, 500);
    drag_to(&d, cx, cy);
    release(&d, cx, cy);
    assert_int_equal(s.clicks, 1);
    // Hovering inside the panel: the UI wants the mouse; away from it, not.
    move_to(&d, cx, cy);
    assert_int_equal(ui_wants_mouse(d.ui), 1);
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    move_to(&d, 700, 500);
    assert_int_equal(ui_wants_mouse(d.ui), 0);
    move_to(&d, button_panel.x + 2, button_panel.y + button_panel.h - 2); // panel, no widget
    assert_int_equal(ui_wants_mouse(d.ui), 1);
    drv_free(&d);
}

typedef struct choices {
    int check, check_changes, radio, radio_changes;
} choices;

static void build_choices(drv *d) {
    choices *s = d->user;
    ui_panel_begin(d->ui, "Opts", (ui_rect){0, 0, 300, 300});
    s->check_changes += ui_checkbox(d->ui, "Wire", &s->check);
    s->radio_changes += ui_radio(d->ui, "Low", &s->radio, 0);
    s->radio_changes += ui_radio(d->ui, "Mid", &s->radio, 1);
    s->radio_changes += ui_radio(d->ui, "High", &s->radio, 2);
    ui_panel_end(d->ui);
}

static void test_checkbox_and_radio(void **state) {
    (void)state;
    choices s = {0};
    drv d;
    drv_init(&d, build_choices, &s);
    ui_rect r = rect_of(&d, "Opts/Wire");
    press(&d, r.x + 5, r.y + r.h / 2);
    assert_int_equal(s.check, 0); // not on the press
    release(&d, r.x + 5, r.y + r.h / 2);
    assert_int_equal(s.check, 1);
    assert_int_equal(s.check_changes, 1);
    click_widget(&d, "Opts/Wire");
    assert_int_equal(s.check, 0);
    assert_int_equal(s.check_changes, 2);
    // Radios: picking one sets the option; picking it again changes nothing.
    click_widget(&d, "Opts/High");
    assert_int_equal(s.radio, 2);
    assert_int_equal(s.radio_changes, 1);
    click_widget(&d, "Opts/High");
    assert_int_equal(s.radio, 2);
    assert_int_equal(s.radio_changes, 1);
    click_widget(&d, "Opts/Mid");
    assert_int_equal(s.radio, 1);
    assert_int_equal(s.radio_changes, 2);
    assert_int_equal(s.check, 0); // untouched by the others
    drv_free(&d);
}

// ---- the curve editor ---------------------------------------------------------------------

typedef struct curve_state {
    float t[8], v[8];
    int n, changes;
} curve_state;

static void build_curve(drv *d) {
    curve_state *c = d->user;
    ui_panel_begin(d->ui, "C", (ui_rect){10, 10, 300, 220});
    ui_row(d->ui, 1, NULL, 200);
    if (ui_curve(d->ui, "Curve", c->t, c->v, &c->n, 8)) c->changes++;
    ui_panel_end(d->ui);
}

// Where (t, v) is drawn: the widget's unit square sits inside its rectangle.
static void curve_xy(drv *d, float t, float v, float *x, float *y) {
    ui_rect r = rect_of(d, "C/Curve");
    float pad = ui_em(d->ui, 0.45f);
    *x = r.x + pad + t * (r.w - 2 * pad);
    *y = r.y + pad + (1 - v) * (r.h - 2 * pad);
}

static void test_curve_editor(void **state) {
    (void)state;
    curve_state c = {.t = {0, 1}, .v = {1, 0}, .n = 2};
    drv d;
    drv_init(&d, build_curve, &c);
    float x, y, x2, y2;
    // A double click on the square adds a point there, between the ends.
    curve_xy(&d, 0.5f, 0.8f, &x, &y);
    d.in.double_click = 1;
    press(&d, x, y);
    release(&d, x, y);
    assert_int_equal(c.n, 3);
    assert_int_equal(c.changes, 1);
    assert_true(fabsf(c.t[1] - 0.5f) < 0.01f && fabsf(c.v[1] - 0.8f) < 0.01f);
    // Dragging it changes nothing until the release; then it is where it was dropped.
    press(&d, x, y);
    curve_xy(&d, 0.3f, 0.4f, &x2, &y2);
    drag_to(&d, x2, y2);
    assert_true(fabsf(c.t[1] - 0.5f) < 0.01f);
    assert_int_equal(c.changes, 1);
    release(&d, x2, y2);
    assert_int_equal(c.changes, 2);
    assert_true(fabsf(c.t[1] - 0.3f) < 0.01f && fabsf(c.v[1] - 0.4f) < 0.01f);
    // An inner point cannot pass its neighbours; values clamp to [0, 1].
    curve_xy(&d, c.t[1], c.v[1], &x, &y);
    press(&d, x, y);
    curve_xy(&d, 1.5f, -0.5f, &x2, &y2);
    drag_to(&d, x2, y2);
    release(&d, x2, y2);
    assert_true(c.t[1] < 1.0f && c.t[1] > 0.99f && c.v[1] == 0.0f);
    assert_true(c.t[0] == 0.0f && c.t[2] == 1.0f);
    // An end moves only up and down.
    curve_xy(&d, 0, 1, &x, &y);
    press(&d, x, y);
    curve_xy(&d, 0.4f, 0.6f, &x2, &y2);
    drag_to(&d, x2, y2);
    release(&d, x2, y2);
    assert_true(c.t[0] == 0.0f && fabsf(c.v[0] - 0.6f) < 0.01f);
    // A press that does not move is no change.
    int before = c.changes;
    curve_xy(&d, c.t[0], c.v[0], &x, &y);
    click(&d, x, y);
    assert_int_equal(c.changes, before);
    // Right-click removes an inner point, never an end.
    curve_xy(&d, c.t[1], c.v[1], &x, &y);
    d.in.mouse_x = x, d.in.mouse_y = y;
    d.in.mouse_pressed[1] = 1;
    frame(&d);
    assert_int_equal(c.n, 2);
    curve_xy(&d, c.t[0], c.v[0], &x, &y);
    d.in.mouse_x = x, d.in.mouse_y = y;
    d.in.mouse_pressed[1] = 1;
    frame(&d);
    assert_int_equal(c.n, 2);
    // The arrays' room is respected: a full curve takes no more points.
    for (int i = 0; i < 10; i++) {
        curve_xy(&d, 0.05f + 0.09f * i, 0.5f, &x, &y);
        d.in.double_click = 1;
        press(&d, x, y);
        release(&d, x, y);
    }
    assert_int_equal(c.n, 8);
    for (int i = 1; i < c.n; i++)
        assert_true(c.t[i] > c.t[i - 1]);
    drv_free(&d);
}

// ---- trees and colour swatches ----------------------------------------------------------

typedef struct tree_state {
    int clicks[3];
    int open_seen;
} tree_state;

static void build_tree(drv *d) {
    tree_state *t = d->user;
    ui_panel_begin(d->ui, "P", (ui_rect){10, 10, 300, 300});
    ui_row(d->ui, 1, NULL, 0);
    t->open_seen = 0;
    if (ui_tree_push(d->ui, "Node", 1)) {
        t->open_seen = 1;
        if (ui_color_swatch(d->ui, "Red", UI_RGBA(255, 0, 0, 255), t->clicks[0] > 0))
            t->clicks[0]++;
        if (ui_tree_push(d->ui, "Inner", 0)) {
            if (ui_button(d->ui, "Deep")) t->clicks[2]++;
            ui_tree_pop(d->ui);
        }
        ui_tree_pop(d->ui);
    }
    if (ui_button(d->ui, "After")) t->clicks[1]++;
    ui_panel_end(d->ui);
}

static void test_tree_and_swatch(void **state) {
    (void)state;
    tree_state t = {{0}, 0};
    drv d;
    drv_init(&d, build_tree, &t);
    // Open by default: its child is named below it and indented; the closed inner node
    // hides its own child.
    ui_rect node = rect_of(&d, "P/Node"), red = rect_of(&d, "P/Node/Red");
    ui_rect after = rect_of(&d, "P/After");
    assert_true(red.x > node.x + 5 && red.w < node.w);
    assert_true(after.x == node.x && after.w == node.w); // the indent ends with the node
    assert_null(ui_widget_find(d.ui, "P/Node/Inner/Deep"));
    click_widget(&d, "P/Node/Red");
    assert_int_equal(t.clicks[0], 1);
    // Opening the inner node shows its child, indented twice.
    click_widget(&d, "P/Node/Inner");
    frame(&d);
    ui_rect deep = rect_of(&d, "P/Node/Inner/Deep");
    assert_true(deep.x > red.x + 5);
    click_widget(&d, "P/Node/Inner/Deep");
    assert_int_equal(t.clicks[2], 1);
    // Closing the outer node hides everything below it; the row after moves up.
    click_widget(&d, "P/Node");
    frame(&d);
    assert_int_equal(t.open_seen, 0);
    assert_null(ui_widget_find(d.ui, "P/Node/Red"));
    assert_true(rect_of(&d, "P/After").y < after.y);
    click_widget(&d, "P/After");
    assert_int_equal(t.clicks[1], 1);
    drv_free(&d);
}

// ---- sliders --------------------------------------------------------------------------

typedef struct slider_state {
    double v, lo, hi;
    int changes;
} slider_state;

static void build_slider(drv *d) {
    slider_state *s = d->user;
    ui_panel_begin(d->ui, "S", (ui_rect){0, 0, 800, 200});
    ui_row(d->ui, 2, (const float[]){100, 0}, 0);
    ui_label(d->ui, "Strength");
    s->changes += ui_slider(d->ui, "Value", &s->v, s->lo, s->hi, "%.2f");
    ui_row(d->ui, 1, NULL, 0);
    ui_button(d->ui, "Elsewhere");
    ui_panel_end(d->ui);
}

// The x of value v on the slider.
static float slider_x(ui_rect r, const slider_state *s, double v) {
    return r.x + (float)((v - s->lo) / (s->hi - s->lo)) * r.w;
}

static void test_slider_drag(void **state) {
    (void)state;
    slider_state s = {.v = 50, .lo = 0, .hi = 100};
    drv d;
    drv_init(&d, build_slider, &s);
    ui_rect r = rect_of(&d, "S/Value");
    assert_true(r.w > 100);
    float cy = r.y + r.h / 2;
    double per_px = (s.hi - s.lo) / r.w;
    // A press changes nothing (as Unreal's and Blender's number fields): a drag scrubs
    // from the value.
    press(&d, slider_x(r, &s, 25), cy);
    assert_true(s.v == 50);
    assert_int_equal(s.changes, 0);
    // Dragging right adds in proportion.
    drag_to(&d, slider_x(r, &s, 25) + 40, cy);
    double coarse = s.v - 50;
    assert_true(fabs(coarse - 40 * per_px) < 1e-4);
    drag_to(&d, slider_x(r, &s, 25) + 80, cy);
    assert_true(fabs(s.v - 50 - 80 * per_px) < 1e-4);
    release(&d, slider_x(r, &s, 25) + 80, cy);
    assert_int_equal(ui_wants_keyboard(d.ui), 0); // a drag opens no text field
    double after = s.v;
    frame(&d);
    move_to(&d, 10, 190);
    assert_true(s.v == after); // moving without the button does nothing
    // Shift: the same 40 px add a tenth as much.
    d.in.mods = UI_MOD_SHIFT;
    press(&d, slider_x(r, &s, 25), cy);
    assert_true(s.v == after);
    drag_to(&d, slider_x(r, &s, 25) + 40, cy);
    double fine = s.v - after;
    release(&d, slider_x(r, &s, 25) + 40, cy);
    d.in.mods = 0;
    assert_true(fine > 0);
    assert_true(fabs(coarse / fine - 10) < 1e-6);
    // Values clamp to [lo, hi].
    press(&d, slider_x(r, &s, 50), cy);
    drag_to(&d, -500, cy);
    assert_true(s.v == s.lo);
    drag_to(&d, 5000, cy);
    assert_true(s.v == s.hi);
    release(&d, 5000, cy);
    assert_true(s.v == s.hi);
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    // A value outside the range scrubs from the end it is shown at; the pointer's place
    // in the frame the button is let go counts.
    s.v = -500;
    press(&d, slider_x(r, &s, 50), cy);
    release(&d, slider_x(r, &s, 50) + 40, cy);
    assert_true(fabs(s.v - 40 * per_px) < 1e-4);
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    // A pointer that shakes by a pixel or two is still a click: no change, a field.
    s.v = 1.0 / 3.0;
    press(&d, slider_x(r, &s, 60), cy);
    drag_to(&d, slider_x(r, &s, 60) + 2, cy);
    release(&d, slider_x(r, &s, 60) + 2, cy);
    assert_true(s.v == 1.0 / 3.0);
    assert_int_equal(ui_wants_keyboard(d.ui), 1);
    drv_free(&d);
}

// Ctrl+click, then type.
static void slider_type(drv *d, slider_state *s, const char *text, ui_key finish) {
    ui_rect r = rect_of(d, "S/Value");
    double before = s->v;
    d->in.mods = UI_MOD_CTRL;
    press(d, r.x + r.w * 0.9f, r.y + r.h / 2);
    release(d, r.x + r.w * 0.9f, r.y + r.h / 2);
    d->in.mods = 0;
    assert_true(s->v == before); // Ctrl+click does not drag
    assert_int_equal(ui_wants_keyboard(d->ui), 1);
    type(d, text);
    assert_true(s->v == before); // not until Enter
    key(d, finish, 0);
}

static void test_slider_typing(void **state) {
    (void)state;
    slider_state s = {.v = 5, .lo = 0, .hi = 100};
    drv d;
    drv_init(&d, build_slider, &s);
    ui_rect r = rect_of(&d, "S/Value");
    slider_type(&d, &s, "42", UI_KEY_ENTER);
    assert_true(s.v == 42);
    assert_int_equal(s.changes, 1);
    assert_string_equal(ui_field_error(d.ui), "");
    slider_type(&d, &s, "12.25", UI_KEY_ENTER);
    assert_true(s.v == 12.25);
    // Out of range: refused, the field stays open and says why.
    slider_type(&d, &s, "250", UI_KEY_ENTER);
    assert_true(s.v == 12.25);
    assert_int_equal(ui_wants_keyboard(d.ui), 1);
    assert_non_null(strstr(ui_field_error(d.ui), "250 is outside 0 .. 100"));
    assert_int_equal(ui_message_count(d.ui), 1); // listed where it shows, for ui_messages
    assert_string_equal(ui_message_at(d.ui, 0)->where, "S/Value");
    assert_string_equal(ui_message_at(d.ui, 0)->text, ui_field_error(d.ui));
    // Typing again clears the reason; a good number then goes in.
    key(&d, UI_KEY_BACKSPACE, 0);
    assert_string_equal(ui_field_error(d.ui), "");
    key(&d, UI_KEY_ESCAPE, 0);
    assert_true(s.v == 12.25);
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    // Not a number: refused the same way.
    slider_type(&d, &s, "abc", UI_KEY_ENTER);
    assert_true(s.v == 12.25);
    assert_int_equal(ui_wants_keyboard(d.ui), 1);
    assert_non_null(strstr(ui_field_error(d.ui), "\"abc\" is not a number"));
    key(&d, UI_KEY_A, UI_MOD_CTRL);
    type(&d, "7.5");
    key(&d, UI_KEY_ENTER, 0);
    assert_true(s.v == 7.5);
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    assert_string_equal(ui_field_error(d.ui), "");
    // Esc restores the value bit for bit, whatever was typed.
    s.v = 0.1 + 0.2; // not 0.3: a value no short text prints
    int changes = s.changes;
    slider_type(&d, &s, "77", UI_KEY_ESCAPE);
    assert_true(s.v == 0.1 + 0.2);
    assert_int_equal(s.changes, changes);
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    // Enter on the untouched text changes nothing either (it reads back as the value).
    d.in.mods = UI_MOD_CTRL;
    press(&d, r.x + r.w * 0.9f, r.y + r.h / 2);
    release(&d, r.x + r.w * 0.9f, r.y + r.h / 2);
    d.in.mods = 0;
    key(&d, UI_KEY_ENTER, 0);
    assert_true(s.v == 0.1 + 0.2);
    assert_int_equal(s.changes, changes);
    // A plain click opens the field without changing the value.
    click(&d, slider_x(r, &s, 75), r.y + r.h / 2);
    assert_true(s.v == 0.1 + 0.2);
    assert_int_equal(ui_wants_keyboard(d.ui), 1);
    key(&d, UI_KEY_ESCAPE, 0);
    // A double click: the first click changes nothing, the second keeps the field open
    // with all its text selected, so typing replaces it.
    click(&d, r.x + 10, r.y + r.h / 2);
    d.in.double_click = 1;
    press(&d, r.x + 10, r.y + r.h / 2);
    d.in.double_click = 0;
    release(&d, r.x + 10, r.y + r.h / 2);
    assert_true(s.v == 0.1 + 0.2);
    assert_int_equal(s.changes, changes);
    type(&d, "3");
    assert_true(s.v == 0.1 + 0.2);
    key(&d, UI_KEY_ENTER, 0);
    assert_true(s.v == 3);
    drv_free(&d);
}

// After Enter has set the value, the slider is no longer typed into: it must let go of
// the keyboard (the viewport's shortcuts work again).
static void test_slider_enter_releases_keyboard(void **state) {
    (void)state;
    slider_state s = {.v = 5, .lo = 0, .hi = 100};
    drv d;
    drv_init(&d, build_slider, &s);
    slider_type(&d, &s, "42", UI_KEY_ENTER);
    assert_true(s.v == 42);
    frame(&d);
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    drv_free(&d);
}

// ---- text boxes ------------------------------------------------------------------------

typedef struct form {
    char name[32], path[32], tag[32];
    int rc[3];
    const char *focus_request;
} form;

static const ui_rect form_panel = {20, 20, 400, 300};

static void build_form(drv *d) {
    form *f = d->user;
    ui_panel_begin(d->ui, "Form", form_panel);
    f->rc[0] = ui_textbox(d->ui, "Name", f->name, sizeof f->name);
    f->rc[1] = ui_textbox(d->ui, "Path", f->path, sizeof f->path);
    f->rc[2] = ui_textbox(d->ui, "Tag", f->tag, sizeof f->tag);
    ui_button(d->ui, "OK");
    if (f->focus_request) {
        ui_focus(d->ui, f->focus_request);
        f->focus_request = NULL;
    }
    ui_panel_end(d->ui);
}

// Clicks at the right end of a box: focused, the caret after the text.
static void focus_end(drv *d, const char *name) {
    ui_rect r = rect_of(d, name);
    click(d, r.x + r.w - 3, r.y + r.h / 2);
}

static void form_init(drv *d, form *f, const char *name, const char *path, const char *tag) {
    memset(f, 0, sizeof *f);
    snprintf(f->name, sizeof f->name, "%s", name);
    snprintf(f->path, sizeof f->path, "%s", path);
    snprintf(f->tag, sizeof f->tag, "%s", tag);
    drv_init(d, build_form, f);
}

static void test_textbox_focus_and_caret(void **state) {
    (void)state;
    form f;
    drv d;
    form_init(&d, &f, "abcd", "", "");
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    type(&d, "x"); // unfocused: typing goes nowhere
    assert_string_equal(f.name, "abcd");
    // A click between "ab" and "cd" focuses with the caret there.
    ui_rect r = rect_of(&d, "Form/Name");
    float pad = ui_em(d.ui, 0.3f);
    float x = r.x + pad + ui_font_text_width(font, UI_FACE_SANS, "ab", 2);
    click(&d, x, r.y + r.h / 2);
    assert_int_equal(ui_wants_keyboard(d.ui), 1);
    type(&d, "X");
    assert_string_equal(f.name, "abXcd");
    assert_int_equal(f.rc[0], UI_TEXT_CHANGED);
    frame(&d);
    assert_int_equal(f.rc[0], 0);
    type(&d, "\xC3\xA9"); // é, two bytes
    assert_string_equal(f.name, "abX\xC3\xA9"
                                "cd");
    key(&d, UI_KEY_LEFT, 0); // over é as one character
    type(&d, "1");
    assert_string_equal(f.name, "abX1\xC3\xA9"
                                "cd");
    key(&d, UI_KEY_RIGHT, 0);
    type(&d, "2");
    assert_string_equal(f.name, "abX1\xC3\xA9"
                                "2cd");
    key(&d, UI_KEY_HOME, 0);
    type(&d, "H");
    assert_string_equal(f.name, "HabX1\xC3\xA9"
                                "2cd");
    key(&d, UI_KEY_END, 0);
    type(&d, "E");
    assert_string_equal(f.name, "HabX1\xC3\xA9"
                                "2cdE");
    key(&d, UI_KEY_RIGHT, 0); // at the end: stays
    key(&d, UI_KEY_HOME, 0);
    key(&d, UI_KEY_LEFT, 0); // at the start: stays
    type(&d, "<");
    assert_string_equal(f.name, "<HabX1\xC3\xA9"
                                "2cdE");
    assert_string_equal(f.path, ""); // only the focused box changes
    assert_string_equal(f.tag, "");
    drv_free(&d);
}

// A select-all field (numbers, paths): the click that focuses it selects everything,
// held over a frame or more, so typing replaces the text; a drag still selects a part.
static void build_select_all(drv *d) {
    form *f = d->user;
    ui_panel_begin(d->ui, "Form", form_panel);
    f->rc[0] = ui_textbox_flags(d->ui, "Name", f->name, sizeof f->name, UI_TEXTBOX_SELECT_ALL);
    ui_panel_end(d->ui);
}

static void test_textbox_select_all_on_click(void **state) {
    (void)state;
    form f;
    drv d;
    memset(&f, 0, sizeof f);
    snprintf(f.name, sizeof f.name, "1234");
    drv_init(&d, build_select_all, &f);
    ui_rect r = rect_of(&d, "Form/Name");
    press(&d, r.x + r.w / 2, r.y + r.h / 2);
    frame(&d); // the button still down a frame later (a slow frame)
    release(&d, r.x + r.w / 2, r.y + r.h / 2);
    type(&d, "50000");
    assert_string_equal(f.name, "50000");
    // Focused already, a click places the caret as usual.
    float pad = ui_em(d.ui, 0.3f);
    click(&d, r.x + pad + ui_font_text_width(font, UI_FACE_SANS, "50", 2), r.y + r.h / 2);
    type(&d, "x");
    assert_string_equal(f.name, "50x000");
    drv_free(&d);
}

static void test_textbox_selection_and_delete(void **state) {
    (void)state;
    form f;
    drv d;
    form_init(&d, &f, "hello", "", "");
    focus_end(&d, "Form/Name");
    key(&d, UI_KEY_LEFT, UI_MOD_SHIFT);
    key(&d, UI_KEY_LEFT, UI_MOD_SHIFT);
    type(&d, "P"); // replaces the selected "lo"
    assert_string_equal(f.name, "helP");
    key(&d, UI_KEY_BACKSPACE, 0); // a character
    assert_string_equal(f.name, "hel");
    assert_int_equal(f.rc[0], UI_TEXT_CHANGED);
    key(&d, UI_KEY_LEFT, UI_MOD_SHIFT);
    key(&d, UI_KEY_LEFT, UI_MOD_SHIFT);
    key(&d, UI_KEY_BACKSPACE, 0); // the selection
    assert_string_equal(f.name, "h");
    key(&d, UI_KEY_BACKSPACE, 0);
    assert_string_equal(f.name, "");
    key(&d, UI_KEY_BACKSPACE, 0); // nothing left: no change
    assert_int_equal(f.rc[0], 0);
    type(&d, "ab\xE2\x82\xAC"
             "cd"); // "ab€cd"
    key(&d, UI_KEY_HOME, 0);
    key(&d, UI_KEY_DELETE, 0);
    assert_string_equal(f.name, "b\xE2\x82\xAC"
                                "cd");
    key(&d, UI_KEY_RIGHT, 0);
    key(&d, UI_KEY_DELETE, 0); // € as one character
    assert_string_equal(f.name, "bcd");
    // Shift+End selects to the end.
    key(&d, UI_KEY_HOME, 0);
    key(&d, UI_KEY_END, UI_MOD_SHIFT);
    key(&d, UI_KEY_BACKSPACE, 0);
    assert_string_equal(f.name, "");
    assert_true(valid_utf8(f.name));
    drv_free(&d);
}

static void test_textbox_word_jumps(void **state) {
    (void)state;
    form f;
    drv d;
    form_init(&d, &f, "foo bar baz", "", "");
    focus_end(&d, "Form/Name");
    key(&d, UI_KEY_HOME, 0);
    key(&d, UI_KEY_RIGHT, UI_MOD_CTRL); // after "foo"
    type(&d, "1");
    assert_string_equal(f.name, "foo1 bar baz");
    key(&d, UI_KEY_RIGHT, UI_MOD_CTRL); // over the space, after "bar"
    type(&d, "2");
    assert_string_equal(f.name, "foo1 bar2 baz");
    key(&d, UI_KEY_END, 0);
    key(&d, UI_KEY_LEFT, UI_MOD_CTRL); // the start of "baz"
    type(&d, "3");
    assert_string_equal(f.name, "foo1 bar2 3baz");
    key(&d, UI_KEY_LEFT, UI_MOD_CTRL); // "3baz" is one word
    key(&d, UI_KEY_LEFT, UI_MOD_CTRL); // the start of "bar2"
    type(&d, "<");
    assert_string_equal(f.name, "foo1 <bar2 3baz");
    // Ctrl+Shift+Left selects a word.
    key(&d, UI_KEY_END, 0);
    key(&d, UI_KEY_LEFT, UI_MOD_CTRL | UI_MOD_SHIFT);
    key(&d, UI_KEY_BACKSPACE, 0);
    assert_string_equal(f.name, "foo1 <bar2 ");
    drv_free(&d);
}

typedef struct clip_board {
    char text[256];
    int sets, gets;
} clip_board;

static const char *clip_get(void *user) {
    clip_board *c = user;
    c->gets++;
    return c->text;
}

static void clip_set(void *user, const char *text) {
    clip_board *c = user;
    snprintf(c->text, sizeof c->text, "%s", text);
    c->sets++;
}

static void test_textbox_select_all_and_clipboard(void **state) {
    (void)state;
    form f;
    drv d;
    clip_board cb = {"", 0, 0};
    form_init(&d, &f, "hello world", "", "");
    ui_set_clipboard(d.ui, (ui_clipboard){clip_get, clip_set, &cb});
    focus_end(&d, "Form/Name");
    // Nothing selected: Ctrl+C copies nothing.
    key(&d, UI_KEY_C, UI_MOD_CTRL);
    assert_int_equal(cb.sets, 0);
    key(&d, UI_KEY_A, UI_MOD_CTRL);
    key(&d, UI_KEY_C, UI_MOD_CTRL);
    assert_int_equal(cb.sets, 1);
    assert_string_equal(cb.text, "hello world");
    assert_string_equal(f.name, "hello world"); // copying leaves the text
    // Cut the first word.
    key(&d, UI_KEY_HOME, 0);
    key(&d, UI_KEY_RIGHT, UI_MOD_CTRL | UI_MOD_SHIFT);
    key(&d, UI_KEY_X, UI_MOD_CTRL);
    assert_string_equal(cb.text, "hello");
    assert_string_equal(f.name, " world");
    assert_int_equal(f.rc[0], UI_TEXT_CHANGED);
    // Paste at the end.
    key(&d, UI_KEY_END, 0);
    key(&d, UI_KEY_V, UI_MOD_CTRL);
    assert_true(cb.gets >= 1);
    assert_string_equal(f.name, " worldhello");
    assert_int_equal(f.rc[0], UI_TEXT_CHANGED);
    // A paste replaces the selection and stops at a newline.
    snprintf(cb.text, sizeof cb.text, "one\ntwo");
    key(&d, UI_KEY_A, UI_MOD_CTRL);
    key(&d, UI_KEY_V, UI_MOD_CTRL);
    assert_string_equal(f.name, "one");
    // Ctrl+A, then typing replaces everything.
    key(&d, UI_KEY_A, UI_MOD_CTRL);
    type(&d, "new");
    assert_string_equal(f.name, "new");
    // Typing with Ctrl held is a shortcut, not text.
    d.in.mods = UI_MOD_CTRL;
    type(&d, "q");
    d.in.mods = 0;
    assert_string_equal(f.name, "new");
    drv_free(&d);
}

static void test_textbox_undo(void **state) {
    (void)state;
    form f;
    drv d;
    form_init(&d, &f, "abc", "", "");
    focus_end(&d, "Form/Name");
    type(&d, "d");
    type(&d, "e"); // one run of typing
    assert_string_equal(f.name, "abcde");
    key(&d, UI_KEY_LEFT, 0); // moving ends the run
    type(&d, "X");
    type(&d, "Y");
    assert_string_equal(f.name, "abcdXYe");
    key(&d, UI_KEY_Z, UI_MOD_CTRL);
    assert_string_equal(f.name, "abcde");
    assert_int_equal(f.rc[0], UI_TEXT_CHANGED);
    key(&d, UI_KEY_Z, UI_MOD_CTRL);
    assert_string_equal(f.name, "abc");
    key(&d, UI_KEY_Z, UI_MOD_CTRL); // nothing more to undo
    assert_string_equal(f.name, "abc");
    assert_int_equal(f.rc[0], 0);
    // A deletion is its own step.
    key(&d, UI_KEY_BACKSPACE, 0);
    assert_string_equal(f.name, "ab");
    key(&d, UI_KEY_Z, UI_MOD_CTRL);
    assert_string_equal(f.name, "abc");
    drv_free(&d);
}

static void test_textbox_enter_and_escape(void **state) {
    (void)state;
    form f;
    drv d;
    form_init(&d, &f, "orig", "", "");
    focus_end(&d, "Form/Name");
    assert_int_equal(ui_wants_keyboard(d.ui), 1);
    type(&d, "inal");
    key(&d, UI_KEY_ENTER, 0);
    assert_int_equal(f.rc[0], UI_TEXT_SUBMIT); // this frame only
    assert_string_equal(f.name, "original");
    frame(&d);
    assert_int_equal(f.rc[0], 0);
    assert_int_equal(f.rc[1], 0);
    // Esc: back to the text it had on focus, and the focus goes.
    type(&d, "!!");
    assert_string_equal(f.name, "original!!");
    key(&d, UI_KEY_ESCAPE, 0);
    assert_string_equal(f.name, "orig");
    assert_true(f.rc[0] & UI_TEXT_CHANGED);
    assert_false(f.rc[0] & UI_TEXT_SUBMIT);
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    type(&d, "zz");
    assert_string_equal(f.name, "orig");
    // Focused again: Esc with nothing changed reports no change.
    focus_end(&d, "Form/Name");
    key(&d, UI_KEY_ESCAPE, 0);
    assert_int_equal(f.rc[0], 0);
    assert_string_equal(f.name, "orig");
    // A click on nothing drops the focus too.
    focus_end(&d, "Form/Name");
    assert_int_equal(ui_wants_keyboard(d.ui), 1);
    click(&d, 700, 500);
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    type(&d, "zz");
    assert_string_equal(f.name, "orig");
    drv_free(&d);
}

// A focused text box owns the keyboard, not the mouse: with the pointer away from
// every panel the viewport gets the mouse (its wheel, its clicks).
static void test_textbox_focus_does_not_hold_the_mouse(void **state) {
    (void)state;
    form f;
    drv d;
    form_init(&d, &f, "abc", "", "");
    focus_end(&d, "Form/Name");
    move_to(&d, 700, 500);
    assert_int_equal(ui_wants_keyboard(d.ui), 1);
    assert_int_equal(ui_wants_mouse(d.ui), 0);
    drv_free(&d);
}

typedef struct small_box {
    char buf[8];
    char guard[8];
} small_box;

static void build_small(drv *d) {
    small_box *s = d->user;
    ui_textbox(d->ui, "Small", s->buf, sizeof s->buf);
}

static void assert_guard(const small_box *s) {
    for (int i = 0; i < 8; i++)
        assert_int_equal((unsigned char)s->guard[i], 0x5A);
    assert_true(memchr(s->buf, 0, sizeof s->buf) != NULL);
    assert_true(valid_utf8(s->buf));
}

static void test_textbox_never_overflows(void **state) {
    (void)state;
    small_box s;
    memset(&s, 0, sizeof s);
    memset(s.guard, 0x5A, sizeof s.guard);
    clip_board cb = {"", 0, 0};
    drv d;
    drv_init(&d, build_small, &s);
    ui_set_clipboard(d.ui, (ui_clipboard){clip_get, clip_set, &cb});
    focus_end(&d, "Small");
    type(&d, "abcdefghijkl");
    assert_string_equal(s.buf, "abcdefg");
    assert_guard(&s);
    type(&d, "z"); // full
    assert_string_equal(s.buf, "abcdefg");
    assert_guard(&s);
    // Multi-byte characters are never cut: two € (6 bytes) fit, the third does not.
    key(&d, UI_KEY_A, UI_MOD_CTRL);
    type(&d, "\xE2\x82\xAC\xE2\x82\xAC\xE2\x82\xAC");
    assert_string_equal(s.buf, "\xE2\x82\xAC\xE2\x82\xAC");
    assert_guard(&s);
    type(&d, "\xC3\xA9"); // one byte left: é (two) does not fit
    assert_string_equal(s.buf, "\xE2\x82\xAC\xE2\x82\xAC");
    type(&d, "x");
    assert_string_equal(s.buf, "\xE2\x82\xAC\xE2\x82\xAC"
                               "x");
    assert_guard(&s);
    // In the middle of the text too.
    key(&d, UI_KEY_HOME, 0);
    type(&d, "\xC3\xA9");
    assert_string_equal(s.buf, "\xE2\x82\xAC\xE2\x82\xAC"
                               "x");
    assert_guard(&s);
    // Pasting: as much as fits, whole characters.
    snprintf(cb.text, sizeof cb.text, "ab\xE2\x82\xAC\xE2\x82\xAC\xE2\x82\xAC");
    key(&d, UI_KEY_A, UI_MOD_CTRL);
    key(&d, UI_KEY_V, UI_MOD_CTRL);
    assert_string_equal(s.buf, "ab\xE2\x82\xAC");
    assert_guard(&s);
    // Backspace removes whole characters.
    key(&d, UI_KEY_END, 0);
    key(&d, UI_KEY_BACKSPACE, 0);
    assert_string_equal(s.buf, "ab");
    // Esc restores what fits, undo too.
    key(&d, UI_KEY_Z, UI_MOD_CTRL);
    assert_guard(&s);
    key(&d, UI_KEY_ESCAPE, 0);
    assert_guard(&s);
    drv_free(&d);
}

static void test_textbox_tab_and_focus_request(void **state) {
    (void)state;
    form f;
    drv d;
    form_init(&d, &f, "n0", "p0", "t0");
    focus_end(&d, "Form/Name");
    key(&d, UI_KEY_TAB, 0); // Name -> Path (its text all selected)
    assert_int_equal(ui_wants_keyboard(d.ui), 1);
    type(&d, "P");
    assert_string_equal(f.name, "n0");
    assert_string_equal(f.path, "P");
    key(&d, UI_KEY_TAB, 0); // Path -> Tag
    type(&d, "T");
    assert_string_equal(f.path, "P");
    assert_string_equal(f.tag, "T");
    key(&d, UI_KEY_TAB, 0); // Tag, the last -> Name, the first
    type(&d, "N");
    assert_string_equal(f.name, "N");
    assert_string_equal(f.path, "P");
    assert_string_equal(f.tag, "T");
    // Esc: back to what Name had when Tab focused it.
    key(&d, UI_KEY_ESCAPE, 0);
    assert_string_equal(f.name, "n0");
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    // ui_focus by label: the next frame.
    f.focus_request = "Tag";
    frame(&d);
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    type(&d, "Q");
    assert_string_equal(f.tag, "Q");
    assert_string_equal(f.name, "n0");
    assert_int_equal(ui_wants_keyboard(d.ui), 1);
    drv_free(&d);
}

// ---- clipping and the draw list ---------------------------------------------------------

static const ui_rect clip_panel = {100, 100, 200, 120};

static void build_clipped(drv *d) {
    ui_panel_begin(d->ui, "Clip", clip_panel);
    ui_button(d->ui, "Inside");
    ui_label(d->ui, "A label far wider than the panel it sits in, to be clipped at its edge");
    ui_panel_end(d->ui);
}

static void test_clipping(void **state) {
    (void)state;
    drv d;
    drv_init(&d, build_clipped, NULL);
    const ui_draw_list *dl = frame(&d);
    assert_true(dl->cmd_count >= 2);
    assert_true(dl->vtx_count > 0);
    // The panel's background under the window's clip, then the widgets under the panel's.
    ui_rect screen = {0, 0, WIN_W, WIN_H};
    assert_memory_equal(&dl->cmds[0].clip, &screen, sizeof screen);
    assert_int_equal(dl->cmds[0].index_count, 6); // the background alone
    int inside = 0;
    for (uint32_t c = 1; c < dl->cmd_count; c++) {
        ui_rect k = dl->cmds[c].clip;
        if (!rect_within(k, clip_panel))
            fail_msg("command %u clips to {%g, %g, %g, %g}, outside the panel", c, k.x, k.y, k.w,
                     k.h);
        inside += dl->cmds[c].index_count > 0;
    }
    assert_true(inside >= 1);
    // UI quads all sample the atlas (texture 0) inside it.
    for (uint32_t c = 0; c < dl->cmd_count; c++)
        assert_int_equal(dl->cmds[c].texture, 0);
    for (uint32_t v = 0; v < dl->vtx_count; v++) {
        assert_true(dl->vtx[v].u >= 0 && dl->vtx[v].u <= 1);
        assert_true(dl->vtx[v].v >= 0 && dl->vtx[v].v <= 1);
    }
    drv_free(&d);
}

typedef struct far_widget {
    float spacer;
    int with_button;
} far_widget;

static void build_far(drv *d) {
    far_widget *s = d->user;
    ui_row(d->ui, 1, NULL, s->spacer);
    ui_next_cell(d->ui); // an empty cell
    ui_row(d->ui, 1, NULL, 0);
    if (s->with_button) ui_button(d->ui, "Far");
}

static uint32_t far_vertices(float spacer, int with_button) {
    far_widget s = {spacer, with_button};
    drv d;
    drv_init(&d, build_far, &s);
    uint32_t n = frame(&d)->vtx_count;
    drv_free(&d);
    return n;
}

static void test_outside_the_clip_draws_nothing(void **state) {
    (void)state;
    // A button below the window adds no vertices; the same button in view does.
    assert_int_equal(far_vertices(700, 1), far_vertices(700, 0));
    assert_true(far_vertices(100, 1) > far_vertices(100, 0));
    // The draw list itself.
    ui_draw_list *dl = &scratch_list;
    ui_draw_reset(dl, font, WIN_W, WIN_H);
    ui_draw_push_clip(dl, (ui_rect){10, 10, 50, 50});
    ui_draw_rect(dl, (ui_rect){100, 100, 10, 10}, UI_RGBA(255, 0, 0, 255));
    ui_draw_rect(dl, (ui_rect){60, 20, 10, 10}, UI_RGBA(255, 0, 0, 255)); // touches the edge
    assert_true(ui_draw_text(dl, UI_FACE_SANS, 200, 200, "far", 3, 0xFFFFFFFFu) > 0);
    assert_int_equal(dl->vtx_count, 0);
    assert_int_equal(dl->cmd_count, 0);
    ui_draw_rect(dl, (ui_rect){50, 50, 30, 30}, UI_RGBA(0, 255, 0, 255)); // partly inside
    assert_int_equal(dl->vtx_count, 4);
    assert_int_equal(dl->cmd_count, 1);
    assert_rect(dl->cmds[0].clip, 10, 10, 50, 50);
    assert_int_equal(dl->cmds[0].texture, 0);
    // Nested clips intersect; popping restores.
    ui_draw_push_clip(dl, (ui_rect){40, 0, 100, 30});
    assert_rect(ui_draw_clip(dl), 40, 10, 20, 20);
    ui_draw_pop_clip(dl);
    ui_draw_pop_clip(dl);
    assert_rect(ui_draw_clip(dl), 0, 0, WIN_W, WIN_H);
    ui_draw_pop_clip(dl); // never below the window's
    assert_rect(ui_draw_clip(dl), 0, 0, WIN_W, WIN_H);
    // Images: the renderer's texture, their own command; texture 0 is refused.
    ui_draw_image(dl, 7, (ui_rect){0, 0, 10, 10}, 0, 0, 1, 1, 0xFFFFFFFFu);
    assert_int_equal(dl->cmd_count, 2);
    assert_int_equal(dl->cmds[1].texture, 7);
    ui_draw_image(dl, 0, (ui_rect){0, 0, 10, 10}, 0, 0, 1, 1, 0xFFFFFFFFu);
    assert_int_equal(dl->cmd_count, 2);
    ui_draw_rect(dl, (ui_rect){0, 0, 10, 10}, 0xFFFFFFFFu);
    assert_int_equal(dl->cmd_count, 3);
    assert_int_equal(dl->cmds[2].texture, 0);
    check_draw_list(dl);
    ui_draw_free(dl);
}

// ---- scrolling ----------------------------------------------------------------------------

static const ui_rect list_panel = {0, 0, 300, 200};

static void build_list(drv *d) {
    ui_panel_begin(d->ui, "List", list_panel);
    for (int i = 0; i < 100; i++) {
        char name[32];
        snprintf(name, sizeof name, "Row %d", i);
        ui_label(d->ui, name);
    }
    ui_panel_end(d->ui);
}

static void test_scroll(void **state) {
    (void)state;
    drv d;
    drv_init(&d, build_list, NULL);
    move_to(&d, 150, 100);
    float pad = ui_em(d.ui, 0.3f), step = ui_em(d.ui, 3);
    ui_rect top = rect_of(&d, "List/Row 0");
    assert_true(top.y == list_panel.y + pad);
    // Toward the user: the rows move up.
    d.in.wheel = -1;
    frame(&d);
    frame(&d);
    assert_true(rect_of(&d, "List/Row 0").y == top.y - step);
    d.in.wheel = -2;
    frame(&d);
    frame(&d);
    assert_true(rect_of(&d, "List/Row 0").y == top.y - 3 * step);
    // To the end: the last row's bottom on the panel's bottom padding, and no further.
    d.in.wheel = -1000;
    frame(&d);
    frame(&d);
    ui_rect last = rect_of(&d, "List/Row 99");
    assert_true(fabsf(last.y + last.h - (list_panel.y + list_panel.h - pad)) < 0.01f);
    float end_y = rect_of(&d, "List/Row 0").y;
    d.in.wheel = -1;
    frame(&d);
    frame(&d);
    assert_true(rect_of(&d, "List/Row 0").y == end_y);
    // Back up, clamped at the top.
    d.in.wheel = 1000;
    frame(&d);
    frame(&d);
    assert_true(rect_of(&d, "List/Row 0").y == top.y);
    // The wheel away from the panel does not scroll it.
    move_to(&d, 600, 400);
    d.in.wheel = -1;
    frame(&d);
    frame(&d);
    assert_true(rect_of(&d, "List/Row 0").y == top.y);
    drv_free(&d);
}

// A list panel inside a scrolling panel (the History steps in the dock): the wheel over
// the inner list scrolls it alone; over the rest of the outer panel, the outer one.
static void build_nested(drv *d) {
    ui_panel_begin(d->ui, "Dock", list_panel);
    ui_label(d->ui, "Top");
    ui_row(d->ui, 1, NULL, 100);
    ui_panel_begin(d->ui, "Steps", ui_next_cell(d->ui));
    for (int i = 0; i < 40; i++) {
        char name[32];
        snprintf(name, sizeof name, "Step %d", i);
        ui_label(d->ui, name);
    }
    ui_panel_end(d->ui);
    ui_row(d->ui, 1, NULL, 0);
    for (int i = 0; i < 40; i++) {
        char name[32];
        snprintf(name, sizeof name, "Row %d", i);
        ui_label(d->ui, name);
    }
    ui_panel_end(d->ui);
}

static void test_scroll_nested(void **state) {
    (void)state;
    drv d;
    drv_init(&d, build_nested, NULL);
    float step = ui_em(d.ui, 3);
    ui_rect top = rect_of(&d, "Dock/Top"), first = rect_of(&d, "Dock/Steps/Step 0");
    move_to(&d, first.x + 5, first.y + first.h / 2);
    frame(&d);
    d.in.wheel = -1;
    frame(&d);
    frame(&d);
    assert_true(rect_of(&d, "Dock/Steps/Step 0").y == first.y - step);
    assert_true(rect_of(&d, "Dock/Top").y == top.y); // the dock stays
    // Over the dock's own rows the dock scrolls (and the list with it).
    move_to(&d, top.x + 5, top.y + top.h / 2);
    frame(&d);
    d.in.wheel = -1;
    frame(&d);
    frame(&d);
    assert_true(rect_of(&d, "Dock/Top").y == top.y - step);
    drv_free(&d);
}

// ---- menus and combos -------------------------------------------------------------------

typedef struct menus {
    int save, quit, undo, under, go, shape, shape_changes;
    char find[32];
} menus;

static void build_menus(drv *d) {
    menus *m = d->user;
    ui_context *ui = d->ui;
    ui_menubar_begin(ui, (ui_rect){0, 0, WIN_W, 24});
    if (ui_menu_begin(ui, "File")) {
        m->save += ui_menu_item(ui, "Save", "Ctrl+S", 1);
        ui_menu_separator(ui);
        m->quit += ui_menu_item(ui, "Quit", NULL, 1);
        ui_menu_end(ui);
    }
    if (ui_menu_begin(ui, "Edit")) {
        m->undo += ui_menu_item(ui, "Undo", "Ctrl+Z", 0); // disabled
        ui_menu_end(ui);
    }
    ui_menubar_end(ui);
    ui_panel_begin(ui, "Body", (ui_rect){0, 24, WIN_W, WIN_H - 24});
    ui_row(ui, 1, NULL, 200); // a big button under the menus
    m->under += ui_button(ui, "Under");
    ui_row(ui, 1, NULL, 0);
    static const char *const shapes[] = {"Small", "Medium", "Large"};
    m->shape_changes += ui_combo(ui, "Shape", &m->shape, shapes, 3);
    ui_textbox(ui, "Find", m->find, sizeof m->find);
    m->go += ui_button(ui, "Go");
    ui_panel_end(ui);
}

static void open_file_menu(drv *d) {
    click_widget(d, "Menu/File");
    frame(d); // popups size themselves from the frame before
    assert_non_null(ui_widget_find(d->ui, "Menu/File/Save"));
}

static void test_menu_items(void **state) {
    (void)state;
    menus m = {0};
    drv d;
    drv_init(&d, build_menus, &m);
    assert_null(ui_widget_find(d.ui, "Menu/File/Save")); // closed
    ui_rect file = rect_of(&d, "Menu/File");
    assert_true(file.y == 0 && file.h == 24);
    open_file_menu(&d);
    assert_non_null(ui_widget_find(d.ui, "Menu/File/Quit"));
    assert_null(ui_widget_find(d.ui, "Menu/Edit/Undo"));
    ui_rect save = rect_of(&d, "Menu/File/Save");
    assert_true(save.y >= 24);
    // The item works on its release; the button it covers does not.
    press(&d, save.x + save.w / 2, save.y + save.h / 2);
    assert_int_equal(m.save, 0);
    assert_non_null(ui_widget_find(d.ui, "Menu/File/Save"));
    release(&d, save.x + save.w / 2, save.y + save.h / 2);
    assert_int_equal(m.save, 1);
    assert_int_equal(m.under, 0);
    frame(&d);
    assert_null(ui_widget_find(d.ui, "Menu/File/Save")); // closed
    assert_int_equal(m.save, 1);
    // Clicking the title twice closes it.
    open_file_menu(&d);
    click_widget(&d, "Menu/File");
    frame(&d);
    assert_null(ui_widget_find(d.ui, "Menu/File/Save"));
    // Esc closes it.
    open_file_menu(&d);
    key(&d, UI_KEY_ESCAPE, 0);
    assert_null(ui_widget_find(d.ui, "Menu/File/Save"));
    assert_int_equal(m.save + m.quit + m.under, 1);
    // A disabled item does nothing and leaves the menu open.
    click_widget(&d, "Menu/Edit");
    frame(&d);
    click_widget(&d, "Menu/Edit/Undo");
    assert_int_equal(m.undo, 0);
    assert_int_equal(m.under, 0);
    assert_non_null(ui_widget_find(d.ui, "Menu/Edit/Undo"));
    // With a menu open, moving along the bar opens the other.
    move_to(&d, file.x + file.w / 2, file.y + file.h / 2);
    frame(&d);
    assert_non_null(ui_widget_find(d.ui, "Menu/File/Save"));
    assert_null(ui_widget_find(d.ui, "Menu/Edit/Undo"));
    drv_free(&d);
}

// A click outside an open menu closes it and does nothing else: not the button under
// the pointer.
static void test_menu_click_outside(void **state) {
    (void)state;
    menus m = {0};
    drv d;
    drv_init(&d, build_menus, &m);
    ui_rect under = rect_of(&d, "Body/Under");
    float x = under.x + under.w - 20, y = under.y + under.h / 2; // right of the popup
    open_file_menu(&d);
    ui_rect save = rect_of(&d, "Menu/File/Save");
    assert_false(x >= save.x && x < save.x + save.w);
    click(&d, x, y);
    frame(&d);
    assert_null(ui_widget_find(d.ui, "Menu/File/Save"));
    assert_int_equal(m.save + m.quit, 0);
    assert_int_equal(m.under, 0);
    // Closed, the same click works.
    click(&d, x, y);
    assert_int_equal(m.under, 1);
    drv_free(&d);
}

// Esc closes a menu even after a text box lost its focus to a button.
static void test_menu_escape_after_text_focus_moved(void **state) {
    (void)state;
    menus m = {0};
    drv d;
    drv_init(&d, build_menus, &m);
    click_widget(&d, "Body/Find");
    assert_int_equal(ui_wants_keyboard(d.ui), 1);
    click_widget(&d, "Body/Go");
    assert_int_equal(m.go, 1);
    assert_int_equal(ui_wants_keyboard(d.ui), 0);
    open_file_menu(&d);
    key(&d, UI_KEY_ESCAPE, 0);
    assert_null(ui_widget_find(d.ui, "Menu/File/Save"));
    drv_free(&d);
}

static void test_combo(void **state) {
    (void)state;
    menus m = {0};
    drv d;
    drv_init(&d, build_menus, &m);
    assert_null(ui_widget_find(d.ui, "Body/Shape/Large"));
    click_widget(&d, "Body/Shape");
    frame(&d);
    ui_rect combo = rect_of(&d, "Body/Shape"), large = rect_of(&d, "Body/Shape/Large");
    assert_true(large.y >= combo.y + combo.h);
    assert_non_null(ui_widget_find(d.ui, "Body/Shape/Small"));
    assert_non_null(ui_widget_find(d.ui, "Body/Shape/Medium"));
    press(&d, large.x + large.w / 2, large.y + large.h / 2);
    assert_int_equal(m.shape, 0);
    release(&d, large.x + large.w / 2, large.y + large.h / 2);
    assert_int_equal(m.shape, 2);
    assert_int_equal(m.shape_changes, 1);
    frame(&d);
    assert_null(ui_widget_find(d.ui, "Body/Shape/Large")); // closed
    // Picking the current item: closed, no change.
    click_widget(&d, "Body/Shape");
    frame(&d);
    click_widget(&d, "Body/Shape/Large");
    assert_int_equal(m.shape, 2);
    assert_int_equal(m.shape_changes, 1);
    frame(&d);
    assert_null(ui_widget_find(d.ui, "Body/Shape/Large"));
    // Esc closes without a change.
    click_widget(&d, "Body/Shape");
    frame(&d);
    key(&d, UI_KEY_ESCAPE, 0);
    assert_null(ui_widget_find(d.ui, "Body/Shape/Small"));
    assert_int_equal(m.shape, 2);
    assert_int_equal(m.under + m.save, 0);
    drv_free(&d);
}

// A row with a context menu and a range over a histogram.
typedef struct row_menu {
    int duplicate, remove, row_clicks, dragging, done;
    double lo, hi;
} row_menu;

static void build_row_menu(drv *d) {
    row_menu *m = d->user;
    ui_context *ui = d->ui;
    ui_panel_begin(ui, "Body", (ui_rect){0, 0, WIN_W, WIN_H});
    ui_row(ui, 1, NULL, 0);
    m->row_clicks += ui_selectable(ui, "Row", 0);
    if (ui_context_menu_begin(ui, "Row menu")) {
        m->duplicate += ui_menu_item(ui, "Duplicate", NULL, 1);
        m->remove += ui_menu_item(ui, "Delete", NULL, 1);
        ui_context_menu_end(ui);
    }
    ui_row(ui, 1, NULL, 60);
    static const float bars[4] = {1, 3, 2, 0};
    int r = ui_range(ui, "Slope", &m->lo, &m->hi, 5, 0, 100, bars, 4);
    m->dragging += r == UI_RANGE_DRAGGING;
    m->done += r == UI_RANGE_DONE;
    ui_row(ui, 1, NULL, 0);
    double amount = 3;
    ui_slider(ui, "##Amount", &amount, 0, 10, "%.0f"); // shows 3, named Amount
    ui_panel_end(ui);
}

static void right_click(drv *d, float x, float y) {
    d->in.mouse_x = x, d->in.mouse_y = y;
    d->in.mouse_pressed[1] = d->in.mouse_down[1] = 1;
    frame(d);
    d->in.mouse_down[1] = 0;
    d->in.mouse_released[1] = 1;
    frame(d);
    d->in.mouse_released[1] = 0;
}

static void test_context_menu_and_range(void **state) {
    (void)state;
    row_menu m = {.lo = 20, .hi = 40};
    drv d;
    drv_init(&d, build_row_menu, &m);
    assert_null(ui_widget_find(d.ui, "Body/Row menu/Delete"));
    assert_non_null(ui_widget_find(d.ui, "Body/Amount")); // a label showing nothing: its suffix
    ui_rect row = rect_of(&d, "Body/Row");
    right_click(&d, row.x + 30, row.y + row.h / 2);
    frame(&d);
    ui_rect del = rect_of(&d, "Body/Row menu/Delete");
    assert_true(del.x >= row.x + 29 && del.y >= row.y + row.h / 2); // at the pointer
    assert_int_equal(m.row_clicks, 0);                              // a right click is no click
    click_widget(&d, "Body/Row menu/Delete");
    assert_int_equal(m.remove, 1);
    assert_int_equal(m.duplicate + m.row_clicks, 0); // the row under the menu saw nothing
    frame(&d);
    assert_null(ui_widget_find(d.ui, "Body/Row menu/Delete")); // closed by the pick
    // Opened again, a click elsewhere closes it without a pick.
    right_click(&d, row.x + 30, row.y + row.h / 2);
    frame(&d);
    assert_non_null(ui_widget_find(d.ui, "Body/Row menu/Duplicate"));
    click(&d, 700, 500);
    frame(&d);
    assert_null(ui_widget_find(d.ui, "Body/Row menu/Duplicate"));
    assert_int_equal(m.duplicate, 0);

    // The range: a press near the high end drags it, live, and not below the low end.
    ui_rect r = rect_of(&d, "Body/Slope");
    float x40 = r.x + r.w * 0.4f;
    press(&d, x40 + 3, r.y + 10);
    drag_to(&d, r.x + r.w * 0.7f, r.y + 10);
    assert_true(fabs(m.hi - 70) < 0.5 && m.lo == 20);
    assert_true(m.dragging > 0 && m.done == 0);
    drag_to(&d, r.x + r.w * 0.1f, r.y + 10); // past the low end: stops at it
    assert_true(m.hi == 20);
    release(&d, r.x + r.w * 0.5f, r.y + 10);
    assert_int_equal(m.done, 1);
    assert_true(fabs(m.hi - 50) < 0.5);
    // A press nearer the low end moves that end; beyond the cell it clamps to the minimum.
    press(&d, r.x + r.w * 0.15f, r.y + 10);
    release(&d, r.x - 50, r.y + 10);
    assert_true(m.lo == 0 && fabs(m.hi - 50) < 0.5);
    assert_int_equal(m.done, 2);
    drv_free(&d);
}

// A dialog: a modal rectangle just tall enough for a combo box, whose list falls below
// it, and a button outside the dialog.
typedef struct dialog_combo {
    int index, behind_clicks;
} dialog_combo;

static void build_dialog_combo(drv *d) {
    dialog_combo *m = d->user;
    ui_rect dialog = {100, 100, 200, 40};
    ui_modal(d->ui, dialog);
    ui_panel_begin(d->ui, "Behind", (ui_rect){0, 300, 200, 40});
    ui_row(d->ui, 1, NULL, 0);
    m->behind_clicks += ui_button(d->ui, "Button");
    ui_panel_end(d->ui);
    ui_panel_begin(d->ui, "Dialog", dialog);
    ui_row(d->ui, 1, NULL, 0);
    static const char *const items[] = {"One", "Two", "Three", "Four", "Five", "Six"};
    ui_combo(d->ui, "Pick", &m->index, items, 6);
    ui_panel_end(d->ui);
}

// A combo box in a modal dialog stays open and its items answer, though they lie past
// the dialog's rectangle; what lies outside the dialog still does not.
static void test_combo_in_a_modal_dialog(void **state) {
    (void)state;
    dialog_combo m = {0};
    drv d;
    drv_init(&d, build_dialog_combo, &m);
    click_widget(&d, "Dialog/Pick");
    frame(&d);
    frame(&d);
    ui_rect six = rect_of(&d, "Dialog/Pick/Six");
    assert_true(six.y > 140); // below the dialog
    click_widget(&d, "Dialog/Pick/Six");
    assert_int_equal(m.index, 5);
    frame(&d);
    assert_null(ui_widget_find(d.ui, "Dialog/Pick/Six")); // closed
    click_widget(&d, "Behind/Button");
    assert_int_equal(m.behind_clicks, 0);
    // Esc closes the open list and is spent there (the dialog would close on the next).
    click_widget(&d, "Dialog/Pick");
    frame(&d);
    key(&d, UI_KEY_ESCAPE, 0);
    assert_null(ui_widget_find(d.ui, "Dialog/Pick/Six"));
    assert_int_equal(ui_get_input(d.ui)->key_pressed[UI_KEY_ESCAPE], 0);
    drv_free(&d);
}

typedef struct list_over_button {
    int index, button_clicks, menu_picks;
} list_over_button;

// A combo box and a menu whose lists open over a button drawn after them.
static void build_list_over_button(drv *d) {
    list_over_button *m = d->user;
    ui_menubar_begin(d->ui, (ui_rect){0, 0, 400, 24});
    if (ui_menu_begin(d->ui, "File")) {
        m->menu_picks += ui_menu_item(d->ui, "Open", NULL, 1);
        m->menu_picks += ui_menu_item(d->ui, "Save", NULL, 1);
        ui_menu_end(d->ui);
    }
    ui_menubar_end(d->ui);
    ui_panel_begin(d->ui, "Panel", (ui_rect){0, 30, 200, 200});
    ui_row(d->ui, 1, NULL, 0);
    static const char *const items[] = {"One", "Two", "Three", "Four"};
    ui_combo(d->ui, "Pick", &m->index, items, 4);
    for (int i = 0; i < 6; i++) {
        char name[16];
        snprintf(name, sizeof name, "Under %d", i);
        m->button_clicks += ui_button(d->ui, name);
    }
    ui_panel_end(d->ui);
}

// A press and its release in one frame (a slow frame, a quick click): the list item
// takes the click and nothing under it sees it, though the list closes before the
// widgets below are drawn; the viewport is told the mouse was the UI's.
static void quick_click(drv *d, ui_rect item) {
    ui_rect r = {0, 0, 0, 0}; // where the item covers one of the buttons
    for (int i = 0; i < 6 && r.h <= 2; i++) {
        char name[32];
        snprintf(name, sizeof name, "Panel/Under %d", i);
        r = ui_rect_intersect(item, rect_of(d, name));
    }
    assert_true(r.h > 2);
    d->in.mouse_x = r.x + r.w * 0.5f;
    d->in.mouse_y = r.y + r.h * 0.5f;
    d->in.mouse_pressed[0] = 1;
    d->in.mouse_released[0] = 1;
    d->in.mouse_down[0] = 0;
    frame(d);
}

static void test_quick_click_on_a_list_over_a_button(void **state) {
    (void)state;
    list_over_button m = {0};
    drv d;
    drv_init(&d, build_list_over_button, &m);
    click_widget(&d, "Panel/Pick");
    frame(&d);
    ui_rect four = rect_of(&d, "Panel/Pick/Four");
    quick_click(&d, four);
    assert_int_equal(m.index, 3);
    assert_int_equal(m.button_clicks, 0);
    assert_int_equal(ui_wants_mouse(d.ui), 1);
    frame(&d);
    assert_null(ui_widget_find(d.ui, "Panel/Pick/Four")); // closed
    // The same with a menu item over the panel's buttons.
    click_widget(&d, "Menu/File");
    frame(&d);
    quick_click(&d, rect_of(&d, "Menu/File/Save"));
    assert_int_equal(m.menu_picks, 1);
    assert_int_equal(m.button_clicks, 0);
    assert_int_equal(ui_wants_mouse(d.ui), 1);
    // A quick click on a button itself still counts.
    frame(&d);
    quick_click(&d, rect_of(&d, "Panel/Under 2"));
    assert_int_equal(m.button_clicks, 1);
    drv_free(&d);
}

// ---- tooltips ---------------------------------------------------------------------------

static void build_tooltip(drv *d) {
    ui_row(d->ui, 1, (const float[]){200}, 0);
    ui_button(d->ui, "Hover");
    ui_tooltip(d->ui, "Raises the terrain");
}

static void test_tooltip(void **state) {
    (void)state;
    drv d;
    drv_init(&d, build_tooltip, NULL);
    ui_rect r = rect_of(&d, "Hover");
    uint32_t away = frame(&d)->vtx_count;
    d.in.time = 10.0;
    move_to(&d, r.x + 20, r.y + r.h / 2);
    uint32_t hover = d.dl->vtx_count;
    assert_int_equal(hover, away); // no tooltip yet
    assert_int_equal(ui_needs_frame(d.ui), 1);
    d.in.time = 10.3;
    assert_int_equal(frame(&d)->vtx_count, hover);
    assert_int_equal(ui_needs_frame(d.ui), 1); // still waiting
    d.in.time = 10.6;
    uint32_t shown = frame(&d)->vtx_count;
    // A box, its outline and the text ("Raises the terrain": 16 glyphs with quads).
    assert_true(shown >= hover + 4 + 16 + 16 * 4);
    // Drawn last, on top, below the pointer: the last command's triangles are its.
    const ui_draw_cmd *last = &d.dl->cmds[d.dl->cmd_count - 1];
    assert_true(last->index_count >= 6 * 16);
    for (uint32_t i = last->first_index; i < last->first_index + last->index_count; i++)
        assert_true(d.dl->vtx[d.dl->idx[i]].y > d.in.mouse_y);
    // Away: gone, and back to waiting when it returns.
    d.in.time = 10.7;
    move_to(&d, 700, 500);
    assert_int_equal(d.dl->vtx_count, away);
    d.in.time = 10.8;
    move_to(&d, r.x + 20, r.y + r.h / 2);
    assert_int_equal(d.dl->vtx_count, hover);
    drv_free(&d);
}

// A widget in the window's right part (a dock) and a row under it: its tooltip lies left
// of the dock, level with it, clear of the row below (the second layer's name at UI
// scale 1.5) and of the widgets beside it.
static void build_dock_tooltip(drv *d) {
    ui_panel_begin(d->ui, "Dock", (ui_rect){560, 0, 240, 300});
    ui_row(d->ui, 1, NULL, 0);
    ui_button(d->ui, "Opacity");
    ui_tooltip(d->ui, "How much of the layer shows (0-100%)");
    ui_button(d->ui, "Next row");
    ui_panel_end(d->ui);
}

static void test_tooltip_beside_the_dock(void **state) {
    (void)state;
    drv d;
    drv_init(&d, build_dock_tooltip, NULL);
    ui_rect r = rect_of(&d, "Dock/Opacity"), below = rect_of(&d, "Dock/Next row");
    frame(&d);
    d.in.time = 10.0;
    move_to(&d, r.x + 20, r.y + r.h / 2);
    d.in.time = 10.6;
    frame(&d);
    const ui_draw_cmd *last = &d.dl->cmds[d.dl->cmd_count - 1];
    assert_true(last->index_count >= 6 * 16);
    for (uint32_t i = last->first_index; i < last->first_index + last->index_count; i++) {
        const ui_vertex *v = &d.dl->vtx[d.dl->idx[i]];
        assert_true(v->x <= 560 && v->y < below.y); // left of the dock, above the next row
    }
    drv_free(&d);
}

// A tooltip longer than the window (the materials panel's rule at UI scale 1.5 in a
// 1024 x 640 window ran off its right edge): broken into rows, every glyph inside the
// window, beside the dock or below the pointer alike.
static const char long_tip[] =
    "A rule: its material covers the ground where its terms hold (click to pick it and edit "
    "it below; drag it up or down to change which rule wins where several hold, the last one "
    "listed on top of the others, as layers in a painting program stack)";

static void build_long_tooltips(drv *d) {
    ui_row(d->ui, 1, (const float[]){200}, 0);
    ui_button(d->ui, "Left");
    ui_tooltip(d->ui, long_tip);
    ui_panel_begin(d->ui, "Dock", (ui_rect){560, 0, 240, 300});
    ui_row(d->ui, 1, NULL, 0);
    ui_button(d->ui, "Rule");
    ui_tooltip(d->ui, long_tip);
    ui_panel_end(d->ui);
}

static void test_long_tooltip_wraps_inside_the_window(void **state) {
    (void)state;
    const char *names[] = {"Left", "Dock/Rule"};
    for (int k = 0; k < 2; k++) {
        drv d;
        drv_init(&d, build_long_tooltips, NULL);
        ui_rect r = rect_of(&d, names[k]);
        d.in.time = 10.0;
        move_to(&d, r.x + 20, r.y + r.h / 2);
        d.in.time = 10.6;
        frame(&d);
        const ui_draw_cmd *last = &d.dl->cmds[d.dl->cmd_count - 1];
        assert_true(last->index_count >= 6 * 100); // the whole text is drawn
        float top = 1e9f, bottom = -1e9f;
        for (uint32_t i = last->first_index; i < last->first_index + last->index_count; i++) {
            const ui_vertex *v = &d.dl->vtx[d.dl->idx[i]];
            assert_true(v->x >= 0 && v->x <= WIN_W && v->y >= 0 && v->y <= WIN_H);
            top = fminf(top, v->y), bottom = fmaxf(bottom, v->y);
        }
        assert_true(bottom - top > 2.5f * ui_em(d.ui, 1.0f)); // several rows
        drv_free(&d);
    }
}

// ---- id identity: sections, conflicts -------------------------------------------------

// A brush's Radius and a planet's Radius in one panel, under two sections (the Dock).
typedef struct two_radii {
    double brush, planet;
    int dup; // also two "Go" buttons in one section: a conflict
} two_radii;

static void build_two_radii(drv *d) {
    two_radii *t = d->user;
    ui_panel_begin(d->ui, "Dock", (ui_rect){0, 0, 400, 400});
    ui_row(d->ui, 1, NULL, 0);
    if (ui_section(d->ui, "Raise", 1)) ui_slider(d->ui, "Radius", &t->brush, 0, 500, "%.1f");
    if (ui_section(d->ui, "World", 1)) {
        ui_slider(d->ui, "Radius", &t->planet, 0, 10000, "%.1f");
        if (ui_section(d->ui, "More", 1) && t->dup) { // a section in a section ends it
            ui_button(d->ui, "Go");
            ui_button(d->ui, "Go");
        }
    }
    ui_panel_end(d->ui);
    ui_button(d->ui, "Radius"); // outside the panel: its own id
}

static void test_ids_scoped_by_section(void **state) {
    (void)state;
    two_radii t = {.brush = 40, .planet = 6371};
    drv d;
    drv_init(&d, build_two_radii, &t);
    ui_set_strict_ids(d.ui, 1); // a conflict would abort the test
    frame(&d);
    assert_int_equal(ui_id_conflict_count(d.ui), 0);
    // Both are named Dock/Radius (the names tests use leave sections out); drag the
    // brush's: only the brush's value moves.
    ui_rect rr[2];
    int n = 0;
    for (size_t i = 0; i < ui_widget_count(d.ui); i++)
        if (strcmp(ui_widget_at(d.ui, i)->name, "Dock/Radius") == 0 && n < 2)
            rr[n++] = ui_widget_at(d.ui, i)->rect;
    assert_int_equal(n, 2);
    float cy = rr[0].y + rr[0].h / 2;
    press(&d, rr[0].x + 10, cy);
    drag_to(&d, rr[0].x + 60, cy);
    release(&d, rr[0].x + 60, cy);
    assert_true(t.brush > 40);
    assert_true(t.planet == 6371);
    // And typing into it leaves the planet alone as well.
    d.in.mods = UI_MOD_CTRL;
    click(&d, rr[0].x + 10, cy);
    d.in.mods = 0;
    type(&d, "245.153");
    key(&d, UI_KEY_ENTER, 0);
    assert_true(t.brush == 245.153);
    assert_true(t.planet == 6371);
    drv_free(&d);
}

static void test_id_conflict_reported(void **state) {
    (void)state;
    two_radii t = {.brush = 40, .planet = 6371, .dup = 1};
    drv d;
    drv_init(&d, NULL, &t);
    ui_set_strict_ids(d.ui, 0);
    d.build = build_two_radii;
    frame(&d);
    assert_int_equal(ui_id_conflict_count(d.ui), 1);
    assert_string_equal(ui_id_conflict(d.ui, 0, 0), "Dock/More/Go");
    assert_string_equal(ui_id_conflict(d.ui, 0, 1), "Dock/More/Go");
    assert_null(ui_id_conflict(d.ui, 1, 0));
    t.dup = 0;
    frame(&d);
    assert_int_equal(ui_id_conflict_count(d.ui), 0);
    drv_free(&d);
}

// Strict (debug builds, OROGEN_UI_STRICT=1): the process stops, naming both widgets.
static void test_id_conflict_strict_aborts(void **state) {
    (void)state;
    int fds[2];
    assert_int_equal(pipe(fds), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        dup2(fds[1], 2);
        close(fds[0]);
        two_radii t = {.dup = 1};
        ui_context *ui = ui_create(font);
        ui_set_strict_ids(ui, 1);
        ui_input in = {0};
        drv d = {.ui = ui, .user = &t};
        ui_begin(ui, &in, WIN_W, WIN_H);
        build_two_radii(&d);
        ui_end(ui);
        _exit(0); // not reached
    }
    close(fds[1]);
    char err[1024] = {0};
    size_t got = 0;
    ssize_t k;
    while ((k = read(fds[0], err + got, sizeof err - 1 - got)) > 0)
        got += (size_t)k;
    close(fds[0]);
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT);
    assert_non_null(strstr(err, "\"Dock/More/Go\" and \"Dock/More/Go\""));
}

// ---- the input queue ---------------------------------------------------------------

static ui_event key_event(int key, int code, int down, int mods, double time) {
    return (ui_event){
        .kind = UI_EVENT_KEY, .key = key, .code = code, .down = down, .mods = mods, .time = time};
}
static ui_event text_event(const char *t, double time) {
    ui_event e = {.kind = UI_EVENT_TEXT, .time = time};
    snprintf(e.text, sizeof e.text, "%s", t);
    return e;
}
static ui_event button_event(int down, float x, float y, int mods, double time) {
    return (ui_event){.kind = UI_EVENT_BUTTON,
                      .button = 0,
                      .down = down,
                      .x = x,
                      .y = y,
                      .mods = mods,
                      .time = time};
}
// A key as a window system sends it: press, its text, release.
static void push_typed(ui_input_queue *q, char c, double time) {
    char t[2] = {c, 0};
    ui_event e = key_event(-1, c, 1, 0, time);
    ui_input_queue_push(q, &e);
    e = text_event(t, time);
    ui_input_queue_push(q, &e);
    e = key_event(-1, c, 0, 0, time);
    ui_input_queue_push(q, &e);
}

// Frames from the queue until it is empty; returns how many.
static int run_queue(drv *d, ui_input_queue *q) {
    int frames = 0;
    size_t left = 1;
    while (left > 0 && frames < 1000) {
        left = ui_input_queue_frame(q, ui_wants_keyboard(d->ui), &d->in);
        frame(d);
        frames++;
    }
    return frames;
}

static void test_queue_keeps_every_key_once(void **state) {
    (void)state;
    ui_input_queue *q = malloc(sizeof *q);
    assert_non_null(q);
    ui_input_queue_init(q);
    ui_input in;
    // Five ']' pressed during one slow frame: five frames, one press each, for shortcuts.
    for (int i = 0; i < 5; i++) {
        ui_event e = key_event(-1, ']', 1, 0, i * 0.01);
        ui_input_queue_push(q, &e);
        e = text_event("]", i * 0.01);
        ui_input_queue_push(q, &e);
        e = key_event(-1, ']', 0, 0, i * 0.01);
        ui_input_queue_push(q, &e);
    }
    int presses = 0, frames = 0;
    size_t left = 1;
    while (left > 0) {
        left = ui_input_queue_frame(q, 0, &in);
        int here = 0;
        for (int i = 0; i < in.event_count; i++)
            here += in.events[i].kind == UI_EVENT_KEY && in.events[i].down;
        assert_true(here <= 1);
        presses += here;
        frames++;
    }
    assert_int_equal(presses, 5);
    assert_int_equal(frames, 5);
    // A press and its release in one batch: two frames, the press where it happened.
    ui_event e = {.kind = UI_EVENT_MOVE, .x = 10, .y = 10};
    ui_input_queue_push(q, &e);
    e = button_event(1, 10, 10, 0, 1.0);
    ui_input_queue_push(q, &e);
    e = (ui_event){.kind = UI_EVENT_MOVE, .x = 30, .y = 10};
    ui_input_queue_push(q, &e);
    e = button_event(0, 30, 10, 0, 1.05);
    ui_input_queue_push(q, &e);
    ui_input_queue_frame(q, 0, &in);
    assert_true(in.mouse_pressed[0] && in.mouse_down[0] && !in.mouse_released[0]);
    assert_true(in.mouse_x == 10);
    assert_int_equal(ui_input_queue_frame(q, 0, &in), 0); // the move, then the release
    assert_true(!in.mouse_pressed[0] && in.mouse_released[0] && !in.mouse_down[0]);
    assert_true(in.mouse_x == 30);
    // A second press soon after, near: a double click; a third is not another.
    for (int i = 0; i < 3; i++) {
        e = button_event(1, 30, 11, 0, 2.1 + 0.1 * i);
        ui_input_queue_push(q, &e);
        e = button_event(0, 30, 11, 0, 2.15 + 0.1 * i);
        ui_input_queue_push(q, &e);
        ui_input_queue_frame(q, 0, &in);
        assert_int_equal(in.double_click, i == 1); // the first follows a press far away
        ui_input_queue_frame(q, 0, &in);
    }
    // Thousands of moves with no frame: a press among them is kept.
    for (int i = 0; i < UI_QUEUE_MAX + 100; i++) {
        e = (ui_event){.kind = UI_EVENT_MOVE, .x = (float)i, .y = 5};
        ui_input_queue_push(q, &e);
        if (i == 50) {
            e = button_event(1, 50, 5, 0, 3.0);
            ui_input_queue_push(q, &e);
        }
    }
    int pressed = 0;
    while (ui_input_queue_frame(q, 0, &in) > 0 || in.event_count > 0)
        pressed += in.mouse_pressed[0];
    assert_int_equal(pressed, 1);
    assert_true(q->merged > 0);
    free(q);
}

typedef struct field {
    char text[32];
    slider_state s;
} field;

static void build_field(drv *d) {
    field *f = d->user;
    ui_panel_begin(d->ui, "F", (ui_rect){0, 0, 400, 200});
    ui_row(d->ui, 1, NULL, 0);
    ui_textbox(d->ui, "Name", f->text, sizeof f->text);
    f->s.changes += ui_slider(d->ui, "Value", &f->s.v, f->s.lo, f->s.hi, "%.2f");
    ui_panel_end(d->ui);
}

// Typing into a field during slow frames: every character once, in order; a slider's
// Ctrl+click and the digits after it in one batch: the digits are the field's.
static void test_queue_typing(void **state) {
    (void)state;
    field f = {.s = {.v = 40, .lo = 0, .hi = 500}};
    drv d;
    drv_init(&d, build_field, &f);
    ui_input_queue *q = malloc(sizeof *q);
    assert_non_null(q);
    ui_input_queue_init(q);
    ui_rect r = rect_of(&d, "F/Name");
    ui_event e = button_event(1, r.x + 5, r.y + 5, 0, 0.0);
    ui_input_queue_push(q, &e);
    e = button_event(0, r.x + 5, r.y + 5, 0, 0.05);
    ui_input_queue_push(q, &e);
    for (const char *c = "abc"; *c; c++)
        push_typed(q, *c, 0.1);
    e = key_event(UI_KEY_BACKSPACE, 0, 1, 0, 0.2);
    ui_input_queue_push(q, &e);
    push_typed(q, 'd', 0.3);
    run_queue(&d, q);
    assert_string_equal(f.text, "abd");
    // The slider: Ctrl+click, "150", Enter, then ']' for the viewport, all at once.
    ui_rect sr = rect_of(&d, "F/Value");
    e = button_event(1, sr.x + 5, sr.y + 5, UI_MOD_CTRL, 1.0);
    ui_input_queue_push(q, &e);
    e = button_event(0, sr.x + 5, sr.y + 5, UI_MOD_CTRL, 1.01);
    ui_input_queue_push(q, &e);
    for (const char *c = "150"; *c; c++)
        push_typed(q, *c, 1.02);
    e = key_event(UI_KEY_ENTER, 0, 1, 0, 1.03);
    ui_input_queue_push(q, &e);
    push_typed(q, ']', 1.04);
    int shortcuts = 0; // key presses the UI left for the viewport
    size_t left = 1;
    while (left > 0) {
        left = ui_input_queue_frame(q, ui_wants_keyboard(d.ui), &d.in);
        frame(&d);
        for (int i = 0; i < d.in.event_count; i++)
            if (d.in.events[i].kind == UI_EVENT_KEY && d.in.events[i].down && !ui_took_keys(d.ui))
                shortcuts += d.in.events[i].code == ']' ? 1 : 100; // a digit would be a bug
    }
    assert_true(f.s.v == 150);
    assert_int_equal(shortcuts, 1);
    free(q);
    drv_free(&d);
}

// A menu longer than the window is tall wraps into columns: every item inside the
// window and the popup, each one clickable.
typedef struct long_menu {
    int picked;
} long_menu;

static void build_long_menu(drv *d) {
    long_menu *m = d->user;
    ui_menubar_begin(d->ui, (ui_rect){0, 0, WIN_W, 24});
    if (ui_menu_begin(d->ui, "View")) {
        for (int i = 0; i < 40; i++) {
            char label[32];
            snprintf(label, sizeof label, "Item %d", i);
            if (i % 10 == 9) ui_menu_separator(d->ui);
            if (ui_menu_item(d->ui, label, "Ctrl+1", 1)) m->picked = i;
        }
        ui_menu_end(d->ui);
    }
    ui_menubar_end(d->ui);
}

static void test_menu_wraps_into_columns(void **state) {
    (void)state;
    long_menu m = {-1};
    drv d;
    drv_init(&d, build_long_menu, &m);
    click_widget(&d, "Menu/View");
    frame(&d);
    frame(&d); // sized from the frames before
    float right = 0, first_x = rect_of(&d, "Menu/View/Item 0").x;
    for (int i = 0; i < 40; i++) {
        char name[64];
        snprintf(name, sizeof name, "Menu/View/Item %d", i);
        ui_rect r = rect_of(&d, name);
        if (!rect_within(r, (ui_rect){0, 0, WIN_W, WIN_H}))
            fail_msg("%s at {%g %g %g %g} leaves the window", name, r.x, r.y, r.w, r.h);
        right = fmaxf(right, r.x + r.w);
    }
    assert_true(right > first_x + 2 * rect_of(&d, "Menu/View/Item 0").w); // 3 columns or more
    click_widget(&d, "Menu/View/Item 39");
    assert_int_equal(m.picked, 39);
    drv_free(&d);
}

// Labels in the error colour are the messages the frame shows.
static void build_error_label(drv *d) {
    ui_panel_begin(d->ui, "Import options", (ui_rect){0, 0, 300, 200});
    ui_row(d->ui, 1, NULL, 0);
    ui_label(d->ui, "fine");
    ui_label_colored(d->ui, "x.hgt: over the limit", ui_get_theme(d->ui)->text_error);
    ui_label_wrapped(d->ui,
                     "/a/very/long/path/that/does/not/fit/in/one/row/of/the/panel/at/all.hgt: it "
                     "covers 40000 x 40000 samples of the world (2 m apart), over the limit",
                     ui_get_theme(d->ui)->text_error);
    ui_button(d->ui, "After");
    ui_panel_end(d->ui);
}

static void test_messages_listed(void **state) {
    (void)state;
    drv d;
    drv_init(&d, build_error_label, NULL);
    assert_string_equal(ui_message_at(d.ui, 0)->where, "Import options");
    assert_string_equal(ui_message_at(d.ui, 0)->text, "x.hgt: over the limit");
    assert_int_equal(ui_message_count(d.ui), 2); // the wrapped one is one message, whole
    assert_non_null(strstr(ui_message_at(d.ui, 1)->text, "(2 m apart), over the limit"));
    assert_null(ui_message_at(d.ui, 2));
    // It took several rows: what follows is below them, inside the panel.
    ui_rect after = rect_of(&d, "Import options/After");
    assert_true(after.y > 4 * ui_em(d.ui, 1.4f));
    assert_true(rect_within(after, (ui_rect){0, 0, 300, 200}));
    drv_free(&d);
}

#define T(f) cmocka_unit_test_teardown(f, free_contexts)

int main(void) {
    const struct CMUnitTest tests[] = {
        T(test_font_atlas),
        T(test_curve_editor),
        T(test_tree_and_swatch),
        T(test_font_widths_and_fallback),
        T(test_utf8_decode),
        T(test_font_offset_at),
        T(test_font_errors),
        T(test_ids),
        T(test_ids_scope_is_not_a_label_prefix),
        T(test_ids_hash_suffix),
        T(test_widget_find_by_path),
        T(test_split),
        T(test_split_rounding_tiles_exactly),
        T(test_rows),
        T(test_button),
        T(test_checkbox_and_radio),
        T(test_slider_drag),
        T(test_slider_typing),
        T(test_slider_enter_releases_keyboard),
        T(test_ids_scoped_by_section),
        T(test_id_conflict_reported),
        T(test_id_conflict_strict_aborts),
        T(test_queue_keeps_every_key_once),
        T(test_queue_typing),
        T(test_menu_wraps_into_columns),
        T(test_messages_listed),
        T(test_textbox_focus_and_caret),
        T(test_textbox_select_all_on_click),
        T(test_textbox_selection_and_delete),
        T(test_textbox_word_jumps),
        T(test_textbox_select_all_and_clipboard),
        T(test_textbox_undo),
        T(test_textbox_enter_and_escape),
        T(test_textbox_focus_does_not_hold_the_mouse),
        T(test_textbox_never_overflows),
        T(test_textbox_tab_and_focus_request),
        T(test_clipping),
        T(test_outside_the_clip_draws_nothing),
        T(test_scroll),
        T(test_scroll_nested),
        T(test_menu_items),
        T(test_menu_click_outside),
        T(test_menu_escape_after_text_focus_moved),
        T(test_combo),
        T(test_context_menu_and_range),
        T(test_combo_in_a_modal_dialog),
        T(test_quick_click_on_a_list_over_a_button),
        T(test_tooltip),
        T(test_tooltip_beside_the_dock),
        T(test_long_tooltip_wraps_inside_the_window),
    };
    return cmocka_run_group_tests(tests, load_font, free_font);
}
