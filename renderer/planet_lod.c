// LOD selection: each face's quadtree walked from its root, a chunk split where its
// samples would cover more than split_pixels on the screen.
#include "renderer/planet_internal.h"
#include "renderer/planet_renderer.h"

#include "editor/world/world.h"
#include "renderer/planet_camera.h"

#include <string.h>

// How much a sample's projected size shrinks seen at a grazing angle: the geometric mean
// of its two projected sides (1 when not judged). From high up, not where the chunk has
// a coast: coarser chunks would draw coastlines (the sea is per vertex) in visibly large
// steps toward the limb. Not for a chunk the camera stands in (the view across it
// varies too much).

static double grazing(const planet_renderer *r, const node_bounds *b, double centre_dist,
                      const double d[3]) {
    if (!(centre_dist > 2.0 * b->radius)) return 1.0;
    const double ocean = world_params_ocean_height(&r->params);
    const int coast = b->hmin <= ocean && ocean <= b->hmax;
    if (!near_ground(r) && coast) return 1.0;
    double rc = sqrt(b->centre[0] * b->centre[0] + b->centre[1] * b->centre[1] +
                     b->centre[2] * b->centre[2]);
    double cosv =
        fabs(d[0] * b->centre[0] + d[1] * b->centre[1] + d[2] * b->centre[2]) / (centre_dist * rc);
    return fmax(sqrt(cosv), 0.3);
}

// The distance at which a sample of `cell` metres covers split_pixels, and the node's.
static double split_distance(const planet_renderer *r, const node_bounds *b, double cell,
                             double *node_dist) {
    double d[3] = {b->centre[0] - r->cam->pos[0], b->centre[1] - r->cam->pos[1],
                   b->centre[2] - r->cam->pos[2]};
    double centre_dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    *node_dist = fmax(centre_dist - b->radius, b->cell);
    // Open sea (a built chunk wholly under it) is the sphere's smooth surface: its
    // samples shape nothing but the water's depth colour, so they may be 8 times wider.
    const double sea = b->hmax < world_params_ocean_height(&r->params) ? 8.0 : 1.0;
    return cell * r->pixels_per_radian * grazing(r, b, centre_dist, d) / (sea * r->split_pixels);
}

static int wants_split(const planet_renderer *r, const node *n, const node_bounds *b) {
    if (n->level == 0) return 0;
    double dist;
    return split_distance(r, b, b->cell, &dist) > dist;
}

static void children_of(const node *n, node out[4]) {
    for (int k = 0; k < 4; k++)
        out[k] = (node){n->face, n->level - 1, 2 * n->bx + (k & 1), 2 * n->by + (k >> 1)};
}

static void bounds_heights(planet_renderer *r, const node *n, double *lo, double *hi) {
    chunk *c = planet_find_chunk(r, node_key(n));
    // Unbuilt: the generator's range, with room for edits beyond it.
    *lo = c ? c->hmin : -1.5 * r->params.max_height;
    *hi = c ? c->hmax : 1.5 * r->params.max_height;
}

// 0: the node is drawn (itself or its children) or culled; 1: it could not be drawn.
static int select_node(planet_renderer *r, const node *n) {
    double lo, hi;
    bounds_heights(r, n, &lo, &hi);
    node_bounds b;
    if (!planet_node_visible(r, n, lo, hi, &b)) {
        r->stats.chunks_culled++;
        return 0;
    }
    chunk *c = planet_find_chunk(r, node_key(n));
    if (!c && !(c = planet_try_build(r, n))) return 1;
    c->used = r->frame;
    if (wants_split(r, n, &b)) {
        node kids[4];
        children_of(n, kids);
        int ready = 1;
        for (int k = 0; k < 4; k++) {
            if (!node_exists(r, &kids[k]) || planet_find_chunk(r, node_key(&kids[k]))) continue;
            double klo, khi;
            bounds_heights(r, &kids[k], &klo, &khi);
            node_bounds kb;
            if (planet_node_visible(r, &kids[k], klo, khi, &kb) && !planet_try_build(r, &kids[k]))
                ready = 0;
        }
        if (ready) {
            int missing = 0;
            for (int k = 0; k < 4; k++)
                if (node_exists(r, &kids[k])) missing |= select_node(r, &kids[k]);
            if (!missing) return 0;
        }
        r->all_current = 0;
    }
    double dist;
    c->morph_reach = split_distance(r, &b, 2.0 * b.cell, &dist);
    c->near_dist = dist;
    if (r->draw_count < MAX_CHUNKS) r->draw_list[r->draw_count++] = (int)(c - r->chunks);
    return 0;
}

// The detail window follows the camera near the ground; the ground under the camera is
// the top of the nearest chunk drawn (no tile is read here).
static int update_detail(planet_renderer *r, const render_settings *s, og_error *err) {
    double nearest = INFINITY, ground = r->camera_altitude;
    for (int i = 0; i < r->draw_count; i++) {
        const chunk *c = &r->chunks[r->draw_list[i]];
        double d[3] = {c->origin[0] - r->cam->pos[0], c->origin[1] - r->cam->pos[1],
                       c->origin[2] - r->cam->pos[2]};
        double dist = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if (dist < nearest) nearest = dist, ground = c->hmax;
    }
    int rc = planet_detail_update(r->detail, world_cache(r->world), r->cam->pos,
                                  r->camera_altitude - ground, r->face_samples, r->cell_arc,
                                  r->params.detail_ratio, s);
    if (rc < 0) return og_error_set(err, "the planet's detail window could not read its tiles");
    if (rc == 0) r->all_current = 0;
    r->stats.detail_texels_uploaded = planet_detail_take_uploads(r->detail);
    return 0;
}

// Whether the chunks built for a stay right for b: the edit layer table aside (a layer
// command's changes arrive as area events), the parameters are the same.
static int same_terrain(const world_params *a, const world_params *b) {
    if (!memcmp(a, b, sizeof *a)) return 1;
    world_params x = *a, y = *b;
    memset(&x.layers, 0, sizeof x.layers);
    memset(&y.layers, 0, sizeof y.layers);
    return !memcmp(&x, &y, sizeof x);
}

int planet_renderer_update(planet_renderer *r, world *w, const camera *cam,
                           const render_settings *s, double aspect, int height_px, og_error *err) {
    r->split_pixels = s->lod_pixels >= 1 ? s->lod_pixels : 6.0; // render lod_pixels=
    r->update_start_ms = now_ms();
    const world_params *p = world_get_params(w);
    if (p->kind != WORLD_PLANET) return og_error_set(err, "planet renderer: not a planet");
    if (r->world != w || !same_terrain(&r->params, p)) {
        planet_drop_all(r);
        planet_detail_forget(r->detail);
    }
    r->world = w;
    r->params = *p;
    r->face_samples = world_grid_face_samples(p);
    if (r->face_samples / BLOCK >= ((int64_t)1 << 28)) // the chunk keys' block indices
        return og_error_set(err,
                            "planet renderer: %lld samples per face side (radius %g m at %g m "
                            "spacing) is more than the viewport addresses (2^32)",
                            (long long)r->face_samples, p->radius, p->spacing);
    r->cell_arc = (M_PI / 2.0) * p->radius / (double)r->face_samples;
    r->root_level = 0;
    while (level_samples(r, r->root_level) > BLOCK)
        r->root_level++;
    r->frame++;
    r->cam = cam;
    r->all_current = 1;
    { // the last draw's figures stand until the next draw (the status bar shows them)
        uint64_t triangles = r->stats.triangles;
        int draw_calls = r->stats.draw_calls;
        memset(&r->stats, 0, sizeof r->stats);
        r->stats.triangles = triangles, r->stats.draw_calls = draw_calls;
    }
    float vp[16];
    planet_camera_view_projection(cam, aspect, vp);
    frustum_from_matrix(&r->fr, vp);
    double fov = cam->fov_y >= 1 && cam->fov_y <= 170 ? cam->fov_y : 60;
    r->pixels_per_radian = (height_px > 0 ? height_px : 720) / (2.0 * tan(fov * M_PI / 360.0));
    r->camera_altitude =
        sqrt(cam->pos[0] * cam->pos[0] + cam->pos[1] * cam->pos[1] + cam->pos[2] * cam->pos[2]) -
        p->radius;
    r->occluder_radius = p->radius - 1.5 * p->max_height;
    if (r->occluder_radius < 0.5 * p->radius) r->occluder_radius = 0.5 * p->radius;
    planet_tighten_occluder(r); // from the last frame's chunks
    r->draw_count = 0;
    for (int f = 0; f < 6; f++) {
        node root = {f, r->root_level, 0, 0};
        if (select_node(r, &root)) r->all_current = 0;
    }
    planet_normals_refine(r);
    if (update_detail(r, s, err) < 0) return -1;
    r->stats.chunks_resident = r->resident;
    r->stats.finest_level = 99, r->stats.coarsest_level = -1;
    for (int i = 0; i < r->draw_count; i++) {
        int l = r->chunks[r->draw_list[i]].level;
        if (l < r->stats.finest_level) r->stats.finest_level = l;
        if (l > r->stats.coarsest_level) r->stats.coarsest_level = l;
    }
    r->stats.cpu_ms = now_ms() - r->update_start_ms;
    return r->all_current;
}
