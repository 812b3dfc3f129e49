// Shading normals finer than the mesh. A chunk's vertices are split_pixels (6) apart on
// the screen, and normals taken from its own level's heights flattened everything a
// chunk's cells are too coarse to hold: from 2,000 km a level-10 chunk's cells are 100 km
// across and the mountain ranges' ridges and valleys shaded as a plain. Each chunk gets a
// texture of normals from the heights NORMAL_FINER levels below its own (samples about
// 1.5 pixels apart on the screen): the same tiles its grandchildren are built from, so
// they are what zooming in needs next. Until that level's tiles have arrived the texture
// is made from the finest level resident and made again when they come.
//
// A texel holds the normal's components along the face's s axis and its perpendicular in
// the local tangent plane (planet.frag's fine_normal rebuilds the normal from them and the
// interpolated vertical). Texels run from one sample before the chunk's first to one past
// its last, so bilinear lookups are continuous across neighbouring chunks of a level;
// samples past a face's edge are the neighbouring face's ground (as the vertex ring's
// are), so the light runs on across face edges.
#include "renderer/planet_internal.h"

#include "io/tile_cache.h"

#include <string.h>

// A face's s axis on the cube (world_grid_face_direction_warped's a coefficient).
static void face_axis(int face, double out[3]) {
    double centre[3], along[3];
    world_grid_face_direction_warped(face, 0.0, 0.0, centre);
    world_grid_face_direction_warped(face, 1.0, 0.0, along); // (centre + axis) / sqrt 2
    for (int a = 0; a < 3; a++)
        out[a] = along[a] * sqrt(2.0) - centre[a];
}

int planet_normals_create(planet_renderer *r, og_error *err) {
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &r->normals);
    glTextureStorage3D(
        r->normals, 1, GL_RG16F, NORMAL_ATLAS * NORMAL_TEXELS, NORMAL_ATLAS * NORMAL_TEXELS,
        (MAX_CHUNKS + NORMAL_ATLAS * NORMAL_ATLAS - 1) / (NORMAL_ATLAS * NORMAL_ATLAS));
    glTextureParameteri(r->normals, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(r->normals, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(r->normals, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(r->normals, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    for (int f = 0; f < 6; f++)
        face_axis(f, r->face_axis[f]);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR)
        return og_error_set(err, "planet renderer: no room for the normal textures (GL 0x%x)", e);
    return 0;
}

// Chunk slot's place in the atlas: its layer and its first texel there.
void planet_normals_place(int slot, int *layer, int *x, int *y) {
    const int per_layer = NORMAL_ATLAS * NORMAL_ATLAS, k = slot % per_layer;
    *layer = slot / per_layer;
    *x = (k % NORMAL_ATLAS) * NORMAL_TEXELS, *y = (k / NORMAL_ATLAS) * NORMAL_TEXELS;
}

// texels x texels (rows NORMAL_TEXELS apart) into chunk slot's place.
static void upload(planet_renderer *r, int slot, int texels, const float *data) {
    int layer, x, y;
    planet_normals_place(slot, &layer, &x, &y);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, NORMAL_TEXELS);
    glTextureSubImage3D(r->normals, 0, x, y, layer, texels, texels, 1, GL_RG, GL_FLOAT, data);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
}

// The level whose heights a chunk's normals want: its own under the sea, whose surface
// is drawn flat (no finer tiles generated for ground nobody sees).
static int normal_target(const planet_renderer *r, const chunk *c, int level) {
    if (c->hmax < world_params_ocean_height(&r->params)) return level;
    return level > NORMAL_FINER ? level - NORMAL_FINER : 0;
}

// A level's height at sample (i, j) of a face, or past its edges the neighbouring face's
// ground at that direction; dir is where the sample lies. 1 when read, 0 while a tile is
// pending.
static int sample_height(planet_renderer *r, int face, int level, int64_t i, int64_t j, int inside,
                         const tile_view *main, int64_t tx, int64_t ty, const double dir[3],
                         float *out) {
    if (!inside) return planet_edge_height(r, level, dir, out);
    if (i / TILE_SIZE == tx && j / TILE_SIZE == ty) {
        *out = ((const float *)main->data)[(j % TILE_SIZE) * TILE_SIZE + i % TILE_SIZE];
        return 1;
    }
    return planet_face_height(r, face, level, (double)i, (double)j, out);
}

// Makes chunk c's normals (node n) from level lk's heights. 1 when made, 0 while a tile
// is pending.
static int build_from(planet_renderer *r, chunk *c, const node *n, int lk) {
    enum { SPAN = NORMAL_TEXELS + 2 }; // the texels and one sample more on each side
    const int k = n->level - lk, texels = (BLOCK << k) + 2;
    const int64_t base_i = (n->bx * BLOCK << k) - 2, base_j = (n->by * BLOCK << k) - 2;
    const int64_t m = level_samples(r, lk);
    const int64_t tx = (base_i + 2) / TILE_SIZE, ty = (base_j + 2) / TILE_SIZE;
    tile_cache *cache = world_cache(r->world);
    tile_view main;
    tile_key key = {TILE_LAYER_COARSE, n->face, lk, (int32_t)tx, (int32_t)ty};
    if (tile_cache_request(cache, key, &main) != TILE_READY) {
        if (main.data) tile_cache_release(cache, &main);
        return 0;
    }
    static double pos[SPAN][SPAN][3], tan_s[SPAN], tan_t[SPAN];
    static int in_s[SPAN], in_t[SPAN];
    const double cell = ldexp(1.0, lk), samples = (double)r->face_samples;
    for (int g = 0; g < texels + 2; g++) {
        const double s = ((double)(base_i + g) + 0.5) * cell / samples * 2.0 - 1.0;
        const double t = ((double)(base_j + g) + 0.5) * cell / samples * 2.0 - 1.0;
        tan_s[g] = tan(s * (M_PI / 4.0)), tan_t[g] = tan(t * (M_PI / 4.0));
        in_s[g] = base_i + g >= 0 && base_i + g < m && s <= 1.0;
        in_t[g] = base_j + g >= 0 && base_j + g < m && t <= 1.0;
    }
    int ok = 1;
    for (int gj = 0; gj < texels + 2 && ok; gj++)
        for (int gi = 0; gi < texels + 2 && ok; gi++) {
            double *p = pos[gj][gi];
            world_grid_face_direction_warped(n->face, tan_s[gi], tan_t[gj], p);
            float h;
            ok = sample_height(r, n->face, lk, base_i + gi, base_j + gj, in_s[gi] && in_t[gj],
                               &main, tx, ty, p, &h);
            for (int a = 0; a < 3; a++)
                p[a] *= r->params.radius + h;
        }
    tile_cache_release(cache, &main);
    if (!ok) return 0;
    static float texel[NORMAL_TEXELS * NORMAL_TEXELS][2];
    const double *axis = r->face_axis[n->face];
    for (int gj = 1; gj <= texels; gj++)
        for (int gi = 1; gi <= texels; gi++) {
            const double *l = pos[gj][gi - 1], *rt = pos[gj][gi + 1], *dn = pos[gj - 1][gi],
                         *upp = pos[gj + 1][gi], *p = pos[gj][gi];
            const double du[3] = {rt[0] - l[0], rt[1] - l[1], rt[2] - l[2]};
            const double dv[3] = {upp[0] - dn[0], upp[1] - dn[1], upp[2] - dn[2]};
            double nn[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2],
                            du[0] * dv[1] - du[1] * dv[0]};
            const double lp = sqrt(dot3(p, p)), ln = sqrt(dot3(nn, nn));
            double up[3], tx_axis[3];
            for (int a = 0; a < 3; a++)
                up[a] = p[a] / lp;
            const double along = dot3(axis, up);
            for (int a = 0; a < 3; a++)
                tx_axis[a] = axis[a] - up[a] * along;
            const double lt = sqrt(dot3(tx_axis, tx_axis));
            const double by_axis[3] = {up[1] * tx_axis[2] - up[2] * tx_axis[1],
                                       up[2] * tx_axis[0] - up[0] * tx_axis[2],
                                       up[0] * tx_axis[1] - up[1] * tx_axis[0]};
            const double sign = dot3(nn, up) < 0 ? -1.0 : 1.0;
            float *o = texel[(gj - 1) * NORMAL_TEXELS + gi - 1];
            o[0] = ln > 0 ? (float)(sign * dot3(nn, tx_axis) / (ln * lt)) : 0.0f;
            o[1] = ln > 0 ? (float)(sign * dot3(nn, by_axis) / (ln * lt)) : 0.0f;
        }
    upload(r, (int)(c - r->chunks), texels, &texel[0][0]);
    c->normal_level = (signed char)lk;
    return 1;
}

void planet_normals_build(planet_renderer *r, chunk *c, const node *n) {
    for (int lk = normal_target(r, c, n->level); lk <= n->level; lk++)
        if (build_from(r, c, n, lk)) return;
    // A neighbouring tile of the chunk's own level is pending: the local vertical until
    // it comes (planet_normals_refine tries again).
    static const float flat[NORMAL_TEXELS * NORMAL_TEXELS][2];
    upload(r, (int)(c - r->chunks), NORMAL_TEXELS, &flat[0][0]);
    c->normal_level = -1;
}

void planet_normals_refine(planet_renderer *r) {
    // Its own share of a frame, at least one chunk: selecting and building on a busy
    // machine can take the whole build budget, and the normals must still come.
    const double start = now_ms();
    int made = 0;
    for (int i = 0; i < r->draw_count; i++) {
        chunk *c = &r->chunks[r->draw_list[i]];
        const int target = normal_target(r, c, c->level);
        if (c->normal_level >= 0 && c->normal_level <= target) continue;
        if (made > 0 && now_ms() - start > 0.5 * BUILD_BUDGET_MS) {
            r->all_current = 0;
            return;
        }
        const node n = chunk_node(c);
        const int from = c->normal_level < 0 ? c->level : c->normal_level - 1;
        for (int lk = target; lk <= from; lk++)
            if (build_from(r, c, &n, lk)) {
                made++;
                break;
            }
        if (c->normal_level < 0 || c->normal_level > target) r->all_current = 0;
    }
}
