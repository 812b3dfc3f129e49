#include "view/view_commands.h"

#include "io/parse.h"
#include "editor/world/volume_grid.h"
#include "renderer/planet_camera.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define DEFAULT_WIDTH 1280
#define DEFAULT_HEIGHT 720
#define MAX_IMAGE_SIDE 8192

viewport *view_commands_viewport(cmd_context *ctx) {
    if (!ctx->view_state) ctx->view_state = viewport_create(ctx->resource_dir);
    return ctx->view_state;
}

void view_commands_set_viewport(cmd_context *ctx, viewport *v) {
    ctx->view_state = v;
}

static viewport *get_viewport(cmd_context *ctx, og_error *err) {
    viewport *v = view_commands_viewport(ctx);
    if (!v) {
        og_error_set(err, "out of memory");
        return NULL;
    }
    // A camera placed for an earlier world (`new` or `load` came since) is not this one's:
    // the next picture places the new world's default camera, as the window does.
    // (The window keeps cam_world_serial for its own reset: only commands placing the
    // camera set it there.)
    if (!v->window_context && v->cam_world_serial != ctx->world_serial) {
        v->cam_set = 0;
        v->cam_world_serial = ctx->world_serial;
    }
    return v;
}

static void print_camera(cmd_context *ctx, const camera *c) {
    fprintf(ctx->out, "camera %.3f %.3f %.3f %.3f %.3f %.3f\n", c->pos[0], c->pos[1], c->pos[2],
            c->yaw, c->pitch, c->fov_y);
    const world_params *p = world_get_params(ctx->world);
    if (p->kind == WORLD_PLANET) {
        double lat, lon,
            r = sqrt(c->pos[0] * c->pos[0] + c->pos[1] * c->pos[1] + c->pos[2] * c->pos[2]);
        planet_lat_lon(c->pos, &lat, &lon);
        fprintf(ctx->out, "camera_geo %.6f %.6f %.3f %.3f %.3f %.3f\n", lat, lon, r - p->radius,
                c->yaw, c->pitch, c->fov_y);
    }
}

// Planets: the camera by latitude, longitude and altitude above the datum; yaw and
// pitch in the local frame there (yaw 0 north, pitch -90 straight down).
static int cmd_camera_geo(cmd_context *ctx, int argc, char **argv, og_error *err) {
    viewport *v = get_viewport(ctx, err);
    if (!v) return -1;
    const world_params *p = world_get_params(ctx->world);
    if (p->kind != WORLD_PLANET)
        return og_error_set(err, "camera_geo: planets only (flat worlds: camera X Y Z YAW PITCH)");
    const char *names[6] = {"LAT", "LON", "ALT", "YAW", "PITCH", "FOV"};
    double val[6] = {0, 0, 0, 0, -90, v->cam.fov_y};
    int above_ground = 0;
    if (argc > 1 && strcmp(argv[argc - 1], "ground") == 0) above_ground = 1, argc--;
    if (argc < 4)
        return og_error_set(err, "usage: camera_geo LAT LON ALT [YAW PITCH [FOV]] [ground]");
    for (int i = 1; i < argc; i++)
        if (parse_number(argv[i], names[i - 1], &val[i - 1], err) != 0) return -1;
    if (fabs(val[0]) > 90)
        return og_error_set(err, "LAT: expected degrees in [-90, 90], got '%g'", val[0]);
    if (val[2] < -p->radius * 0.5 || val[2] > 1e10)
        return og_error_set(err, "ALT: %g m is outside -radius/2 .. 1e10 m", val[2]);
    if (val[4] < -90 || val[4] > 90)
        return og_error_set(err, "PITCH: expected degrees in [-90, 90], got '%g'", val[4]);
    if (val[5] < 1 || val[5] > 170)
        return og_error_set(err, "FOV: expected degrees in [1, 170], got '%g'", val[5]);
    camera c = v->cam;
    planet_position(val[0], val[1], p->radius + val[2], c.pos);
    double ground = 0;
    if (above_ground) { // ALT above the surface there (the sea's over the sea), not the datum
        if (planet_surface_height(ctx->world, c.pos, &ground, err) != 0) return -1;
        planet_position(val[0], val[1], p->radius + ground + val[2], c.pos);
    }
    c.yaw = 0, c.pitch = 0;
    camera_look(&c, val[3], val[4]);
    c.fov_y = val[5];
    v->cam = c;
    v->cam_set = 1;
    v->cam_world_serial = ctx->world_serial;
    return 0;
}

// A camera put inside the ground (a typed Y under the terrain) sees the surface from
// below: torn slivers in the sky and the sea drawn over them. The position stands, as in
// Blender or Unreal, but the console says so. Caves count as air (volume_sample).
static void note_if_inside_ground(cmd_context *ctx, const double pos[3]) {
    if (world_get_params(ctx->world)->kind == WORLD_PLANET) return; // camera_geo ... ground
    double d = 0;
    og_error ignored;
    if (volume_sample(ctx->world, pos, &d, &ignored) != 0 || !(d < 0)) return;
    fprintf(ctx->out,
            "note: the camera is inside the ground, %.1f m from its surface (camera default puts "
            "it back over the land)\n",
            -d);
}

static int cmd_camera(cmd_context *ctx, int argc, char **argv, og_error *err) {
    viewport *v = get_viewport(ctx, err);
    if (!v) return -1;
    if (argc == 1) {
        if (!v->cam_set && viewport_default_camera(v, ctx->world, err) != 0) return -1;
        print_camera(ctx, &v->cam);
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "default") == 0) {
        if (viewport_default_camera(v, ctx->world, err) != 0) return -1;
        v->cam_world_serial = ctx->world_serial;
        print_camera(ctx, &v->cam);
        return 0;
    }
    if (argc < 6)
        return og_error_set(err, "usage: camera X Y Z YAW PITCH [FOV] (or camera default)");
    const char *names[6] = {"X", "Y", "Z", "YAW", "PITCH", "FOV"};
    double val[6] = {0, 0, 0, 0, 0, v->cam.fov_y};
    for (int i = 1; i < argc; i++)
        if (parse_number(argv[i], names[i - 1], &val[i - 1], err) != 0) return -1;
    for (int i = 0; i < 3; i++)
        if (fabs(val[i]) > 1e12)
            return og_error_set(err, "%s: %g m is too far (limit 1e12 m)", names[i], val[i]);
    if (val[4] < -90 || val[4] > 90)
        return og_error_set(err, "PITCH: expected degrees in [-90, 90], got '%g'", val[4]);
    if (val[5] < 1 || val[5] > 170)
        return og_error_set(err, "FOV: expected degrees in [1, 170], got '%g'", val[5]);
    camera c = v->cam;
    c.pos[0] = val[0], c.pos[1] = val[1], c.pos[2] = val[2];
    c.yaw = 0, c.pitch = 0;
    camera_look(&c, val[3], val[4]); // wraps yaw and clamps pitch the same way as the window
    c.fov_y = val[5];
    v->cam = c;
    v->cam_set = 1;
    v->cam_world_serial = ctx->world_serial;
    note_if_inside_ground(ctx, c.pos);
    return 0;
}

static int cmd_view(cmd_context *ctx, int argc, char **argv, og_error *err) {
    viewport *v = get_viewport(ctx, err);
    if (!v) return -1;
    if (argc == 1) {
        fprintf(ctx->out, "view %s\n", view_mode_name(v->settings.view));
        return 0;
    }
    int m = view_mode_parse(argv[1]);
    if (m < 0)
        return og_error_set(
            err, "view: unknown mode '%s' (shaded, wireframe, levels, height, slope)", argv[1]);
    v->settings.view = (view_mode)m;
    return 0;
}

// An integer setting in [lo, hi].
static int parse_int_in(const char *key, const char *value, int lo, int hi, int *out,
                        og_error *err) {
    double d;
    if (parse_integer_in(value, key, lo, hi, &d, err) != 0) return -1;
    *out = (int)d;
    return 0;
}

static void print_settings(cmd_context *ctx, const render_settings *s) {
    fprintf(ctx->out,
            "render levels=%d parallax=%s quality=%d detail_distance=%g culling=%s morph=%s "
            "sun=%g,%g sun_rotation=%g fog=%g contours=%g tile_grid=%s level_grid=%s "
            "auto_materials=%s antialias=%s lod_pixels=%g refine=%g skyline=%g view=%s\n",
            s->levels, s->parallax ? "on" : "off", s->parallax_steps, s->detail_distance,
            s->culling ? "on" : "off", s->morph ? "on" : "off", s->sun_yaw, s->sun_pitch,
            s->sun_rotation, s->fog_density, s->contours, s->tile_grid ? "on" : "off",
            s->level_grid ? "on" : "off", s->auto_materials ? "on" : "off",
            s->antialias ? "on" : "off", s->lod_pixels, s->refine_pixels, s->skyline_pixels,
            view_mode_name(s->view));
}

static int cmd_render(cmd_context *ctx, int argc, char **argv, og_error *err) {
    viewport *v = get_viewport(ctx, err);
    if (!v) return -1;
    render_settings s = v->settings; // applied only if every argument is good
    for (int i = 1; i < argc; i++) {
        char buf[256], *key, *value;
        if (parse_setting(argv[i], buf, sizeof buf, &key, &value, err) != 0) return -1;
        int rc;
        if (strcmp(key, "levels") == 0)
            rc = parse_int_in(key, value, RENDER_MIN_LEVELS, RENDER_MAX_LEVELS, &s.levels, err);
        else if (strcmp(key, "parallax") == 0)
            rc = parse_switch(value, key, &s.parallax, err);
        else if (strcmp(key, "quality") == 0)
            rc = parse_int_in(key, value, 1, 32, &s.parallax_steps, err);
        else if (strcmp(key, "detail_distance") == 0)
            rc = parse_number_in(value, key, 1, 100000, &s.detail_distance, err);
        else if (strcmp(key, "culling") == 0)
            rc = parse_switch(value, key, &s.culling, err);
        else if (strcmp(key, "morph") == 0)
            rc = parse_switch(value, key, &s.morph, err);
        else if (strcmp(key, "contours") == 0)
            rc = parse_number_in(value, key, 0, 100000, &s.contours, err);
        else if (strcmp(key, "tile_grid") == 0)
            rc = parse_switch(value, key, &s.tile_grid, err);
        else if (strcmp(key, "level_grid") == 0)
            rc = parse_switch(value, key, &s.level_grid, err);
        else if (strcmp(key, "auto_materials") == 0)
            rc = parse_switch(value, key, &s.auto_materials, err);
        else if (strcmp(key, "antialias") == 0)
            rc = parse_switch(value, key, &s.antialias, err);
        else if (strcmp(key, "lod_pixels") == 0)
            rc = parse_number_in(value, key, 1, 64, &s.lod_pixels, err);
        else if (strcmp(key, "refine") == 0)
            rc = parse_number_in(value, key, 0, 64, &s.refine_pixels, err);
        else if (strcmp(key, "skyline") == 0)
            rc = parse_number_in(value, key, 0, 64, &s.skyline_pixels, err);
        else if (strcmp(key, "sun_rotation") == 0)
            rc = parse_number_in(value, key, -360, 360, &s.sun_rotation, err);
        else if (strcmp(key, "fog") == 0)
            rc = parse_number_in(value, key, 0, 1, &s.fog_density, err);
        else if (strcmp(key, "sun") == 0) {
            double yaw, pitch;
            const char *comma, *end;
            if (parse_scan_f64(value, &yaw, &comma) != 0 || *comma != ',' ||
                parse_scan_f64(comma + 1, &pitch, &end) != 0 || *end || !isfinite(yaw) ||
                !isfinite(pitch) || pitch < -90 || pitch > 90)
                return og_error_set(
                    err, "sun: expected YAW,PITCH in degrees (pitch -90 .. 90), got '%s'", value);
            s.sun_yaw = yaw, s.sun_pitch = pitch, rc = 0;
        } else
            return og_error_set(
                err,
                "render: unknown setting '%s' (levels parallax quality "
                "detail_distance culling morph fog sun sun_rotation contours tile_grid "
                "level_grid auto_materials antialias lod_pixels refine skyline)",
                key);
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
    if (parse_int_in("W", argv[first], 16, MAX_IMAGE_SIDE, w, err) != 0 ||
        parse_int_in("H", argv[first + 1], 16, MAX_IMAGE_SIDE, h, err) != 0)
        return -1;
    return 0;
}

static int cmd_screenshot(cmd_context *ctx, int argc, char **argv, og_error *err) {
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

static int cmd_pick(cmd_context *ctx, int argc, char **argv, og_error *err) {
    viewport *v = get_viewport(ctx, err);
    if (!v) return -1;
    double px, py;
    int w, h;
    const int floor = argc > 1 && strcmp(argv[argc - 1], "floor") == 0; // the sea floor
    if (floor) argc--;
    if (parse_number(argv[1], "PX", &px, err) != 0 || parse_number(argv[2], "PY", &py, err) != 0 ||
        parse_size(argc, argv, 3, &w, &h, err) != 0)
        return -1;
    if (px < 0 || py < 0 || px > w || py > h)
        return og_error_set(err, "pixel (%g, %g) lies outside the %d x %d image", px, py, w, h);
    double hit[3];
    if ((floor ? viewport_pick_floor(v, ctx->world, px, py, w, h, hit, err)
               : viewport_pick(v, ctx->world, px, py, w, h, hit, err)) != 0)
        return -1;
    fprintf(ctx->out, "pick %.3f %.3f %.3f\n", hit[0], hit[1], hit[2]);
    return 0;
}

static const cmd_def view_commands[] = {
    {"camera", "camera [X Y Z YAW PITCH [FOV] | default]",
     "Places the viewport camera: position in metres, yaw (0 looks toward -Z, 90 toward +X) and "
     "pitch in degrees, vertical field of view (60). Without arguments, prints it.",
     0, 6, cmd_camera, 0},
    {"camera_geo", "camera_geo LAT LON ALT [YAW PITCH [FOV]] [ground]",
     "Planets: places the camera at latitude, longitude (degrees; longitude 0 on +Z, east toward "
     "+X) and ALT metres above the datum (with `ground`: above the surface there, the ground or "
     "the sea's surface over it), turned by yaw "
     "(0 north, 90 east) and pitch (-90, the default, looks straight down) in the local frame.",
     3, 7, cmd_camera_geo, 0},
    {"view", "view [MODE]",
     "Picks what the viewport shows: shaded, wireframe, levels (clipmap level colours), height or "
     "slope colours.",
     0, 1, cmd_view, 0},
    {"render", "render [KEY=VALUE ...]",
     "Viewport settings: levels (3-12 clipmap levels), parallax (on/off), quality (parallax steps "
     "1-32), detail_distance (m), culling (on/off: skip what is outside the view; on planets also "
     "the ground hidden behind nearer ground), morph (on/off), fog (per metre, 0 = automatic), "
     "sun=YAW,PITCH, sun_rotation (degrees a second the editor turns the sun; R toggles it), "
     "contours (metres between contour lines, 0 = none), tile_grid=on|off (the tiles' edges), "
     "level_grid=on|off (each clipmap level's vertex grid), auto_materials=on|off (the "
     "automatic material rules on unpainted ground), lod_pixels (planets: pixels a sample may "
     "cover before its chunk splits, 1-64, 6), refine (flat worlds: pixels of error at which far "
     "rough ground is drawn at twice the density, 0-64, 0 = never), skyline (the same for the "
     "ground near the skyline only, while refine is 0; 0-64, 0 = never, the default), "
     "antialias=on|off (edges "
     "smoothed in the finished image). Without arguments, prints them.",
     0, 16, cmd_render, 0},
    {"screenshot", "screenshot FILE [W H]",
     "Renders the viewport offscreen (no display needed) to an RGB PNG, W x H pixels (1280 x 720), "
     "once every visible tile is loaded.",
     1, 3, cmd_screenshot, 0},
    {"pick", "pick PX PY [W H] [floor]",
     "Prints the terrain point (x y z metres) under pixel PX, PY of a W x H (1280 x 720) view; on "
     "a planet the sea's surface where the sea covers the ground (`floor`: the ground under it).",
     2, 5, cmd_pick, 0},
};

int view_commands_register(og_error *err) {
    static int registered;
    if (registered) return 0;
    if (cmd_register(view_commands, sizeof view_commands / sizeof view_commands[0], err) != 0)
        return -1;
    registered = 1;
    return 0;
}
