#include "renderer/view_commands.h"

#include "editor/edit_commands.h"
#include "renderer/viewport.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define DEFAULT_WIDTH 1280
#define DEFAULT_HEIGHT 720
#define MAX_IMAGE_SIDE 8192

static viewport *get_viewport(cmd_context *ctx, og_error *err) {
    if (!ctx->viewport) ctx->viewport = viewport_create(ctx->resource_dir);
    if (!ctx->viewport) og_error_set(err, "out of memory");
    return ctx->viewport;
}

static void print_camera(cmd_context *ctx, const camera *c) {
    fprintf(ctx->out, "camera %.3f %.3f %.3f %.3f %.3f %.3f\n", c->pos[0], c->pos[1], c->pos[2],
            c->yaw, c->pitch, c->fov_y);
}

int cmd_camera(cmd_context *ctx, int argc, char **argv, og_error *err) {
    viewport *v = get_viewport(ctx, err);
    if (!v) return -1;
    if (argc == 1) {
        if (!v->cam_set && viewport_default_camera(v, ctx->world, err) != 0) return -1;
        print_camera(ctx, &v->cam);
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "default") == 0) {
        if (viewport_default_camera(v, ctx->world, err) != 0) return -1;
        print_camera(ctx, &v->cam);
        return 0;
    }
    if (argc < 6) return og_error_set(err, "usage: camera X Y Z YAW PITCH [FOV] (or camera default)");
    const char *names[6] = {"X", "Y", "Z", "YAW", "PITCH", "FOV"};
    double val[6] = {0, 0, 0, 0, 0, v->cam.fov_y};
    for (int i = 1; i < argc; i++)
        if (cmd_parse_number(argv[i], names[i - 1], &val[i - 1], err) != 0) return -1;
    for (int i = 0; i < 3; i++)
        if (fabs(val[i]) > 1e12) return og_error_set(err, "%s: %g m is too far (limit 1e12 m)", names[i], val[i]);
    if (val[4] < -90 || val[4] > 90)
        return og_error_set(err, "PITCH: %g is outside -90 .. 90 degrees", val[4]);
    if (val[5] < 1 || val[5] > 170)
        return og_error_set(err, "FOV: %g is outside 1 .. 170 degrees", val[5]);
    camera c = v->cam;
    c.pos[0] = val[0], c.pos[1] = val[1], c.pos[2] = val[2];
    c.yaw = 0, c.pitch = 0;
    camera_look(&c, val[3], val[4]); // wraps yaw and clamps pitch the same way as the window
    c.fov_y = val[5];
    v->cam = c;
    v->cam_set = 1;
    return 0;
}

int cmd_view(cmd_context *ctx, int argc, char **argv, og_error *err) {
    viewport *v = get_viewport(ctx, err);
    if (!v) return -1;
    if (argc == 1) {
        fprintf(ctx->out, "view %s\n", view_mode_name(v->settings.view));
        return 0;
    }
    int m = view_mode_parse(argv[1]);
    if (m < 0)
        return og_error_set(err, "view: unknown mode '%s' (shaded, wireframe, levels, height, slope)",
                            argv[1]);
    v->settings.view = (view_mode)m;
    return 0;
}

static int parse_switch(const char *key, const char *value, int *out, og_error *err) {
    if (strcmp(value, "on") == 0 || strcmp(value, "1") == 0) return *out = 1, 0;
    if (strcmp(value, "off") == 0 || strcmp(value, "0") == 0) return *out = 0, 0;
    return og_error_set(err, "%s: expected on or off, got '%s'", key, value);
}

static int parse_ranged(const char *key, const char *value, double lo, double hi, double *out,
                        og_error *err) {
    if (cmd_parse_number(value, key, out, err) != 0) return -1;
    if (*out < lo || *out > hi) return og_error_set(err, "%s: %g is outside %g .. %g", key, *out, lo, hi);
    return 0;
}

static int parse_integer(const char *key, const char *value, int lo, int hi, int *out, og_error *err) {
    double d;
    if (parse_ranged(key, value, lo, hi, &d, err) != 0) return -1;
    if (d != floor(d)) return og_error_set(err, "%s: expected a whole number, got '%s'", key, value);
    *out = (int)d;
    return 0;
}

static void print_settings(cmd_context *ctx, const render_settings *s) {
    fprintf(ctx->out,
            "render levels=%d parallax=%s quality=%d detail_distance=%g culling=%s morph=%s "
            "sun=%g,%g fog=%g view=%s\n",
            s->levels, s->parallax ? "on" : "off", s->parallax_steps, s->detail_distance,
            s->culling ? "on" : "off", s->morph ? "on" : "off", s->sun_yaw, s->sun_pitch,
            s->fog_density, view_mode_name(s->view));
}

int cmd_render(cmd_context *ctx, int argc, char **argv, og_error *err) {
    viewport *v = get_viewport(ctx, err);
    if (!v) return -1;
    render_settings s = v->settings; // applied only if every argument is good
    for (int i = 1; i < argc; i++) {
        char buf[256], *key, *value;
        if (cmd_split_setting(argv[i], buf, sizeof buf, &key, &value, err) != 0) return -1;
        int rc;
        if (strcmp(key, "levels") == 0)
            rc = parse_integer(key, value, RENDER_MIN_LEVELS, RENDER_MAX_LEVELS, &s.levels, err);
        else if (strcmp(key, "parallax") == 0)
            rc = parse_switch(key, value, &s.parallax, err);
        else if (strcmp(key, "quality") == 0)
            rc = parse_integer(key, value, 1, 32, &s.parallax_steps, err);
        else if (strcmp(key, "detail_distance") == 0)
            rc = parse_ranged(key, value, 1, 100000, &s.detail_distance, err);
        else if (strcmp(key, "culling") == 0)
            rc = parse_switch(key, value, &s.culling, err);
        else if (strcmp(key, "morph") == 0)
            rc = parse_switch(key, value, &s.morph, err);
        else if (strcmp(key, "fog") == 0)
            rc = parse_ranged(key, value, 0, 1, &s.fog_density, err);
        else if (strcmp(key, "sun") == 0) {
            double yaw, pitch;
            char tail;
            if (sscanf(value, "%lf,%lf%c", &yaw, &pitch, &tail) != 2 || !isfinite(yaw) ||
                !isfinite(pitch) || pitch < -90 || pitch > 90)
                return og_error_set(err, "sun: expected YAW,PITCH in degrees (pitch -90 .. 90), got '%s'", value);
            s.sun_yaw = yaw, s.sun_pitch = pitch, rc = 0;
        } else
            return og_error_set(err, "render: unknown setting '%s' (levels parallax quality "
                                     "detail_distance culling morph fog sun)", key);
        if (rc != 0) return -1;
    }
    v->settings = s;
    if (argc == 1) print_settings(ctx, &v->settings);
    return 0;
}

static int parse_size(int argc, char **argv, int first, int *w, int *h, og_error *err) {
    *w = DEFAULT_WIDTH, *h = DEFAULT_HEIGHT;
    if (argc == first) return 0;
    if (argc != first + 2) return og_error_set(err, "give both W and H, or neither");
    if (parse_integer("W", argv[first], 16, MAX_IMAGE_SIDE, w, err) != 0 ||
        parse_integer("H", argv[first + 1], 16, MAX_IMAGE_SIDE, h, err) != 0)
        return -1;
    return 0;
}

int cmd_screenshot(cmd_context *ctx, int argc, char **argv, og_error *err) {
    viewport *v = get_viewport(ctx, err);
    if (!v) return -1;
    int w, h;
    if (parse_size(argc, argv, 2, &w, &h, err) != 0) return -1;
    if (viewport_screenshot(v, ctx->world, argv[1], w, h, err) != 0) return -1;
    render_stats st;
    terrain_renderer_stats(v->renderer, &st);
    fprintf(ctx->out, "screenshot %s %dx%d triangles=%llu levels=%d\n", argv[1], w, h,
            (unsigned long long)st.triangles, st.levels_drawn);
    return 0;
}

int cmd_pick(cmd_context *ctx, int argc, char **argv, og_error *err) {
    viewport *v = get_viewport(ctx, err);
    if (!v) return -1;
    double px, py;
    int w, h;
    if (cmd_parse_number(argv[1], "PX", &px, err) != 0 || cmd_parse_number(argv[2], "PY", &py, err) != 0 ||
        parse_size(argc, argv, 3, &w, &h, err) != 0)
        return -1;
    if (px < 0 || py < 0 || px > w || py > h)
        return og_error_set(err, "pixel (%g, %g) lies outside the %d x %d image", px, py, w, h);
    double hit[3];
    if (viewport_pick(v, ctx->world, px, py, w, h, hit, err) != 0) return -1;
    fprintf(ctx->out, "pick %.3f %.3f %.3f\n", hit[0], hit[1], hit[2]);
    return 0;
}
