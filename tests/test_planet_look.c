// The Earth-like planet reads as a planet at every altitude (issue 29, finding 4): seen
// over a mountain range from 2,000, 500, 100 and 10 km, the land is
//  - shaded by its relief: the median luminance step between neighbouring land pixels
//    is at least the pose's `relief` (a flat colour with a few contour lines has a
//    median of 0: the lines are too few to move it; closer, more relief per pixel);
//  - coloured by more than its height: of the land's chromaticity variance (colour with
//    the light's brightness divided out), at least OTHER_THAN_HEIGHT lies within pixels
//    of one height (70 m bins of the drawn ground's height, from the depth buffer), so
//    materials follow slope, climate and region, not contour bands.
// The look before per-chunk normal textures and the climate rules (6b1a195) failed both
// at every altitude but one: relief steps 0.3, 0.7, 1.7, 3.2 and colour beside height
// 0.19, 0.17, 0.10 (0.86 at 10 km, in snow and rock); after, 1.8, 3.7, 19, 24 and 0.79,
// 0.48, 0.62, 0.93. And
//  - its snow fields are not flat white: of the pixels inside them (at least MIN_SNOW),
//    at most MAX_FLAT_SNOW within FLAT_SNOW of their median luminance (lit by the
//    relief, broken into patches); before the snow's shading: 0.53, 0.61, 0.56 from
//    2,000, 500 and 100 km and 0.65 over the border below, after 0.14, 0.41, 0.42, 0.44;
//  - the desert blends into grassland over a width (a pose over their border, straight
//    down from 500 km): at least MIN_BORDER_WIDTH pixels of mixed colour per pixel of
//    the desert's outline (a hard border: 3.0; blended by moisture's patches: 5.8).
// Frames that fail are written to $TMPDIR/orogen-look-failures/.
#include "editor/params/planet_presets.h"
#include "editor/world/world.h"
#include "io/image_read.h"
#include "renderer/camera.h"
#include "renderer/planet_camera.h"
#include "renderer/terrain_renderer.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <cmocka.h>

#include "support/planet_view.h"

#define W 320
#define H 180
#define OTHER_THAN_HEIGHT 0.3
#define HEIGHT_BIN 70.0 // metres
#define HEIGHT_BINS 256
#define FLAT_SNOW 4.0 // luminance
#define MIN_SNOW 300  // snow pixels for its flatness to count
#define MAX_FLAT_SNOW 0.49
#define MIN_BORDER_WIDTH 4.5 // pixels (at 320 x 180, from 500 km)
#define SAND_GREEN -0.03     // greenness (g - r over the sum) of sand and grassland from orbit
#define GRASS_GREEN 0.08

static planet_view view;

static int setup(void **state) {
    (void)state;
    return planet_view_open(&view, W, H, "test_planet_look");
}

static int teardown(void **state) {
    (void)state;
    planet_view_close(&view);
    return 0;
}

static double luminance(const unsigned char *p) {
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

static int by_value(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef struct look {
    int land;            // land pixels
    double relief_step;  // median luminance step to the next land pixel (right, down)
    double other_share;  // chromaticity variance within height bins over all of it
    int snow;            // snow pixels inside a snow field (their four neighbours snow too)
    double snow_flat;    // the share of them within FLAT_SNOW of the field's median
    double border_width; // desert to grassland: pixels of mixed colour per pixel of outline
} look;

// Snow: bright and grey (white under any light); desert: sand's warm hue; green: more
// green than red. Chromaticity of the pixel (r, g, b over their sum).
static int is_snow(const unsigned char *p) {
    const int hi = p[0] > p[1] ? (p[0] > p[2] ? p[0] : p[2]) : (p[1] > p[2] ? p[1] : p[2]);
    const int lo = p[0] < p[1] ? (p[0] < p[2] ? p[0] : p[2]) : (p[1] < p[2] ? p[1] : p[2]);
    return luminance(p) > 140 && hi - lo < 0.1 * hi;
}

// Where a colour lies between sand's (0) and grassland's (1) as seen from orbit, by its
// warmth (red over blue) and greenness (green over red), each over the sum; outside
// 0..1 for colours beyond either, NAN for colours of neither kind (rock, snow, sea).
static double sand_to_green(const unsigned char *p) {
    const double sum = (double)p[0] + p[1] + p[2] + 1.0;
    const double warm = (p[0] - (double)p[2]) / sum, green = (p[1] - (double)p[0]) / sum;
    if (warm < 0.025 && green < 0.04) return NAN;
    return (green - SAND_GREEN) / (GRASS_GREEN - SAND_GREEN);
}

// The two measures over a frame and its heights.
static look measure(const unsigned char *shaded, const double *height, double sea) {
    static unsigned char land[W * H];
    static int bin[W * H];
    static double steps[W * H];
    look out = {0};
    for (int i = 0; i < W * H; i++) {
        land[i] = height[i] > sea + 1.0; // the sea is drawn at its level
        bin[i] = land[i] ? (int)fmin((height[i] - sea) / HEIGHT_BIN, HEIGHT_BINS - 1) : 0;
        out.land += land[i];
    }
    int n = 0;
    for (int y = 0; y + 1 < H; y++)
        for (int x = 0; x + 1 < W; x++) {
            const int i = y * W + x;
            if (!land[i] || !land[i + 1] || !land[i + W]) continue;
            const double l = luminance(shaded + 3 * i);
            steps[n++] = fabs(luminance(shaded + 3 * (i + 1)) - l) +
                         fabs(luminance(shaded + 3 * (i + W)) - l);
        }
    if (n > 0) {
        qsort(steps, (size_t)n, sizeof steps[0], by_value);
        out.relief_step = steps[n / 2];
    }
    // Snow fields: how much of their inside is one flat white (a field lit alike all over).
    n = 0;
    for (int y = 1; y + 1 < H; y++)
        for (int x = 1; x + 1 < W; x++) {
            const int i = y * W + x;
            if (land[i] && is_snow(shaded + 3 * i) && is_snow(shaded + 3 * (i - 1)) &&
                is_snow(shaded + 3 * (i + 1)) && is_snow(shaded + 3 * (i - W)) &&
                is_snow(shaded + 3 * (i + W)))
                steps[n++] = luminance(shaded + 3 * i);
        }
    out.snow = n;
    if (n > 0) {
        qsort(steps, (size_t)n, sizeof steps[0], by_value);
        int flat = 0;
        for (int k = 0; k < n; k++)
            flat += fabs(steps[k] - steps[n / 2]) <= FLAT_SNOW;
        out.snow_flat = (double)flat / n;
    }
    // Desert beside grassland: a hard border passes from one to the other within a pixel
    // or two, a blended one through mixed colours over a width. The border's width: the
    // land pixels of mixed colour over the desert's outline (desert pixels with a
    // neighbour that is not desert).
    int mixed = 0, outline = 0;
    for (int y = 1; y + 1 < H; y++)
        for (int x = 1; x + 1 < W; x++) {
            const int i = y * W + x;
            if (!land[i]) continue;
            const double t = sand_to_green(shaded + 3 * i);
            mixed += t >= 0.2 && t <= 0.8;
            if (!(t < 0.2)) continue;
            const int around[4] = {i - 1, i + 1, i - W, i + W};
            for (int k = 0; k < 4; k++)
                if (land[around[k]] && !(sand_to_green(shaded + 3 * around[k]) < 0.2)) {
                    outline++;
                    break;
                }
        }
    out.border_width = outline > 0 ? (double)mixed / outline : 0;
    // Chromaticity (r, g over the sum) per height bin: the share of its variance left
    // within the bins.
    static double sum[HEIGHT_BINS][2], sum2[HEIGHT_BINS], count[HEIGHT_BINS];
    memset(sum, 0, sizeof sum), memset(sum2, 0, sizeof sum2), memset(count, 0, sizeof count);
    double all[2] = {0, 0}, all2 = 0, total = 0;
    for (int i = 0; i < W * H; i++) {
        if (!land[i]) continue;
        const unsigned char *p = shaded + 3 * i;
        const double s = (double)p[0] + p[1] + p[2] + 1.0;
        const double c[2] = {p[0] / s, p[1] / s};
        const int b = bin[i];
        sum[b][0] += c[0], sum[b][1] += c[1], sum2[b] += c[0] * c[0] + c[1] * c[1], count[b]++;
        all[0] += c[0], all[1] += c[1], all2 += c[0] * c[0] + c[1] * c[1], total++;
    }
    if (total < 2) return out;
    const double variance = all2 - (all[0] * all[0] + all[1] * all[1]) / total;
    double within = 0;
    for (int b = 0; b < HEIGHT_BINS; b++)
        if (count[b] > 0)
            within += sum2[b] - (sum[b][0] * sum[b][0] + sum[b][1] * sum[b][1]) / count[b];
    out.other_share = variance > 0 ? within / variance : 0;
    return out;
}

static void save_failure(const char *name, const unsigned char *rgb) {
    const char *tmp = getenv("TMPDIR");
    char dir[4200], path[4400];
    snprintf(dir, sizeof dir, "%s/orogen-look-failures", tmp ? tmp : "/tmp");
    mkdir(dir, 0755);
    snprintf(path, sizeof path, "%s/%s.png", dir, name);
    og_error err;
    image_write_rgb8(path, rgb, W, H, &err);
}

static void test_relief_and_colour(void **state) {
    (void)state;
    // Over the ranges of the Earth-like preset's big continent (seed 1337), looking north.
    static const struct {
        const char *name;
        double lat, lon, altitude, pitch, relief;
        int border; // the desert's border with grassland in view: its width is measured
    } poses[] = {
        {"2000km", 22.0, 5.7, 2e6, -90, 1.2, 0}, {"500km", 18.0, 5.7, 5e5, -50, 2.0, 0},
        {"100km", 21.0, 5.7, 1e5, -25, 6.0, 0},  {"10km", 21.8, 5.7, 1e4, -12, 10.0, 0},
        {"border", 24.0, 0.5, 5e5, -90, 2.0, 1}, // west of the range, straight down
    };
    static unsigned char shaded[W * H * 3];
    static double height[W * H];
    int failed = 0;
    for (size_t k = 0; k < sizeof poses / sizeof poses[0]; k++) {
        camera c;
        camera_default(&c);
        const world_params *p = world_get_params(view.earth);
        double ground = 0;
        og_error err;
        planet_position(poses[k].lat, poses[k].lon, p->radius, c.pos);
        assert_int_equal(planet_surface_height(view.earth, c.pos, &ground, &err), 0);
        const double above = poses[k].altitude < 5e4 ? ground : 0.0;
        planet_position(poses[k].lat, poses[k].lon, p->radius + above + poses[k].altitude, c.pos);
        c.yaw = 0, c.pitch = poses[k].pitch;
        planet_view_draw(&view, view.earth, &c, NULL, shaded, NULL, height);
        const look l = measure(shaded, height, world_params_ocean_height(p));
        const int ok = l.land > W * H / 10 && l.relief_step >= poses[k].relief &&
                       l.other_share >= OTHER_THAN_HEIGHT &&
                       (l.snow < MIN_SNOW || l.snow_flat <= MAX_FLAT_SNOW) &&
                       (!poses[k].border || l.border_width >= MIN_BORDER_WIDTH);
        printf("%-7s land %5.1f%%  relief step %4.1f (>= %.1f)  colour beside height %.2f "
               "(>= %.2f)  snow %d, flat %.2f (<= %.2f)  border width %.1f%s\n",
               poses[k].name, 100.0 * l.land / (W * H), l.relief_step, poses[k].relief,
               l.other_share, OTHER_THAN_HEIGHT, l.snow, l.snow_flat, MAX_FLAT_SNOW, l.border_width,
               ok ? "" : "  FAIL");
        if (!ok) {
            failed++;
            save_failure(poses[k].name, shaded);
        }
    }
    assert_int_equal(failed, 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_relief_and_colour)};
    return cmocka_run_group_tests(tests, setup, teardown);
}
