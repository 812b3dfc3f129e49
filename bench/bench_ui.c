// The editor UI's cost against the terrain's, in one run (issue 11's goals):
//  1. CPU time to build the whole editor UI and its draw list per frame (median, 99th
//     percentile; goal: median under 1 ms), against one terrain frame at 1280 x 800.
//  2. Wall time of a UI-only frame (the terrain image reused: blit + UI draw) against a
//     full terrain frame, both at 1280 x 800 (goal: under 10 ms on llvmpipe).
//  3. Terrain frames while orbiting, with the window's dynamic-resolution controller
//     (goal: under its 50 ms target) against fixed full resolution.
//  4. Latency from a mouse move to the frame that shows its dab, through the window's
//     path (work queue, change notifications, clipmap update, a frame at the moving
//     scale), against that frame's own time (goal: within 2 frames, no input lost).
//  5. Time from a mouse release (the stroke's end) to the final full-resolution,
//     smoothed image, in frames and ms, against one such frame (goal: within 2 frames
//     of the last change).
// The pointer sweeps over the panels while the UI is built, as a user's would.
#include "app/dynamic_resolution.h"
#include "app/editor_ui.h"
#include "bench_journals.h"
#include "bench_timing.h"
#include "editor/cmd/commands.h"
#include "renderer/gl_target.h"
#include "renderer/ui_renderer.h"
#include "view/view_commands.h"
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
    bench_journals_private(); // no crash journals left in the user's folder
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
    editor_ui *ed = editor_ui_create();
    if (!ed) {
        fprintf(stderr, "bench_ui: out of memory\n");
        return 1;
    }
    editor_ui_console(ed)->open = 1; // the heaviest layout: every panel and the console
    for (int i = 0; i < 200; i++)
        console_add(editor_ui_console(ed), CONSOLE_OUTPUT, "a line of output");
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
        view = editor_ui_build(ed, ui, &ctx, v, &info, WIDTH, HEIGHT);
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
        editor_ui_build(ed, ui, &ctx, v, &info, WIDTH, HEIGHT);
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

    // 3. Orbiting: each frame turns the camera, brings the clipmaps up to date and draws;
    // the window's controller picks the scale from the last frame's time.
    enum { ORBIT = 40 };
    double fixed_ms[ORBIT], dyn_ms[ORBIT];
    float scale = 1.0f, scale_sum = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (int f = 0; f < ORBIT; f++) {
            v->cam.yaw += 1.0; // a degree a frame
            check(terrain_renderer_update(v->renderer, w, &v->cam, &v->settings, &err) < 0 ? -1 : 0,
                  &err, "update");
            float s = pass == 0 ? 1.0f : scale;
            int sw = (int)(vw * s), sh = (int)(vh * s);
            gl_target t = {0};
            check(gl_target_create(&t, sw, sh, &err), &err, "scaled target");
            glFinish();
            double t0 = bench_now();
            glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
            check(terrain_renderer_draw(v->renderer, w, &v->cam, &v->settings, NULL, sw, sh, &err),
                  &err, "terrain");
            glFinish();
            double ms = (bench_now() - t0) * 1e3;
            gl_target_destroy(&t);
            if (pass == 0) {
                fixed_ms[f] = ms;
            } else {
                dyn_ms[f] = ms;
                scale_sum += s;
                scale = dynamic_resolution_next(scale, ms, 50.0);
            }
        }
    }
    // The first frames find the scale: the steady state is what a user feels.
    double fixed_med = bench_median(fixed_ms, ORBIT), fixed_p90 = percentile(fixed_ms, ORBIT, 0.9);
    double dyn_med = bench_median(dyn_ms + 10, ORBIT - 10);
    double dyn_p90 = percentile(dyn_ms + 10, ORBIT - 10, 0.9);
    printf("3. Orbiting a degree a frame (%d frames, %d x %d viewport):\n", ORBIT, vw, vh);
    printf("   fixed full resolution:          median %6.1f ms, 90th percentile %6.1f ms\n",
           fixed_med, fixed_p90);
    printf("   dynamic resolution (50 ms goal): median %6.1f ms, 90th percentile %6.1f ms "
           "(after 10 frames; mean scale %.2f) -> %.1fx faster%s\n",
           dyn_med, dyn_p90, scale_sum / ORBIT, fixed_med / dyn_med,
           dyn_med <= 50 ? ", within the target" : "");

    // 4. Mouse move to the frame that shows the dab: the window's path for one stroke
    // point, then frames at the moving scale until the picture changes.
    console con;
    console_init(&con);
    work_queue q;
    work_queue_init(&q, &ctx, &con, NULL, NULL);
    world_subscription *changes = world_events_subscribe(world_event_hub(w), NULL, NULL);
    // Dry land in view (a dab under the water plane would not show).
    double hit[3];
    int found = 0;
    for (int k = 0; k < 64 && !found; k++)
        found = viewport_pick_loaded(v, w, 0.1 + 0.1 * (k % 8), 0.3 + 0.08 * (k / 8),
                                     (double)vw / vh, hit) == 0 &&
                hit[1] > world_get_params(w)->ocean_level + 50;
    if (!found) {
        fprintf(stderr, "bench_ui: no dry land in view\n");
        return 1;
    }
    og_error ignored = {{0}};
    const char *setup = "tool raise radius=40 strength=1 amount=20; stroke_begin";
    check(cmd_run(&ctx, setup, strlen(setup), "bench", &err), &err, "stroke_begin");
    int sw = (int)(vw * scale), sh = (int)(vh * scale);
    gl_target t = {0};
    check(gl_target_create(&t, sw, sh, &err), &err, "latency target");
    unsigned char *before = malloc((size_t)sw * sh * 4), *after = malloc((size_t)sw * sh * 4);
    enum { DABS = 15 };
    double latency_ms[DABS], frame_ms[DABS];
    int frames_needed[DABS];
    for (int d = 0; d < DABS; d++) {
        // The picture before the mouse moves.
        terrain_renderer_update(v->renderer, w, &v->cam, &v->settings, &err);
        glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
        terrain_renderer_draw(v->renderer, w, &v->cam, &v->settings, NULL, sw, sh, &err);
        glReadPixels(0, 0, sw, sh, GL_RGBA, GL_UNSIGNED_BYTE, before);
        world_event ev[64];
        while (world_subscription_take(changes, ev, 64) > 0) {
        }
        // Around the picked point (5 x 3 spots 25 m apart): every dab is in view.
        cmd_stroke_point pt = {hit[0] + 25.0 * (d % 5 - 2), 0, hit[2] + 25.0 * (d / 5 - 1), 0};
        double t0 = bench_now(), shown = 0, one_frame = 0;
        work_queue_add_point(&q, &pt);
        while (!work_queue_idle(&q))
            work_queue_pump(&q, 30);
        frames_needed[d] = 0;
        for (int f = 1; f <= 10 && !shown; f++) { // the window's frames after the event
            double f0 = bench_now();
            while (world_subscription_take(changes, ev, 64) > 0) {
            }
            terrain_renderer_update(v->renderer, w, &v->cam, &v->settings, &err);
            glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
            terrain_renderer_draw(v->renderer, w, &v->cam, &v->settings, NULL, sw, sh, &err);
            glReadPixels(0, 0, sw, sh, GL_RGBA, GL_UNSIGNED_BYTE, after);
            if (f == 1) one_frame = (bench_now() - f0) * 1e3;
            if (memcmp(before, after, (size_t)sw * sh * 4) != 0) {
                shown = bench_now();
                frames_needed[d] = f;
            }
        }
        latency_ms[d] = shown ? (shown - t0) * 1e3 : -1;
        frame_ms[d] = one_frame;
    }
    int next_frame = 0, within_two = 0, lost = 0, most_frames = 0;
    for (int d = 0; d < DABS; d++) {
        next_frame += frames_needed[d] == 1;
        within_two += frames_needed[d] >= 1 && frames_needed[d] <= 2;
        lost += frames_needed[d] == 0;
        if (frames_needed[d] > most_frames) most_frames = frames_needed[d];
    }
    double move_ms = bench_median(latency_ms, DABS), move_frame_ms = bench_median(frame_ms, DABS);
    printf("4. Mouse move -> the frame showing its dab (%d dabs, %d x %d at the moving scale):\n",
           DABS, sw, sh);
    printf("   latency median %.1f ms, of which the frame itself %.1f ms (%.2fx one frame); shown "
           "by the next frame for %d of %d dabs, at most %d frames; %d never shown\n",
           move_ms, move_frame_ms, move_ms / move_frame_ms, next_frame, DABS, most_frames, lost);
    printf("   %s: every dab on screen within 2 frames of its mouse move, no input lost "
           "(%d of %d)\n",
           within_two == DABS && lost == 0 ? "PASS" : "MISS", within_two, DABS);
    cmd_run(&ctx, "stroke_end", 10, "bench", &ignored);

    // 5. Mouse release -> the final full-resolution image: the release's stroke_end runs
    // through the queue (the edit's coarser levels brought up to date), then the window's
    // frames once nothing moves: full size and smoothed, until the picture is the one a
    // settled renderer draws. Against one such frame's own time.
    enum { RELEASES = 5, MAX_AFTER = 8 };
    gl_target full = {0}, smooth = {0};
    check(gl_target_create(&full, vw, vh, &err), &err, "full-size target");
    check(gl_target_create(&smooth, vw, vh, &err), &err, "smoothed target");
    size_t bytes = (size_t)vw * vh * 4;
    unsigned char *frames = malloc(bytes * MAX_AFTER), *settled = malloc(bytes);
    if (!frames || !settled) check(-1, &err, "out of memory");
    double release_ms[RELEASES], full_frame_ms[RELEASES];
    int release_frames[RELEASES], release_within_two = 0;
    for (int r = 0; r < RELEASES; r++) {
        work_queue_add(&q, "stroke_begin", "bench", WORK_STROKE | WORK_STROKE_BEGIN);
        for (int k = 0; k < 4; k++) { // a short drag, 10 m a move
            cmd_stroke_point pt = {hit[0] - 60.0 + 30.0 * r, 0, hit[2] - 20.0 + 10.0 * k, 0};
            work_queue_add_point(&q, &pt);
        }
        while (!work_queue_idle(&q))
            work_queue_pump(&q, 30);
        double t0 = bench_now();
        work_queue_add(&q, "stroke_end", "bench", WORK_STROKE); // the mouse button goes up
        while (!work_queue_idle(&q))
            work_queue_pump(&q, 30);
        double at[MAX_AFTER];
        for (int f = 0; f < MAX_AFTER; f++) {
            double f0 = bench_now();
            world_event ev[64];
            while (world_subscription_take(changes, ev, 64) > 0) {
            }
            terrain_renderer_update(v->renderer, w, &v->cam, &v->settings, &err);
            glBindFramebuffer(GL_FRAMEBUFFER, full.fbo);
            terrain_renderer_draw(v->renderer, w, &v->cam, &v->settings, NULL, vw, vh, &err);
            check(viewport_antialias(v, &full, &smooth, &err), &err, "smoothing");
            glBindFramebuffer(GL_FRAMEBUFFER, smooth.fbo);
            glReadPixels(0, 0, vw, vh, GL_RGBA, GL_UNSIGNED_BYTE, frames + bytes * f);
            at[f] = (bench_now() - t0) * 1e3;
            if (f == 0) full_frame_ms[r] = (bench_now() - f0) * 1e3;
        }
        // The picture once every tile and level is current.
        check(viewport_settle(v, w, &err), &err, "settle");
        glBindFramebuffer(GL_FRAMEBUFFER, full.fbo);
        terrain_renderer_draw(v->renderer, w, &v->cam, &v->settings, NULL, vw, vh, &err);
        check(viewport_antialias(v, &full, &smooth, &err), &err, "smoothing");
        glBindFramebuffer(GL_FRAMEBUFFER, smooth.fbo);
        glReadPixels(0, 0, vw, vh, GL_RGBA, GL_UNSIGNED_BYTE, settled);
        int last_wrong = -1; // the final image is the one from which every frame is right
        for (int f = 0; f < MAX_AFTER; f++)
            if (memcmp(frames + bytes * f, settled, bytes) != 0) last_wrong = f;
        release_frames[r] = last_wrong + 2 <= MAX_AFTER ? last_wrong + 2 : 0; // 0: not reached
        release_ms[r] = release_frames[r] ? at[release_frames[r] - 1] : -1;
        release_within_two += release_frames[r] >= 1 && release_frames[r] <= 2;
    }
    int release_most = 0, never = 0;
    for (int r = 0; r < RELEASES; r++) {
        if (release_frames[r] > release_most) release_most = release_frames[r];
        never += release_frames[r] == 0;
    }
    double rel_ms = bench_median(release_ms, RELEASES);
    double one_full = bench_median(full_frame_ms, RELEASES);
    printf("5. Mouse release -> the final full-resolution image (%d strokes, %d x %d, "
           "smoothed):\n",
           RELEASES, vw, vh);
    printf("   median %.1f ms from the release, one full-size frame %.1f ms (%.2fx); the final "
           "image in at most %d frames%s\n",
           rel_ms, one_full, rel_ms / one_full, release_most,
           never ? " (some never within 8: MISS)" : "");
    printf("   %s: the final image within 2 frames of the last change (%d of %d)\n",
           release_within_two == RELEASES ? "PASS" : "MISS", release_within_two, RELEASES);
    free(frames), free(settled);
    gl_target_destroy(&full);
    gl_target_destroy(&smooth);
    free(before), free(after);
    gl_target_destroy(&t);
    world_events_unsubscribe(changes);
    work_queue_free(&q);
    console_free(&con);

    ui_renderer_destroy(uir);
    gl_target_destroy(&screen);
    gl_target_destroy(&terrain);
    editor_ui_destroy(ed);
    ui_destroy(ui);
    ui_font_destroy(font);
    viewport_destroy(v);
    world_close(ctx.world);
    fclose(sink);
    return 0;
}
