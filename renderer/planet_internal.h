// The planet renderer's insides, shared by its files (planet_renderer.h is the outside):
// the chunk table (planet_chunk_table.c), LOD selection (planet_lod.c), culling and
// occlusion (planet_culling.c), chunk meshes and their uploads (planet_uploads.c),
// drawing the ground (planet_draw.c), and the sky and the light (planet_sky.c).
#ifndef OROGEN_RENDERER_PLANET_INTERNAL_H
#define OROGEN_RENDERER_PLANET_INTERNAL_H

#include "editor/layers/material_rules.h"
#include "editor/params/world_grid.h"
#include "editor/world/world.h"
#include "io/err.h"
#include "renderer/camera.h"
#include "renderer/frustum.h"
#include "renderer/ground_horizon.h"
#include "renderer/ground_occlusion.h"
#include "renderer/material_textures.h"
#include "renderer/planet_detail.h"
#include "renderer/planet_stats.h"
#include "renderer/render_settings.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdint.h>
#include <time.h>

// planet_renderer.h's handle, whose insides these are.
typedef struct planet_renderer planet_renderer;

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
// Then the 8 painted material weights (uint8 each, packed in two 32-bit slots), and near
// a face's edge the (up to two) neighbouring faces' texture metres and weights
// (planet_face_blend.c).
#define VERTEX_FLOATS 24
#define BLEND_FLOAT0 18
#define MAX_CHUNKS 3072 // resident meshes (~80 MB): several views' worth
#define TABLE_SIZE 8192 // open addressing, power of two, > 2 x MAX_CHUNKS
#define BUILD_BUDGET_MS 10.0
#define TEX_PERIOD_NEAR 4.0    // metres per repeat of the material textures
#define TEX_PERIOD_FAR 64.0    // the larger scale that breaks up repetition (a multiple)
#define EARTH_RADIUS 6371000.0 // the atmosphere scales with the planet from Earth's
#define EARTH_SCALE_HEIGHT 8000.0
// Shading normals come from the heights this many levels finer than a chunk's own
// (planet_normals.c): its samples then lie 6 / 2^2 = 1.5 pixels apart on the screen.
#define NORMAL_FINER 2
#define NORMAL_TEXELS ((BLOCK << NORMAL_FINER) + 2) // a side: the samples and one past each end
// Slopes measured over samples 2^L cells apart are gentler than the level-0 samples' by
// about 2^(-L x this) on the planet generator's ranges and hills (tests/test_planet_look.c
// measures it): the material rules scale them back, so ranges are rock from orbit too.
#define SLOPE_SCALE_EXPONENT 0.3
#define NORMAL_ATLAS 8  // chunks' textures per side of a layer (GL allows 2048 layers, not 3072)
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
    int blended;      // how many other faces' textures it blends in (planet_face_blend)
    int level;
    signed char normal_level;        // the level its normal texture was made from (-1: none yet)
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
    unsigned short variant;
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
    V_SEAM = 256,
    V_RULES = 512,
    VARIANTS = 1024
};

typedef struct ground_program {
    GLuint prog;
    GLint offset, level, morph, detail, wrap, tile, cell; // the per-chunk uniforms
    GLint normal_map, face_axis, slope_scale, face_edges;
    uint64_t frame; // its frame uniforms were set for
} ground_program;

typedef struct node {
    int face, level;
    int64_t bx, by;
} node;

struct planet_renderer {
    char shader_dir[4200];
    ground_program ground[VARIANTS]; // built when first needed
    GLuint prog_sky, vao, empty_vao, ibo, albedo, falloff;
    GLuint normals;         // the chunks' normal textures, a layer per chunk slot
    double face_axis[6][3]; // each face's s axis on the cube (the normals' tangent frame)
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
    material_rules_resolved rules; // this frame: the world's material rules (V_RULES)
    // Drawing: the chosen chunks nearest first, those hidden by nearer ground left out.
    int shown_count;
    int shown[MAX_CHUNKS];
    chunk_look looks[MAX_CHUNKS]; // of shown[i]
    ground_occlusion occlusion;
    ground_horizon horizon;
    planet_stats stats;
};

typedef struct node_bounds {
    double centre[3], radius; // bounding sphere, planet coordinates
    double cell;              // metres per sample at this level
    double hmin, hmax;        // metres above the datum (the generator's range when unbuilt)
} node_bounds;

static inline double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

static inline uint64_t node_key(const node *n) {
    return ((uint64_t)n->face | (uint64_t)n->level << 3 | (uint64_t)n->bx << 8 |
            (uint64_t)n->by << 36) +
           1;
}

static inline int chunk_face(const chunk *c) {
    return (int)((c->key - 1) & 7);
}

static inline node chunk_node(const chunk *c) {
    const uint64_t k = c->key - 1;
    return (node){(int)(k & 7), (int)((k >> 3) & 31), (int64_t)((k >> 8) & ((1ull << 28) - 1)),
                  (int64_t)(k >> 36)};
}

// Level-L samples per face side (the last one may reach past the face's edge).
static inline int64_t level_samples(const planet_renderer *r, int level) {
    return (r->face_samples + ((int64_t)1 << level) - 1) >> level;
}

static inline int node_exists(const planet_renderer *r, const node *n) {
    int64_t m = level_samples(r, n->level);
    return n->bx >= 0 && n->by >= 0 && n->bx * BLOCK < m && n->by * BLOCK < m;
}

// Face coordinate of level-L cell edge e (clipped to the face).
static inline double edge_coord(const planet_renderer *r, int level, int64_t e) {
    int64_t cells = e < 0 ? 0 : e << level;
    if (cells > r->face_samples) cells = r->face_samples;
    return (double)cells / (double)r->face_samples * 2.0 - 1.0;
}

static inline void surface_point(const planet_renderer *r, int face, double s, double t, double h,
                                 double out[3]) {
    double d[3];
    world_grid_face_direction(face, s, t, d);
    for (int k = 0; k < 3; k++)
        out[k] = d[k] * (r->params.radius + h);
}

// Near the ground: within 1% of the radius (the occluder and the grazing judgement).
static inline int near_ground(const planet_renderer *r) {
    return r->camera_altitude < 0.01 * r->params.radius;
}

// How far a chunk's skirts hang: enough to hide the cracks between levels and faces (a
// level's samples differ from the next one's by about a cell on gentle ground; on the
// planet generator's ridged crests, steeper than 1 in 1, by up to two).
static inline double skirt_depth(const planet_renderer *r, int level) {
    return fmin(2.0 * ldexp(r->cell_arc, level), 2.0 * r->params.max_height) + 0.25 * r->cell_arc;
}

static inline double dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// How far a level's drawn triangles can lie under their corners: the sag of chords as
// long as a parent cell's diagonal, and the vertices' float precision.
static inline double chord_sag(const planet_renderer *r, int level) {
    const double cell = ldexp(r->cell_arc, level);
    return cell * cell / r->params.radius + 1e-6 * BLOCK * cell + 0.01;
}

// The chunk table (planet_chunk_table.c): chunks by node key, open addressing.
chunk *planet_find_chunk(planet_renderer *r, uint64_t key);
void planet_table_insert(planet_renderer *r, int index);
void planet_table_remove(planet_renderer *r, uint64_t key);
void planet_drop_all(planet_renderer *r);
// A free chunk slot, evicting the least recently selected chunk not used this frame.
int planet_take_slot(planet_renderer *r);

// Culling (planet_culling.c).
// Returns 1 when the node is visible (not behind the horizon, in the view), its bounds in b.
int planet_node_visible(planet_renderer *r, const node *n, double hmin, double hmax,
                        node_bounds *b);
// Raises the occluder sphere near the ground from the last frame's chunks.
void planet_tighten_occluder(planet_renderer *r);
// The chunks to draw (r->shown), nearest first, those hidden by nearer ground left out.
void planet_choose_shown(planet_renderer *r, const camera *cam, const render_settings *s,
                         double aspect);

// Chunk meshes (planet_uploads.c): builds and uploads the node's chunk when its tile is
// resident and the frame's budget allows.
chunk *planet_try_build(planet_renderer *r, const node *n);

// Shading normals finer than the mesh (planet_normals.c): the texture array, a chunk's
// layer made from the finest resident level down to NORMAL_FINER below its own, and made
// again for drawn chunks once that level's tiles are there (within the frame's budget;
// all_current stays 0 until then).
int planet_normals_create(planet_renderer *r, og_error *err);
void planet_normals_build(planet_renderer *r, chunk *c, const node *n);
void planet_normals_refine(planet_renderer *r);
// A chunk slot's place in the texture array: its layer and first texel there.
void planet_normals_place(int slot, int *layer, int *x, int *y);

// Where faces meet (planet_face_edges.c): the level's height at a direction on a face's
// edge or corner (the mean of the faces there) or past it (the neighbouring face's).
// 1 when read, 0 while a tile is pending.
int planet_edge_height(planet_renderer *r, int level, const double dir[3], float *out);
// The bilinear height at sample coordinates (u, v) of a face's level (clamped to the
// face), from whichever tiles hold them. 1 when read, 0 while a tile is pending.
int planet_face_height(planet_renderer *r, int face, int level, double u, double v, float *out);
// The ground's normal at unit direction dir on a face's edge, the same from every face
// there (planet_face_edges.c). 1 when made, 0 while a tile is pending.
int planet_edge_normal(planet_renderer *r, int level, const double dir[3], double normal[3]);
// Fills the grid vertices' blend floats (BLEND_FLOAT0 on) of a chunk of `face` whose
// vertex coordinates are s, t (the ring's, RING long) and positions pos (ring x ring,
// 3 doubles each); returns how many other faces it blends in.
int planet_face_blend(const planet_renderer *r, int face, const double s[], const double t[],
                      const double *pos, int ring, float *out);

// Drawing (planet_draw.c): the ground program for a variant (V_* bits), built on first use.
ground_program *planet_ground_variant(planet_renderer *r, int variant, og_error *err);

// The sky and the light (planet_sky.c).
void planet_set_common(const planet_renderer *r, GLuint prog, const camera *cam,
                       const render_settings *s);
void planet_draw_sky(planet_renderer *r, const camera *cam, const render_settings *s,
                     double aspect);

#endif
