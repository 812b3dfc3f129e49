// Viewport renderer benchmarks, all offscreen on one headless context in one run,
// each figure beside its reference from the same run:
//  1. frames per second of the geometry clipmap against a naive full-resolution mesh
//     (bench/naive_mesh.c: every sample of a bounded 4096^2 world, one draw call) on
//     the same fly-over; the naive mesh is timed on three frames of the path only;
//  2. triangles and draw calls per frame, both;
//  3. CPU milliseconds per frame (render_stats.cpu_ms: the calling thread's CPU time in
//     update + draw submission, which on llvmpipe includes its vertex work) and wall
//     time with glFinish, on a bounded 1024^2 world against an unbounded one (same
//     parameters, same path, levels settled first; goal: within 1.2x);
//  4. texels uploaded per frame in straight flight at 50, 100 and 200 m/s (60 frames
//     per second of simulated time), against the full level textures (levels x 256^2);
//  5. parallax detail off and on (4, 8 and 16 steps) a few metres above sculpted
//     detail (a noise brush on the detail layer, through the command language);
//  6. clipmap levels 3, 5, 7, 9, 11 against frames per second (Crause 2010's Table 10);
//  7. visual accuracy: Tabakovic 2024's RMSE between the clipmap and the naive mesh in the
//     height view (same camera, projection, sun, sky and fog), goal <= 3, from three
//     cameras, both images drawn at 4 x 4 samples a pixel (the one-sample RMSE beside);
//     the images and an amplified difference are written as PNGs; the same with
//     the coarse levels refined where their error exceeds a pixel (render refine=1), with
//     the triangles and frame times of both;
//  8. the anti-aliasing pass (renderer/antialias.h) against the shaded frame it smooths.
// Usage: bench_render [OUT_DIR [SECTIONS]]: images go to OUT_DIR (default $TMPDIR, else
// /tmp; created if missing); SECTIONS picks sections, e.g. "7" or "345" (default all).
// llvmpipe on two cores is slow (the naive mesh's 33M triangles take seconds a frame,
// the clipmap most of one), so passes are short: figures are medians over frames of
// interleaved passes (the machine is noisy); goals are reported (PASS/MISS), not asserted.
// The load average is printed at the start and with the summary, and llvmpipe's threads
// (LP_NUM_THREADS, else one per core); section 1 also gives the CPU time of all threads.
#include "bench/bench_journals.h"
#include "bench/bench_timing.h"
#include "bench/naive_mesh.h"
#include "renderer/antialias.h"

#include "editor/cmd/commands.h"
#include "editor/world/layer_grid.h"
#include "editor/world/world.h"
#include "io/image_compare.h"
#include "io/image_read.h"
#include "renderer/camera.h"
#include "renderer/clip_slopes.h"
#include "renderer/gl_context.h"
#include "renderer/gl_target.h"
#include "renderer/terrain_renderer.h"

#include <epoxy/gl.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#ifndef OROGEN_BENCH_SHADER_DIR
#error "bench/CMakeLists.txt defines OROGEN_BENCH_SHADER_DIR"
#endif

#define WIDTH 960
#define HEIGHT 540
#define FLY_FRAMES 60  // the fly-over (1): two passes in the height view, one shaded
#define CPU_FRAMES 30  // the bounded/unbounded flight (3): two passes over each world
#define MAX_FRAMES 120 // the longest path (4)
#define REPEATS 5      // interleaved repeats at a fixed camera (5, 6), one frame each
#define SETTLE_SECONDS 300.0

static void quiet(void *u, const char *m) {
    (void)u, (void)m;
}

static void check(int rc, const og_error *err, const char *what) {
    if (rc == 0) return;
    fprintf(stderr, "bench_render: %s: %s\n", what, err->msg);
    exit(1);
}

static void *xmalloc(size_t n) {
    void *p = malloc(n);
    if (!p) {
        fprintf(stderr, "bench_render: out of memory (%zu bytes)\n", n);
        exit(1);
    }
    return p;
}

// ---- the summary ----------------------------------------------------------------------

static struct {
    char text[200];
    int pass;
} goals[16];
static int goal_count;

static void goal(const char *what, double value, double limit, int at_least, const char *unit) {
    if (goal_count == (int)(sizeof goals / sizeof *goals)) { // never silently: a goal missing
        fprintf(stderr, "bench_render: no room for goal '%s' in the summary\n", what);
        exit(1);
    }
    int pass = at_least ? value >= limit : value <= limit;
    snprintf(goals[goal_count].text, sizeof goals[0].text, "%-52s %9.2f%s  (goal %s %g%s)", what,
             value, unit, at_least ? ">=" : "<=", limit, unit);
    goals[goal_count++].pass = pass;
}

// ---- set-up ---------------------------------------------------------------------------

static double t_start;

// Progress on stderr, so a long run shows where it is.
static void progress(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "[%6.1f s] ", bench_now() - t_start);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

typedef struct bench {
    gl_headless *ctx;
    gl_target target;
    terrain_renderer *r;
    unsigned char *rgb;
    const char *out_dir;
    double t_start;
} bench;

// resources/default.world with `size` samples per side (0: unbounded).
static world *make_world(int64_t size) {
    world_params p;
    int errors = 0;
    og_error err;
    world_params_default(&p, WORLD_FLAT);
    check(world_params_load(OROGEN_RESOURCE_DIR "/default.world", &p, &errors, NULL, NULL, &err),
          &err, "default.world");
    p.size = size;
    world_settings s = {.warn = quiet};
    world *w = world_create(&p, &s, &err);
    if (!w) check(-1, &err, "world_create");
    return w;
}

// The ground height (0 outside a bounded world).
static double ground_at(world *w, double x, double z) {
    double h = 0;
    og_error err;
    if (world_sample(w, 0, x, z, &h, &err) != 0) return 0;
    return h;
}

// The ground or the water surface, whichever is higher.
static double surface_at(world *w, double x, double z) {
    return fmax(ground_at(w, x, z), world_get_params(w)->ocean_level);
}

// Updates until every level is current twice in a row (as viewport_settle does).
static void settle(bench *b, world *w, const camera *c, const render_settings *s) {
    og_error err;
    double t0 = bench_now();
    for (;;) {
        int rc = terrain_renderer_update(b->r, w, c, s, &err);
        check(rc < 0 ? -1 : 0, &err, "terrain_renderer_update");
        if (rc == 1 && terrain_renderer_update(b->r, w, c, s, &err) == 1) return;
        if (bench_now() - t0 > SETTLE_SECONDS) {
            fprintf(stderr, "bench_render: tiles did not arrive within %.0f s\n", SETTLE_SECONDS);
            exit(1);
        }
        struct timespec nap = {0, 2000000};
        nanosleep(&nap, NULL);
    }
}

typedef struct frame_time {
    double wall_ms;    // update + draw + glFinish
    double update_ms;  // terrain_renderer_update alone
    double process_ms; // CPU time of every thread over the frame (llvmpipe's too)
    render_stats st;
} frame_time;

// One clipmap frame into the offscreen target.
static frame_time clip_frame(bench *b, world *w, const camera *c, const render_settings *s) {
    og_error err;
    frame_time f;
    double t0 = bench_now(), c0 = bench_process_cpu();
    check(terrain_renderer_update(b->r, w, c, s, &err) < 0 ? -1 : 0, &err, "update");
    f.update_ms = (bench_now() - t0) * 1e3;
    glBindFramebuffer(GL_FRAMEBUFFER, b->target.fbo);
    check(terrain_renderer_draw(b->r, w, c, s, NULL, WIDTH, HEIGHT, &err), &err, "draw");
    glFinish();
    f.wall_ms = (bench_now() - t0) * 1e3;
    f.process_ms = (bench_process_cpu() - c0) * 1e3;
    terrain_renderer_stats(b->r, &f.st);
    return f;
}

// All threads' CPU milliseconds for one shaded frame of `width` x `height` into t, and
// its triangles.
static double sized_frame(bench *b, world *w, const camera *c, const render_settings *s,
                          const gl_target *t, uint64_t *triangles) {
    og_error err;
    check(terrain_renderer_update(b->r, w, c, s, &err) < 0 ? -1 : 0, &err, "update");
    glFinish();
    double c0 = bench_process_cpu();
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    check(terrain_renderer_draw(b->r, w, c, s, NULL, t->width, t->height, &err), &err, "draw");
    glFinish();
    render_stats st;
    terrain_renderer_stats(b->r, &st);
    *triangles = st.triangles;
    return (bench_process_cpu() - c0) * 1e3;
}

static double naive_frame(bench *b, naive_mesh *m, const camera *c, const render_settings *s) {
    og_error err;
    double t0 = bench_now();
    glBindFramebuffer(GL_FRAMEBUFFER, b->target.fbo);
    check(naive_mesh_draw(m, c, s, WIDTH, HEIGHT, &err), &err, "naive draw");
    glFinish();
    return (bench_now() - t0) * 1e3;
}

static void read_image(bench *b, unsigned char *rgb) {
    og_error err;
    check(gl_target_read_rgb(&b->target, rgb, &err), &err, "read pixels");
}

static void write_image(bench *b, const char *name, const unsigned char *rgb) {
    char path[4200];
    og_error err;
    snprintf(path, sizeof path, "%s/%s", b->out_dir, name);
    check(image_write_rgb8(path, rgb, WIDTH, HEIGHT, &err), &err, path);
}

// ---- camera paths ---------------------------------------------------------------------

// A straight flight at constant altitude: `above` metres over the highest ground
// along the way, looking along the flight (yaw from the direction) at `pitch`.
typedef struct path {
    camera cam[MAX_FRAMES];
    int frames;
    double metres_per_frame;
} path;

static void make_path(path *p, world *w, double x0, double z0, double x1, double z1, int frames,
                      double above, double pitch) {
    p->frames = frames;
    double dx = x1 - x0, dz = z1 - z0, len = sqrt(dx * dx + dz * dz);
    p->metres_per_frame = len / (frames - 1);
    double top = -1e30;
    for (double t = 0; t <= 1.0 + 1e-9; t += 1.0 / 256)
        top = fmax(top, surface_at(w, x0 + dx * t, z0 + dz * t));
    double yaw = atan2(dx, -dz) * 180.0 / M_PI; // 0 looks toward -Z, 90 toward +X
    if (yaw < 0) yaw += 360;
    for (int i = 0; i < frames; i++) {
        double t = (double)i / (frames - 1);
        camera *c = &p->cam[i];
        camera_default(c);
        c->pos[0] = x0 + dx * t, c->pos[2] = z0 + dz * t, c->pos[1] = top + above;
        c->yaw = yaw, c->pitch = pitch;
    }
}

// Settles every camera of the path once so that every tile it needs is in the cache.
static void warm_path(bench *b, world *w, const path *p, const render_settings *s) {
    for (int i = 0; i < p->frames; i++)
        settle(b, w, &p->cam[i], s);
}

// ---- 1 and 2: clipmap against the naive full-resolution mesh ---------------------------

// Frames of several passes pooled: FPS over all of them, medians per frame.
typedef struct pool {
    double wall[4 * MAX_FRAMES], cpu[4 * MAX_FRAMES], update[4 * MAX_FRAMES];
    double process[4 * MAX_FRAMES];
    double level_tris[RENDER_MAX_LEVELS]; // summed over the frames
    double tris[4 * MAX_FRAMES], calls[4 * MAX_FRAMES];
    int n;
} pool;

// Flies the path after settling at its start; the first frame's image goes to `image`
// unless that is NULL.
static void fly_into(bench *b, world *w, const path *p, const render_settings *s, pool *out,
                     const char *image) {
    settle(b, w, &p->cam[0], s);
    double total = 0;
    for (int i = 0; i < p->frames; i++) {
        frame_time f = clip_frame(b, w, &p->cam[i], s);
        if (i == 0 && image) {
            unsigned char *rgb = xmalloc((size_t)WIDTH * HEIGHT * 3);
            read_image(b, rgb);
            write_image(b, image, rgb);
            free(rgb);
        }
        int k = out->n++;
        out->wall[k] = f.wall_ms, out->cpu[k] = f.st.cpu_ms, out->update[k] = f.update_ms;
        out->process[k] = f.process_ms;
        for (int l = 0; l < RENDER_MAX_LEVELS; l++)
            out->level_tris[l] += (double)f.st.level_triangles[l];
        out->tris[k] = (double)f.st.triangles, out->calls[k] = f.st.draw_calls;
        total += f.wall_ms;
    }
    progress("  pass: %d frames in %.1f s, view %s", p->frames, total * 1e-3,
             view_mode_name(s->view));
}

typedef struct pooled {
    double fps, frame_ms, cpu_ms, update_ms, tris, calls, process_ms;
} pooled;

static pooled pool_result(pool *p) {
    double total = 0;
    for (int i = 0; i < p->n; i++)
        total += p->wall[i];
    return (pooled){.fps = p->n / (total * 1e-3),
                    .frame_ms = bench_median(p->wall, p->n),
                    .cpu_ms = bench_median(p->cpu, p->n),
                    .update_ms = bench_median(p->update, p->n),
                    .process_ms = bench_median(p->process, p->n),
                    .tris = bench_median(p->tris, p->n),
                    .calls = bench_median(p->calls, p->n)};
}

// The shaded frame's CPU time split into what grows with its pixels and the rest (the
// triangles: vertex work, set-up, and the pixels each touches at least), from the same
// frames at full and at quarter size, interleaved: cost = fixed + per-pixel x pixels.
static void split_costs(bench *b, world *w, const path *p, const render_settings *shaded) {
    og_error err;
    gl_target quarter;
    check(gl_target_create(&quarter, WIDTH / 2, HEIGHT / 2, &err), &err, "quarter target");
    enum { N = 9 };
    double full[N], small[N];
    uint64_t tris = 0, t;
    for (int i = 0; i < N; i++) {
        const camera *c = &p->cam[(i % 3) * (p->frames - 1) / 2];
        settle(b, w, c, shaded);
        full[i] = sized_frame(b, w, c, shaded, &b->target, &tris);
        small[i] = sized_frame(b, w, c, shaded, &quarter, &t);
    }
    gl_target_destroy(&quarter);
    glBindFramebuffer(GL_FRAMEBUFFER, b->target.fbo);
    const double f = bench_median(full, N), q = bench_median(small, N);
    const double pixels = (double)WIDTH * HEIGHT, per_pixel = (f - q) / (0.75 * pixels);
    const double fixed = f - per_pixel * pixels;
    printf("   shaded frame, CPU of all threads (median of %d, first/middle/last camera): %.0f ms "
           "at %dx%d, %.0f ms at %dx%d\n",
           N, f, WIDTH, HEIGHT, q, WIDTH / 2, HEIGHT / 2);
    printf(
        "   of which per pixel %.0f ms (%.3f us a pixel), per triangle and fixed %.0f ms (%.1f ms "
        "per 10k of the %.0fk triangles)\n",
        per_pixel * pixels, per_pixel * 1e3, fixed, fixed / (double)tris * 1e4,
        (double)tris * 1e-3);
}

static void bench_vs_naive(bench *b, world *w4096, naive_mesh *m) {
    render_settings s;
    render_settings_default(&s);
    static path p;
    const double above = 120;
    make_path(&p, w4096, 2000, 2500, 2000 + 520, 2500 + 300, FLY_FRAMES, above, -12);
    progress("1. warming the fly-over");
    warm_path(b, w4096, &p, &s);
    static pool shaded, height;
    double naive_ms[3];
    for (int rep = 0; rep < 3; rep++) {
        if (rep < 2) {
            s.view = VIEW_HEIGHT;
            fly_into(b, w4096, &p, &s, &height, NULL);
        } else {
            s.view = VIEW_SHADED;
            fly_into(b, w4096, &p, &s, &shaded, NULL);
        }
        // The naive mesh: one frame per pass (first, middle, last frame of the path).
        int i = rep * (p.frames - 1) / 2;
        s.view = VIEW_HEIGHT;
        naive_ms[rep] = naive_frame(b, m, &p.cam[i], &s);
        progress("  naive frame %d: %.0f ms", i, naive_ms[rep]);
    }
    pooled rs = pool_result(&shaded), rh = pool_result(&height);
    double naive_med = bench_median(naive_ms, 3);
    double naive_fps = 1e3 / naive_med;
    printf("\n1. Frames per second, %dx%d, fly-over of %d frames (%.1f m/frame, %.0f m above the "
           "highest ground) over a bounded 4096^2 world (spacing %.0f m)\n",
           WIDTH, HEIGHT, p.frames, p.metres_per_frame, above, world_get_params(w4096)->spacing);
    printf("   %-44s %10s %16s %8s %16s\n", "renderer", "FPS", "median frame ms", "frames",
           "CPU ms, threads");
    printf("   %-44s %10.3f %16.0f %8d %16.0f\n", "clipmap, height view (8 levels)", rh.fps,
           rh.frame_ms, height.n, rh.process_ms);
    printf("   %-44s %10.3f %16.0f %8d %16.0f\n", "clipmap, shaded view (8 levels)", rs.fps,
           rs.frame_ms, shaded.n, rs.process_ms);
    printf("   %-44s %10.3f %16.0f %8d   (first/middle/last frame of the path)\n",
           "naive full-resolution mesh, height view", naive_fps, naive_med, 3);
    printf("   clipmap / naive, same view and shading: %.2fx the frame rate\n", rh.fps / naive_fps);
    s.view = VIEW_SHADED;
    split_costs(b, w4096, &p, &s);
    goal("1. shaded fly-over, 960x540, frames per second", rs.fps, 15, 1, " FPS");
    printf("   (the shaded frame is drawn deferred: depth and level first, then each pixel shaded "
           "once; on a loaded machine its FPS follows the CPU it gets, see CPU ms)\n");

    printf("\n2. Geometry per frame (medians over the fly-over)\n");
    printf("   %-44s %14s %12s\n", "renderer", "triangles", "draw calls");
    printf("   %-44s %14.0f %12.0f   (per level part: triangles and a shading pass; sky, copy, "
           "water)\n",
           "clipmap, shaded view", rs.tris, rs.calls);
    printf("   %-44s %14.0f %12.0f   (sky + one per level)\n", "clipmap, height view", rh.tris,
           rh.calls);
    printf("   %-44s %14llu %12d   (sky + the mesh; %zu MB of vertex and index buffers)\n",
           "naive full-resolution mesh", (unsigned long long)m->triangles, 2, m->gpu_bytes >> 20);
    printf("   clipmap triangles / naive: %.4f; clipmap triangles per pixel: %.2f\n",
           rh.tris / (double)m->triangles, rh.tris / ((double)WIDTH * HEIGHT));
}

// ---- 7: visual accuracy ---------------------------------------------------------------

// Both images are compared at SUPERSAMPLE x SUPERSAMPLE samples a pixel (rendered that
// many times larger, box-filtered down): at one sample a pixel the full-resolution mesh
// aliases (ridges and spikes narrower than a pixel cover it or not, 2 m normals shade
// one point of a pixel-wide patch), and its image differs from its own supersampled one
// by an RMSE of 1.5-2.1, which no clipmap could match. The one-sample figures are shown
// beside them.
#define SUPERSAMPLE 4

// The frame of camera c, drawn SUPERSAMPLE times larger into `big` and reduced into rgb:
// the naive mesh m when given, else the clipmap (settled at c).
static void supersampled(bench *b, world *w, naive_mesh *m, const camera *c,
                         const render_settings *s, const gl_target *big, unsigned char *rgb) {
    og_error err;
    const int k = SUPERSAMPLE;
    if (!m) check(terrain_renderer_update(b->r, w, c, s, &err) < 0 ? -1 : 0, &err, "update");
    glBindFramebuffer(GL_FRAMEBUFFER, big->fbo);
    if (m)
        check(naive_mesh_draw(m, c, s, WIDTH * k, HEIGHT * k, &err), &err, "naive draw");
    else
        check(terrain_renderer_draw(b->r, w, c, s, NULL, WIDTH * k, HEIGHT * k, &err), &err,
              "draw");
    glFinish();
    unsigned char *samples = xmalloc((size_t)WIDTH * HEIGHT * k * k * 3);
    check(gl_target_read_rgb(big, samples, &err), &err, "read pixels");
    image_box_down_rgb8(samples, WIDTH, HEIGHT, k, rgb);
    free(samples);
}

// The clipmap (refine: render refine=1 when set) against the naive mesh from camera c:
// the RMSE against the naive image at one sample a pixel (naive) and supersampled
// (naive_ss), the images, and the clipmap's triangles and median frame and CPU times over
// a few frames.
typedef struct accuracy {
    double rmse, rmse_1x, differ, tris, frame_ms, cpu_ms;
} accuracy;

enum { AS_DEFAULT, AS_REFINED, AS_SKYLINE }; // the defaults; refine=1; skyline=1
static const char *const accuracy_suffix[] = {"", "_refined", "_skyline"};

static accuracy accuracy_of(bench *b, world *w, const camera *c, const char *name, int refine,
                            const unsigned char *naive, const unsigned char *naive_ss,
                            const gl_target *big) {
    render_settings s;
    render_settings_default(&s);
    s.view = VIEW_HEIGHT;
    s.fog_density = 1.0 / 12000.0; // explicit: the same for both
    s.refine_pixels = refine == AS_REFINED ? 1.0 : 0.0;
    s.skyline_pixels = refine == AS_SKYLINE ? 1.0 : 0.0;
    size_t px = (size_t)WIDTH * HEIGHT;
    unsigned char *a = xmalloc(px * 3), *d = xmalloc(px * 3);
    settle(b, w, c, &s);
    frame_time f = clip_frame(b, w, c, &s);
    read_image(b, a);
    double wall[3], cpu[3];
    for (int k = 0; k < 3; k++) {
        frame_time t = clip_frame(b, w, c, &s);
        wall[k] = t.wall_ms, cpu[k] = t.st.cpu_ms;
    }
    accuracy r = {.rmse_1x = image_rmse_rgb8(a, naive, px),
                  .tris = (double)f.st.triangles,
                  .frame_ms = bench_median(wall, 3),
                  .cpu_ms = bench_median(cpu, 3)};
    char file[256];
    snprintf(file, sizeof file, "render_%s%s_clipmap.png", name, accuracy_suffix[refine]);
    write_image(b, file, a);
    // The same parts refined: their error in pixels of the one-sample frame.
    s.refine_pixels *= SUPERSAMPLE, s.skyline_pixels *= SUPERSAMPLE;
    supersampled(b, w, NULL, c, &s, big, a);
    r.rmse = image_rmse_rgb8(a, naive_ss, px);
    image_diff_rgb8(a, naive_ss, px, 8, d);
    snprintf(file, sizeof file, "render_%s%s_clipmap_ss.png", name, accuracy_suffix[refine]);
    write_image(b, file, a);
    snprintf(file, sizeof file, "render_%s%s_diff_x8.png", name, accuracy_suffix[refine]);
    write_image(b, file, d);
    size_t differ = 0;
    for (size_t i = 0; i < px * 3; i++)
        differ += abs((int)a[i] - (int)naive_ss[i]) > 8;
    r.differ = 100.0 * differ / (px * 3);
    free(a), free(d);
    return r;
}

static void accuracy_view(bench *b, world *w, naive_mesh *m, const camera *c, const char *name,
                          double *rmse_out, double *skyline_out, double *refined_out) {
    render_settings s;
    render_settings_default(&s);
    s.view = VIEW_HEIGHT;
    s.fog_density = 1.0 / 12000.0;
    size_t px = (size_t)WIDTH * HEIGHT;
    unsigned char *n = xmalloc(px * 3), *n_ss = xmalloc(px * 3);
    og_error err;
    gl_target big;
    check(gl_target_create(&big, WIDTH * SUPERSAMPLE, HEIGHT * SUPERSAMPLE, &err), &err,
          "supersampled target");
    // A clipmap frame at this camera first, as this section drew before: drawn right after
    // the naive mesh's, the first one shaded without its finer slopes (seen once the
    // deferred shading of 4c5ebdc landed; not the refinement's doing, not chased here).
    settle(b, w, c, &s);
    clip_frame(b, w, c, &s);
    naive_frame(b, m, c, &s);
    read_image(b, n);
    supersampled(b, w, m, c, &s, &big, n_ss);
    char file[256];
    snprintf(file, sizeof file, "render_%s_naive.png", name);
    write_image(b, file, n);
    snprintf(file, sizeof file, "render_%s_naive_ss.png", name);
    write_image(b, file, n_ss);
    accuracy plain = accuracy_of(b, w, c, name, AS_DEFAULT, n, n_ss, &big);
    accuracy sky = accuracy_of(b, w, c, name, AS_SKYLINE, n, n_ss, &big);
    accuracy fine = accuracy_of(b, w, c, name, AS_REFINED, n, n_ss, &big);
    render_stats st;
    terrain_renderer_stats(b->r, &st);
    double above = c->pos[1] - ground_at(w, c->pos[0], c->pos[2]);
    printf("   %-10s %8.0f %8d %8.2f %8.2f %8.2f %11.2f%% %10.0f %9.0f %8.1f   render_%s_*.png\n",
           name, above, st.finest_level, plain.rmse, plain.rmse_1x, image_rmse_rgb8(n, n_ss, px),
           plain.differ, plain.tris, plain.frame_ms, plain.cpu_ms, name);
    printf("   %-10s %8s %8s %8.2f %8.2f %8s %11.2f%% %10.0f %9.0f %8.1f   (skyline=1: %.2fx the "
           "triangles, %.2fx the CPU)\n",
           "  skyline", "", "", sky.rmse, sky.rmse_1x, "", sky.differ, sky.tris, sky.frame_ms,
           sky.cpu_ms, sky.tris / plain.tris, sky.cpu_ms / plain.cpu_ms);
    printf("   %-10s %8s %8s %8.2f %8.2f %8s %11.2f%% %10.0f %9.0f %8.1f   (refine=1: %.2fx the "
           "triangles, %.2fx the CPU)\n",
           "  refined", "", "", fine.rmse, fine.rmse_1x, "", fine.differ, fine.tris, fine.frame_ms,
           fine.cpu_ms, fine.tris / plain.tris, fine.cpu_ms / plain.cpu_ms);
    gl_target_destroy(&big);
    free(n), free(n_ss);
    *rmse_out = plain.rmse, *skyline_out = sky.rmse, *refined_out = fine.rmse;
}

static void bench_accuracy(bench *b, world *w4096, naive_mesh *m) {
    const world_params *p = world_get_params(w4096);
    printf(
        "\n7. Visual accuracy: RMSE (Tabakovic 2024, 8-bit RGB) of the clipmap against the naive "
        "full-resolution mesh,\n   height view, fog 1/12000 per metre, %dx%d, both at %d x %d "
        "samples a pixel (RMSE 1x: one sample, as drawn;\n   naive 1x: the naive image's own "
        "aliasing, one sample against %d x %d); images in %s\n",
        WIDTH, HEIGHT, SUPERSAMPLE, SUPERSAMPLE, SUPERSAMPLE, SUPERSAMPLE, b->out_dir);
    printf("   %-10s %8s %8s %8s %8s %8s %12s %10s %9s %8s\n", "view", "above m", "finest", "RMSE",
           "RMSE 1x", "naive 1x", "off by > 8", "triangles", "frame ms", "CPU ms");
    // The viewport's default camera (renderer/viewport.c viewport_default_camera).
    camera c;
    camera_default(&c);
    double centre = 0.5 * (double)(p->size - 1) * p->spacing;
    c.pos[0] = c.pos[2] = centre;
    c.pos[1] = surface_at(w4096, centre, centre) + fmax(40.0, 0.25 * p->max_height);
    c.yaw = 30, c.pitch = -18;
    double r1, r2, r3, k1, k2, k3, f1, f2, f3;
    accuracy_view(b, w4096, m, &c, "default", &r1, &k1, &f1);
    // Low (60 m) over the middle of the world looking north across half of it: the finest
    // level in front, the far levels at grazing angles.
    camera_default(&c);
    c.pos[0] = centre, c.pos[2] = centre + 2500;
    c.pos[1] = ground_at(w4096, c.pos[0], c.pos[2]) + 60;
    c.yaw = 0, c.pitch = -4;
    accuracy_view(b, w4096, m, &c, "low", &r2, &k2, &f2);
    // Seed 002's "large section of the terrain at a great distance": 3.5 km up, 9 km
    // south-west of the world, looking at its centre.
    camera_default(&c);
    c.pos[0] = -2500, c.pos[2] = centre + 6600;
    c.pos[1] = 3500;
    c.yaw = 45, c.pitch = -20;
    accuracy_view(b, w4096, m, &c, "distant", &r3, &k3, &f3);
    printf(
        "   refined: the coarse levels' parts whose geometric error exceeds 1 px on the screen\n"
        "   drawn at twice the density from the finer shading heights (renderer/clip_refine.h);\n"
        "   off by default: it doubles the triangles and the vertex work the CPU does on "
        "llvmpipe.\n"
        "   The coarse levels' heights (renderer/clip_window.h clip_window_init_ridges): each\n"
        "   vertex the higher of its level's tent-filtered sample and the point sample 2 mips\n"
        "   finer at its place (3.90 / 2.79 / 3.17 -> 3.38 / 2.74 / 3.00; skyline=1 2.87 /\n"
        "   1.91 / 2.88 -> 2.70 / 1.89 / 2.81; six other poses: five closer, one the same).\n"
        "   Tried: the point sample alone (3.68 / 2.81 / 3.05: the low view worse), the mean of\n"
        "   both (3.75 / 2.80 / 3.07), the higher of its 3 x 3 finer neighbours (half way 3.80 /\n"
        "   2.95 / 3.19: ground stands where the sky is), the point 1 mip finer (the same as 2);\n"
        "   shading slopes 3 mips finer than the level (4x the slope texels; before the ridges\n"
        "   3.99 / 2.84 / 2.98: finer shading on a coarse surface moves the error more than it\n"
        "   removes it); a morph band of n/80 (3.36 / 2.72 / 2.98: a faster morph, not taken).\n"
        "   Each pixel of a level with finer slopes is shaded where its ray meets the finer\n"
        "   heights, one Newton step from the level's surface (terrain.frag toward_finer_ground;\n"
        "   3.38 / 2.74 / 3.00 -> these; skyline=1 2.70 / 1.89 / 2.81 -> 2.18 / 1.81 / 2.52;\n"
        "   refine=1 1.91 / 1.47 / 2.43 -> 1.67 / 1.40 / 2.32; the slope view 11.9 / 7.1 / 11.5\n"
        "   -> 7.6 / 4.6 / 9.6; six other poses, 30 m to 1.5 km up, 3.21 / 2.32 / 2.40 / 3.28 /\n"
        "   2.80 / 4.44 -> 3.07 / 2.12 / 2.19 / 2.53 / 2.44 / 3.76, and closer with skyline=1\n"
        "   and refine=1 too): at grazing views the coarse surface's place lay metres along\n"
        "   the ray from the ground, and most of the error was shading read there (before it,\n"
        "   with the sun's light held constant in both images, 2.20 / 2.21 / 1.58, nearly all\n"
        "   at the sky). Tried: 2 and 3 steps (2.92 / 2.60 / 2.70, 2.90 / 2.59 / 2.69: one is\n"
        "   enough); before the step, finer slopes' differences half a texel apart (3.42 /\n"
        "   2.77 / 2.89), the fine slopes' detail scaled by 0.7 or 1.3 (3.47 / 2.74 / 3.19,\n"
        "   3.56 / 2.89 / 2.99), a limit of 1/2, 3/2 or 3 spacings for the step instead of\n"
        "   3/4 (2.88 / 2.56 / 2.69, 2.93 / 2.58 / 2.70, 2.94 / 2.58 / 2.71: not taken).\n"
        "   Then the finer slopes (levels 3 and up) are differences half a texel apart seen\n"
        "   from above (rays 17 degrees down or more; a texel apart at 6 degrees or less,\n"
        "   between them between): 2.89 / 2.57 / 2.70 -> 2.89 / 2.57 / 2.47, skyline=1 2.18 /\n"
        "   1.81 / 2.52 -> 2.18 / 1.81 / 2.27, refine=1 1.67 / 1.40 / 2.32 -> 1.67 / 1.40 /\n"
        "   2.02; the six poses 3.07 / 2.12 / 2.19 / 2.53 / 2.44 / 3.76 -> 3.07 / 2.12 / 2.19 /\n"
        "   2.42 / 2.43 / 3.71. Half a texel at every angle: the same distant view, but low\n"
        "   poses worse (2.19 -> 2.24 from 30 m up, 3.07 -> 3.11 from 150 m): not taken.\n"
        "   What is left: the skyline, drawn from coarse levels' heights, misses the full-\n"
        "   resolution ridges' 1-px teeth (before the step pixels within 3 px of the sky held\n"
        "   47%% / 76%% / 26%% of the squared error), and the shading detail finer than the\n"
        "   slopes' mip (the distant view: fine texture all over).\n"
        "   Earlier: a morph band of n/40 level units instead of n/10 (kept: 4.07 / 3.01 / 3.28\n"
        "   -> 3.90 / 2.79 / 3.17); raising coarse vertices toward the highest finer sample at\n"
        "   grazing views (RMSE 1x default 4.94 -> 4.58 but low 3.90 -> 4.07: not kept);\n"
        "   refining only the levels from 4, 5 or 6 on (default 2.64 for 200k triangles, 4.07,\n"
        "   4.07; low 2.69, 2.87, 3.01; n/10 band). Refining everywhere costs 2-3x the triangles\n"
        "   the shaded frame rate (goal 1) cannot spend. skyline: only the parts (8 x 8 quads)\n"
        "   whose cells' tops come within 2 px of the skyline (renderer/clip_skyline.h) refined:\n"
        "   PASSes here for ~1.2-1.6x the triangles, but in sections 1 and 3's flights it added\n"
        "   19%% and 7%% / 15%% (bounded / unbounded) triangles at ~2x a base triangle's CPU "
        "each,\n"
        "   so goal 3's ratio went 1.88x -> 2.16x: off by default until the frame can pay for\n"
        "   it. Tried: refined vertices with 4 texture reads instead of ~18 (kept; the cost did\n"
        "   not change within the noise); the error weighted by what the fog leaves of it\n"
        "   (section 3's extra triangles +6k / +31k -> +6k / +17k, but default / distant 3.15 /\n"
        "   3.02; with P x 0.7 2.83 / 1.91 / 2.94 for +8k / +23k: no worse a ratio in\n"
        "   triangles, but still ~11%% more of them in section 3 and a worse distant view: not\n"
        "   kept). Next: the skyline in screen space (sky pixels just above the ground marched\n"
        "   against the finer heights) instead of in triangles; a normal map per level of the\n"
        "   mean full-resolution normal (its length the roughness darkening) for the distant\n"
        "   view's shading detail, which needs a mip chain of normals beside the heights'.\n");
    goal("7. RMSE clipmap vs naive, default view", r1, 3, 0, "");
    goal("7. RMSE clipmap vs naive, low view", r2, 3, 0, "");
    goal("7. RMSE clipmap vs naive, distant view", r3, 3, 0, "");
    goal("7. RMSE clipmap skyline=1 vs naive, default view", k1, 3, 0, "");
    goal("7. RMSE clipmap skyline=1 vs naive, low view", k2, 3, 0, "");
    goal("7. RMSE clipmap skyline=1 vs naive, distant view", k3, 3, 0, "");
    goal("7. RMSE clipmap refine=1 vs naive, default view", f1, 3, 0, "");
    goal("7. RMSE clipmap refine=1 vs naive, low view", f2, 3, 0, "");
    goal("7. RMSE clipmap refine=1 vs naive, distant view", f3, 3, 0, "");
}

// ---- 3: CPU cost, bounded against unbounded -------------------------------------------

// Section 3's flight at `pitch` over both worlds, warmed first, two interleaved passes
// each; the first frames' images go to names[0] (bounded) and names[1].
static void fly_both(bench *b, world *w1024, world *winf, path *p, double pitch,
                     const render_settings *s, pool out[2], const char *const names[2]) {
    make_path(p, winf, 500, 1500, 500 + 600, 1500 - 800, CPU_FRAMES, 120, pitch);
    progress("3. warming the flight at pitch %.0f", pitch);
    warm_path(b, w1024, p, s);
    warm_path(b, winf, p, s);
    for (int rep = 0; rep < 2; rep++) {
        fly_into(b, w1024, p, s, &out[0], rep ? NULL : names[0]);
        fly_into(b, winf, p, s, &out[1], rep ? NULL : names[1]);
    }
}

static void bench_cpu(bench *b, world *w1024, world *winf) {
    render_settings s;
    render_settings_default(&s);
    static path p;
    static pool flights[2];
    const char *const images[2] = {"render_cpu_bounded.png", "render_cpu_unbounded.png"};
    fly_both(b, w1024, winf, &p, -12, &s, flights, images);
    pooled rb = pool_result(&flights[0]), ru = pool_result(&flights[1]);
    printf("\n3. CPU per frame, shaded view, %d-frame flight (%.1f m/frame) inside the 1024^2 "
           "world, 2 interleaved passes per world, levels settled first\n",
           p.frames, p.metres_per_frame);
    printf("   %-24s %18s %16s %18s %10s %8s\n", "world", "cpu ms (upd+draw)", "update wall ms",
           "wall ms (glFinish)", "triangles", "FPS");
    printf("   %-24s %18.2f %16.2f %18.0f %10.0f %8.3f\n", "bounded 1024^2", rb.cpu_ms,
           rb.update_ms, rb.frame_ms, rb.tris, rb.fps);
    printf("   %-24s %18.2f %16.2f %18.0f %10.0f %8.3f\n", "unbounded (reference)", ru.cpu_ms,
           ru.update_ms, ru.frame_ms, ru.tris, ru.fps);
    printf("   (medians per frame; cpu ms: the calling thread's CPU time in update and draw, which "
           "on llvmpipe includes the driver's vertex work; first frames: render_cpu_*.png)\n");
    for (int k = 0; k < 2; k++) { // where the extra triangles are
        const pool *q = &flights[k];
        printf("   %-24s", k ? "  unbounded, per level" : "  bounded, per level");
        for (int l = 0; l < RENDER_MAX_LEVELS; l++)
            if (q->level_tris[l] > 0) printf(" L%d %.0fk", l, q->level_tris[l] / q->n * 1e-3);
        printf("   (mean triangles)\n");
    }
    double ratio = rb.cpu_ms > ru.cpu_ms ? rb.cpu_ms / ru.cpu_ms : ru.cpu_ms / rb.cpu_ms;
    printf("   cpu ms ratio (larger / smaller): %.3f; wall ratio bounded / unbounded: %.3f\n",
           ratio, rb.frame_ms / ru.frame_ms);
    if (ratio > 1.2) { // why, and what was tried (issue 31)
        // The calling thread's cost per submitted triangle from the two worlds' difference,
        // and what is left for the rest of a frame: how many triangles 1.2x would allow.
        const double per_tri = (ru.cpu_ms - rb.cpu_ms) / (ru.tris - rb.tris);
        const double rest = rb.cpu_ms - per_tri * rb.tris;
        if (ru.tris > rb.tris && per_tri > 0)
            printf(
                "   the calling thread pays %.0f ns a triangle (llvmpipe's vertex shading, "
                "set-up and binning) and %.2f ms a frame besides: 1.2x would allow the unbounded "
                "view %.0fk triangles, it draws %.0fk\n",
                per_tri * 1e6, rest, (1.2 * rb.cpu_ms - rest) / per_tri * 1e-3, ru.tris * 1e-3);
        printf("   the unbounded world's extra triangles are its levels 3-7 beyond the bounded "
               "world's edge, ground on the horizon: tried (issue 31), occluders under each 8 x "
               "8-sample cell's highest row and column hid 5%% of the view's triangles; occluders "
               "at each part's highest point (not conservative: a bound on what culling can hide) "
               "24%%, 35%% with 8 x 8-quad parts; measured exactly (occlusion queries against the "
               "finished depth buffer), 52%% of levels 3-7's 136k triangles lie in 16 x 16-quad "
               "blocks of which no pixel shows, 73%% in 2-row strips, but hidden ones are cheap: "
               "exact depth probes (each far block's rows in 4 boxed bands drawn against the "
               "depth before it, 2 rounds a level, ~0.1 ms a round for the probes and a flush) "
               "left out 51k of 214k triangles yet took only ~0.3 ms off the unbounded frame and "
               "added ~0.1 ms to the bounded one (ratio 1.80 -> 1.73 alternated, load 7-8); "
               "levels 6-7 alone: 32k fewer, no change. So a hidden triangle costs ~12-26 ns "
               "(many are back faces, which llvmpipe drops in set-up before binning) against ~45 "
               "ns on average, and culling cannot reach 1.2x: the cost is in the far ground that "
               "shows; no varyings in the G-buffer, or the vertex heights by texelFetch, cost the "
               "same; coarser far rings would change the silhouettes: drawing a 16 x 16-quad part "
               "of levels 3-7 at half (quarter) density where its largest height error seen from "
               "its nearest point stays under 1 px would spare ~1k of their 130k triangles (3 px: "
               "38k, 11k); of those levels' cost the vertex work is ~2.7 ms (rasterizer discard), "
               "llvmpipe's triangle set-up and binning ~10 ms (all faces culled). Where the "
               "calling thread's time goes (perf over this section's flights, Mesa 22.3 read "
               "without symbols): 33%% llvmpipe's triangle set-up (13%% at two spots just after a "
               "triangle is allocated in the scene, likely its first writes to fresh memory), "
               "16%% vertex fetch and shader, 6%% the set-up's interpolants, 3%% the draw "
               "module's vertex cache, 7%% the ground culling (now 3-4x cheaper, the same answers: "
               "0.67 / 1.78 -> 0.18 / 0.46 ms "
               "bounded / unbounded). Tried: levels 3-7 left out, unbounded 11.8 -> 7.2 ms, only "
               "their vertex work (rasterizer discard) 8.7; two more height reads a vertex "
               "+0.2-0.5 ms (texture reads are not the cost); a glFlush after each level "
               "(smaller scenes) +0.4 / +0.6 ms; a level's draws sorted and joined, glibc "
               "keeping freed memory: no change. What is left is llvmpipe's cost per triangle "
               "that faces the camera, which only fewer such triangles can lower\n");
    }
    // The same flight looking 60 degrees down: only ground inside the bounded world in
    // view, so both draw the same picture (the first frames' RMSE says how nearly): the
    // ratio is what the unbounded world costs by itself, not the farther ground it shows.
    static path down;
    static pool down_flights[2];
    const char *const names[2] = {"render_cpu_down_bounded.png", "render_cpu_down_unbounded.png"};
    fly_both(b, w1024, winf, &down, -60, &s, down_flights, names);
    pooled db = pool_result(&down_flights[0]), du = pool_result(&down_flights[1]);
    char paths[2][4200];
    for (int k = 0; k < 2; k++)
        snprintf(paths[k], sizeof paths[k], "%s/%s", b->out_dir, names[k]);
    double rmse;
    og_error err;
    check(image_rmse_files(paths[0], paths[1], &rmse, &err), &err, "3. compare");
    printf("   the same flight looking 60 degrees down, only ground inside the bounded world in "
           "view (first frames' RMSE %.2f): cpu ms %.2f bounded, %.2f unbounded (%.3fx), "
           "triangles %.0f, %.0f\n",
           rmse, db.cpu_ms, du.cpu_ms, du.cpu_ms / db.cpu_ms, db.tris, du.tris);
    goal("3. CPU ms per frame, bounded vs unbounded (ratio)", ratio, 1.2, 0, "x");
}

// ---- 4: texels uploaded while flying --------------------------------------------------

static void bench_uploads(bench *b, world *w1024, world *winf) {
    (void)w1024;
    render_settings s;
    render_settings_default(&s);
    const double speeds[] = {50, 100, 200};
    const int frames = 120;
    const double full = (double)s.levels * 256 * 256;
    // The shading slopes' windows (renderer/clip_slopes.h), one per level but the finest.
    const double full_slopes = (double)(s.levels - 1) * CLIP_SLOPES_TEXELS * CLIP_SLOPES_TEXELS;
    double largest = 0, largest_slopes = 0; // the largest share of any frame at any speed
    printf("\n4. Texels uploaded per frame, straight flight 60 m above the highest ground, "
           "60 frames/s of simulated time, %d frames, update only\n",
           frames);
    printf("   %-9s %12s %12s %12s %12s %10s   %s\n", "speed", "mean texels", "median",
           "max texels", "mean / full", "max / full",
           "worst frame: metres above ground, finest level (frame before -> it)");
    for (int k = 0; k < 3; k++) {
        static path p;
        double len = speeds[k] / 60.0 * (frames - 1);
        double x0 = 5000.0 * (k + 1), z0 = -3000;
        make_path(&p, winf, x0, z0, x0 + len * 0.6, z0 + len * 0.8, frames, 60, -10);
        warm_path(b, winf, &p, &s);
        settle(b, winf, &p.cam[0], &s);
        double sum = 0, mx = -1, texels[MAX_FRAMES];
        int worst = 1, finest[MAX_FRAMES] = {0};
        og_error err;
        render_stats st;
        terrain_renderer_stats(b->r, &st);
        finest[0] = st.finest_level;
        for (int i = 1; i < p.frames; i++) {
            check(terrain_renderer_update(b->r, winf, &p.cam[i], &s, &err) < 0 ? -1 : 0, &err,
                  "update");
            terrain_renderer_stats(b->r, &st);
            texels[i - 1] = (double)st.texels_uploaded;
            largest_slopes = fmax(largest_slopes, (double)st.slope_texels_uploaded / full_slopes);
            finest[i] = st.finest_level;
            sum += texels[i - 1];
            if (texels[i - 1] > mx) mx = texels[i - 1], worst = i;
        }
        double mean = sum / (p.frames - 1);
        largest = fmax(largest, mx / full);
        double median = bench_median(texels, p.frames - 1);
        char label[32];
        snprintf(label, sizeof label, "%.0f m/s", speeds[k]);
        const camera *a = &p.cam[worst - 1], *c = &p.cam[worst];
        printf("   %-9s %12.0f %12.0f %12.0f %11.2f%% %9.2f%%   %.0f -> %.0f m, level %d -> %d\n",
               label, mean, median, mx, 100 * mean / full, 100 * mx / full,
               a->pos[1] - ground_at(winf, a->pos[0], a->pos[2]),
               c->pos[1] - ground_at(winf, c->pos[0], c->pos[2]), finest[worst - 1], finest[worst]);
    }
    printf("   reference: the full level textures, %d levels x 256^2 = %.0f texels (heights; the "
           "material and detail windows add 256^2 + 2 x 512^2;\n   the detail windows are filled "
           "only within %.0f m of the ground)\n",
           s.levels, full, s.detail_distance);
    printf("   shading slopes (%d windows of %d^2 = %.0f texels): at most %.2f%% of them in a "
           "frame\n",
           s.levels - 1, CLIP_SLOPES_TEXELS, full_slopes, 100 * largest_slopes);
    goal("4. texels uploaded in a frame (any speed) / full levels, %", 100 * largest, 10, 0, "%");
    goal("4. shading-slope texels uploaded in a frame / their windows, %", 100 * largest_slopes, 10,
         0, "%");
}

// ---- 5: parallax ----------------------------------------------------------------------

// The gentlest dry 200 m x 200 m square of a bounded world (coarse 40 m grid), by its
// height range: where a camera a few metres up sees ground, not a hillside.
static void flattest_square(world *w, double *x0, double *z0) {
    const world_params *p = world_get_params(w);
    double extent = (double)(p->size - 1) * p->spacing, best = INFINITY;
    for (double z = 100; z + 300 < extent; z += 100)
        for (double x = 100; x + 300 < extent; x += 100) {
            double lo = INFINITY, hi = -INFINITY;
            for (double dz = 0; dz <= 200; dz += 40)
                for (double dx = 0; dx <= 200; dx += 40) {
                    double h = ground_at(w, x + dx, z + dz);
                    lo = fmin(lo, h), hi = fmax(hi, h);
                }
            if (lo > p->ocean_level + 2 && hi - lo < best) best = hi - lo, *x0 = x, *z0 = z;
        }
}

static void bench_parallax(bench *b, world *w1024, world *winf) {
    (void)winf;
    double x0 = 900, z0 = 880;
    flattest_square(w1024, &x0, &z0);
    // Sculpt the detail layer over the square through the command language: 11 noise
    // strokes 20 m apart.
    cmd_context ctx;
    world_settings ws = {.warn = quiet};
    cmd_context_init(&ctx, w1024, &ws, stdout, OROGEN_RESOURCE_DIR);
    char script[8192];
    size_t n = (size_t)snprintf(script, sizeof script,
                                "tool noise target=detail radius=20 strength=1 amount=0.25 "
                                "scale=4 octaves=3\n");
    for (int k = 0; k <= 10; k++)
        n += (size_t)snprintf(script + n, sizeof script - n, "stroke %.0f %.0f %.0f %.0f\n", x0,
                              z0 + 20 * k, x0 + 200, z0 + 20 * k);
    og_error err;
    double t0 = bench_now();
    check(cmd_run(&ctx, script, n, "bench_render", &err), &err, "sculpting detail");
    double sculpt_s = bench_now() - t0;
    // The camera: 3 m up at the square's south edge, looking north across it.
    camera c;
    camera_default(&c);
    c.pos[0] = x0 + 100, c.pos[2] = z0 + 195;
    c.pos[1] = ground_at(w1024, c.pos[0], c.pos[2]) + 3.0;
    c.yaw = 0, c.pitch = -15;
    // What the detail layer now holds in front of the camera (a 40 m square).
    layer_grid g;
    check(layer_grid_init(&g, world_get_params(w1024), TILE_LAYER_DETAIL, 0, &err), &err, "grid");
    grid_rect rect = layer_grid_disc_rect(&g, c.pos[0], c.pos[2] - 25, 20);
    size_t cells = (size_t)((rect.x1 - rect.x0) * (rect.z1 - rect.z0));
    float *dh = xmalloc(cells * sizeof *dh);
    check(layer_grid_read(w1024, &g, rect, dh, &err), &err, "reading the detail layer");
    float dmin = INFINITY, dmax = -INFINITY;
    for (size_t i = 0; i < cells; i++)
        dmin = fminf(dmin, dh[i]), dmax = fmaxf(dmax, dh[i]);
    free(dh);

    render_settings s;
    render_settings_default(&s);
    struct {
        const char *name;
        int parallax, steps;
    } cfg[] = {{"parallax off", 0, 8},
               {"parallax on, 4 steps", 1, 4},
               {"parallax on, 8 steps (default)", 1, 8},
               {"parallax on, 16 steps", 1, 16}};
    enum { CFG = 4 };
    double ms[CFG][REPEATS];
    settle(b, w1024, &c, &s);
    progress("5. parallax frames");
    for (int rep = 0; rep < REPEATS; rep++)
        for (int k = 0; k < CFG; k++) {
            s.parallax = cfg[k].parallax, s.parallax_steps = cfg[k].steps;
            if (rep == 0) clip_frame(b, w1024, &c, &s); // the first frame is not timed
            ms[k][rep] = clip_frame(b, w1024, &c, &s).wall_ms;
            if (rep == 0 && (k == 0 || k == 2)) {
                size_t px = (size_t)WIDTH * HEIGHT;
                unsigned char *rgb = xmalloc(px * 3);
                read_image(b, rgb);
                write_image(b, k == 0 ? "render_parallax_off.png" : "render_parallax_on.png", rgb);
                free(rgb);
            }
        }
    printf("\n5. Parallax detail, shaded view, camera 3 m above noise-sculpted detail "
           "(11 strokes on the detail layer in %.1f s; detail heights %.2f .. %.2f m in view)\n",
           sculpt_s, dmin, dmax);
    printf("   %-34s %10s %12s %14s\n", "setting", "FPS", "frame ms", "vs off");
    double off = bench_median(ms[0], REPEATS);
    for (int k = 0; k < CFG; k++) {
        double med = k == 0 ? off : bench_median(ms[k], REPEATS);
        printf("   %-34s %10.2f %12.1f %13.2fx\n", cfg[k].name, 1e3 / med, med, med / off);
    }
    printf("   images: render_parallax_off.png, render_parallax_on.png\n");
}

// ---- 6: levels against FPS ------------------------------------------------------------

// Sections 6 and 8: 150 m above the unbounded world's ground, looking 8 degrees down.
static camera levels_camera(world *winf) {
    camera c;
    camera_default(&c);
    c.pos[0] = 1200, c.pos[2] = -800;
    c.pos[1] = surface_at(winf, c.pos[0], c.pos[2]) + 150;
    c.yaw = 30, c.pitch = -8;
    return c;
}

static void bench_levels(bench *b, world *w1024, world *winf) {
    (void)w1024;
    camera c = levels_camera(winf);
    render_settings s;
    render_settings_default(&s);
    enum { NL = 5 };            // 3, 5, 7, 9, 11 as in Crause 2010's Table 10
    double ms[NL][REPEATS * 3]; // 3 frames per level count and repeat
    uint64_t tris[NL];
    progress("6. levels");
    for (int rep = 0; rep < REPEATS; rep++)
        for (int k = 0; k < NL; k++) {
            s.levels = 3 + 2 * k;
            settle(b, winf, &c, &s);
            if (rep == 0) clip_frame(b, winf, &c, &s); // the first frame is not timed
            for (int f = 0; f < 3; f++) {
                frame_time t = clip_frame(b, winf, &c, &s);
                ms[k][rep * 3 + f] = t.wall_ms;
                tris[k] = t.st.triangles;
            }
        }
    printf("\n6. Clipmap levels against frames per second, shaded view, fixed camera 150 m up "
           "looking 8 degrees down, unbounded world (Crause 2010 Table 10)\n");
    printf("   %-8s %12s %10s %12s %12s %12s\n", "levels", "reach (km)", "FPS", "frame ms",
           "triangles", "FPS / L3");
    double base = 0;
    for (int k = 0; k < NL; k++) {
        double med = bench_median(ms[k], REPEATS * 3);
        if (k == 0) base = 1e3 / med;
        int levels = 3 + 2 * k;
        double reach =
            0.5 * 254 * world_get_params(winf)->spacing * (double)(1 << (levels - 1)) / 1e3;
        printf("   %-8d %12.1f %10.3f %12.0f %12llu %12.2f\n", levels, reach, 1e3 / med, med,
               (unsigned long long)tris[k], 1e3 / med / base);
    }
}

// 8. The anti-aliasing pass on the finished image against the shaded frame it smooths,
// interleaved (same camera as 6, 8 levels).
static void bench_antialias(bench *b, world *w1024, world *winf) {
    (void)w1024;
    og_error err;
    char dir[4200];
    snprintf(dir, sizeof dir, "%s/shaders", OROGEN_RESOURCE_DIR);
    antialias *aa = antialias_create(dir, &err);
    if (!aa) check(-1, &err, "anti-aliasing pass");
    gl_target smooth;
    check(gl_target_create(&smooth, WIDTH, HEIGHT, &err), &err, "second target");
    camera c = levels_camera(winf);
    render_settings s;
    render_settings_default(&s);
    progress("8. anti-aliasing");
    settle(b, winf, &c, &s);
    clip_frame(b, winf, &c, &s);
    enum { N = 9 };
    double frame[N], pass[N];
    for (int i = 0; i < N; i++) {
        frame[i] = clip_frame(b, winf, &c, &s).wall_ms;
        double t0 = bench_now();
        check(antialias_apply(aa, &b->target, &smooth, &err), &err, "anti-aliasing");
        glFinish();
        pass[i] = (bench_now() - t0) * 1e3;
    }
    double f = bench_median(frame, N), a = bench_median(pass, N);
    printf("\n8. Anti-aliasing pass at %dx%d: %.1f ms against the shaded frame's %.1f ms "
           "(%.0f%% more)\n",
           WIDTH, HEIGHT, a, f, 100.0 * a / f);
    gl_target_destroy(&smooth);
    antialias_destroy(aa);
}

// The load average and llvmpipe's rasteriser threads (its default: one per core).
static void print_machine(const char *when) {
    double load[3] = {-1, -1, -1};
    getloadavg(load, 3);
    const char *threads = getenv("LP_NUM_THREADS");
    printf("   machine %s: load average %.2f %.2f %.2f on %ld cores; llvmpipe threads: %s\n", when,
           load[0], load[1], load[2], sysconf(_SC_NPROCESSORS_ONLN),
           threads && *threads ? threads : "one per core (LP_NUM_THREADS unset)");
}

static int wanted(const char *sections, char c) {
    return strchr(sections, c) != NULL;
}

int main(int argc, char **argv) {
    bench_journals_private(); // no crash journals left in the user's folder
    bench b = {0};
    const char *tmp = getenv("TMPDIR");
    b.out_dir = argc > 1 ? argv[1] : tmp && *tmp ? tmp : "/tmp";
    // Optional second argument: the sections to run, e.g. "7" or "356" (default all).
    const char *sections = argc > 2 ? argv[2] : "12345678";
    if (mkdir(b.out_dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "bench_render: cannot create %s: %s\n", b.out_dir, strerror(errno));
        return 1;
    }
    b.t_start = t_start = bench_now();
    setvbuf(stdout, NULL, _IOLBF, 0);
    og_error err;
    b.ctx = gl_headless_create(&err);
    if (!b.ctx) check(-1, &err, "headless GL context");
    check(gl_require_features(&err), &err, "GL features");
    check(gl_target_create(&b.target, WIDTH, HEIGHT, &err), &err, "offscreen target");
    b.r = terrain_renderer_create(OROGEN_RESOURCE_DIR, &err);
    if (!b.r) check(-1, &err, "terrain_renderer_create");
    printf("bench_render: %s, %dx%d offscreen, images in %s\n",
           (const char *)glGetString(GL_RENDERER), WIDTH, HEIGHT, b.out_dir);
    print_machine("at the start");

    world *w4096 = make_world(4096), *w1024 = make_world(1024), *winf = make_world(0);
    double times[9] = {0};
    if (wanted(sections, '1') || wanted(sections, '2') || wanted(sections, '7')) {
        naive_mesh m;
        double t0 = bench_now();
        check(naive_mesh_create(&m, w4096, OROGEN_BENCH_SHADER_DIR, OROGEN_RESOURCE_DIR, &err),
              &err, "naive mesh");
        printf("naive mesh: %lld^2 vertices, %llu triangles, built and uploaded in %.1f s\n",
               (long long)m.size, (unsigned long long)m.triangles, bench_now() - t0);
        t0 = bench_now();
        if (wanted(sections, '1') || wanted(sections, '2')) bench_vs_naive(&b, w4096, &m);
        times[1] = bench_now() - t0;
        t0 = bench_now();
        if (wanted(sections, '7')) bench_accuracy(&b, w4096, &m);
        times[7] = bench_now() - t0;
        naive_mesh_destroy(&m);
    }
    struct {
        char id;
        void (*run)(bench *, world *, world *);
    } rest[] = {{'3', bench_cpu},
                {'4', bench_uploads},
                {'5', bench_parallax},
                {'6', bench_levels},
                {'8', bench_antialias}};
    for (int i = 0; i < 5; i++) {
        if (!wanted(sections, rest[i].id)) continue;
        double t0 = bench_now();
        rest[i].run(&b, w1024, winf);
        times[rest[i].id - '0'] = bench_now() - t0;
    }

    printf("\nSummary\n");
    print_machine("at the end");
    for (int i = 0; i < goal_count; i++)
        printf("   %s %s\n", goals[i].pass ? "PASS" : "MISS", goals[i].text);
    printf("time: 1+2 %.0f s, 3 %.0f s, 4 %.0f s, 5 %.0f s, 6 %.0f s, 7 %.0f s, 8 %.0f s; total "
           "%.0f s\n",
           times[1], times[3], times[4], times[5], times[6], times[7], times[8],
           bench_now() - b.t_start);

    terrain_renderer_destroy(b.r);
    gl_target_destroy(&b.target);
    world_close(w4096), world_close(w1024), world_close(winf);
    gl_headless_destroy(b.ctx);
    return 0;
}
