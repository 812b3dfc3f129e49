// The renderer's GL foundations on a headless context: the context and feature
// check, shader loading with #include and errors at the original file:line, and
// offscreen targets read back top row first, the anti-aliasing pass.
#include "renderer/antialias.h"
#include "renderer/gl_context.h"
#include "renderer/gl_target.h"
#include "renderer/shader.h"
#include "support/test_support.h"

#include <stdarg.h>
#include <math.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <cmocka.h>

static gl_headless *context;
static char dir[4096]; // this run's shader folder

static int setup_context(void **state) {
    (void)state;
    og_error err = {{0}};
    context = gl_headless_create(&err);
    if (!context) {
        fprintf(stderr, "gl_headless_create: %s\n", err.msg);
        return -1;
    }
    gl_debug_enable();
    snprintf(dir, sizeof dir, "%s", test_tmpdir("gl"));
    return 0;
}

static int teardown_context(void **state) {
    (void)state;
    gl_headless_destroy(context);
    test_rmtree(dir);
    return 0;
}

static void write_shader(const char *name, const char *source) {
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    char *slash = strrchr(path, '/');
    if (slash > path + strlen(dir)) { // a subfolder like inc/
        *slash = '\0';
        mkdir(path, 0755);
        *slash = '/';
    }
    test_write_file(path, source, strlen(source));
}

// Loads a program that must fail and returns its message (static storage).
static const char *load_error(const char *vs, const char *gs, const char *fs) {
    static og_error err;
    memset(&err, 0, sizeof err);
    GLuint program = shader_program_load_gs(dir, vs, gs, fs, &err);
    assert_int_equal(program, 0);
    assert_true(err.msg[0] != '\0');
    assert_null(strchr(err.msg, '\n')); // one line
    print_message("  %s\n", err.msg);
    return err.msg;
}

static void assert_starts_with(const char *s, const char *prefix) {
    if (strncmp(s, prefix, strlen(prefix)) != 0)
        fail_msg("\"%s\" does not start with \"%s\"", s, prefix);
}

static char *path_in_dir(const char *name) {
    static char path[4200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return path;
}

static const char *plain_vert = "#version 450 core\n"
                                "void main() { gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }\n";

static void test_context_is_gl45_core_with_features(void **state) {
    (void)state;
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    print_message("  %s / %s\n", (const char *)glGetString(GL_VERSION),
                  (const char *)glGetString(GL_RENDERER));
    assert_true(major > 4 || (major == 4 && minor >= 5));
    assert_true(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    og_error err = {{0}};
    if (gl_require_features(&err) != 0) fail_msg("%s", err.msg);
    assert_int_equal(gl_check_error("after feature check", &err), 0);
}

static void test_check_error_names_and_drains(void **state) {
    (void)state;
    og_error err = {{0}};
    assert_int_equal(gl_check_error("clean", &err), 0);
    glEnable(0xBEEF); // not a capability
    assert_int_equal(gl_check_error("enable", &err), -1);
    assert_string_equal(err.msg, "enable: GL_INVALID_ENUM (0x500)");
    assert_int_equal(gl_check_error("again", &err), 0);
}

static void test_valid_program_with_nested_includes(void **state) {
    (void)state;
    write_shader("inc/colour.glsl", "vec4 base_colour() { return vec4(1.0, 0.5, 0.25, 1.0); }\n");
    write_shader("lighting.glsl", "#include \"inc/colour.glsl\"\n"
                                  "vec4 lit() { return base_colour() * 0.5; }\n");
    write_shader("ok.frag", "#version 450 core\n"
                            "#include \"lighting.glsl\"\n"
                            "out vec4 colour;\n"
                            "void main() { colour = lit(); }\n");
    write_shader("ok.vert", plain_vert);
    og_error err = {{0}};
    GLuint program = shader_program_load(dir, "ok.vert", "ok.frag", &err);
    if (!program) fail_msg("%s", err.msg);
    assert_true(glIsProgram(program));
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    assert_true(linked);
    glDeleteProgram(program);
    assert_int_equal(gl_check_error("valid program", &err), 0);
}

static void test_error_in_included_file_names_that_file_and_line(void **state) {
    (void)state;
    write_shader("inc/broken.glsl", "// a helper with a mistake\n"
                                    "float helper(float x) {\n"
                                    "    float y = x * 2.0;\n"
                                    "    return y + undefined_thing;\n" // line 4
                                    "}\n");
    write_shader("middle.glsl", "float twice(float x) { return 2.0 * x; }\n"
                                "#include \"inc/broken.glsl\"\n");
    write_shader("uses_broken.frag", "#version 450 core\n"
                                     "\n"
                                     "#include \"middle.glsl\"\n"
                                     "out vec4 colour;\n"
                                     "void main() { colour = vec4(helper(1.0)); }\n");
    write_shader("ok.vert", plain_vert);
    const char *msg = load_error("ok.vert", NULL, "uses_broken.frag");
    char want[4300];
    snprintf(want, sizeof want, "%s:4: error", path_in_dir("inc/broken.glsl"));
    assert_starts_with(msg, want);
    assert_non_null(strstr(msg, "undefined_thing"));

    // The preprocessor's errors map the same way.
    write_shader("inc/stop.glsl", "// fine\n#error stop here\n");
    write_shader("uses_stop.frag", "#version 450 core\n"
                                   "#include \"inc/stop.glsl\"\n"
                                   "out vec4 colour;\n"
                                   "void main() { colour = vec4(1.0); }\n");
    msg = load_error("ok.vert", NULL, "uses_stop.frag");
    snprintf(want, sizeof want, "%s:2: ", path_in_dir("inc/stop.glsl"));
    assert_starts_with(msg, want);
    assert_non_null(strstr(msg, "stop here"));
}

static void test_error_in_main_file_after_include_has_main_line(void **state) {
    (void)state;
    write_shader("five_lines.glsl", "// 1\n// 2\nconst float k = 1.0;\n// 4\n// 5\n");
    write_shader("after.frag", "#version 450 core\n"
                               "#include \"five_lines.glsl\"\n"
                               "out vec4 colour;\n"
                               "void main() {\n"
                               "    colour = vec4(k);\n"
                               "    colour += missing_name;\n" // line 6
                               "}\n");
    write_shader("ok.vert", plain_vert);
    const char *msg = load_error("ok.vert", NULL, "after.frag");
    char want[4300];
    snprintf(want, sizeof want, "%s:6: error", path_in_dir("after.frag"));
    assert_starts_with(msg, want);

    // And in a file with no include: the #line after #version keeps numbers right.
    write_shader("no_include.vert", "#version 450 core\n"
                                    "void main() {\n"
                                    "    gl_Position = vec4(0.0);\n"
                                    "    gl_Position.x = nope;\n" // line 4
                                    "}\n");
    write_shader("ok.frag", "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
    msg = load_error("no_include.vert", NULL, "ok.frag");
    snprintf(want, sizeof want, "%s:4: error", path_in_dir("no_include.vert"));
    assert_starts_with(msg, want);
}

// Defines land after #version in both stages; errors keep the files' own lines.
static void test_variant_defines(void **state) {
    (void)state;
    write_shader("variant.frag", "#version 450 core\n"
                                 "out vec4 colour;\n"
                                 "void main() {\n"
                                 "#if defined(RED) && defined(STAGE_SEEN)\n"
                                 "    colour = vec4(1.0, 0.0, 0.0, 1.0);\n"
                                 "#else\n"
                                 "    colour = not_red;\n" // line 7
                                 "#endif\n"
                                 "}\n");
    write_shader("variant.vert", "#version 450 core\n"
                                 "#ifndef RED\n"
                                 "#error the vertex stage lacks the define\n"
                                 "#endif\n"
                                 "void main() { gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }\n");
    write_shader("ok.vert", plain_vert);
    write_shader("ok.frag", "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
    og_error err = {{0}};
    GLuint program = shader_program_load_variant(dir, "variant.vert", "variant.frag",
                                                 "#define RED\n#define STAGE_SEEN", &err);
    if (!program) fail_msg("%s", err.msg);
    glDeleteProgram(program);
    memset(&err, 0, sizeof err);
    program = shader_program_load_variant(dir, "ok.vert", "variant.frag", "#define RED\n", &err);
    assert_int_equal(program, 0);
    char want[4300];
    snprintf(want, sizeof want, "%s:7: error", path_in_dir("variant.frag"));
    assert_starts_with(err.msg, want);
    memset(&err, 0, sizeof err);
    program = shader_program_load_variant(dir, "variant.vert", "ok.frag", NULL, &err);
    assert_int_equal(program, 0);
    snprintf(want, sizeof want, "%s:3: ", path_in_dir("variant.vert"));
    assert_starts_with(err.msg, want);
}

// Builds vs + fs with every combination of the defines (one per bit of the variant).
static void compile_all_variants(const char *vs, const char *fs, const char *const *names,
                                 int count) {
    char shaders[4200];
    snprintf(shaders, sizeof shaders, "%s/shaders", OROGEN_RESOURCE_DIR);
    for (int v = 0; v < 1 << count; v++) {
        og_error err = {{0}};
        GLuint program =
            shader_program_load_flags(shaders, vs, fs, names, count, (unsigned)v, &err);
        if (!program) fail_msg("%s variant %d: %s", fs, v, err.msg);
        glDeleteProgram(program);
    }
}

// The planet's ground and the flat terrain compile in every variant their renderers
// can ask for (renderer/planet_renderer.c, renderer/terrain_renderer.c).
static void test_shader_variants_compile(void **state) {
    (void)state;
    static const char *const planet[] = {"SHADED", "DETAIL", "SEA",      "PAINTED",
                                         "BARE",   "BRUSH",  "OVERLAYS", "MINIFIED"};
    compile_all_variants("planet.vert", "planet.frag", planet, 8);
    static const char *const terrain[] = {"SHADED", "DETAIL",   "PAINTED",
                                          "BRUSH",  "OVERLAYS", "CONTOURS"};
    compile_all_variants("terrain.vert", "terrain.frag", terrain, 6);
    // The deferred passes (renderer/deferred_target.h): the shading pass with each
    // per-level define alone and all together, and the depth pass.
    char shaders[4200];
    snprintf(shaders, sizeof shaders, "%s/shaders", OROGEN_RESOURCE_DIR);
    static const char *const resolve[] = {"RESOLVE",  "SHADED",    "DETAIL",   "PAINTED",
                                          "BRUSH",    "OVERLAYS",  "CONTOURS", "MINIFIED",
                                          "NO_MORPH", "CURVATURE", "SLOPES_A", "SLOPES_B"};
    const int count = (int)(sizeof resolve / sizeof *resolve);
    for (int b = 1; b <= count; b++) {
        unsigned flags = b == count ? (1u << count) - 1 : 3u | (1u << b);
        og_error err = {{0}};
        GLuint program = shader_program_load_flags(shaders, "fullscreen.vert", "terrain.frag",
                                                   resolve, count, flags, &err);
        if (!program) fail_msg("terrain.frag resolve variant %#x: %s", flags, err.msg);
        glDeleteProgram(program);
    }
    static const char *const depth[] = {"GBUFFER", "NO_MORPH", "VOLUME"};
    for (unsigned flags = 1; flags < 8; flags += 2) {
        og_error err = {{0}};
        GLuint program = shader_program_load_flags(shaders, "terrain.vert", "terrain.frag", depth,
                                                   3, flags, &err);
        if (!program) fail_msg("terrain.frag depth variant %#x: %s", flags, err.msg);
        glDeleteProgram(program);
    }
    // Refined parts (renderer/clip_refine.h), with and without the morph band, drawn
    // directly or into the depth pass.
    static const char *const refined[] = {"REFINED", "NO_MORPH", "GBUFFER", "SHADED"};
    compile_all_variants("terrain.vert", "terrain.frag", refined, 4);
    // Their seams (renderer/clip_refine_mesh.h), in the same variants.
    static const char *const seams[] = {"NO_MORPH", "GBUFFER", "SHADED", "REFINED", "SEAM"};
    for (unsigned flags = 0; flags < 8; flags++) {
        og_error err = {{0}};
        GLuint program = shader_program_load_flags(shaders, "terrain.vert", "terrain.frag", seams,
                                                   5, flags | 8u | 16u, &err);
        if (!program) fail_msg("terrain.frag seam variant %#x: %s", flags, err.msg);
        glDeleteProgram(program);
    }
}

static void test_missing_files(void **state) {
    (void)state;
    write_shader("ok.frag", "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
    const char *msg = load_error("nowhere.vert", NULL, "ok.frag");
    char want[4300];
    snprintf(want, sizeof want, "%s: cannot open: No such file or directory",
             path_in_dir("nowhere.vert"));
    assert_string_equal(msg, want);

    write_shader("includes_missing.vert", "#version 450 core\n"
                                          "#include \"gone.glsl\"\n"
                                          "void main() { gl_Position = vec4(0.0); }\n");
    msg = load_error("includes_missing.vert", NULL, "ok.frag");
    snprintf(want, sizeof want, "%s: cannot open: ", path_in_dir("gone.glsl"));
    assert_starts_with(msg, want);
    snprintf(want, sizeof want, "(included from %s:2)", path_in_dir("includes_missing.vert"));
    assert_non_null(strstr(msg, want));
}

static void test_include_cycle_and_depth(void **state) {
    (void)state;
    write_shader("ok.frag", "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
    write_shader("cycle_a.glsl", "// a\n#include \"cycle_b.glsl\"\n");
    write_shader("cycle_b.glsl", "// b\n// b\n#include \"cycle_a.glsl\"\n");
    write_shader("cycle.vert", "#version 450 core\n"
                               "#include \"cycle_a.glsl\"\n"
                               "void main() { gl_Position = vec4(0.0); }\n");
    const char *msg = load_error("cycle.vert", NULL, "ok.frag");
    char want[4300];
    snprintf(want, sizeof want, "%s:3: error: #include cycle", path_in_dir("cycle_b.glsl"));
    assert_starts_with(msg, want);

    // A chain of 8 includes is fine; a 9th nests too deep.
    for (int i = 1; i <= 9; i++) {
        char name[32], source[64];
        snprintf(name, sizeof name, "depth%d.glsl", i);
        if (i < 9)
            snprintf(source, sizeof source, "// %d\n#include \"depth%d.glsl\"\n", i, i + 1);
        else
            snprintf(source, sizeof source, "// the ninth\n");
        write_shader(name, source);
    }
    write_shader("depth8.glsl", "// the eighth, last allowed\n");
    write_shader("deep.vert", "#version 450 core\n"
                              "#include \"depth1.glsl\"\n"
                              "void main() { gl_Position = vec4(0.0); }\n");
    og_error err = {{0}};
    GLuint program = shader_program_load(dir, "deep.vert", "ok.frag", &err);
    if (!program) fail_msg("%s", err.msg);
    glDeleteProgram(program);
    write_shader("depth8.glsl", "// 8\n#include \"depth9.glsl\"\n");
    msg = load_error("deep.vert", NULL, "ok.frag");
    snprintf(want, sizeof want, "%s:2: error: #include \"depth9.glsl\" nests deeper than 8",
             path_in_dir("depth8.glsl"));
    assert_starts_with(msg, want);

    write_shader("versioned.glsl", "#version 450 core\n");
    write_shader("two_versions.vert", "#version 450 core\n"
                                      "#include \"versioned.glsl\"\n"
                                      "void main() { gl_Position = vec4(0.0); }\n");
    msg = load_error("two_versions.vert", NULL, "ok.frag");
    snprintf(want, sizeof want, "%s:1: error: #version", path_in_dir("versioned.glsl"));
    assert_starts_with(msg, want);
}

static void test_link_error_names_both_files(void **state) {
    (void)state;
    write_shader("ok.vert", plain_vert);
    write_shader("needs_normal.frag", "#version 450 core\n"
                                      "in vec3 v_normal;\n"
                                      "out vec4 colour;\n"
                                      "void main() { colour = vec4(v_normal, 1.0); }\n");
    const char *msg = load_error("ok.vert", NULL, "needs_normal.frag");
    char both[8500];
    snprintf(both, sizeof both, "%s, ", path_in_dir("ok.vert"));
    snprintf(both + strlen(both), sizeof both - strlen(both),
             "%s: link error: ", path_in_dir("needs_normal.frag"));
    assert_starts_with(msg, both);
    assert_non_null(strstr(msg, "v_normal"));
}

static void test_geometry_stage(void **state) {
    (void)state;
    write_shader("ok.vert", plain_vert);
    write_shader("ok.frag", "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
    write_shader("pass.geom", "#version 450 core\n"
                              "layout(triangles) in;\n"
                              "layout(triangle_strip, max_vertices = 3) out;\n"
                              "void main() {\n"
                              "    for (int i = 0; i < 3; i++) {\n"
                              "        gl_Position = gl_in[i].gl_Position;\n"
                              "        EmitVertex();\n"
                              "    }\n"
                              "}\n");
    og_error err = {{0}};
    GLuint program = shader_program_load_gs(dir, "ok.vert", "pass.geom", "ok.frag", &err);
    if (!program) fail_msg("%s", err.msg);
    glDeleteProgram(program);

    write_shader("broken.geom", "#version 450 core\n"
                                "layout(triangles) in;\n"
                                "layout(triangle_strip, max_vertices = 3) out;\n"
                                "void main() { EmitVertex(); oops }\n");
    const char *msg = load_error("ok.vert", "broken.geom", "ok.frag");
    char want[4300];
    snprintf(want, sizeof want, "%s:4: ", path_in_dir("broken.geom"));
    assert_starts_with(msg, want);
}

static void test_target_rejects_bad_sizes(void **state) {
    (void)state;
    const int sizes[][2] = {{0, 10}, {10, 0}, {-1, 5}, {16385, 4}, {4, 16385}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        gl_target t;
        og_error err = {{0}};
        assert_int_equal(gl_target_create(&t, sizes[i][0], sizes[i][1], &err), -1);
        assert_non_null(strstr(err.msg, "sizes must be 1.."));
        assert_int_equal(t.fbo, 0);
    }
}

enum { TW = 16, TH = 10 };

static void assert_pixel(const unsigned char *rgb, int x, int y, int r, int g, int b) {
    const unsigned char *p = rgb + 3 * ((size_t)y * TW + (size_t)x);
    if (p[0] != r || p[1] != g || p[2] != b)
        fail_msg("pixel (%d, %d) from the top is %d %d %d, expected %d %d %d", x, y, p[0], p[1],
                 p[2], r, g, b);
}

static void test_target_reads_top_row_first(void **state) {
    (void)state;
    gl_target t;
    og_error err = {{0}};
    if (gl_target_create(&t, TW, TH, &err) != 0) fail_msg("%s", err.msg);
    assert_int_equal(t.width, TW);
    assert_int_equal(t.height, TH);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t.fbo);
    glViewport(0, 0, TW, TH);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, TH / 2, TW, TH - TH / 2); // GL's y is up: the top half
    glClearColor(1, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glScissor(0, 0, TW, TH / 2);
    glClearColor(0, 0, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);

    unsigned char rgb[TW * TH * 3];
    memset(rgb, 0x55, sizeof rgb);
    if (gl_target_read_rgb(&t, rgb, &err) != 0) fail_msg("%s", err.msg);
    for (int y = 0; y < TH; y++)
        for (int x = 0; x < TW; x++)
            y < TH / 2 ? assert_pixel(rgb, x, y, 255, 0, 0) : assert_pixel(rgb, x, y, 0, 0, 255);
    gl_target_destroy(&t);
    assert_int_equal(t.fbo, 0);
    assert_int_equal(gl_check_error("scissor clears", &err), 0);
}

// Fills rows [0, below) of columns [x0, x1) white, as GL counts rows (bottom up).
static void white_below(int x0, int x1, int below) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(x0, 0, x1 - x0, below);
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
}

// A nearly horizontal edge with a one-pixel step (as the horizon makes): the pass turns
// the step into a ramp of greys along the edge, leaves flat areas exactly as they were
// and keeps the image's mean; a flat image comes out unchanged.
static void test_antialias_smooths_a_stepped_edge(void **state) {
    (void)state;
    enum { W = 64, H = 32 };
    og_error err = {{0}};
    char shaders[4200];
    snprintf(shaders, sizeof shaders, "%s/shaders", OROGEN_RESOURCE_DIR);
    antialias *aa = antialias_create(shaders, &err);
    if (!aa) fail_msg("%s", err.msg);
    gl_target src, dst;
    if (gl_target_create(&src, W, H, &err) != 0 || gl_target_create(&dst, W, H, &err) != 0)
        fail_msg("%s", err.msg);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, src.fbo);
    glViewport(0, 0, W, H);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    white_below(0, W / 2, 12);
    white_below(W / 2, W, 13);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    if (antialias_apply(aa, &src, &dst, &err) != 0) fail_msg("%s", err.msg);
    static unsigned char before[W * H * 3], after[W * H * 3];
    if (gl_target_read_rgb(&src, before, &err) != 0 || gl_target_read_rgb(&dst, after, &err) != 0)
        fail_msg("%s", err.msg);
    long sum_before = 0, sum_after = 0;
    int greys = 0;
    for (int i = 0; i < W * H * 3; i++)
        sum_before += before[i], sum_after += after[i];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int v = after[(y * W + x) * 3];
            int rows_from_edge = abs((H - 1 - y) - 12); // the edge lies between rows 11 and 13
            if (rows_from_edge > 2 && v != before[(y * W + x) * 3])
                fail_msg("pixel (%d, %d) far from the edge changed: %d", x, y, v);
            if (v > 20 && v < 235 && abs(x - W / 2) <= 16) greys++;
        }
    if (greys < 8) fail_msg("only %d grey pixels along the step", greys);
    double drift = fabs((double)(sum_after - sum_before)) / (double)sum_before;
    if (drift > 0.02) fail_msg("the image's mean moved by %.1f%%", 100 * drift);

    // A flat image: nothing to smooth.
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, src.fbo);
    glClearColor(0.3f, 0.5f, 0.7f, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    if (antialias_apply(aa, &src, &dst, &err) != 0) fail_msg("%s", err.msg);
    if (gl_target_read_rgb(&src, before, &err) != 0 || gl_target_read_rgb(&dst, after, &err) != 0)
        fail_msg("%s", err.msg);
    assert_memory_equal(before, after, sizeof before);

    // Targets of different sizes are refused by name.
    gl_target small;
    if (gl_target_create(&small, 8, 8, &err) != 0) fail_msg("%s", err.msg);
    assert_int_equal(antialias_apply(aa, &src, &small, &err), -1);
    assert_starts_with(err.msg, "anti-aliasing: the images must");
    gl_target_destroy(&small);
    gl_target_destroy(&src);
    gl_target_destroy(&dst);
    antialias_destroy(aa);
    assert_int_equal(gl_check_error("anti-aliasing", &err), 0);
}

// A green triangle over the lower-left half at depth 0.75, then a red full-screen
// triangle behind it (reversed-Z: 0.25 is farther): red must only fill the rest.
static void test_target_renders_triangle_with_reversed_z(void **state) {
    (void)state;
    write_shader("flat.glsl", "uniform vec4 u_colour;\n");
    write_shader("tri.vert",
                 "#version 450 core\n"
                 "uniform vec2 u_corners[3];\n"
                 "uniform float u_depth;\n"
                 "void main() { gl_Position = vec4(u_corners[gl_VertexID], u_depth, 1.0); }\n");
    write_shader("tri.frag", "#version 450 core\n"
                             "#include \"flat.glsl\"\n"
                             "out vec4 colour;\n"
                             "void main() { colour = u_colour; }\n");
    og_error err = {{0}};
    GLuint program = shader_program_load(dir, "tri.vert", "tri.frag", &err);
    if (!program) fail_msg("%s", err.msg);
    gl_target t;
    if (gl_target_create(&t, TW, TH, &err) != 0) fail_msg("%s", err.msg);
    GLuint vao;
    glCreateVertexArrays(1, &vao); // core profile draws need one, even without attributes

    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t.fbo);
    glViewport(0, 0, TW, TH);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glClearDepth(0.0);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(program);
    glBindVertexArray(vao);
    GLint corners = glGetUniformLocation(program, "u_corners");
    GLint depth = glGetUniformLocation(program, "u_depth");
    GLint colour = glGetUniformLocation(program, "u_colour");
    assert_true(corners >= 0 && depth >= 0 && colour >= 0);
    const float lower_left[6] = {-1, -1, 1, -1, -1, 1}, everything[6] = {-1, -1, 3, -1, -1, 3};
    glUniform2fv(corners, 3, lower_left);
    glUniform1f(depth, 0.75f);
    glUniform4f(colour, 0, 1, 0, 1);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glUniform2fv(corners, 3, everything);
    glUniform1f(depth, 0.25f);
    glUniform4f(colour, 1, 0, 0, 1);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    assert_int_equal(gl_check_error("triangle", &err), 0);

    unsigned char rgb[TW * TH * 3];
    if (gl_target_read_rgb(&t, rgb, &err) != 0) fail_msg("%s", err.msg);
    int green = 0, red = 0;
    for (int y = 0; y < TH; y++) {
        for (int x = 0; x < TW; x++) {
            // Pixel centre in NDC, with y up; the green triangle is x + y < 0.
            float nx = (x + 0.5f) / TW * 2 - 1, ny = 1 - (y + 0.5f) / TH * 2;
            if (nx + ny < -0.15f)
                assert_pixel(rgb, x, y, 0, 255, 0), green++;
            else if (nx + ny > 0.15f)
                assert_pixel(rgb, x, y, 255, 0, 0), red++;
        }
    }
    assert_true(green > TW * TH / 4 && red > TW * TH / 4);
    assert_pixel(rgb, 0, TH - 1, 0, 255, 0); // bottom-left is green: rows come top first
    assert_pixel(rgb, TW - 1, 0, 255, 0, 0);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(program);
    gl_target_destroy(&t);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_context_is_gl45_core_with_features),
        cmocka_unit_test(test_check_error_names_and_drains),
        cmocka_unit_test(test_valid_program_with_nested_includes),
        cmocka_unit_test(test_error_in_included_file_names_that_file_and_line),
        cmocka_unit_test(test_error_in_main_file_after_include_has_main_line),
        cmocka_unit_test(test_variant_defines),
        cmocka_unit_test(test_shader_variants_compile),
        cmocka_unit_test(test_missing_files),
        cmocka_unit_test(test_include_cycle_and_depth),
        cmocka_unit_test(test_link_error_names_both_files),
        cmocka_unit_test(test_geometry_stage),
        cmocka_unit_test(test_target_rejects_bad_sizes),
        cmocka_unit_test(test_target_reads_top_row_first),
        cmocka_unit_test(test_antialias_smooths_a_stepped_edge),
        cmocka_unit_test(test_target_renders_triangle_with_reversed_z),
    };
    return cmocka_run_group_tests(tests, setup_context, teardown_context);
}
