#include "support/planet_view.h"

#include "editor/params/planet_presets.h"
#include "renderer/planet_camera.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "support/test_world.h"

int planet_view_open(planet_view *v, int w, int h, const char *test) {
    og_error err = {{0}};
    *v = (planet_view){.w = w, .h = h};
    if (!(v->ctx = gl_headless_create(&err)) || gl_require_features(&err) != 0 ||
        gl_target_create(&v->target, w, h, &err) != 0 ||
        !(v->renderer = terrain_renderer_create(OROGEN_RESOURCE_DIR, &err))) {
        fprintf(stderr, "%s: %s\n", test, err.msg);
        return -1;
    }
    terrain_renderer_set_view_size(v->renderer, w, h);
    world_params wp;
    world_params_default(&wp, WORLD_PLANET);
    if (planet_preset_apply(&wp, "earth", &err) != 0) return -1;
    world_settings ws = {.cache_budget_bytes = (size_t)1 << 30, .workers = 2, .warn = test_silent};
    return (v->earth = world_create(&wp, &ws, &err)) ? 0 : -1;
}

void planet_view_close(planet_view *v) {
    world_close(v->earth);
    terrain_renderer_destroy(v->renderer);
    gl_target_destroy(&v->target);
    gl_headless_destroy(v->ctx);
}

static double now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

void planet_view_draw(planet_view *v, world *world, const camera *c, const render_settings *s,
                      unsigned char *rgb, double (*pos)[3], double *height) {
    og_error err = {{0}};
    render_settings defaults;
    render_settings_default(&defaults);
    if (!s) s = &defaults;
    const double t0 = now_s();
    int rc;
    while ((rc = terrain_renderer_update(v->renderer, world, c, s, &err)) == 0 &&
           now_s() - t0 < 60) {
        struct timespec nap = {0, 1000000};
        nanosleep(&nap, NULL);
    }
    assert_true(rc >= 0);
    glBindFramebuffer(GL_FRAMEBUFFER, v->target.fbo);
    assert_int_equal(terrain_renderer_draw(v->renderer, world, c, s, NULL, v->w, v->h, &err), 0);
    assert_int_equal(gl_target_read_rgb(&v->target, rgb, &err), 0); // top row first
    if (!pos && !height) return;
    const int w = v->w, h = v->h;
    float *depth = malloc(sizeof(float) * (size_t)w * h);
    assert_non_null(depth);
    glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depth); // bottom row first
    const world_params *p = world_get_params(world);
    double f[3], rt[3], up[3];
    if (p->kind == WORLD_PLANET)
        planet_camera_basis(c, f, rt, up);
    else
        camera_forward(c, f), camera_right(c, rt), camera_up(c, up);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const float d = depth[(h - 1 - y) * w + x]; // reversed z: 0 is infinitely far
            double dir[3], at[3] = {NAN, NAN, NAN};
            if (d > 0.0f) {
                camera_basis_ray(c, rt, up, f, (double)w / h, (x + 0.5) / w, (y + 0.5) / h, dir);
                const double along =
                    c->near_m / d / (dir[0] * f[0] + dir[1] * f[1] + dir[2] * f[2]);
                for (int a = 0; a < 3; a++)
                    at[a] = c->pos[a] + dir[a] * along;
            }
            if (pos)
                for (int a = 0; a < 3; a++)
                    pos[y * w + x][a] = at[a];
            if (height)
                height[y * w + x] = sqrt(at[0] * at[0] + at[1] * at[1] + at[2] * at[2]) - p->radius;
        }
    free(depth);
}
