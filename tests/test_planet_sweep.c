// The planet viewport where users look: over 200 camera poses from 2 m to 40,000 km,
// pitch -90 to +20 degrees, over land, sea and coasts, on and beside face edges and
// corners and near the poles, on the four presets, each frame (small, 160 x 90) checked
// by two detectors:
//  - holes: pixels whose ray meets a sphere under all the drawn ground (the sea's surface
//    on a planet with a sea, less the chords' sag) must show ground (depth written), and
//    where the sun is well up there, not black;
//  - seams: across a face edge seen on the screen (neighbouring pixels whose ground lies
//    on different faces) the colour steps no more than the steps beside it, and the
//    ground on the two sides is alike (the mean of a band on each side).
// Failing frames are written to $TMPDIR/orogen-sweep-failures/ for a look.
#include "editor/params/planet_presets.h"
#include "editor/params/world_grid.h"
#include "editor/world/world.h"
#include "io/image_read.h"
#include "renderer/camera.h"
#include "renderer/gl_context.h"
#include "renderer/gl_target.h"
#include "renderer/lighting.h"
#include "renderer/planet_camera.h"
#include "renderer/terrain_renderer.h"
#include "support/test_support.h"

#include <epoxy/gl.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <cmocka.h>

#define W 160
#define H 90
// Rasterisation leaves the odd pixel between triangles that meet edge to edge at a
// T-junction (llvmpipe's rules, sub-pixel slivers): a frame may have this many.
#define HOLE_TOLERANCE 2
#define SEAM_MIN_PAIRS 40 // fewer: a disc a few pixels across, too coarse to judge

typedef struct sweep {
    gl_headless *ctx;
    gl_target target;
    terrain_renderer *r;
    render_settings s;
    world_settings ws;
    int poses, holes, seams;
    char failures[4096];
} sweep;

static sweep S;

static void quiet(void *u, const char *m) {
    (void)u, (void)m;
}

static double now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static int setup(void **state) {
    (void)state;
    og_error err = {{0}};
    if (!(S.ctx = gl_headless_create(&err)) || gl_require_features(&err) != 0 ||
        gl_target_create(&S.target, W, H, &err) != 0 ||
        !(S.r = terrain_renderer_create(OROGEN_RESOURCE_DIR, &err))) {
        fprintf(stderr, "test_planet_sweep: %s\n", err.msg);
        return -1;
    }
    terrain_renderer_set_view_size(S.r, W, H);
    render_settings_default(&S.s);
    S.ws = (world_settings){.cache_budget_bytes = (size_t)1 << 30, .workers = 2, .warn = quiet};
    const char *tmp = getenv("TMPDIR");
    snprintf(S.failures, sizeof S.failures, "%s/orogen-sweep-failures", tmp ? tmp : "/tmp");
    mkdir(S.failures, 0755);
    return 0;
}

static int teardown(void **state) {
    (void)state;
    terrain_renderer_destroy(S.r);
    gl_target_destroy(&S.target);
    gl_headless_destroy(S.ctx);
    return 0;
}

// The surface a camera stands or floats on: the ground, or the sea above it.
static double surface_at(world *w, double lat, double lon) {
    const world_params *p = world_get_params(w);
    double pos[3], ground = 0;
    og_error err;
    planet_position(lat, lon, p->radius, pos);
    assert_int_equal(planet_ground_height(w, pos, &ground, &err), 0);
    return ground;
}

// Updates until every chunk wanted is drawn at its own level (or 20 s pass), then draws.
static void render(world *w, const camera *c) {
    og_error err = {{0}};
    const double t0 = now_s();
    int rc;
    while ((rc = terrain_renderer_update(S.r, w, c, &S.s, &err)) == 0 && now_s() - t0 < 20) {
        struct timespec nap = {0, 1000000};
        nanosleep(&nap, NULL);
    }
    assert_true(rc >= 0);
    glBindFramebuffer(GL_FRAMEBUFFER, S.target.fbo);
    assert_int_equal(terrain_renderer_draw(S.r, w, c, &S.s, NULL, W, H, &err), 0);
}

static double luminance(const unsigned char *p) {
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// The ray through pixel (x, y) (top row first) meets the sphere of radius rin.
static int meets(const camera *c, const double f[3], const double rt[3], const double up[3],
                 double x, double y, double rin) {
    double dir[3];
    camera_basis_ray(c, rt, up, f, (double)W / H, x / W, y / H, dir);
    const double *o = c->pos;
    const double b = o[0] * dir[0] + o[1] * dir[1] + o[2] * dir[2];
    const double cc = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - rin * rin;
    return b * b - cc >= 0 && (b < 0 || cc < 0);
}

static unsigned char edge_mark[W * H]; // the last frame's pixels beside a face edge

typedef struct frame_result {
    int holes, black, seam_pairs;
    int hole_x, hole_y; // the first hole
    double edge_step, beside_step, band_gap;
    int seam;
} frame_result;

static int by_value(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n) {
    qsort(v, (size_t)n, sizeof v[0], by_value);
    return v[n / 2];
}

// The two detectors over the frame just drawn.
static frame_result inspect(const camera *c, const world_params *p) {
    static float depth[W * H];
    static unsigned char rgb[W * H * 3];
    static int face[W * H];
    static unsigned char must[W * H];
    frame_result out = {0};
    og_error err;
    glBindFramebuffer(GL_FRAMEBUFFER, S.target.fbo);
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, depth); // bottom row first
    assert_int_equal(gl_target_read_rgb(&S.target, rgb, &err), 0); // top row first
    double f[3], rt[3], up[3];
    planet_camera_basis(c, f, rt, up);
    const double ocean = world_params_ocean_height(p);
    const double lowest = ocean > -p->max_height ? ocean : -1.5 * p->max_height;
    const double rin = p->radius + lowest - 1e-3 * p->radius;
    float sun[3];
    render_sun_direction(&S.s, sun);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            // Must show ground: the pixel's corners all meet the inner sphere.
            must[y * W + x] =
                meets(c, f, rt, up, x, y, rin) && meets(c, f, rt, up, x + 1, y, rin) &&
                meets(c, f, rt, up, x, y + 1, rin) && meets(c, f, rt, up, x + 1, y + 1, rin);
            const float d = depth[(H - 1 - y) * W + x];
            face[y * W + x] = -1;
            if (!(d > 0.0f)) continue;
            double dir[3], pos[3];
            camera_basis_ray(c, rt, up, f, (double)W / H, (x + 0.5) / W, (y + 0.5) / H, dir);
            const double along = c->near_m / d / (dir[0] * f[0] + dir[1] * f[1] + dir[2] * f[2]);
            for (int a = 0; a < 3; a++)
                pos[a] = c->pos[a] + dir[a] * along;
            double s, t;
            world_grid_direction_face(pos, &face[y * W + x], &s, &t);
            const double len = sqrt(pos[0] * pos[0] + pos[1] * pos[1] + pos[2] * pos[2]);
            const double lit = (pos[0] * sun[0] + pos[1] * sun[1] + pos[2] * sun[2]) / len;
            const unsigned char *px = rgb + (size_t)(y * W + x) * 3;
            if (must[y * W + x] && lit > 0.3 && px[0] < 6 && px[1] < 6 && px[2] < 6) out.black++;
        }
    for (int i = 0; i < W * H; i++)
        if (must[i] && face[i] < 0 && out.holes++ == 0) out.hole_x = i % W, out.hole_y = i / W;
    // Seams: pairs across a face edge (both sides ground on one face each for 3 pixels).
    memset(edge_mark, 0, sizeof edge_mark);
    static double edge[W * H * 2], beside[W * H * 2];
    double side_a = 0, side_b = 0;
    int pairs = 0;
    for (int dirn = 0; dirn < 2; dirn++) {
        const int dx = dirn == 0 ? 1 : 0, dy = dirn == 0 ? 0 : 1;
        for (int y = 3 * dy; y < H - 4 * dy; y++)
            for (int x = 3 * dx; x < W - 4 * dx; x++) {
                const int a = y * W + x, b = (y + dy) * W + (x + dx), step = dy * W + dx;
                if (face[a] < 0 || face[b] < 0 || face[a] == face[b]) continue;
                int clean = 1;
                for (int k = 1; k < 4; k++)
                    clean &=
                        face[a - k * step + step] == face[a] && face[b + (k - 1) * step] == face[b];
                if (!clean || face[a - 3 * step] != face[a] || face[b + 3 * step] != face[b])
                    continue;
                double la[4], lb[4];
                for (int k = 0; k < 4; k++) {
                    la[k] = luminance(rgb + (size_t)(a - k * step) * 3);
                    lb[k] = luminance(rgb + (size_t)(b + k * step) * 3);
                }
                edge_mark[a] = edge_mark[b] = 1;
                edge[pairs] = fabs(la[0] - lb[0]);
                beside[pairs] = 0.5 * (fabs(la[0] - la[1]) + fabs(lb[0] - lb[1]));
                // The bands' difference less what each side's own gradient predicts
                // for bands 4 pixels apart (the haze brightens toward the horizon: an
                // edge along it has a brighter band on its far side).
                const double predicted =
                    (la[0] + la[1] - la[2] - la[3]) / 2 + (lb[2] + lb[3] - lb[0] - lb[1]) / 2;
                side_a += (la[0] + la[1] + la[2] + la[3]) / 4,
                    side_b += (lb[0] + lb[1] + lb[2] + lb[3]) / 4 - predicted;
                pairs++;
            }
    }
    out.seam_pairs = pairs;
    if (pairs >= SEAM_MIN_PAIRS) {
        // Medians: a coastline crossing the edge here and there is no seam.
        out.edge_step = median(edge, pairs), out.beside_step = median(beside, pairs);
        out.band_gap = fabs(side_a - side_b) / pairs;
        out.seam = out.edge_step > 2.0 * out.beside_step + 3.0 || out.band_gap > 8.0;
    }
    return out;
}

static void save_failure(const char *name) {
    static unsigned char rgb[W * H * 3];
    og_error err;
    char path[4600];
    snprintf(path, sizeof path, "%s/%s.png", S.failures, name);
    if (gl_target_read_rgb(&S.target, rgb, &err) != 0) return;
    image_write_rgb8(path, rgb, W, H, &err);
    for (int i = 0; i < W * H; i++) // and with the face edges' pixels marked
        if (edge_mark[i]) rgb[3 * i] = 255, rgb[3 * i + 1] = 0, rgb[3 * i + 2] = 255;
    snprintf(path, sizeof path, "%s/%s-edges.png", S.failures, name);
    image_write_rgb8(path, rgb, W, H, &err);
}

typedef struct place {
    const char *name;
    double lat, lon;
} place;

// One pose: above_surface metres over the ground or the sea, pitch, yaw.
static void pose_fov(world *w, const char *preset, const place *pl, double above, double pitch,
                     double yaw, double fov) {
    const world_params *p = world_get_params(w);
    camera c;
    camera_default(&c);
    double surface = 0;
    og_error err;
    planet_position(pl->lat, pl->lon, p->radius, c.pos);
    assert_int_equal(planet_surface_height(w, c.pos, &surface, &err), 0);
    planet_position(pl->lat, pl->lon, p->radius + surface + above, c.pos);
    c.pitch = pitch, c.yaw = yaw, c.fov_y = fov;
    render(w, &c);
    frame_result fr = inspect(&c, p);
    S.poses++;
    char name[256];
    snprintf(name, sizeof name, "%s-%s-%gm-pitch%g-yaw%g-fov%g", preset, pl->name, above, pitch,
             yaw, fov);
    // Slivers a fraction of a pixel wide at 60 degrees are that many times wider in a
    // narrower view.
    const double tolerance = HOLE_TOLERANCE * fmax(60.0 / fov, 1.0);
    if (fr.holes > tolerance || fr.black > tolerance) {
        S.holes++;
        printf("HOLE %s (%.5f, %.5f): %d pixels without ground (the first at %d, %d), %d black in "
               "sunlight\n",
               name, pl->lat, pl->lon, fr.holes, fr.hole_x, fr.hole_y, fr.black);
        save_failure(name);
    }
    if (fr.seam) {
        S.seams++;
        printf("SEAM %s: %d pairs across a face edge, step %.1f against %.1f beside, sides "
               "differ by %.1f\n",
               name, fr.seam_pairs, fr.edge_step, fr.beside_step, fr.band_gap);
        save_failure(name);
    }
}

static void pose(world *w, const char *preset, const place *pl, double above, double pitch,
                 double yaw) {
    pose_fov(w, preset, pl, above, pitch, yaw, 60);
}

// A place whose surface is land (want 1) or sea (want 0) at least `margin` from the
// sea's level, the first of a fixed scan.
static int find_place(world *w, int want_land, double margin, place *out) {
    const double ocean = world_params_ocean_height(world_get_params(w));
    for (int k = 0; k < 97; k++) {
        const double lat = -50 + 100.0 * ((k * 37) % 97) / 97,
                     lon = -180 + 360.0 * ((k * 23) % 97) / 97;
        const double h = surface_at(w, lat, lon);
        if (want_land ? h > ocean + margin : h < ocean - margin) {
            out->lat = lat, out->lon = lon;
            return 1;
        }
    }
    return 0;
}

// A coast: bisection between a land and a sea place to within a few metres of the sea.
static void find_coast(world *w, const place *land, const place *sea, place *out) {
    const double ocean = world_params_ocean_height(world_get_params(w));
    double a[2] = {land->lat, land->lon}, b[2] = {sea->lat, sea->lon};
    for (int k = 0; k < 30; k++) {
        double m[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
        const double h = surface_at(w, m[0], m[1]);
        if (h > ocean)
            a[0] = m[0], a[1] = m[1];
        else
            b[0] = m[0], b[1] = m[1];
    }
    out->lat = a[0], out->lon = a[1];
}

// Altitudes (metres over the surface) and pitches each place is seen from.
static const double POSES[][2] = {
    {2, -5},     {2, -35},   {2, 20},    {10, -12},  {100, -10}, {100, -60},
    {1000, -20}, {1e4, -15}, {1e4, -90}, {1e5, -30}, {1e6, -60}, {4e7, -90},
};

static void sweep_preset(const char *preset) {
    og_error err = {{0}};
    world_params wp;
    world_params_default(&wp, WORLD_PLANET);
    assert_int_equal(planet_preset_apply(&wp, preset, &err), 0);
    world *w = world_create(&wp, &S.ws, &err);
    assert_non_null(w);
    place places[8];
    int n = 0;
    place land = {"land", 0, 0}, sea = {"sea", 0, 0};
    if (find_place(w, 1, 200, &land)) places[n++] = land;
    if (world_params_ocean_height(&wp) > -wp.max_height && find_place(w, 0, 200, &sea)) {
        places[n++] = sea;
        place coast = {"coast", 0, 0};
        find_coast(w, &land, &sea, &coast);
        places[n++] = coast;
    }
    // The equator's face edge at 45 E, beside it, and the cube's corner over 45 E.
    places[n++] = (place){"edge", 10.004, 45};
    places[n++] = (place){"beside-edge", 10.004, 45.01};
    places[n++] = (place){"corner", 35.2644, 45};
    places[n++] = (place){"pole", 89.9, 10};
    for (int i = 0; i < n; i++)
        for (size_t k = 0; k < sizeof POSES / sizeof POSES[0]; k++)
            pose(w, preset, &places[i], POSES[k][0], POSES[k][1], fmod(110.0 + 47.0 * k, 360.0));
    // The material textures close up, magnified (a narrow field of view makes a pixel a
    // few millimetres of ground): across the edge and at the corners their coordinates
    // must run on, or the texture's pattern breaks along a line. And the cube's corner
    // over land on the Earth-like preset (45 W), where the light stepped along the edges.
    const place west = {"corner-west", 35.2644, -45};
    pose_fov(w, preset, &places[n - 4], 2, -70, 160, 12); // the edge
    pose_fov(w, preset, &places[n - 2], 2, -70, 160, 12); // the corner
    pose_fov(w, preset, &west, 2, -70, 160, 12);
    pose(w, preset, &west, 2, -35, 157);
    pose(w, preset, &west, 100, -10, 298);
    pose(w, preset, &west, 600, -80, 200);
    world_close(w);
}

static void test_sweep(void **state) {
    (void)state;
    const double t0 = now_s();
    for (size_t i = 0; i < planet_preset_count(); i++)
        sweep_preset(planet_preset_name(i));
    printf("sweep: %d poses, %d with holes, %d with seams (%.0f s)\n", S.poses, S.holes, S.seams,
           now_s() - t0);
    assert_true(S.poses >= 200);
    assert_int_equal(S.holes, 0);
    assert_int_equal(S.seams, 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_sweep)};
    return cmocka_run_group_tests(tests, setup, teardown);
}
