// Chunk meshes: a 16 x 16-sample block of a face at one level meshed from its tile in
// double precision around its own origin, with its morph targets, skirts and painted
// weights, and uploaded to its vertex buffer.
#include "renderer/planet_internal.h"
#include "renderer/planet_renderer.h"

#include "editor/world/world.h"
#include "io/tile_cache.h"

#include <string.h>

// Positions with a ring one cell wider than the block, so every vertex's normal is a
// central difference and neighbouring chunks shade their shared edge alike.
#define RING (BLOCK + 3)

// Face coordinate of a chunk's vertex g (-1 to BLOCK + 1, the ring included) along one
// axis from block edge e0: its cell edge, clipped to the face, except that the ring's
// vertex past the face's edge lies a cell beyond it, on the neighbouring face. *edge: the
// vertex lies on the face's edge or past it (planet_face_edges.c gives its height).
static double vertex_coord(const planet_renderer *r, int level, int64_t e0, int g, int *edge) {
    const int64_t cells = (e0 + g) * ((int64_t)1 << level); // e0 + g may be -1
    const double past = 2.0 * ldexp(1.0, level) / (double)r->face_samples;
    *edge = cells <= 0 || cells >= r->face_samples;
    if (g == -1 && cells < 0) return -1.0 - past;
    if (g == BLOCK + 1 && (e0 + BLOCK) * ((int64_t)1 << level) >= r->face_samples)
        return 1.0 + past;
    return edge_coord(r, level, e0 + g);
}

// The heights of a chunk's vertices on or past its face's edges (NaN elsewhere: its own
// tile's), at its level and, for the morph targets, at its parent's. 0 while a tile of a
// neighbouring face is pending.
static int edge_heights(planet_renderer *r, const node *n, double s[RING], double t[RING],
                        float *heights, float *parent_heights, double (*normals)[3]) {
    int edge_s[RING], edge_t[RING], any = 0;
    for (int g = -1; g <= BLOCK + 1; g++) {
        s[g + 1] = vertex_coord(r, n->level, n->bx * BLOCK, g, &edge_s[g + 1]);
        t[g + 1] = vertex_coord(r, n->level, n->by * BLOCK, g, &edge_t[g + 1]);
        any |= edge_s[g + 1] | edge_t[g + 1];
    }
    for (int k = 0; k < RING * RING; k++)
        heights[k] = NAN;
    for (int k = 0; k < GRID_VERTS; k++)
        parent_heights[k] = normals[k][0] = NAN;
    // A vertex half a cell past its tile's first or last sample lies between that tile's
    // samples and the next tile's: the tile alone (clamped) gave it its own sample's
    // height, the neighbouring chunk the other's, and in rough ground the mesh under a
    // camera stood metres off the ground it was placed over.
    const double ox = (double)(n->bx % BLOCKS_PER_TILE) * BLOCK - 0.5,
                 oy = (double)(n->by % BLOCKS_PER_TILE) * BLOCK - 0.5;
    const double fx = (double)(n->bx / BLOCKS_PER_TILE) * TILE_SIZE,
                 fy = (double)(n->by / BLOCKS_PER_TILE) * TILE_SIZE;
    for (int gj = -1; gj <= BLOCK + 1; gj++)
        for (int gi = -1; gi <= BLOCK + 1; gi++) {
            const double u = ox + gi, v = oy + gj;
            if (edge_s[gi + 1] || edge_t[gj + 1] ||
                (u >= 0 && u <= TILE_SIZE - 1 && v >= 0 && v <= TILE_SIZE - 1))
                continue;
            if (!planet_face_height(r, n->face, n->level, fx + u, fy + v,
                                    &heights[(gj + 1) * RING + gi + 1]))
                return 0;
        }
    if (!any) return 1;
    for (int gj = -1; gj <= BLOCK + 1; gj++)
        for (int gi = -1; gi <= BLOCK + 1; gi++) {
            if (!edge_s[gi + 1] && !edge_t[gj + 1]) continue;
            double d[3];
            world_grid_face_direction(n->face, s[gi + 1], t[gj + 1], d);
            if (!planet_edge_height(r, n->level, d, &heights[(gj + 1) * RING + gi + 1])) return 0;
            const int grid = gi >= 0 && gj >= 0 && gi <= BLOCK && gj <= BLOCK;
            if (grid && !planet_edge_normal(r, n->level, d, normals[gj * (BLOCK + 1) + gi]))
                return 0;
            if (grid && gi % 2 == 0 && gj % 2 == 0 && n->level < r->root_level &&
                !planet_edge_height(r, n->level + 1, d, &parent_heights[gj * (BLOCK + 1) + gi]))
                return 0;
        }
    return 1;
}

static float sample_bilinear(const float *tile, double u, double v) {
    int i = (int)u, j = (int)v;
    int i1 = i + 1 < TILE_SIZE ? i + 1 : i, j1 = j + 1 < TILE_SIZE ? j + 1 : j;
    double fu = u - i, fv = v - j;
    double top =
        tile[j * TILE_SIZE + i] + (tile[j * TILE_SIZE + i1] - tile[j * TILE_SIZE + i]) * fu;
    double bottom =
        tile[j1 * TILE_SIZE + i] + (tile[j1 * TILE_SIZE + i1] - tile[j1 * TILE_SIZE + i]) * fu;
    return (float)(top + (bottom - top) * fv);
}

// Vertices at the block's cell edges (so neighbours share their edge positions and
// the outermost reach the face's edge), heights interpolated between sample centres.
// The parent level's mesh under a chunk: the vertices both levels share take the parent's
// heights; the others sit on the parent's edges and diagonals between them, so a chunk
// morphed all the way is exactly its parent (no pop when the parent takes over).
static void morph_targets(const planet_renderer *r, const node *n, const float *parent,
                          const float *parent_edge, double (*pos)[3], const float *heights,
                          int ring, double (*coarse)[3], float *coarse_h) {
    for (int gj = 0; gj <= BLOCK; gj++)
        for (int gi = 0; gi <= BLOCK; gi++) {
            const int k = gj * (BLOCK + 1) + gi, f = (gj + 1) * ring + gi + 1;
            memcpy(coarse[k], pos[f], sizeof coarse[k]);
            coarse_h[k] = heights[f];
        }
    if (!parent) return;
    const int64_t pm = level_samples(r, n->level + 1);
    const int64_t pbx = n->bx / 2, pby = n->by / 2;
    const int64_t ptx = pbx / BLOCKS_PER_TILE, pty = pby / BLOCKS_PER_TILE;
    const double hi_u = fmin(TILE_SIZE - 1, (double)(pm - 1 - ptx * TILE_SIZE));
    const double hi_v = fmin(TILE_SIZE - 1, (double)(pm - 1 - pty * TILE_SIZE));
    // This block's first parent cell edge inside the parent's tile.
    const double ou = (double)((pbx % BLOCKS_PER_TILE) * BLOCK + (n->bx % 2) * (BLOCK / 2));
    const double ov = (double)((pby % BLOCKS_PER_TILE) * BLOCK + (n->by % 2) * (BLOCK / 2));
    for (int gj = 0; gj <= BLOCK; gj += 2)
        for (int gi = 0; gi <= BLOCK; gi += 2) {
            const int k = gj * (BLOCK + 1) + gi;
            double u = fmin(fmax(ou + gi / 2 - 0.5, 0.0), hi_u);
            double v = fmin(fmax(ov + gj / 2 - 0.5, 0.0), hi_v);
            const float edge = parent_edge[k];
            float h = isnan(edge) ? sample_bilinear(parent, u, v) : edge;
            double len = sqrt(coarse[k][0] * coarse[k][0] + coarse[k][1] * coarse[k][1] +
                              coarse[k][2] * coarse[k][2]);
            double scale = (r->params.radius + h) / len;
            for (int a = 0; a < 3; a++)
                coarse[k][a] *= scale;
            coarse_h[k] = h;
        }
    for (int gj = 0; gj <= BLOCK; gj++)
        for (int gi = 0; gi <= BLOCK; gi++) {
            if (gi % 2 == 0 && gj % 2 == 0) continue;
            int a, b; // the two parent vertices whose edge (or diagonal) this one halves
            const int row = BLOCK + 1;
            if (gj % 2 == 0)
                a = gj * row + gi - 1, b = gj * row + gi + 1;
            else if (gi % 2 == 0)
                a = (gj - 1) * row + gi, b = (gj + 1) * row + gi;
            else // the parent's quads split along (i + 1, j) - (i, j + 1)
                a = (gj - 1) * row + gi + 1, b = (gj + 1) * row + gi - 1;
            const int k = gj * row + gi;
            for (int c = 0; c < 3; c++)
                coarse[k][c] = 0.5 * (coarse[a][c] + coarse[b][c]);
            coarse_h[k] = 0.5f * (coarse_h[a] + coarse_h[b]);
        }
}

// The painted weights at each grid vertex: the nearest material sample's (level-0
// chunks; coarser ones show the automatic rules alone, as the flat viewport's far
// levels do).
static int painted_weights(const node *n, const uint8_t *material, float *out) {
    int painted = 0;
    const int ox = (int)(n->bx % BLOCKS_PER_TILE) * BLOCK,
              oy = (int)(n->by % BLOCKS_PER_TILE) * BLOCK;
    for (int gj = 0; gj <= BLOCK; gj++)
        for (int gi = 0; gi <= BLOCK; gi++) {
            uint8_t w[TILE_MATERIALS] = {255};
            if (material) {
                int u = ox + gi < TILE_SIZE ? ox + gi : TILE_SIZE - 1;
                int v = oy + gj < TILE_SIZE ? oy + gj : TILE_SIZE - 1;
                memcpy(w, material + ((size_t)v * TILE_SIZE + u) * TILE_MATERIALS, sizeof w);
            }
            painted |= w[0] != 255;
            uint32_t packed[2] = {0, 0};
            for (int k = 0; k < TILE_MATERIALS; k++)
                packed[k / 4] |= (uint32_t)w[k] << (8 * (k % 4));
            memcpy(out + (size_t)(gj * (BLOCK + 1) + gi) * VERTEX_FLOATS + 16, packed,
                   sizeof packed);
        }
    return painted;
}

static void build_vertices(const planet_renderer *r, const node *n, const float *tile,
                           const float *parent, const uint8_t *material, const double s[RING],
                           const double t[RING], const float *edge_h, const float *parent_edge_h,
                           const double (*edge_n)[3], float *out, chunk *c) {
    static double pos[RING * RING][3];
    static float heights[RING * RING];
    static double metres[RING][2];
    const int64_t m = level_samples(r, n->level);
    const int64_t tx = n->bx / BLOCKS_PER_TILE, ty = n->by / BLOCKS_PER_TILE;
    const int ox = (int)(n->bx % BLOCKS_PER_TILE) * BLOCK,
              oy = (int)(n->by % BLOCKS_PER_TILE) * BLOCK;
    const double hi_u = fmin(TILE_SIZE - 1, (double)(m - 1 - tx * TILE_SIZE));
    const double hi_v = fmin(TILE_SIZE - 1, (double)(m - 1 - ty * TILE_SIZE));
    double tan_s[RING], tan_t[RING];
    for (int g = 0; g < RING; g++) {
        tan_s[g] = tan(s[g] * (M_PI / 4.0));
        tan_t[g] = tan(t[g] * (M_PI / 4.0));
        // Face-local metres, for the material textures' coordinates.
        metres[g][0] = (s[g] + 1.0) * 0.5 * (double)r->face_samples * r->cell_arc;
        metres[g][1] = (t[g] + 1.0) * 0.5 * (double)r->face_samples * r->cell_arc;
    }
    const double base_u = floor(metres[1][0] / TEX_PERIOD_FAR) * TEX_PERIOD_FAR;
    const double base_v = floor(metres[1][1] / TEX_PERIOD_FAR) * TEX_PERIOD_FAR;
    c->metres_base[0] = base_u, c->metres_base[1] = base_v;
    for (int a = 0; a < 2; a++)
        c->metres_lo[a] = metres[1][a], c->metres_hi[a] = metres[BLOCK + 1][a];
    c->hmin = INFINITY, c->hmax = -INFINITY;
    for (int gj = -1; gj <= BLOCK + 1; gj++)
        for (int gi = -1; gi <= BLOCK + 1; gi++) {
            double u = fmin(fmax(ox + gi - 0.5, 0.0), hi_u);
            double v = fmin(fmax(oy + gj - 0.5, 0.0), hi_v);
            const int k = (gj + 1) * RING + gi + 1;
            float h = isnan(edge_h[k]) ? sample_bilinear(tile, u, v) : edge_h[k];
            double d[3];
            world_grid_face_direction_warped(n->face, tan_s[gi + 1], tan_t[gj + 1], d);
            for (int a = 0; a < 3; a++)
                pos[k][a] = d[a] * (r->params.radius + h);
            heights[k] = h;
            if (gi >= 0 && gj >= 0 && gi <= BLOCK && gj <= BLOCK)
                c->hmin = fminf(c->hmin, h), c->hmax = fmaxf(c->hmax, h);
        }
    const int centre = (BLOCK / 2 + 1) * RING + BLOCK / 2 + 1;
    memcpy(c->origin, pos[centre], sizeof c->origin);
    static double coarse[GRID_VERTS][3];
    static float coarse_h[GRID_VERTS];
    morph_targets(r, n, parent, parent_edge_h, pos, heights, RING, coarse, coarse_h);
    // How far a morph target lies from its vertex's own direction, in cells (the
    // midpoint of two parent vertices at different heights leans toward the higher).
    c->morph_slip = 0;
    for (int gj = 0; gj <= BLOCK; gj++)
        for (int gi = 0; gi <= BLOCK; gi++) { // the ring holds the next vertex for the last
            const double *p = pos[(gj + 1) * RING + gi + 1], *q = coarse[gj * (BLOCK + 1) + gi],
                         *next = pos[(gj + 1) * RING + gi + 2];
            const double lp = sqrt(dot3(p, p)), lq = sqrt(dot3(q, q)), ln = sqrt(dot3(next, next));
            double slip[3], step[3];
            for (int a = 0; a < 3; a++)
                slip[a] = q[a] / lq - p[a] / lp, step[a] = next[a] / ln - p[a] / lp;
            c->morph_slip = fmaxf(c->morph_slip, (float)sqrt(dot3(slip, slip) / dot3(step, step)));
        }
    for (int gj = 0; gj <= BLOCK; gj++)
        for (int gi = 0; gi <= BLOCK; gi++) {
            const int k = (gj + 1) * RING + gi + 1;
            const double *l = pos[k - 1], *rt = pos[k + 1], *dn = pos[k - RING],
                         *upp = pos[k + RING];
            double du[3] = {rt[0] - l[0], rt[1] - l[1], rt[2] - l[2]};
            double dv[3] = {upp[0] - dn[0], upp[1] - dn[1], upp[2] - dn[2]};
            double nn[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2],
                            du[0] * dv[1] - du[1] * dv[0]};
            double up[3],
                len_p = sqrt(pos[k][0] * pos[k][0] + pos[k][1] * pos[k][1] + pos[k][2] * pos[k][2]);
            for (int a = 0; a < 3; a++)
                up[a] = pos[k][a] / len_p;
            double len = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
            double sign = nn[0] * up[0] + nn[1] * up[1] + nn[2] * up[2] < 0 ? -1.0 : 1.0;
            float *o = out + (size_t)(gj * (BLOCK + 1) + gi) * VERTEX_FLOATS;
            const double *edge_normal = edge_n[gj * (BLOCK + 1) + gi];
            for (int a = 0; a < 3; a++) {
                o[a] = (float)(pos[k][a] - c->origin[a]);
                o[3 + a] = (float)(!isnan(edge_normal[0]) ? edge_normal[a]
                                   : len > 0              ? sign * nn[a] / len
                                                          : up[a]);
                o[6 + a] = (float)up[a];
            }
            o[9] = heights[k];
            o[10] = (float)(metres[gi + 1][0] - base_u);
            o[11] = (float)(metres[gj + 1][1] - base_v);
            const int q = gj * (BLOCK + 1) + gi;
            for (int a = 0; a < 3; a++)
                o[12 + a] = (float)(coarse[q][a] - c->origin[a]);
            o[15] = coarse_h[q];
        }
    c->painted = painted_weights(n, material, out);
    c->blended = planet_face_blend(r, n->face, s, t, &pos[0][0], RING, out);
    // A cell's top: its vertices' heights and morph targets (the triangles between them
    // are chords, under their corners; the targets between parent vertices sit on the
    // parent's chords, under the heights given).
    for (int sj = 0; sj < TOP_CELLS; sj++)
        for (int si = 0; si < TOP_CELLS; si++) {
            float top = -INFINITY;
            const int step = BLOCK / TOP_CELLS;
            for (int gj = sj * step; gj <= (sj + 1) * step; gj++)
                for (int gi = si * step; gi <= (si + 1) * step; gi++)
                    top = fmaxf(top, fmaxf(heights[(gj + 1) * RING + gi + 1],
                                           coarse_h[gj * (BLOCK + 1) + gi]));
            c->top[sj][si] = top;
            c->top_max = sj == 0 && si == 0 ? top : fmaxf(c->top_max, top);
        }
    // A square's bottom: the lowest of its vertices and morph targets, less the sag of
    // the chords between them (the parent's are twice as long) and the vertices' float
    // precision.
    const double sag = chord_sag(r, n->level);
    for (int sj = 0; sj < CREST_SQUARES; sj++)
        for (int si = 0; si < CREST_SQUARES; si++) {
            float bottom = INFINITY;
            const int step = BLOCK / CREST_SQUARES;
            for (int gj = sj * step; gj <= (sj + 1) * step; gj++)
                for (int gi = si * step; gi <= (si + 1) * step; gi++)
                    bottom = fminf(bottom, fminf(heights[(gj + 1) * RING + gi + 1],
                                                 coarse_h[gj * (BLOCK + 1) + gi]));
            c->bottom[sj][si] = (float)(bottom - sag);
        }
    c->lowest = c->hmin, c->reach = 0;
    for (int q = 0; q < GRID_VERTS; q++) {
        const float *o = out + (size_t)q * VERTEX_FLOATS;
        c->lowest = fminf(c->lowest, o[15]);
        c->reach = fmaxf(c->reach, sqrtf(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]));
        c->reach = fmaxf(c->reach, sqrtf(o[12] * o[12] + o[13] * o[13] + o[14] * o[14]));
    }
    // Skirts: each edge's vertices again, lowered (skirt_depth).
    const double depth = skirt_depth(r, n->level);
    for (int e = 0; e < 4; e++)
        for (int g = 0; g <= BLOCK; g++) {
            int gi = e < 2 ? g : (e == 2 ? 0 : BLOCK), gj = e < 2 ? (e == 0 ? 0 : BLOCK) : g;
            const float *top = out + (size_t)(gj * (BLOCK + 1) + gi) * VERTEX_FLOATS;
            float *o = out + (size_t)(GRID_VERTS + e * (BLOCK + 1) + g) * VERTEX_FLOATS;
            memcpy(o, top, sizeof(float) * VERTEX_FLOATS);
            for (int a = 0; a < 3; a++) {
                o[a] -= (float)(top[6 + a] * depth);
                o[12 + a] -= (float)(top[6 + a] * depth);
            }
        }
}

// The directions of a chunk's footprint corners; returns the cosine of the widest angle
// between them and the footprint's middle direction. The footprint is the cone of these
// four directions: the cube's grid lines are great circles.
static double footprint_corners(const planet_renderer *r, const node *n, double dir[4][3]) {
    const double s0 = edge_coord(r, n->level, n->bx * BLOCK),
                 s1 = edge_coord(r, n->level, n->bx * BLOCK + BLOCK);
    const double t0 = edge_coord(r, n->level, n->by * BLOCK),
                 t1 = edge_coord(r, n->level, n->by * BLOCK + BLOCK);
    world_grid_face_direction(n->face, s0, t0, dir[0]);
    world_grid_face_direction(n->face, s1, t0, dir[1]);
    world_grid_face_direction(n->face, s0, t1, dir[2]);
    world_grid_face_direction(n->face, s1, t1, dir[3]);
    double mid[3] = {0, 0, 0};
    for (int k = 0; k < 4; k++)
        for (int a = 0; a < 3; a++)
            mid[a] += dir[k][a];
    const double len = sqrt(mid[0] * mid[0] + mid[1] * mid[1] + mid[2] * mid[2]);
    double cos_widest = 1.0;
    for (int k = 0; k < 4; k++)
        cos_widest =
            fmin(cos_widest, (dir[k][0] * mid[0] + dir[k][1] * mid[1] + dir[k][2] * mid[2]) / len);
    return cos_widest;
}

// Builds the node's chunk when its tile is resident and the frame's budget allows.
chunk *planet_try_build(planet_renderer *r, const node *n) {
    if (now_ms() - r->update_start_ms > BUILD_BUDGET_MS) {
        r->all_current = 0;
        return NULL;
    }
    tile_cache *cache = world_cache(r->world);
    tile_key key = {TILE_LAYER_COARSE, n->face, n->level, (int32_t)(n->bx / BLOCKS_PER_TILE),
                    (int32_t)(n->by / BLOCKS_PER_TILE)};
    tile_view view;
    tile_status st = tile_cache_request(cache, key, &view);
    if (st != TILE_READY) {
        if (view.data) tile_cache_release(cache, &view);
        r->all_current = 0;
        return NULL;
    }
    // Level 0 shows the paint: its material tile must be there too.
    tile_view material = {0};
    if (n->level == 0) {
        tile_key mk = key;
        mk.layer = TILE_LAYER_MATERIAL;
        if (tile_cache_request(cache, mk, &material) != TILE_READY) {
            if (material.data) tile_cache_release(cache, &material);
            tile_cache_release(cache, &view);
            r->all_current = 0;
            return NULL;
        }
    }
    // The vertices on the face's edges, from every face there (planet_face_edges.c).
    static double s[RING], t[RING];
    static float edge_h[RING * RING], parent_edge_h[GRID_VERTS];
    static double edge_n[GRID_VERTS][3];
    if (!edge_heights(r, n, s, t, edge_h, parent_edge_h, edge_n)) {
        tile_cache_release(cache, &view);
        if (material.data) tile_cache_release(cache, &material);
        r->all_current = 0;
        return NULL;
    }
    int slot = planet_take_slot(r);
    if (slot < 0) { // every chunk is in use this frame
        tile_cache_release(cache, &view);
        if (material.data) tile_cache_release(cache, &material);
        r->all_current = 0;
        return NULL;
    }
    // The parent level's tile, for the morph targets (none yet: the chunk does not morph).
    tile_view parent = {0};
    if (n->level < r->root_level) {
        tile_key pk = {TILE_LAYER_COARSE, n->face, n->level + 1,
                       (int32_t)(n->bx / 2 / BLOCKS_PER_TILE),
                       (int32_t)(n->by / 2 / BLOCKS_PER_TILE)};
        if (tile_cache_request(cache, pk, &parent) != TILE_READY && parent.data) {
            tile_cache_release(cache, &parent);
            parent.data = NULL;
        }
    }
    static float verts[CHUNK_VERTS * VERTEX_FLOATS];
    chunk *c = &r->chunks[slot];
    build_vertices(r, n, view.data, parent.data, material.data, s, t, edge_h, parent_edge_h,
                   (const double(*)[3])edge_n, verts, c);
    planet_normals_build(r, c, n);
    c->cos_widest = footprint_corners(r, n, c->corner_dir);
    for (int j = 0; j <= CREST_SQUARES; j++)
        for (int i = 0; i <= CREST_SQUARES; i++) {
            const int step = BLOCK / CREST_SQUARES;
            world_grid_face_direction(n->face, edge_coord(r, n->level, n->bx * BLOCK + i * step),
                                      edge_coord(r, n->level, n->by * BLOCK + j * step),
                                      c->square_dir[j][i]);
        }
    tile_cache_release(cache, &view);
    if (material.data) tile_cache_release(cache, &material);
    if (parent.data) tile_cache_release(cache, &parent);
    if (!c->vbo) {
        glCreateBuffers(1, &c->vbo);
        glNamedBufferStorage(c->vbo, sizeof verts, NULL, GL_DYNAMIC_STORAGE_BIT);
    }
    glNamedBufferSubData(c->vbo, 0, sizeof verts, verts);
    c->key = node_key(n);
    c->level = n->level;
    c->used = r->frame;
    planet_table_insert(r, slot);
    r->resident++;
    r->stats.chunks_built++;
    r->stats.vertices_uploaded += CHUNK_VERTS;
    return c;
}
