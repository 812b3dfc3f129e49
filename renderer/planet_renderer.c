#include "renderer/planet_renderer.h"

#include "editor/params/world_grid.h"
#include "io/tile_cache.h"
#include "renderer/frustum.h"
#include "renderer/ground_horizon.h"
#include "renderer/ground_occlusion.h"
#include "renderer/lighting.h"
#include "renderer/material_textures.h"
#include "renderer/planet_detail.h"
#include "renderer/planet_camera.h"
#include "renderer/shader.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

// Samples (quads) per chunk side. 16 rather than 32: the same bound on a sample's size
// on screen with a third of the triangles near the ground (a chunk splits as a whole
// for its nearest point), no visible change; 8 costs more in draw calls than it saves.
#define BLOCK 16
#define BLOCKS_PER_TILE (TILE_SIZE / BLOCK)
#define GRID_VERTS ((BLOCK + 1) * (BLOCK + 1))
#define CHUNK_VERTS (GRID_VERTS + 4 * (BLOCK + 1))
#define CHUNK_INDICES (BLOCK * BLOCK * 6 + 4 * BLOCK * 6)
// Position 3 (from the chunk's origin), normal 3, up 3, height, uv 2, and the morph
// target: where the vertex sits in the parent level's mesh (position 3, height).
// Then the 8 painted material weights (uint8 each, packed in two 32-bit slots).
#define VERTEX_FLOATS 18
#define MAX_CHUNKS 3072 // resident meshes (~80 MB): several views' worth
#define TABLE_SIZE 8192 // open addressing, power of two, > 2 x MAX_CHUNKS
#define BUILD_BUDGET_MS 10.0
#define TEX_PERIOD_NEAR 4.0    // metres per repeat of the material textures
#define TEX_PERIOD_FAR 64.0    // the larger scale that breaks up repetition (a multiple)
#define EARTH_RADIUS 6371000.0 // the atmosphere scales with the planet from Earth's
#define EARTH_SCALE_HEIGHT 8000.0
#define TOP_CELLS 16    // the tops of a chunk's cells, for the ground under the camera and crests
#define CREST_SQUARES 8 // a chunk's floors for occlusion by the horizon: its 2 x 2 cell squares
#define CELLS_PER_SQUARE (TOP_CELLS / CREST_SQUARES) // along a side

typedef struct chunk {
    uint64_t key; // 0: free
    GLuint vbo;
    double origin[3]; // planet coordinates of the vertices' origin
    float hmin, hmax; // metres above the datum
    float lowest;     // under hmin where the morph targets are lower
    float reach;      // metres from the origin to the farthest vertex (skirts aside)
    int painted;      // some vertex has painted weights
    int level;
    float top[TOP_CELLS][TOP_CELLS]; // the highest the mesh reaches over each cell (morphed or not)
    float top_max;                   // and over the whole chunk
    float morph_slip; // the farthest a morph target lies from its vertex's direction, in cells
    double corner_dir[4][3]; // its footprint's corner directions (footprint_corners)
    // Its squares' corner directions and the lowest the mesh reaches over each (the
    // chords' sag and float precision allowed for): ground_horizon.h's patches.
    double square_dir[CREST_SQUARES + 1][CREST_SQUARES + 1][3];
    float bottom[CREST_SQUARES][CREST_SQUARES];
    double cos_widest;     // the cosine of the widest angle from their middle
    double morph_reach;    // this frame: where the parent level would take over (metres)
    double near_dist;      // this frame: from the camera to its bounding sphere (drawing order)
    double metres_base[2]; // face-local metres the vertices' texture metres are relative to
    double metres_lo[2], metres_hi[2]; // its footprint in face-local metres
    uint64_t used;                     // frame it was last selected
} chunk;

// How a shown chunk is drawn this frame: its program variant and detail window.
typedef struct chunk_look {
    float detail[4], wrap[2]; // planet_detail_chunk's
    signed char window;       // its detail window (-1: none)
    unsigned char variant;
} chunk_look;

// The ground program's variants (see planet.frag): what a chunk can show.
enum {
    V_SHADED = 1,
    V_DETAIL = 2,
    V_SEA = 4,
    V_PAINTED = 8,
    V_BARE = 16,
    V_BRUSH = 32,
    V_OVERLAYS = 64,
    V_MINIFIED = 128,
    VARIANTS = 256
};

typedef struct ground_program {
    GLuint prog;
    GLint offset, level, morph, detail, wrap, tile, cell; // the per-chunk uniforms
    uint64_t frame;                                       // its frame uniforms were set for
} ground_program;

typedef struct node {
    int face, level;
    int64_t bx, by;
} node;

struct planet_renderer {
    char shader_dir[4200];
    ground_program ground[VARIANTS]; // built when first needed
    GLuint prog_sky, vao, empty_vao, ibo, albedo, falloff;
    float albedo_mean[MATERIAL_TEXTURE_COUNT][4]; // each material texture's mean colour
    int has_albedo_mean;
    GLenum front[6];       // each face's winding seen from outside
    planet_detail *detail; // the detail layer around the camera, for parallax
    chunk chunks[MAX_CHUNKS];
    int table[TABLE_SIZE]; // chunk index or -1
    int resident;
    // The world this frame.
    world *world;
    world_params params;
    int64_t face_samples;
    double cell_arc; // metres of the datum's arc per level-0 cell (spacing or a little less)
    int root_level;
    uint64_t frame;
    double update_start_ms;
    int all_current;
    // Selection.
    const camera *cam;
    frustum fr;
    double pixels_per_radian; // screen height / (2 tan(fov/2))
    double occluder_radius;   // a sphere inside all the ground, for horizon culling
    double camera_altitude;   // metres above the datum
    double split_pixels;      // a sample wider than this on screen: its chunk splits
    int draw_count;
    int draw_list[MAX_CHUNKS];
    // Drawing: the chosen chunks nearest first, those hidden by nearer ground left out.
    int shown_count;
    int shown[MAX_CHUNKS];
    chunk_look looks[MAX_CHUNKS]; // of shown[i]
    ground_occlusion occlusion;
    ground_horizon horizon;
    planet_stats stats;
};

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

// ---- chunk table ----------------------------------------------------------------

static uint64_t node_key(const node *n) {
    return ((uint64_t)n->face | (uint64_t)n->level << 3 | (uint64_t)n->bx << 8 |
            (uint64_t)n->by << 36) +
           1;
}

static int chunk_face(const chunk *c) {
    return (int)((c->key - 1) & 7);
}

static size_t slot_of(uint64_t key) {
    return (size_t)((key * 0x9E3779B97F4A7C15ull) >> 52) & (TABLE_SIZE - 1);
}

static chunk *find_chunk(planet_renderer *r, uint64_t key) {
    for (size_t s = slot_of(key);; s = (s + 1) & (TABLE_SIZE - 1)) {
        if (r->table[s] < 0) return NULL;
        if (r->chunks[r->table[s]].key == key) return &r->chunks[r->table[s]];
    }
}

static void table_insert(planet_renderer *r, int index) {
    size_t s = slot_of(r->chunks[index].key);
    while (r->table[s] >= 0)
        s = (s + 1) & (TABLE_SIZE - 1);
    r->table[s] = index;
}

// Linear probing's backward-shift deletion: no tombstones.
static void table_remove(planet_renderer *r, uint64_t key) {
    size_t s = slot_of(key);
    while (r->chunks[r->table[s]].key != key)
        s = (s + 1) & (TABLE_SIZE - 1);
    r->table[s] = -1;
    for (size_t j = (s + 1) & (TABLE_SIZE - 1); r->table[j] >= 0; j = (j + 1) & (TABLE_SIZE - 1)) {
        size_t home = slot_of(r->chunks[r->table[j]].key);
        // Move j back into the hole when its home is not in (s, j] cyclically.
        int between = s <= j ? (home > s && home <= j) : (home > s || home <= j);
        if (!between) {
            r->table[s] = r->table[j];
            r->table[j] = -1;
            s = j;
        }
    }
}

static void drop_all(planet_renderer *r) {
    for (int i = 0; i < MAX_CHUNKS; i++)
        r->chunks[i].key = 0;
    for (int i = 0; i < TABLE_SIZE; i++)
        r->table[i] = -1;
    r->resident = 0;
}

// A free chunk slot, evicting the least recently selected chunk not used this frame.
static int take_slot(planet_renderer *r) {
    int best = -1;
    for (int i = 0; i < MAX_CHUNKS; i++) {
        if (r->chunks[i].key == 0) return i;
        if (r->chunks[i].used < r->frame && (best < 0 || r->chunks[i].used < r->chunks[best].used))
            best = i;
    }
    if (best >= 0) {
        table_remove(r, r->chunks[best].key);
        r->chunks[best].key = 0;
        r->resident--;
    }
    return best;
}

// ---- geometry -------------------------------------------------------------------

// Level-L samples per face side (the last one may reach past the face's edge).
static int64_t level_samples(const planet_renderer *r, int level) {
    return (r->face_samples + ((int64_t)1 << level) - 1) >> level;
}

static int node_exists(const planet_renderer *r, const node *n) {
    int64_t m = level_samples(r, n->level);
    return n->bx >= 0 && n->by >= 0 && n->bx * BLOCK < m && n->by * BLOCK < m;
}

// Face coordinate of level-L cell edge e (clipped to the face).
static double edge_coord(const planet_renderer *r, int level, int64_t e) {
    int64_t cells = e < 0 ? 0 : e << level;
    if (cells > r->face_samples) cells = r->face_samples;
    return (double)cells / (double)r->face_samples * 2.0 - 1.0;
}

static void surface_point(const planet_renderer *r, int face, double s, double t, double h,
                          double out[3]) {
    double d[3];
    world_grid_face_direction(face, s, t, d);
    for (int k = 0; k < 3; k++)
        out[k] = d[k] * (r->params.radius + h);
}

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

typedef struct node_bounds {
    double centre[3], radius; // bounding sphere, planet coordinates
    double cell;              // metres per sample at this level
    double hmin, hmax;        // metres above the datum (the generator's range when unbuilt)
} node_bounds;

// Returns 1 when the node is visible (not behind the horizon, in the view).
static int node_visible(planet_renderer *r, const node *n, double hmin, double hmax,
                        node_bounds *b) {
    const int64_t e0x = n->bx * BLOCK, e0y = n->by * BLOCK;
    double s0 = edge_coord(r, n->level, e0x), s1 = edge_coord(r, n->level, e0x + BLOCK);
    double t0 = edge_coord(r, n->level, e0y), t1 = edge_coord(r, n->level, e0y + BLOCK);
    double pts[10][3];
    const double ss[5] = {s0, s1, s0, s1, 0.5 * (s0 + s1)};
    const double ts[5] = {t0, t0, t1, t1, 0.5 * (t0 + t1)};
    for (int k = 0; k < 5; k++) {
        surface_point(r, n->face, ss[k], ts[k], hmax, pts[k]);
        surface_point(r, n->face, ss[k], ts[k], hmin, pts[5 + k]);
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
    if (behind_horizon(r, b->centre, b->radius, r->params.radius + hmax)) return 0;
    // The bounding sphere against each plane (tighter than its box).
    const double rel[3] = {b->centre[0] - r->cam->pos[0], b->centre[1] - r->cam->pos[1],
                           b->centre[2] - r->cam->pos[2]};
    for (int k = 0; k < 6; k++) {
        const float *pl = r->fr.planes[k];
        if (pl[0] * rel[0] + pl[1] * rel[1] + pl[2] * rel[2] + pl[3] < -b->radius) return 0;
    }
    return 1;
}

// How much a sample's projected size shrinks seen at a grazing angle: the geometric mean
// of its two projected sides (1 when not judged). From high up, not where the chunk has
// a coast: coarser chunks would draw coastlines (the sea is per vertex) in visibly large
// steps toward the limb. Not for a chunk the camera stands in (the view across it
// varies too much).
static int near_ground(const planet_renderer *r) {
    return r->camera_altitude < 0.01 * r->params.radius;
}

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
    return cell * r->pixels_per_radian * grazing(r, b, centre_dist, d) / r->split_pixels;
}

static int wants_split(const planet_renderer *r, const node *n, const node_bounds *b) {
    if (n->level == 0) return 0;
    double dist;
    return split_distance(r, b, b->cell, &dist) > dist;
}

// ---- chunk meshes ---------------------------------------------------------------

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
                          double (*pos)[3], const float *heights, int ring, double (*coarse)[3],
                          float *coarse_h) {
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
            float h = sample_bilinear(parent, u, v);
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

// How far a chunk's skirts hang: enough to hide the cracks between levels and faces (a
// level's samples differ from the next one's by about a cell).
static double skirt_depth(const planet_renderer *r, int level) {
    return fmin(ldexp(r->cell_arc, level), 2.0 * r->params.max_height) + 0.25 * r->cell_arc;
}

static double dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// How far a level's drawn triangles can lie under their corners: the sag of chords as
// long as a parent cell's diagonal, and the vertices' float precision.
static double chord_sag(const planet_renderer *r, int level) {
    const double cell = ldexp(r->cell_arc, level);
    return cell * cell / r->params.radius + 1e-6 * BLOCK * cell + 0.01;
}

static void build_vertices(const planet_renderer *r, const node *n, const float *tile,
                           const float *parent, const uint8_t *material, float *out, chunk *c) {
    // Positions with a ring one cell wider than the block, so every vertex's normal is
    // a central difference and neighbouring chunks shade their shared edge alike.
    enum { RING = BLOCK + 3 };
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
    for (int g = -1; g <= BLOCK + 1; g++) {
        double s = edge_coord(r, n->level, n->bx * BLOCK + g);
        double t = edge_coord(r, n->level, n->by * BLOCK + g);
        tan_s[g + 1] = tan(s * (M_PI / 4.0));
        tan_t[g + 1] = tan(t * (M_PI / 4.0));
        // Face-local metres, for the material textures' coordinates.
        metres[g + 1][0] = (s + 1.0) * 0.5 * (double)r->face_samples * r->cell_arc;
        metres[g + 1][1] = (t + 1.0) * 0.5 * (double)r->face_samples * r->cell_arc;
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
            float h = sample_bilinear(tile, u, v);
            double d[3];
            world_grid_face_direction_warped(n->face, tan_s[gi + 1], tan_t[gj + 1], d);
            const int k = (gj + 1) * RING + gi + 1;
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
    morph_targets(r, n, parent, pos, heights, RING, coarse, coarse_h);
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
            for (int a = 0; a < 3; a++) {
                o[a] = (float)(pos[k][a] - c->origin[a]);
                o[3 + a] = (float)(len > 0 ? sign * nn[a] / len : up[a]);
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
static chunk *try_build(planet_renderer *r, const node *n) {
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
    int slot = take_slot(r);
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
    build_vertices(r, n, view.data, parent.data, material.data, verts, c);
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
    table_insert(r, slot);
    r->resident++;
    r->stats.chunks_built++;
    r->stats.vertices_uploaded += CHUNK_VERTS;
    return c;
}

// ---- selection ------------------------------------------------------------------

static void children_of(const node *n, node out[4]) {
    for (int k = 0; k < 4; k++)
        out[k] = (node){n->face, n->level - 1, 2 * n->bx + (k & 1), 2 * n->by + (k >> 1)};
}

static void bounds_heights(planet_renderer *r, const node *n, double *lo, double *hi) {
    chunk *c = find_chunk(r, node_key(n));
    // Unbuilt: the generator's range, with room for edits beyond it.
    *lo = c ? c->hmin : -1.5 * r->params.max_height;
    *hi = c ? c->hmax : 1.5 * r->params.max_height;
}

// 0: the node is drawn (itself or its children) or culled; 1: it could not be drawn.
static int select_node(planet_renderer *r, const node *n) {
    double lo, hi;
    bounds_heights(r, n, &lo, &hi);
    node_bounds b;
    if (!node_visible(r, n, lo, hi, &b)) {
        r->stats.chunks_culled++;
        return 0;
    }
    chunk *c = find_chunk(r, node_key(n));
    if (!c && !(c = try_build(r, n))) return 1;
    c->used = r->frame;
    if (wants_split(r, n, &b)) {
        node kids[4];
        children_of(n, kids);
        int ready = 1;
        for (int k = 0; k < 4; k++) {
            if (!node_exists(r, &kids[k]) || find_chunk(r, node_key(&kids[k]))) continue;
            double klo, khi;
            bounds_heights(r, &kids[k], &klo, &khi);
            node_bounds kb;
            if (node_visible(r, &kids[k], klo, khi, &kb) && !try_build(r, &kids[k])) ready = 0;
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

// ---- the renderer ---------------------------------------------------------------

// A chunk vertex's place in the block's own frame: across (i), along (j) and up (h;
// -1 for a skirt's lowered copy). Used to wind every triangle alike.
static void block_coords(uint16_t index, double out[3]) {
    if (index < GRID_VERTS) {
        out[0] = index % (BLOCK + 1), out[1] = index / (BLOCK + 1), out[2] = 0;
        return;
    }
    int e = (index - GRID_VERTS) / (BLOCK + 1), g = (index - GRID_VERTS) % (BLOCK + 1);
    out[0] = e < 2 ? g : (e == 2 ? 0 : BLOCK);
    out[1] = e < 2 ? (e == 0 ? 0 : BLOCK) : g;
    out[2] = -1;
}

// Winds the triangle counter-clockwise seen from `outward` (in the block's frame), so
// back faces can be culled: the ground from below, a skirt from inside its chunk.
static void wind(uint16_t tri[3], const double outward[3]) {
    double p[3][3];
    for (int v = 0; v < 3; v++)
        block_coords(tri[v], p[v]);
    double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    if (n[0] * outward[0] + n[1] * outward[1] + n[2] * outward[2] < 0) {
        uint16_t t = tri[1];
        tri[1] = tri[2], tri[2] = t;
    }
}

// The winding a face's chunks show from outside the planet: counter-clockwise where the
// face's s, t and the outward direction make a right-handed frame.
static GLenum face_front(int face) {
    double o[3], ds[3], dt[3];
    world_grid_face_direction_warped(face, 0, 0, o);
    world_grid_face_direction_warped(face, 0.01, 0, ds);
    world_grid_face_direction_warped(face, 0, 0.01, dt);
    for (int a = 0; a < 3; a++)
        ds[a] -= o[a], dt[a] -= o[a];
    double n[3] = {ds[1] * dt[2] - ds[2] * dt[1], ds[2] * dt[0] - ds[0] * dt[2],
                   ds[0] * dt[1] - ds[1] * dt[0]};
    return n[0] * o[0] + n[1] * o[1] + n[2] * o[2] > 0 ? GL_CCW : GL_CW;
}

static GLuint make_indices(void) {
    static uint16_t idx[CHUNK_INDICES];
    const double up[3] = {0, 0, 1};
    const double skirt_out[4][3] = {{0, -1, 0}, {0, 1, 0}, {-1, 0, 0}, {1, 0, 0}}; // edges 0-3
    int k = 0;
    for (int j = 0; j < BLOCK; j++)
        for (int i = 0; i < BLOCK; i++) {
            uint16_t a = (uint16_t)(j * (BLOCK + 1) + i), b = a + 1, c = a + BLOCK + 1, d = c + 1;
            uint16_t quad[6] = {a, c, b, b, c, d};
            wind(quad, up), wind(quad + 3, up);
            memcpy(idx + k, quad, sizeof quad);
            k += 6;
        }
    for (int e = 0; e < 4; e++)
        for (int g = 0; g < BLOCK; g++) {
            int gi0 = e < 2 ? g : (e == 2 ? 0 : BLOCK), gj0 = e < 2 ? (e == 0 ? 0 : BLOCK) : g;
            int gi1 = e < 2 ? g + 1 : gi0, gj1 = e < 2 ? gj0 : g + 1;
            uint16_t t0 = (uint16_t)(gj0 * (BLOCK + 1) + gi0),
                     t1 = (uint16_t)(gj1 * (BLOCK + 1) + gi1);
            uint16_t b0 = (uint16_t)(GRID_VERTS + e * (BLOCK + 1) + g), b1 = b0 + 1;
            uint16_t quad[6] = {t0, b0, t1, t1, b0, b1};
            wind(quad, skirt_out[e]), wind(quad + 3, skirt_out[e]);
            memcpy(idx + k, quad, sizeof quad);
            k += 6;
        }
    GLuint ibo;
    glCreateBuffers(1, &ibo);
    glNamedBufferStorage(ibo, sizeof idx, idx, 0);
    return ibo;
}

// Each material texture's 1 x 1 level: what a fully minified lookup returns (the
// MINIFIED variant's albedo, materials.glsl).
static void albedo_means(planet_renderer *r) {
    GLint levels = 0;
    glGetTextureParameteriv(r->albedo, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
    if (levels < 1) return; // not an immutable texture: the MINIFIED variant is never chosen
    glGetTextureImage(r->albedo, levels - 1, GL_RGBA, GL_FLOAT, sizeof r->albedo_mean,
                      r->albedo_mean);
    r->has_albedo_mean = 1;
}

// The ground program for a variant (V_* bits), built on first use.
static ground_program *ground_variant(planet_renderer *r, int variant, og_error *err) {
    ground_program *g = &r->ground[variant];
    if (g->prog) return g;
    static const char *const names[] = {"SHADED", "DETAIL", "SEA",      "PAINTED",
                                        "BARE",   "BRUSH",  "OVERLAYS", "MINIFIED"};
    g->prog = shader_program_load_flags(r->shader_dir, "planet.vert", "planet.frag", names, 8,
                                        (unsigned)variant, err);
    if (!g->prog) return NULL;
    g->offset = glGetUniformLocation(g->prog, "u_offset");
    g->level = glGetUniformLocation(g->prog, "u_level");
    g->morph = glGetUniformLocation(g->prog, "u_morph");
    g->detail = glGetUniformLocation(g->prog, "u_chunk_detail");
    g->wrap = glGetUniformLocation(g->prog, "u_detail_wrap");
    g->tile = glGetUniformLocation(g->prog, "u_chunk_tile");
    g->cell = glGetUniformLocation(g->prog, "u_chunk_cell");
    g->frame = 0;
    return g;
}

planet_renderer *planet_renderer_create(const char *resource_dir, GLuint albedo, GLuint falloff,
                                        og_error *err) {
    planet_renderer *r = calloc(1, sizeof *r);
    if (!r) {
        og_error_set(err, "out of memory for the planet renderer");
        return NULL;
    }
    snprintf(r->shader_dir, sizeof r->shader_dir, "%s/shaders", resource_dir);
    // The plain shaded ground now, so a broken shader shows at once; other variants
    // when a chunk first needs them.
    if (ground_variant(r, V_SHADED, err))
        r->prog_sky = shader_program_load(r->shader_dir, "fullscreen.vert", "planet_sky.frag", err);
    if (!r->prog_sky) {
        planet_renderer_destroy(r);
        return NULL;
    }
    r->albedo = albedo;
    r->falloff = falloff;
    albedo_means(r);
    if (!(r->detail = planet_detail_create(err))) {
        planet_renderer_destroy(r);
        return NULL;
    }
    r->ibo = make_indices();
    for (int f = 0; f < 6; f++)
        r->front[f] = face_front(f);
    glCreateVertexArrays(1, &r->vao);
    glCreateVertexArrays(1, &r->empty_vao);
    glVertexArrayElementBuffer(r->vao, r->ibo);
    const int sizes[6] = {3, 3, 3, 1, 2, 4}, offsets[6] = {0, 3, 6, 9, 10, 12};
    for (int a = 0; a < 6; a++) {
        glEnableVertexArrayAttrib(r->vao, a);
        glVertexArrayAttribFormat(r->vao, a, sizes[a], GL_FLOAT, GL_FALSE,
                                  (GLuint)(offsets[a] * sizeof(float)));
        glVertexArrayAttribBinding(r->vao, a, 0);
    }
    glEnableVertexArrayAttrib(r->vao, 6); // the painted weights, as integers
    glVertexArrayAttribIFormat(r->vao, 6, 2, GL_UNSIGNED_INT, (GLuint)(16 * sizeof(float)));
    glVertexArrayAttribBinding(r->vao, 6, 0);
    drop_all(r);
    return r;
}

void planet_renderer_destroy(planet_renderer *r) {
    if (!r) return;
    for (int i = 0; i < MAX_CHUNKS; i++)
        if (r->chunks[i].vbo) glDeleteBuffers(1, &r->chunks[i].vbo);
    if (r->ibo) glDeleteBuffers(1, &r->ibo);
    if (r->vao) glDeleteVertexArrays(1, &r->vao);
    if (r->empty_vao) glDeleteVertexArrays(1, &r->empty_vao);
    for (int v = 0; v < VARIANTS; v++)
        if (r->ground[v].prog) glDeleteProgram(r->ground[v].prog);
    if (r->prog_sky) glDeleteProgram(r->prog_sky);
    planet_detail_destroy(r->detail);
    free(r);
}

// Near the ground the horizon is the ground's own: the sphere under all the ground
// between the camera and its horizon (from the last frame's chunks there, a margin
// below their lowest height) hides what lies past it, instead of a sphere under the
// whole planet's lowest point (whose horizon, a few metres up, is hundreds of km out).
// The horizon distance and the ground it spans depend on each other: a few rounds.
static void tighten_occluder(planet_renderer *r) {
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

int planet_renderer_update(planet_renderer *r, world *w, const camera *cam,
                           const render_settings *s, double aspect, int height_px, og_error *err) {
    r->split_pixels = s->lod_pixels >= 1 ? s->lod_pixels : 6.0; // render lod_pixels=
    r->update_start_ms = now_ms();
    const world_params *p = world_get_params(w);
    if (p->kind != WORLD_PLANET) return og_error_set(err, "planet renderer: not a planet");
    if (r->world != w || memcmp(&r->params, p, sizeof *p) != 0) {
        drop_all(r);
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
    tighten_occluder(r); // from the last frame's chunks
    r->draw_count = 0;
    for (int f = 0; f < 6; f++) {
        node root = {f, r->root_level, 0, 0};
        if (select_node(r, &root)) r->all_current = 0;
    }
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

// Nearest chunks first: the depth test then rejects what they hide before it is shaded
// (a software renderer shades every fragment that passes).
typedef struct draw_key {
    double dist;
    int chunk;
} draw_key;
static int nearer(const void *a, const void *b) {
    double da = ((const draw_key *)a)->dist, db = ((const draw_key *)b)->dist;
    return (da > db) - (da < db);
}
static void sort_near_first(planet_renderer *r) {
    static draw_key keys[MAX_CHUNKS];
    for (int i = 0; i < r->draw_count; i++)
        keys[i] = (draw_key){r->chunks[r->draw_list[i]].near_dist, r->draw_list[i]};
    qsort(keys, (size_t)r->draw_count, sizeof keys[0], nearer);
    for (int i = 0; i < r->draw_count; i++)
        r->draw_list[i] = keys[i].chunk;
}

// ---- occlusion by nearer ground -------------------------------------------------

static node chunk_node(const chunk *c) {
    const uint64_t k = c->key - 1;
    return (node){(int)(k & 7), (int)((k >> 3) & 31), (int64_t)((k >> 8) & ((1ull << 28) - 1)),
                  (int64_t)(k >> 36)};
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
static void choose_shown(planet_renderer *r, const camera *cam, const render_settings *s,
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

// Atmosphere and light uniforms shared by the sky and the ground.
static void set_common(const planet_renderer *r, GLuint prog, const camera *cam,
                       const render_settings *s) {
    const world_params *p = &r->params;
    double cam_r =
        sqrt(cam->pos[0] * cam->pos[0] + cam->pos[1] * cam->pos[1] + cam->pos[2] * cam->pos[2]);
    double e[3], n[3], up[3];
    planet_local_frame(cam->pos, e, n, up);
    float sun[3];
    render_sun_direction(s, sun);
    // Earth's Rayleigh scattering, its scale height scaled with the radius and the
    // coefficients scaled inversely, so any planet's sky is as thick as Earth's.
    const double hs = EARTH_SCALE_HEIGHT * p->radius / EARTH_RADIUS;
    double k = EARTH_SCALE_HEIGHT / hs;
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_radius"), (float)p->radius);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_scale_height"), (float)hs);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_atm_top"), (float)(hs * 10.0));
    k *= p->atmosphere; // 0: no air at all
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_beta"), (float)(5.8e-6 * k),
                       (float)(13.5e-6 * k), (float)(33.1e-6 * k));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_cam_r"), (float)cam_r);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_cam_alt"), (float)(cam_r - p->radius));
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_cam_up"), (float)up[0], (float)up[1],
                       (float)up[2]);
    glProgramUniform3fv(prog, glGetUniformLocation(prog, "u_sun_dir"), 1, sun);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_sun_colour"), 1.05f, 1.0f, 0.95f);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_view_mode"), s->view);
}

// What every ground program gets this frame.
typedef struct ground_frame {
    const camera *cam;
    const render_settings *s;
    float view_proj[16];
    float brush[4], brush_up[3]; // the cursor's centre relative to the camera, radius (0: none)
    float tint[4], ring[3];      // the tool's colours
} ground_frame;

// The brush cursor: its centre relative to the camera, the local up there, the falloff
// curve (uploaded once) and the tool's colours (as the flat viewport draws them).
static void cursor_frame(planet_renderer *r, const brush_cursor *cursor, ground_frame *f) {
    const camera *cam = f->cam;
    memset(f->brush, 0, sizeof f->brush);
    f->brush_up[0] = 0, f->brush_up[1] = 1, f->brush_up[2] = 0;
    if (cursor && cursor->visible && cursor->radius > 0 && !cursor->sphere) {
        const double c[3] = {cursor->x, cursor->y, cursor->z};
        double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        for (int k = 0; k < 3; k++) {
            f->brush[k] = (float)(c[k] - cam->pos[k]);
            f->brush_up[k] = len > 0 ? (float)(c[k] / len) : 0.0f;
        }
        f->brush[3] = (float)cursor->radius;
        glTextureSubImage2D(r->falloff, 0, 0, 0, BRUSH_FALLOFF_SAMPLES, 1, GL_RED, GL_FLOAT,
                            cursor->falloff);
    }
    const float tint[4] = {1.0f, 0.55f, 0.1f, 0.35f}, ring[3] = {1.0f, 0.9f, 0.3f}; // orange
    memcpy(f->tint, tint, sizeof tint);
    memcpy(f->ring, ring, sizeof ring);
    if (cursor && cursor->opacity > 0) {
        for (int i = 0; i < 3; i++)
            f->tint[i] = cursor->color[i], f->ring[i] = 0.65f * cursor->color[i] + 0.35f;
        f->tint[3] = cursor->opacity;
    }
}

// A ground program's uniforms for this frame, once per frame and program.
static void ground_frame_uniforms(planet_renderer *r, GLuint prog, const ground_frame *f) {
    const world_params *p = &r->params;
    const render_settings *s = f->s;
    set_common(r, prog, f->cam, s);
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE,
                              f->view_proj);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_ocean_h"),
                       (float)world_params_ocean_height(p));
    // The material rules' sea level: a planet without a sea (its radius under all the
    // ground) keeps its beaches and snow line where the ground is.
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_ocean_level"),
                       (float)fmax(world_params_ocean_height(p), -p->max_height));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_max_height"), (float)p->max_height);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_palette"),
                       p->atmosphere < 0.05 ? 1 : 2); // used by the BARE variants
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_tex_period"), (float)TEX_PERIOD_NEAR,
                       (float)TEX_PERIOD_FAR);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_albedo"), 0);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_albedo_mean"), MATERIAL_TEXTURE_COUNT,
                        &r->albedo_mean[0][0]);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_brush"), 1, f->brush);
    glProgramUniform3fv(prog, glGetUniformLocation(prog, "u_brush_up"), 1, f->brush_up);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_brush_tint"), 1, f->tint);
    glProgramUniform3fv(prog, glGetUniformLocation(prog, "u_brush_ring"), 1, f->ring);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_falloff"), 1);
    planet_detail_bind(r->detail, prog, s, 2, 3);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_overlays"),
                       (s->tile_grid ? 1 : 0) | (s->level_grid ? 2 : 0));
}

// The variant a chunk is drawn with: only what it can show this frame.
static int chunk_variant(const planet_renderer *r, const chunk *c, const ground_frame *f,
                         const float detail[4]) {
    const render_settings *s = f->s;
    if (s->view == VIEW_WIREFRAME) return 0;
    const double ocean = world_params_ocean_height(&r->params);
    const int has_sea = ocean > -r->params.max_height;
    double to_chunk = 0; // metres from the camera to the chunk's origin
    for (int k = 0; k < 3; k++)
        to_chunk += (c->origin[k] - f->cam->pos[k]) * (c->origin[k] - f->cam->pos[k]);
    to_chunk = sqrt(to_chunk);
    // Detail where it shows: the detail window covers the chunk, holds some detail
    // there (it is zero until edited) and some of the chunk is nearer than the
    // detail's fade-out distance.
    int v = detail[3] > 0 && to_chunk - c->reach < s->detail_distance ? V_DETAIL : 0;
    if (s->tile_grid || s->level_grid) v |= V_OVERLAYS;
    if (f->brush[3] > 0) { // the cursor reaches the chunk (raised to the sea where under it)
        double d2 = 0;
        for (int k = 0; k < 3; k++) {
            double dk = c->origin[k] - f->cam->pos[k] - f->brush[k];
            d2 += dk * dk;
        }
        double reach = c->reach + fmax(ocean - c->lowest, 0.0) + 1.1 * f->brush[3];
        if (d2 < reach * reach) v |= V_BRUSH;
    }
    if (s->view != VIEW_SHADED) return v;
    v |= V_SHADED;
    // Far enough that the material textures' near scale is smaller than a pixel all
    // over the chunk: every lookup would return the texture's 1 x 1 level. A pixel's
    // footprint shrinks toward the screen's corners and filtering measures it roughly,
    // hence the factor 4.
    const double nearest =
        to_chunk - c->reach - skirt_depth(r, c->level) - fmax(ocean - c->lowest, 0.0);
    if (!(v & V_DETAIL) && r->has_albedo_mean &&
        nearest > 4.0 * TEX_PERIOD_NEAR * r->pixels_per_radian)
        v |= V_MINIFIED;
    if (!has_sea)
        v |= V_BARE;
    else if (c->lowest < ocean)
        v |= V_SEA;
    if (c->painted) v |= V_PAINTED;
    return v;
}

// Space, the sun and the sky, drawn after the ground where nothing was drawn: the
// fullscreen triangle lies on the far plane (depth 0) and passes only where the depth
// buffer still holds its clear value, so ground pixels never run the sky's integral.
static void draw_sky(planet_renderer *r, const camera *cam, const render_settings *s,
                     double aspect) {
    double f[3], rt[3], up[3];
    planet_camera_basis(cam, f, rt, up);
    GLuint prog = r->prog_sky;
    set_common(r, prog, cam, s);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_cam_forward"), (float)f[0], (float)f[1],
                       (float)f[2]);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_cam_right"), (float)rt[0], (float)rt[1],
                       (float)rt[2]);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_cam_upv"), (float)up[0], (float)up[1],
                       (float)up[2]);
    double ty = tan((cam->fov_y >= 1 && cam->fov_y <= 170 ? cam->fov_y : 60) * M_PI / 360.0);
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_tan_half"), (float)(ty * aspect),
                       (float)ty);
    glUseProgram(prog);
    glBindVertexArray(r->empty_vao);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_GEQUAL);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    r->stats.draw_calls++;
}

// The index ranges to draw for a chunk: its grid, and the skirts the camera can see the
// front of. A skirt hangs straight down from its edge, which lies on a great circle,
// so the whole skirt lies in that circle's plane through the centre and shows its front
// (it faces away from its chunk) only to a camera on the outer side of that plane; the
// others would all be culled as back faces, after their vertices were shaded.
static int index_ranges(const chunk *c, const camera *cam, int all_skirts, GLsizei counts[5],
                        const void *offsets[5]) {
    enum { GRID = BLOCK * BLOCK * 6, EDGE = BLOCK * 6 };
    counts[0] = GRID, offsets[0] = NULL;
    int n = 1;
    const double(*dir)[3] = c->corner_dir;
    // Edges 0-3 (make_indices): t = t0, t = t1, s = s0, s = s1; their corners and a
    // corner across the chunk from them.
    static const int ends[4][3] = {{0, 1, 2}, {2, 3, 0}, {0, 2, 1}, {1, 3, 0}};
    for (int e = 0; e < 4; e++) {
        const double *a = dir[ends[e][0]], *b = dir[ends[e][1]], *across = dir[ends[e][2]];
        double plane[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                           a[0] * b[1] - a[1] * b[0]};
        const double inward = plane[0] * across[0] + plane[1] * across[1] + plane[2] * across[2];
        const double camera_side =
            plane[0] * cam->pos[0] + plane[1] * cam->pos[1] + plane[2] * cam->pos[2];
        if (all_skirts || (inward > 0 ? camera_side <= 0 : camera_side >= 0)) {
            counts[n] = EDGE;
            offsets[n] = (const void *)(uintptr_t)((GRID + e * EDGE) * sizeof(uint16_t));
            n++;
        }
    }
    return n;
}

// What stays bound from one chunk's draw to the next.
typedef struct chunk_pass {
    ground_frame *f;
    int all_skirts;
    ground_program *g;
    int variant, window; // bound (-1: none yet)
} chunk_pass;

// Draws shown chunk i, switching the program where the variant changes.
static int draw_chunk(planet_renderer *r, int i, chunk_pass *p, og_error *err) {
    const chunk_look *l = &r->looks[i];
    const int v = l->variant;
    const camera *cam = p->f->cam;
    const render_settings *s = p->f->s;
    if (v != p->variant) {
        p->variant = v;
        if (!(p->g = ground_variant(r, v, err))) return -1;
        if (p->g->frame != r->frame) {
            ground_frame_uniforms(r, p->g->prog, p->f);
            p->g->frame = r->frame;
        }
        glUseProgram(p->g->prog);
    }
    ground_program *g = p->g;
    const chunk *c = &r->chunks[r->shown[i]];
    glProgramUniform3f(g->prog, g->offset, (float)(c->origin[0] - cam->pos[0]),
                       (float)(c->origin[1] - cam->pos[1]), (float)(c->origin[2] - cam->pos[2]));
    glProgramUniform1i(g->prog, g->level, c->level);
    glProgramUniform4fv(g->prog, g->detail, 1, l->detail);
    if (v & V_DETAIL) { // the window of the chunk's face
        if (l->window != p->window) planet_detail_use(r->detail, p->window = l->window, 2, 3);
        glProgramUniform2fv(g->prog, g->wrap, 1, l->wrap);
    }
    if (v & V_OVERLAYS) { // where the chunk's metres meet the grids
        const double tile = TILE_SIZE * r->cell_arc, cell = ldexp(r->cell_arc, c->level);
        glProgramUniform3f(g->prog, g->tile, (float)fmod(c->metres_base[0], tile),
                           (float)fmod(c->metres_base[1], tile), (float)tile);
        glProgramUniform3f(g->prog, g->cell, (float)fmod(c->metres_base[0], cell),
                           (float)fmod(c->metres_base[1], cell), (float)cell);
    }
    // Fully the parent's mesh where the parent would be drawn instead: at the
    // distance its samples shrink to split_pixels. (The haze is measured to the
    // sphere through each fragment's height, not along the morphed chords, so
    // coarse quads do not show in it.)
    const int morph = s->morph && c->level < r->root_level;
    glProgramUniform1f(g->prog, g->morph, morph ? (float)(1.0 / c->morph_reach) : 0.0f);
    glFrontFace(r->front[chunk_face(c)]);
    glVertexArrayVertexBuffer(r->vao, 0, c->vbo, 0, VERTEX_FLOATS * sizeof(float));
    GLsizei counts[5];
    const void *offsets[5];
    const int ranges = index_ranges(c, cam, p->all_skirts, counts, offsets);
    glMultiDrawElements(GL_TRIANGLES, counts, GL_UNSIGNED_SHORT, offsets, ranges);
    for (int k = 0; k < ranges; k++)
        r->stats.triangles += (uint64_t)counts[k] / 3;
    r->stats.draw_calls++;
    return 0;
}

int planet_renderer_draw(planet_renderer *r, const camera *cam, const render_settings *s,
                         const brush_cursor *cursor, int width, int height, og_error *err) {
    double t0 = now_ms();
    double aspect = (double)width / (double)(height > 0 ? height : 1);
    ground_frame f = {.cam = cam, .s = s};
    planet_camera_view_projection(cam, aspect, f.view_proj);
    glViewport(0, 0, width, height);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glClearDepth(0.0);
    const int wire = s->view == VIEW_WIREFRAME;
    // Back faces cost llvmpipe as much as the ground: the skirts seen from inside their
    // chunks, slopes facing away, the ground past the horizon. The wireframe shows all,
    // and under the sea its surface is seen from below.
    const int under_sea = r->camera_altitude < world_params_ocean_height(&r->params);
    if (wire || under_sea)
        glDisable(GL_CULL_FACE);
    else
        glEnable(GL_CULL_FACE), glCullFace(GL_BACK);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    r->stats.triangles = 0;
    r->stats.draw_calls = 0;
    cursor_frame(r, cursor, &f);
    glBindTextureUnit(0, r->albedo);
    glBindTextureUnit(1, r->falloff);
    sort_near_first(r);
    choose_shown(r, cam, s, aspect);
    // Each chunk's variant and detail window, the nearest chunk first.
    for (int i = 0; i < r->shown_count; i++) {
        const chunk *c = &r->chunks[r->shown[i]];
        chunk_look *l = &r->looks[i];
        l->window = (signed char)planet_detail_chunk(r->detail, chunk_face(c), c->level,
                                                     c->metres_lo, c->metres_hi, c->metres_base[0],
                                                     c->metres_base[1], l->detail, l->wrap);
        l->variant = (unsigned char)chunk_variant(r, c, &f, l->detail);
    }
    glBindVertexArray(r->vao);
    if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    chunk_pass pass = {.f = &f, .all_skirts = wire || under_sea, .variant = -1, .window = -1};
    int rc = 0;
    for (int i = 0; i < r->shown_count && rc == 0; i++)
        rc = draw_chunk(r, i, &pass, err);
    if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    if (!wire && rc == 0) draw_sky(r, cam, s, aspect);
    r->stats.chunks_drawn = r->shown_count;
    r->stats.chunks_occluded = r->draw_count - r->shown_count;
    glBindVertexArray(0);
    glUseProgram(0);
    r->stats.cpu_ms += now_ms() - t0;
    if (rc < 0) return -1;
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return og_error_set(err, "planet_renderer_draw: GL error 0x%x", e);
    return 0;
}

void planet_renderer_forget(planet_renderer *r) {
    drop_all(r);
    planet_detail_forget(r->detail);
}

void planet_renderer_detail_touched(planet_renderer *r, tile_cache *cache, int face,
                                    grid_rect rect) {
    planet_detail_touched(r->detail, cache, face, rect);
}

void planet_renderer_touched(planet_renderer *r, int face, grid_rect rect) {
    for (int i = 0; i < MAX_CHUNKS; i++) {
        chunk *c = &r->chunks[i];
        if (!c->key) continue;
        uint64_t k = c->key - 1;
        int cf = (int)(k & 7), level = (int)((k >> 3) & 31);
        int64_t bx = (int64_t)((k >> 8) & ((1u << 28) - 1)), by = (int64_t)(k >> 36);
        if (cf != face) continue;
        // The level-0 cells the chunk's vertices interpolate from, a sample's margin
        // around (mips are box filtered; vertices blend neighbouring samples).
        const int64_t cell = (int64_t)1 << level;
        const int64_t x0 = (bx * BLOCK - 1) * cell, x1 = ((bx + 1) * BLOCK + 1) * cell;
        const int64_t z0 = (by * BLOCK - 1) * cell, z1 = ((by + 1) * BLOCK + 1) * cell;
        if (rect.x1 <= x0 || rect.x0 >= x1 || rect.z1 <= z0 || rect.z0 >= z1) continue;
        table_remove(r, c->key);
        c->key = 0;
        r->resident--;
    }
}

void planet_renderer_stats(const planet_renderer *r, planet_stats *out) {
    *out = r->stats;
}
