// The editor UI's cost against the terrain's, in one run (issue 11's goals):
//  1. CPU time to build the whole editor UI and its draw list per frame (median, 99th
//     percentile; goal: median under 1 ms), against one terrain frame at 1280 x 800.
//  2. Wall time of a UI-only frame (the terrain image reused: blit + UI draw) against a
//     full terrain frame, both at 1280 x 800 (goal: under 10 ms on llvmpipe).
// The pointer sweeps over the panels while the UI is built, as a user's would.
#include "app/editor_ui.h"
#include "bench_timing.h"
#include "editor/cmd/commands.h"
#include "renderer/gl_target.h"
#include "renderer/ui_renderer.h"
#include "renderer/view_commands.h"
#include "renderer/viewport.h"

#include <epoxy/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define WIDTH 1280
#define HEIGHT 800

static void check(int rc, const og_error *err, const char *what) {
    if (rc != 0) {
        fprintf(stderr, "bench_ui: %s: %s\n", what, err->msg);
        exit(1);
    }
}

static double percentile(double *v, int n, double p) {
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    int i = (int)(p * (n - 1) + 0.5);
    return v[i];
}

int main(void) {
    og_error err = {{0}};
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    world *w = world_create(&p, NULL, &err);
    if (!w) check(-1, &err, "world");
    cmd_context ctx;
    FILE *sink = fopen("/dev/null", "w");
    cmd_context_init(&ctx, w, NULL, sink, OROGEN_RESOURCE_DIR);
    check(view_commands_register(&err), &err, "commands");
    viewport *v = view_commands_viewport(&ctx);
    check(viewport_prepare(v, &err), &err, "GL (headless EGL)");
    check(viewport_default_camera(v, w, &err), &err, "camera");
    check(viewport_settle(v, w, &err), &err, "tiles");

    char why[512];
    ui_font *font =
        ui_font_create("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
                       "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf", 15, why, sizeof why);
    if (!font) {
        fprintf(stderr, "bench_ui: font: %s\n", why);
        return 1;
    }
    ui_context *ui = ui_create(font);
    editor_ui ed;
    editor_ui_init(&ed);
    ed.console.open = 1; // the heaviest layout: every panel and the console
    for (int i = 0; i < 200; i++)
        console_add(&ed.console, CONSOLE_OUTPUT, "a line of output");
    editor_frame_info info = {.frame_ms = 100, .resolution_scale = 1, .gl_renderer = "bench"};

    // 1. Building the UI.
    enum { FRAMES = 2000 };
    static double build_ms[FRAMES];
    ui_input in = {0};
    ui_rect view = {0};
    size_t vertices = 0;
    for (int f = 0; f < FRAMES; f++) {
        in.mouse_x = (float)(f * 7 % WIDTH);
        in.mouse_y = (float)(f * 3 % HEIGHT);
        in.time = f / 60.0;
        double t0 = bench_now();
        ui_begin(ui, &in, WIDTH, HEIGHT);
        view = editor_ui_build(&ed, ui, &ctx, v, &info, WIDTH, HEIGHT);
        const ui_draw_list *dl = ui_end(ui);
        build_ms[f] = (bench_now() - t0) * 1e3;
        vertices = dl->vtx_count;
    }
    double build_median = bench_median(build_ms, FRAMES);
    double build_p99 = percentile(build_ms, FRAMES, 0.99);

    // 2. Frames: the terrain at the viewport's size, and the UI-only frame.
    gl_target screen = {0}, terrain = {0};
    int vw = (int)view.w, vh = (int)view.h;
    check(gl_target_create(&screen, WIDTH, HEIGHT, &err), &err, "screen target");
    check(gl_target_create(&terrain, vw, vh, &err), &err, "terrain target");
    ui_renderer *uir = ui_renderer_create(OROGEN_RESOURCE_DIR, &err);
    if (!uir) check(-1, &err, "ui renderer");
    enum { RUNS = 9 };
    double terrain_ms[RUNS], ui_ms[RUNS], full_ms[RUNS];
    for (int r = 0; r < RUNS; r++) {
        glFinish();
        double t0 = bench_now();
        glBindFramebuffer(GL_FRAMEBUFFER, terrain.fbo);
        check(terrain_renderer_draw(v->renderer, w, &v->cam, &v->settings, NULL, vw, vh, &err),
              &err, "terrain");
        glFinish();
        terrain_ms[r] = (bench_now() - t0) * 1e3;

        ui_begin(ui, &in, WIDTH, HEIGHT);
        editor_ui_build(&ed, ui, &ctx, v, &info, WIDTH, HEIGHT);
        const ui_draw_list *dl = ui_end(ui);
        t0 = bench_now();
        glBindFramebuffer(GL_FRAMEBUFFER, screen.fbo);
        glViewport(0, 0, WIDTH, HEIGHT);
        glClear(GL_COLOR_BUFFER_BIT);
        glBlitNamedFramebuffer(terrain.fbo, screen.fbo, 0, 0, vw, vh, (int)view.x,
                               HEIGHT - (int)(view.y + view.h), (int)(view.x + view.w),
                               HEIGHT - (int)view.y, GL_COLOR_BUFFER_BIT, GL_LINEAR);
        check(ui_renderer_draw(uir, dl, font, WIDTH, HEIGHT, &err), &err, "ui draw");
        glFinish();
        ui_ms[r] = (bench_now() - t0) * 1e3;
        full_ms[r] = terrain_ms[r] + ui_ms[r];
    }
    double terrain_median = bench_median(terrain_ms, RUNS), ui_median = bench_median(ui_ms, RUNS);
    double full_median = bench_median(full_ms, RUNS);

    printf("GL renderer: %s\n", (const char *)glGetString(GL_RENDERER));
    printf("1. Building the editor UI and its draw list (%d frames, %zu vertices):\n", FRAMES,
           vertices);
    printf("   median %.3f ms, 99th percentile %.3f ms (goal: median < 1 ms)\n", build_median,
           build_p99);
    printf("   one terrain frame (%d x %d viewport): %.1f ms  -> the UI costs %.2f%% of it\n", vw,
           vh, terrain_median, 100.0 * build_median / terrain_median);
    printf("2. Frames at %d x %d (medians of %d):\n", WIDTH, HEIGHT, RUNS);
    printf("   UI-only frame (terrain image reused: blit + UI draw): %.2f ms (goal < 10 ms)\n",
           ui_median);
    printf("   full frame (terrain rendered + UI):                   %.1f ms  -> %.1fx faster\n",
           full_median, full_median / ui_median);

    // 3. Dynamic resolution: the terrain frame while moving, at the scales the window
    // picks from (it aims at 50 ms), against full resolution. Each run moves the camera.
    printf("3. Terrain frame while the camera moves (median of %d), by resolution scale:\n", RUNS);
    static const float scales[] = {1.0f, 0.7f, 0.5f, 0.35f, 0.25f};
    for (size_t k = 0; k < sizeof scales / sizeof scales[0]; k++) {
        int sw = (int)(vw * scales[k]), sh = (int)(vh * scales[k]);
        gl_target t = {0};
        check(gl_target_create(&t, sw, sh, &err), &err, "scaled target");
        double ms[RUNS];
        for (int r = 0; r < RUNS; r++) {
            v->cam.yaw += 0.5; // orbit a little: the clipmaps stay current
            check(terrain_renderer_update(v->renderer, w, &v->cam, &v->settings, &err) < 0 ? -1 : 0,
                  &err, "update");
            glFinish();
            double t0 = bench_now();
            glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
            check(terrain_renderer_draw(v->renderer, w, &v->cam, &v->settings, NULL, sw, sh, &err),
                  &err, "terrain");
            glFinish();
            ms[r] = (bench_now() - t0) * 1e3;
        }
        double m = bench_median(ms, RUNS);
        printf("   scale %.2f (%4d x %4d): %6.1f ms%s\n", scales[k], sw, sh, m,
               m <= 50 ? "  (within the 50 ms target)" : "");
        gl_target_destroy(&t);
    }

    ui_renderer_destroy(uir);
    gl_target_destroy(&screen);
    gl_target_destroy(&terrain);
    editor_ui_free(&ed);
    ui_destroy(ui);
    ui_font_destroy(font);
    viewport_destroy(v);
    world_close(ctx.world);
    fclose(sink);
    return 0;
}
