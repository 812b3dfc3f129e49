// Culling: chunks behind the horizon or outside the view are never built nor drawn;
// near the ground, those hidden by nearer ground (ground_occlusion.h, ground_horizon.h)
// are not drawn.
#include "renderer/planet_internal.h"
#include "renderer/planet_renderer.h"

#include "renderer/planet_camera.h"

// Horizon culling, conservative for any chunk size: a point at radius rq is hidden by
// the occluder sphere (radius ro) from the camera at distance d exactly when its angle
// from the camera's direction exceeds acos(ro / d) + acos(ro / rq); a chunk is hidden
// when even its bounding cap's nearest edge is.
static int behind_horizon(const planet_renderer *r, const double centre[3], double radius,
                          double top) {
    const double *c = r->cam->pos, ro = r->occluder_radius;
    double d = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    double rc = sqrt(centre[0] * centre[0] + centre[1] * centre[1] + centre[2] * centre[2]);
    if (d <= ro || rc <= radius) return 0;
    double cosang = (c[0] * centre[0] + c[1] * centre[1] + c[2] * centre[2]) / (d * rc);
    double angle = acos(fmax(-1.0, fmin(1.0, cosang))) - asin(fmin(1.0, radius / rc));
    double rq = fmax(top, ro);
    return angle > acos(ro / d) + acos(ro / rq);
}

// Returns 1 when the node is visible (not behind the horizon, in the view).
int planet_node_visible(planet_renderer *r, const node *n, double hmin, double hmax,
                        node_bounds *b) {
    const int64_t e0x = n->bx * BLOCK, e0y = n->by * BLOCK;
    double s0 = edge_coord(r, n->level, e0x), s1 = edge_coord(r, n->level, e0x + BLOCK);
    double t0 = edge_coord(r, n->level, e0y), t1 = edge_coord(r, n->level, e0y + BLOCK);
    double pts[10][3];
    const double ss[5] = {s0, s1, s0, s1, 0.5 * (s0 + s1)};
    const double ts[5] = {t0, t0, t1, t1, 0.5 * (t0 + t1)};
    // The ground under the sea is drawn raised to its surface: the heights drawn (a
    // chunk wholly under the sea is a thin shell at the surface, not as deep as its floor).
    const double ocean = world_params_ocean_height(&r->params);
    const double top = fmax(hmax, ocean), bottom = fmax(hmin, ocean);
    for (int k = 0; k < 5; k++) {
        surface_point(r, n->face, ss[k], ts[k], top, pts[k]);
        surface_point(r, n->face, ss[k], ts[k], bottom, pts[5 + k]);
    }
    // Sphere around the midpoint of the centre's top and bottom.
    for (int k = 0; k < 3; k++)
        b->centre[k] = 0.5 * (pts[4][k] + pts[9][k]);
    b->radius = 0;
    for (int k = 0; k < 10; k++) {
        double d = sqrt((pts[k][0] - b->centre[0]) * (pts[k][0] - b->centre[0]) +
                        (pts[k][1] - b->centre[1]) * (pts[k][1] - b->centre[1]) +
                        (pts[k][2] - b->centre[2]) * (pts[k][2] - b->centre[2]));
        if (d > b->radius) b->radius = d;
    }
    // The faces bulge between the corners: a chunk's arc adds up to ~1/8 of its width.
    b->radius *= 1.15;
    b->cell = ldexp(r->cell_arc, n->level);
    b->hmin = hmin, b->hmax = hmax;
    if (behind_horizon(r, b->centre, b->radius, r->params.radius + top)) return 0;
    // The bounding sphere against each plane (tighter than its box).
    const double rel[3] = {b->centre[0] - r->cam->pos[0], b->centre[1] - r->cam->pos[1],
                           b->centre[2] - r->cam->pos[2]};
    for (int k = 0; k < 6; k++) {
        const float *pl = r->fr.planes[k];
        if (pl[0] * rel[0] + pl[1] * rel[1] + pl[2] * rel[2] + pl[3] < -b->radius) return 0;
    }
    return 1;
}

// Near the ground the horizon is the ground's own: the sphere under all the ground
// between the camera and its horizon (from the last frame's chunks there, a margin
// below their lowest height) hides what lies past it, instead of a sphere under the
// whole planet's lowest point (whose horizon, a few metres up, is hundreds of km out).
// The horizon distance and the ground it spans depend on each other: a few rounds.
void planet_tighten_occluder(planet_renderer *r) {
    if (!near_ground(r) || r->draw_count == 0) return;
    const double R = r->params.radius, margin = 0.05 * r->params.max_height + r->cell_arc;
    double h = r->camera_altitude; // the occluder's height above the datum
    for (int round = 0; round < 4; round++) {
        double reach = sqrt(fmax(2.0 * R * (r->camera_altitude - h + margin), 0.0));
        double lowest = r->camera_altitude;
        for (int i = 0; i < r->draw_count; i++) {
            const chunk *c = &r->chunks[r->draw_list[i]];
            if (!c->key) continue; // dropped since (new parameters, another world)
            double d[3] = {c->origin[0] - r->cam->pos[0], c->origin[1] - r->cam->pos[1],
                           c->origin[2] - r->cam->pos[2]};
            double chunk_reach = ldexp(r->cell_arc, c->level) * BLOCK; // its width
            if (sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - chunk_reach > reach) continue;
            lowest = fmin(lowest, c->hmin);
        }
        h = lowest - margin;
    }
    r->occluder_radius = fmax(r->occluder_radius, R + h);
}

// Whether the camera is above the ground drawn under it (ground_occlusion.h's argument
// needs it): the top of the square under it in the drawn chunk there, or the sea's
// surface. Not known (0) when that chunk is not drawn (outside the view).
static int camera_above_ground(const planet_renderer *r) {
    int face;
    double s, t;
    world_grid_direction_face(r->cam->pos, &face, &s, &t);
    for (int i = 0; i < r->draw_count; i++) {
        const chunk *c = &r->chunks[r->draw_list[i]];
        const node n = chunk_node(c);
        if (n.face != face) continue;
        const double s0 = edge_coord(r, n.level, n.bx * BLOCK),
                     s1 = edge_coord(r, n.level, n.bx * BLOCK + BLOCK);
        const double t0 = edge_coord(r, n.level, n.by * BLOCK),
                     t1 = edge_coord(r, n.level, n.by * BLOCK + BLOCK);
        if (s < s0 || s > s1 || t < t0 || t > t1) continue;
        float top = c->top_max;
        const int64_t full = (int64_t)BLOCK << n.level; // cells: a chunk at a face's end is cut
        if ((n.bx + 1) * full <= r->face_samples && (n.by + 1) * full <= r->face_samples) {
            // The top of the 2 x 2 cell square under the camera: the mesh over it stays
            // over it (a cell's may lean into its neighbours, see behind_crest).
            enum { PER = CELLS_PER_SQUARE };
            int si = (int)((s - s0) / (s1 - s0) * CREST_SQUARES),
                sj = (int)((t - t0) / (t1 - t0) * CREST_SQUARES);
            si = si < 0 ? 0 : si >= CREST_SQUARES ? CREST_SQUARES - 1 : si;
            sj = sj < 0 ? 0 : sj >= CREST_SQUARES ? CREST_SQUARES - 1 : sj;
            top = -INFINITY;
            for (int j = sj * PER; j < (sj + 1) * PER; j++)
                for (int i = si * PER; i < (si + 1) * PER; i++)
                    top = fmaxf(top, c->top[j][i]);
        }
        const double ground = fmax(top, world_params_ocean_height(&r->params));
        return r->camera_altitude > ground + 0.01 + 1e-7 * r->params.radius;
    }
    return 0;
}

// Is everything the chunk draws hidden? The hull of its corners at the bottom (the
// skirts, the chords' sag) and at the top divided by the widest angle's cosine holds
// every point of its cone between those heights.
static int chunk_hidden(planet_renderer *r, const chunk *c) {
    const double cell = ldexp(r->cell_arc, c->level), R = r->params.radius;
    const double high =
        (R + fmax(c->top_max, world_params_ocean_height(&r->params)) + 0.01) / c->cos_widest;
    const double low = R + c->lowest - skirt_depth(r, c->level) - cell * cell / R - 0.01;
    double pts[8][3];
    for (int k = 0; k < 4; k++)
        for (int a = 0; a < 3; a++)
            pts[k][a] = c->corner_dir[k][a] * low, pts[4 + k][a] = c->corner_dir[k][a] * high;
    return ground_occlusion_hidden(&r->occlusion, (const double(*)[3])pts, 8);
}

// The solid under a chunk's ground: its footprint from its lowest point (less the sag of
// the chords between vertices, and a margin for their float precision) as deep again as
// the chunk is wide (so the solids of rising ground overlap on the screen).
static void add_solid_under(planet_renderer *r, const chunk *c) {
    const double cell = ldexp(r->cell_arc, c->level), R = r->params.radius;
    const double floor_r = R + c->lowest - chord_sag(r, c->level);
    const double(*dir)[3] = c->corner_dir;
    double pts[8][3];
    for (int k = 0; k < 4; k++)
        for (int a = 0; a < 3; a++)
            pts[k][a] = dir[k][a] * floor_r, pts[4 + k][a] = dir[k][a] * (floor_r - BLOCK * cell);
    ground_occlusion_add_solid(&r->occlusion, (const double(*)[3])pts, 8);
}

// One of a chunk's squares as a ground_horizon.h patch.
static void square_patch(const chunk *c, int si, int sj, double out[4][3]) {
    for (int a = 0; a < 3; a++) {
        out[0][a] = c->square_dir[sj][si][a], out[1][a] = c->square_dir[sj][si + 1][a];
        out[2][a] = c->square_dir[sj + 1][si][a], out[3][a] = c->square_dir[sj + 1][si + 1][a];
    }
}

// Is the chunk behind the horizon of nearer ground (ground_horizon.h)? As a whole under
// its highest point, else square by square under each one's, else cell by cell. A
// square's mesh stays over it (morph targets lie on its parent cell's edges and
// diagonal), but a morphing vertex leaves its own direction by up to morph_slip cells,
// so a cell's triangles may reach that far into its neighbours in the square, rising
// there by at most about that share of the square's height range: the cells' margin.
static int behind_crest(planet_renderer *r, const chunk *c) {
    const double R = r->params.radius, sea = world_params_ocean_height(&r->params);
    if (ground_horizon_hidden(&r->horizon, (const double(*)[3])c->corner_dir,
                              R + fmax(c->top_max, sea) + 0.01))
        return 1;
    enum { PER = CELLS_PER_SQUARE };
    const node n = chunk_node(c);
    for (int sj = 0; sj < CREST_SQUARES; sj++)
        for (int si = 0; si < CREST_SQUARES; si++) {
            float top = -INFINITY;
            for (int j = sj * PER; j < (sj + 1) * PER; j++)
                for (int i = si * PER; i < (si + 1) * PER; i++)
                    top = fmaxf(top, c->top[j][i]);
            double patch[4][3];
            square_patch(c, si, sj, patch);
            if (ground_horizon_hidden(&r->horizon, (const double(*)[3])patch,
                                      R + fmax(top, sea) + 0.01))
                continue;
            // The square's cells: the directions of its (PER + 1)^2 grid points.
            double dir[PER + 1][PER + 1][3];
            for (int j = 0; j <= PER; j++)
                for (int i = 0; i <= PER; i++)
                    world_grid_face_direction(
                        n.face, edge_coord(r, n.level, n.bx * BLOCK + si * PER + i),
                        edge_coord(r, n.level, n.by * BLOCK + sj * PER + j), dir[j][i]);
            const double margin = 0.01 + 2.0 * c->morph_slip * (top - c->bottom[sj][si]);
            for (int j = 0; j < PER; j++)
                for (int i = 0; i < PER; i++) {
                    double cell[4][3];
                    for (int a = 0; a < 3; a++) {
                        cell[0][a] = dir[j][i][a], cell[1][a] = dir[j][i + 1][a];
                        cell[2][a] = dir[j + 1][i][a], cell[3][a] = dir[j + 1][i + 1][a];
                    }
                    if (!ground_horizon_hidden(&r->horizon, (const double(*)[3])cell,
                                               R + fmax(c->top[sj * PER + j][si * PER + i], sea) +
                                                   margin))
                        return 0;
                }
        }
    return 1;
}

// A chunk's squares as floors of the horizon (the sea's surface where it is higher: the
// ground under it is drawn raised to it).
static void add_floors(planet_renderer *r, const chunk *c) {
    const double sea = world_params_ocean_height(&r->params) - chord_sag(r, c->level);
    for (int sj = 0; sj < CREST_SQUARES; sj++)
        for (int si = 0; si < CREST_SQUARES; si++) {
            double patch[4][3];
            square_patch(c, si, sj, patch);
            ground_horizon_add_floor(&r->horizon, (const double(*)[3])patch,
                                     r->params.radius + fmax(c->bottom[sj][si], sea));
        }
}

// The chunks to draw, nearest first: a few metres up most of the chosen ones lie past the
// horizon the nearby ground makes. Not in the wireframe (it shows everything), nor with
// `render culling=off`.
void planet_choose_shown(planet_renderer *r, const camera *cam, const render_settings *s,
                         double aspect) {
    r->shown_count = 0;
    const int occlude = s->culling && s->view != VIEW_WIREFRAME && camera_above_ground(r);
    if (occlude) {
        double forward[3], right[3], up[3];
        planet_camera_basis(cam, forward, right, up);
        const double ty =
            tan((cam->fov_y >= 1 && cam->fov_y <= 170 ? cam->fov_y : 60) * M_PI / 360.0);
        ground_occlusion_begin(&r->occlusion, cam->pos, forward, right, up, ty * aspect, ty);
        ground_horizon_begin(&r->horizon, cam->pos);
    }
    for (int i = 0; i < r->draw_count; i++) {
        const chunk *c = &r->chunks[r->draw_list[i]];
        if (occlude) {
            if (chunk_hidden(r, c) || behind_crest(r, c)) continue;
            add_solid_under(r, c);
            add_floors(r, c);
        }
        r->shown[r->shown_count++] = r->draw_list[i];
    }
}
