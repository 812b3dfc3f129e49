#include "renderer/viewport.h"

#include "renderer/antialias.h"
#include "renderer/gl_target.h"
#include "renderer/land_scan.h"
#include "renderer/lighting.h"
#include "renderer/planet_camera.h"
#include "renderer/pick.h"
#include "renderer/volume_renderer.h"
#include "io/image_read.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

viewport *viewport_create(const char *resource_dir) {
    viewport *v = calloc(1, sizeof *v);
    if (!v) return NULL;
    camera_default(&v->cam);
    render_settings_default(&v->settings);
    snprintf(v->resource_dir, sizeof v->resource_dir, "%s", resource_dir);
    v->wait_seconds = 600;
    return v;
}

void viewport_destroy(viewport *v) {
    if (!v) return;
    terrain_renderer_destroy(v->renderer);
    antialias_destroy(v->aa);
    gl_headless_destroy(v->headless);
    free(v);
}

int viewport_default_camera(viewport *v, world *w, og_error *err) {
    const world_params *p = world_get_params(w);
    if (p->kind == WORLD_PLANET) {
        // The whole disc from orbit, lit, as a globe viewer opens: the camera looks at the
        // centre from the day side, 28 degrees from the point under the sun (toward the
        // equator and west of it), so the sun stands above and to the right of the view,
        // relief reads by its shading and all but a sliver at the limb is in daylight. The
        // disc (radius plus highest peak) fills DISC of the view's half-height, or of its
        // half-width when the view is taller than wide.
        const double DISC = 0.8;
        float sun[3];
        render_sun_direction(&v->settings, sun);
        const double sun_dir[3] = {sun[0], sun[1], sun[2]};
        double lat, lon;
        planet_lat_lon(sun_dir, &lat, &lon);
        camera_default(&v->cam);
        const double narrow = v->aspect > 0 ? fmin(v->aspect, 1.0) : 1.0;
        const double half = atan(DISC * narrow * tan(0.5 * v->cam.fov_y * M_PI / 180.0));
        const double distance = (p->radius + p->max_height) / sin(half);
        planet_position(lat >= 0 ? lat - 20.0 : lat + 20.0, lon - 22.0, distance, v->cam.pos);
        v->cam.yaw = 0.0; // north up
        v->cam.pitch = -CAMERA_PITCH_LIMIT;
        v->cam_set = 1;
        return 0;
    }
    double centre = p->size > 0 ? 0.5 * (double)(p->size - 1) * p->spacing : 0.0;
    double centre_z = p->size > 0 ? 0.5 * (double)(world_params_size_z(p) - 1) * p->spacing : 0.0;
    double ground = 0;
    if (world_sample(w, 0, centre, centre_z, &ground, err) != 0) return -1;
    camera_default(&v->cam);
    v->cam.pos[0] = centre;
    v->cam.pos[2] = centre_z;
    v->cam.pos[1] = fmax(ground, world_params_ocean_height(p)) + fmax(40.0, 0.25 * p->max_height);
    v->cam.yaw = 30;
    v->cam.pitch = -18;
    v->cam_set = 1;
    return 0;
}

// The ground (or the sea, when higher) at (x, z), read at the nearest point inside a
// bounded world: a camera may stand beyond its edge.
static int ground_or_sea(world *w, const world_params *p, double x, double z, double *out,
                         og_error *err) {
    if (p->size > 0) {
        x = fmin(fmax(x, 0.0), (double)(p->size - 1) * p->spacing);
        z = fmin(fmax(z, 0.0), (double)(world_params_size_z(p) - 1) * p->spacing);
    }
    double g = 0;
    if (world_sample(w, 0, x, z, &g, err) != 0) return -1;
    *out = fmax(g, world_params_ocean_height(p));
    return 0;
}

int viewport_camera_on_land(viewport *v, world *w, og_error *err) {
    if (viewport_default_camera(v, w, err) != 0) return -1;
    const world_params *p = world_get_params(w);
    if (p->kind == WORLD_PLANET) return 0;
    double sea = world_params_ocean_height(p);
    // The ground's floor: the sea, or in a bounded world with relief standing over a
    // plain above the sea (an island's heightmap: its ocean floor at 0 m over the
    // default -400 m sea), that plain. Land stands well above the floor.
    land_scan scan = {0};
    double floor_m = sea;
    if (p->size > 0) {
        if (land_scan_read(w, &scan, err) != 0) return -1;
        if (scan.lowest > sea && scan.highest - scan.lowest > 0.05 * p->max_height)
            floor_m = scan.lowest;
    }
    double land = floor_m + 0.05 * p->max_height;
    double lo = 0, hi = p->size > 0 ? (double)(p->size - 1) * p->spacing : 0;
    double hi_z = p->size > 0 ? (double)(world_params_size_z(p) - 1) * p->spacing : 0;
    double centre = 0.5 * (lo + hi), centre_z = 0.5 * (lo + hi_z);
    double best[3] = {0, 0, 0}, best_slope = 0.4; // 22 degrees
    // The distance at which the whole of a bounded world fits the view (its diagonal
    // across the narrower field of view, with a margin): a small world, say one made from
    // a heightmap, is seen whole rather than as a speck below the view.
    camera *c = &v->cam;
    double narrow = v->aspect > 0 ? fmin(v->aspect, 1.0) : 1.0;
    double half_fov = atan(narrow * tan(0.5 * c->fov_y * M_PI / 180.0));
    double whole = p->size > 0 ? 0.6 * hypot(hi, hi_z) / tan(half_fov) : INFINITY;
    int found = 0;
    static const double rings[] = {0, 600, 1200, 2000, 3000};
    for (int r = 0; r < 5 && !found; r++)
        for (int a = 0; a < (r ? 12 : 1); a++) { // the gentlest land of the nearest ring
            double x = centre + rings[r] * cos(a * M_PI / 6),
                   z = centre_z + rings[r] * sin(a * M_PI / 6);
            if (p->size > 0 && (x < lo || x + 20 > hi || z < lo || z + 20 > hi_z)) continue;
            double g, gx, gz;
            if (world_sample(w, 0, x, z, &g, err) != 0 ||
                world_sample(w, 0, x + 20, z, &gx, err) != 0 ||
                world_sample(w, 0, x, z + 20, &gz, err) != 0) {
                land_scan_free(&scan);
                return -1;
            }
            double slope = hypot(gx - g, gz - g) / 20.0;
            if (g > land && slope < best_slope) {
                best[0] = x, best[1] = g, best[2] = z, best_slope = slope;
                found = 1;
            }
        }
    // None near the centre: the nearest in the whole of a bounded world.
    double far_x, far_z;
    if (!found && scan.height &&
        land_scan_nearest(&scan, centre, centre_z, land, best_slope, &far_x, &far_z)) {
        best[0] = far_x, best[2] = far_z;
        if (world_sample(w, 0, far_x, far_z, &best[1], err) != 0) {
            land_scan_free(&scan);
            return -1;
        }
        found = 1;
    }
    land_scan_free(&scan);
    c->pitch = -35; // from above: the brush lies round on the ground, a raise shows
    // 900 m, or 450 samples of a coarser world: a heightmap of 90 m samples seen from
    // 900 m showed a dozen of them, a blur.
    const double near_view = fmax(900.0, 450.0 * p->spacing);
    double distance = fmax(fmin(near_view, whole), 1.5 * (best[1] - floor_m));
    if (!found) {
        if (!(whole < near_view)) return 0; // a large world of sea or cliffs: the default view
        // A small world all under the sea (or all cliffs): the whole of it.
        best[0] = centre, best[2] = centre_z;
        if (ground_or_sea(w, p, best[0], best[2], &best[1], err) != 0) return -1;
        distance = whole;
    }
    camera_focus(c, best, distance);
    double below = 0; // never under the ground or the sea where the camera stands
    if (ground_or_sea(w, p, c->pos[0], c->pos[2], &below, err) != 0) return -1;
    double floor_y = below + 40.0;
    if (c->pos[1] < floor_y) { // higher, still looking at the land
        c->pos[1] = floor_y;
        double dx = best[0] - c->pos[0], dz = best[2] - c->pos[2];
        c->pitch = atan2(best[1] - c->pos[1], sqrt(dx * dx + dz * dz)) * 180.0 / M_PI;
    }
    return 0;
}

int viewport_prepare(viewport *v, og_error *err) {
    if (!v->window_context && !v->headless) {
        v->headless = gl_headless_create(err);
        if (!v->headless) return -1;
        if (gl_require_features(err) != 0) return -1;
    }
    if (!v->renderer) {
        v->renderer = terrain_renderer_create(v->resource_dir, err);
        if (!v->renderer) return -1;
    }
    return 0;
}

static double seconds_now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

int viewport_settle(viewport *v, world *w, og_error *err) {
    if (viewport_prepare(v, err) != 0) return -1;
    if (!v->cam_set && viewport_default_camera(v, w, err) != 0) return -1;
    double start = seconds_now();
    terrain_renderer_spread_uploads(v->renderer, 0); // no frames to spread them over
    for (;;) {
        int rc = terrain_renderer_update(v->renderer, w, &v->cam, &v->settings, err);
        // Twice current in a row: the finest level depends on the ground height the
        // first current frame reveals.
        if (rc == 1) rc = terrain_renderer_update(v->renderer, w, &v->cam, &v->settings, err);
        if (rc != 0) terrain_renderer_spread_uploads(v->renderer, 1);
        if (rc < 0) return -1;
        if (rc == 1) return 0;
        if (seconds_now() - start > v->wait_seconds) {
            terrain_renderer_spread_uploads(v->renderer, 1);
            return og_error_set(err, "the terrain's tiles did not arrive within %.0f s",
                                v->wait_seconds);
        }
        struct timespec nap = {0, 2000000};
        nanosleep(&nap, NULL);
    }
}

int viewport_antialias(viewport *v, const gl_target *src, const gl_target *dst, og_error *err) {
    if (!v->aa) {
        char dir[sizeof v->resource_dir + 16];
        snprintf(dir, sizeof dir, "%s/shaders", v->resource_dir);
        if (!(v->aa = antialias_create(dir, err))) return -1;
    }
    return antialias_apply(v->aa, src, dst, err);
}

int viewport_screenshot(viewport *v, world *w, const char *path, int width, int height,
                        og_error *err) {
    if (viewport_prepare(v, err) != 0) return -1;
    terrain_renderer_set_view_size(v->renderer, width, height);
    v->aspect = (double)width / height;
    if (viewport_settle(v, w, err) != 0) return -1;
    gl_target target, smooth = {0};
    if (gl_target_create(&target, width, height, err) != 0) return -1;
    unsigned char *rgb = malloc((size_t)width * height * 3);
    int rc = -1;
    if (!rgb) {
        og_error_set(err, "out of memory for a %d x %d image", width, height);
    } else {
        glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
        rc = terrain_renderer_draw(v->renderer, w, &v->cam, &v->settings, &v->cursor, width, height,
                                   err);
        const gl_target *shown = &target;
        if (rc == 0 && render_settings_smooth_edges(&v->settings)) {
            rc = gl_target_create(&smooth, width, height, err);
            if (rc == 0) rc = viewport_antialias(v, &target, &smooth, err);
            shown = &smooth;
        }
        if (rc == 0) rc = gl_target_read_rgb(shown, rgb, err);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        if (rc == 0) rc = image_write_rgb8(path, rgb, width, height, err);
    }
    free(rgb);
    gl_target_destroy(&target);
    gl_target_destroy(&smooth);
    return rc;
}

// The ground the viewport shows: the heightfield, except where a volume mesh replaces it
// (there the ray passes through; the mesh itself is picked separately).
static int shown_height(void *user, double x, double z, double *h) {
    terrain_renderer *r = user;
    if (terrain_renderer_height_at(r, x, z, h) != 0) return -1;
    return volume_renderer_replaces(terrain_renderer_volume(r), x, *h, z) ? -1 : 0;
}

// Planets: the ray against the sphere of the surface's height (the sea's where it covers
// the ground; floor: the ground under it), that height re-read where it lands until it
// settles (a few steps for any view that looks down at the ground).
static int planet_pick(viewport *v, world *w, double sx, double sy, double aspect, int floor,
                       double hit[3]) {
    const world_params *p = world_get_params(w);
    double dir[3], ground = 0, t = -1;
    planet_camera_ray(&v->cam, aspect, sx, sy, dir);
    const double *c = v->cam.pos;
    // Starting from the height under the camera: a camera below the datum (in a deep
    // basin) is inside the datum's sphere, which no ray leaves downward.
    og_error start_err;
    if ((floor ? planet_ground_height(w, c, &ground, &start_err)
               : planet_surface_height(w, c, &ground, &start_err)) != 0)
        return -1;
    for (int i = 0; i < 12; i++) {
        double r = p->radius + ground, b = c[0] * dir[0] + c[1] * dir[1] + c[2] * dir[2];
        double cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2] - r * r, disc = b * b - cc;
        if (disc < 0) return -1; // past the limb
        double nt = -b - sqrt(disc);
        if (nt < 0) return -1; // behind the camera (or inside the ground)
        for (int k = 0; k < 3; k++)
            hit[k] = c[k] + nt * dir[k];
        og_error err;
        if ((floor ? planet_ground_height(w, hit, &ground, &err)
                   : planet_surface_height(w, hit, &ground, &err)) != 0)
            return -1;
        if (t >= 0 && fabs(nt - t) < 1e-3 * fmax(1.0, p->spacing)) break;
        t = nt;
    }
    double len = sqrt(hit[0] * hit[0] + hit[1] * hit[1] + hit[2] * hit[2]);
    for (int k = 0; k < 3; k++)
        hit[k] *= (p->radius + ground) / len;
    return 0;
}

int viewport_pick_loaded(viewport *v, world *w, double sx, double sy, double aspect,
                         double hit[3]) {
    if (!v->renderer) return -1;
    if (world_get_params(w)->kind == WORLD_PLANET) return planet_pick(v, w, sx, sy, aspect, 0, hit);
    return viewport_pick_shown(v, world_get_params(w), sx, sy, aspect, hit);
}

int viewport_pick_shown(viewport *v, const world_params *p, double sx, double sy, double aspect,
                        double hit[3]) {
    if (!v->renderer || p->kind == WORLD_PLANET) return -1;
    double dir[3];
    camera_ray(&v->cam, aspect, sx, sy, dir);
    // As far as the coarsest level reaches; steps of one coarse sample near the camera.
    double reach = 0.75 * 254 * p->spacing * (double)((int64_t)1 << (v->settings.levels - 1));
    int ground = pick_ray(shown_height, v->renderer, v->cam.pos, dir, reach, p->spacing, hit);
    // A bounded world's ground ends at its edges (the clipmap holds samples past them,
    // which the picture does not show): a ray past them finds nothing.
    const double pad = 1e-6 * p->spacing;
    if (ground == 0 && p->size > 0 &&
        (hit[0] < -pad || hit[0] > (double)(p->size - 1) * p->spacing + pad || hit[2] < -pad ||
         hit[2] > (double)(world_params_size_z(p) - 1) * p->spacing + pad))
        ground = -1;
    double t_ground = ground == 0 ? sqrt((hit[0] - v->cam.pos[0]) * (hit[0] - v->cam.pos[0]) +
                                         (hit[1] - v->cam.pos[1]) * (hit[1] - v->cam.pos[1]) +
                                         (hit[2] - v->cam.pos[2]) * (hit[2] - v->cam.pos[2]))
                                  : reach;
    double t_mesh;
    if (volume_renderer_pick(terrain_renderer_volume(v->renderer), v->cam.pos, dir, t_ground,
                             &t_mesh) == 0) {
        for (int a = 0; a < 3; a++)
            hit[a] = v->cam.pos[a] + t_mesh * dir[a];
        return 0;
    }
    return ground;
}

int viewport_pick_floor(viewport *v, world *w, double px, double py, int width, int height,
                        double hit[3], og_error *err) {
    if (world_get_params(w)->kind != WORLD_PLANET)
        return viewport_pick(v, w, px, py, width, height, hit, err);
    if (viewport_settle(v, w, err) != 0) return -1;
    if (!v->renderer ||
        planet_pick(v, w, px / width, py / height, (double)width / height, 1, hit) != 0)
        return og_error_set(err, "no terrain under pixel (%g, %g)", px, py);
    return 0;
}

int viewport_pick(viewport *v, world *w, double px, double py, int width, int height, double hit[3],
                  og_error *err) {
    if (viewport_settle(v, w, err) != 0) return -1;
    if (viewport_pick_loaded(v, w, px / width, py / height, (double)width / height, hit) != 0)
        return og_error_set(err, "no terrain under pixel (%g, %g)", px, py);
    return 0;
}
