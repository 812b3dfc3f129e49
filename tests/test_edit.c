// The editing engine: every tool's tiled path equals its plain-array reference bit
// for bit (tile seams, world edges, unbounded worlds), edits out of core, exact undo
// and redo on every layer, history budget, per-tool invariants, hostile input, the
// detail PD map, mip upkeep, unsaved-change tracking, dirty rectangles and planets.
#include "editor/tools/brush.h"
#include "editor/tools/brush_dab.h"
#include "editor/cmd/commands.h"
#include "editor/edit/detail_pd.h"
#include "editor/edit/edit.h"
#include "editor/edit/edit_commit.h"
#include "editor/edit/edit_mips.h"
#include "editor/edit/material_mips_fill.h"
#include "editor/world/history.h"
#include "editor/world/layer_grid.h"
#include "editor/tools/stroke.h"
#include "editor/tools/volume_brush.h"
#include "editor/world/world.h"
#include "editor/params/world_grid.h"
#include "io/tile_cache.h"
#include "renderer/camera.h"
#include "renderer/viewport.h"
#include "io/tile_store.h"
#include "support/test_support.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zstd.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

// ---------------------------------------------------------------------------
// Worlds, reading and hashing
// ---------------------------------------------------------------------------

static void silent(void *user, const char *m) {
    (void)user, (void)m;
}

// Collects warnings (the history reports dropped steps through them).
typedef struct warn_log {
    pthread_mutex_t lock;
    int count;
    int mentions_dropped;
    char last[512];
} warn_log;

static void log_warn(void *user, const char *m) {
    warn_log *l = user;
    pthread_mutex_lock(&l->lock);
    l->count++;
    if (strstr(m, "dropped")) l->mentions_dropped++;
    snprintf(l->last, sizeof l->last, "%s", m);
    pthread_mutex_unlock(&l->lock);
}

static uint64_t rng_next(uint64_t *s) { // splitmix64
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double rng_uniform(uint64_t *s, double lo, double hi) {
    return lo + (hi - lo) * (double)(rng_next(s) >> 11) * (1.0 / 9007199254740992.0);
}

// Hilly terrain at brush scale (slopes up to a few units), cheap to generate.
static world_params flat_params(int64_t size, double spacing) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.generator = GEN_FBM;
    p.seed = 9001;
    p.octaves = 4;
    p.size = size;
    p.spacing = spacing;
    p.feature_size = 256.0 * spacing;
    p.max_height = 200;
    return p;
}

static world *open_world_with(const world_params *p, size_t cache_bytes, size_t history_bytes,
                              warn_log *log) {
    world_settings s = {.cache_budget_bytes = cache_bytes,
                        .history_budget_bytes = history_bytes,
                        .workers = 2,
                        .warn = log ? log_warn : silent,
                        .warn_user = log};
    og_error err;
    world *w = world_create(p, &s, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    return w;
}

static world *open_world(const world_params *p) {
    return open_world_with(p, (size_t)256 << 20, 0, NULL);
}

static layer_grid grid_of(world *w, tile_layer layer, int face) {
    layer_grid g;
    og_error err;
    if (layer_grid_init(&g, world_get_params(w), layer, face, &err) != 0)
        fail_msg("layer_grid_init: %s", err.msg);
    return g;
}

static size_t sample_bytes(tile_layer layer) {
    return tile_layer_bytes(layer) / TILE_SAMPLES;
}

static size_t rect_samples(grid_rect r) {
    return (size_t)((r.x1 - r.x0) * (r.z1 - r.z0));
}

// The stored samples of r (which must lie inside the world), row-major, any layer
// and level, straight from the tiles.
static void read_tiles(world *w, tile_layer layer, int face, int level, grid_rect r, void *out) {
    size_t el = sample_bytes(layer);
    int64_t width = r.x1 - r.x0;
    tile_cache *c = world_cache(w);
    for (int64_t tz = world_grid_floor_div(r.z0, TILE_SIZE);
         tz <= world_grid_floor_div(r.z1 - 1, TILE_SIZE); tz++)
        for (int64_t tx = world_grid_floor_div(r.x0, TILE_SIZE);
             tx <= world_grid_floor_div(r.x1 - 1, TILE_SIZE); tx++) {
            tile_key key = {layer, face, level, (int32_t)tx, (int32_t)tz};
            tile_view v;
            og_error err;
            if (tile_cache_acquire(c, key, &v, &err) != 0) fail_msg("acquire: %s", err.msg);
            grid_rect t =
                grid_rect_intersect(r, (grid_rect){tx * TILE_SIZE, tz * TILE_SIZE,
                                                   (tx + 1) * TILE_SIZE, (tz + 1) * TILE_SIZE});
            for (int64_t z = t.z0; z < t.z1; z++)
                memcpy((char *)out + ((z - r.z0) * width + (t.x0 - r.x0)) * el,
                       (const char *)v.data +
                           ((z - tz * TILE_SIZE) * TILE_SIZE + (t.x0 - tx * TILE_SIZE)) * el,
                       (size_t)(t.x1 - t.x0) * el);
            tile_cache_release(c, &v);
        }
}

static void *read_area(world *w, tile_layer layer, int face, int level, grid_rect r) {
    void *out = malloc(rect_samples(r) * sample_bytes(layer));
    assert_non_null(out);
    read_tiles(w, layer, face, level, r, out);
    return out;
}

// FNV-1a over 32-bit words (every layer's samples are a multiple of 4 bytes).
static uint64_t fnv_words(const void *data, size_t bytes) {
    assert_int_equal(bytes % 4, 0);
    const uint8_t *b = data;
    uint64_t h = 0xcbf29ce484222325ULL;
    for (size_t i = 0; i < bytes; i += 4) {
        uint32_t v;
        memcpy(&v, b + i, 4);
        h ^= v;
        h *= 0x100000001b3ULL;
    }
    return h;
}

// Digest of a layer's level-0 bytes over r.
static uint64_t layer_hash(world *w, tile_layer layer, int face, grid_rect r) {
    void *a = read_area(w, layer, face, 0, r);
    uint64_t h = fnv_words(a, rect_samples(r) * sample_bytes(layer));
    free(a);
    return h;
}

// world_hash over the samples of r (level 0, coarse).
static uint64_t coarse_hash(world *w, int face, grid_rect r) {
    double sp = world_grid_sample_metres(world_get_params(w)); // true metres on a planet
    uint64_t digest, count;
    og_error err;
    if (world_hash(w, face, (double)r.x0 * sp, (double)r.z0 * sp, (double)(r.x1 - 1) * sp,
                   (double)(r.z1 - 1) * sp, &digest, &count, &err) != 0)
        fail_msg("world_hash: %s", err.msg);
    assert_int_equal(count, rect_samples(r));
    return digest;
}

static grid_rect whole(world *w, tile_layer layer) {
    layer_grid g = grid_of(w, layer, 0);
    assert_true(g.extent > 0);
    return (grid_rect){0, 0, g.extent, g.extent};
}

// Fails naming the first differing sample.
static void expect_same_samples(const void *want, const void *got, grid_rect r, tile_layer layer,
                                const char *what) {
    size_t el = sample_bytes(layer), n = rect_samples(r);
    if (memcmp(want, got, n * el) == 0) return;
    int64_t width = r.x1 - r.x0;
    for (size_t i = 0; i < n; i++) {
        if (memcmp((const char *)want + i * el, (const char *)got + i * el, el) == 0) continue;
        int64_t x = r.x0 + (int64_t)i % width, z = r.z0 + (int64_t)i / width;
        if (layer == TILE_LAYER_MATERIAL) {
            const uint8_t *a = (const uint8_t *)want + i * el, *b = (const uint8_t *)got + i * el;
            fail_msg("%s: sample (%lld, %lld) differs: reference %u %u %u %u %u %u %u %u, tiles %u "
                     "%u %u %u %u %u %u %u",
                     what, (long long)x, (long long)z, a[0], a[1], a[2], a[3], a[4], a[5], a[6],
                     a[7], b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]);
        }
        float a, b;
        memcpy(&a, (const char *)want + i * el, 4);
        memcpy(&b, (const char *)got + i * el, 4);
        fail_msg("%s: sample (%lld, %lld) differs: reference %.9g, tiles %.9g", what, (long long)x,
                 (long long)z, (double)a, (double)b);
    }
}

// One dab as its own edit (one undo step).
static void dab_world(world *w, const layer_grid *g, const brush_dab *d) {
    og_error err;
    edit *e = edit_begin(w, "test dab", &err);
    assert_non_null(e);
    if (brush_dab_apply(e, g, d, &err) != 0) {
        edit_abort(e);
        fail_msg("brush_dab_apply: %s", err.msg);
    }
    if (edit_commit(e, &err) != 0) fail_msg("edit_commit: %s", err.msg);
}

// A stroke through the given points (metres), pressure 1.
static void stroke_world(world *w, const brush *b, const double *xz, int points) {
    og_error err;
    stroke *s = stroke_begin(w, b, &err);
    if (!s) fail_msg("stroke_begin: %s", err.msg);
    for (int i = 0; i < points; i++)
        if (stroke_to(s, xz[2 * i], xz[2 * i + 1], 1.0, &err) != 0) {
            stroke_cancel(s);
            fail_msg("stroke_to: %s", err.msg);
        }
    if (stroke_end(s, &err) != 0) fail_msg("stroke_end: %s", err.msg);
}

static void dab_at(world *w, const brush *b, double x, double z) {
    double xz[2] = {x, z};
    stroke_world(w, b, xz, 1);
}

static void undo(world *w) {
    og_error err;
    int rc = edit_undo(w, &err);
    if (rc < 0) fail_msg("edit_undo: %s", err.msg);
    assert_int_equal(rc, 1);
}

static void redo(world *w) {
    og_error err;
    int rc = edit_redo(w, &err);
    if (rc < 0) fail_msg("edit_redo: %s", err.msg);
    assert_int_equal(rc, 1);
}

// ---------------------------------------------------------------------------
// 1. Seams: the tiled path against the plain-array reference
// ---------------------------------------------------------------------------

static const brush_tool all_tools[] = {BRUSH_RAISE,   BRUSH_RAISE,     BRUSH_SMOOTH, BRUSH_FLATTEN,
                                       BRUSH_SET,     BRUSH_RAMP,      BRUSH_NOISE,  BRUSH_TERRACE,
                                       BRUSH_THERMAL, BRUSH_HYDRAULIC, BRUSH_PAINT,  BRUSH_SMOOTH};
#define TOOL_CASES (sizeof all_tools / sizeof all_tools[0])

// A brush for case i of all_tools (case 1 is lower: raise inverted), with a falloff
// that varies from case to case so every falloff's weights cross the seams; the last
// case is smooth with the smooth falloff (its weights computed row by row as it blends).
static void seam_brush(brush *b, size_t i) {
    brush_defaults(b, all_tools[i]);
    b->invert = i == 1;
    b->strength = 0.8;
    b->falloff = i == TOOL_CASES - 1 ? FALLOFF_SMOOTH : (brush_falloff)(i % FALLOFF_CURVE);
    if (all_tools[i] == BRUSH_TERRACE) {
        og_error err;
        assert_int_equal(brush_set(b, "curve", "0:1,0.4:0.8,0.7:0.3,1:0", &err), 0);
    }
    b->amount = 7.5;
    b->has_height = all_tools[i] == BRUSH_SET || all_tools[i] == BRUSH_FLATTEN;
    b->height = all_tools[i] == BRUSH_SET ? -15.0 : 20.0;
    b->noise_scale = 23.0;
    b->terrace_step = 6.0;
    b->thermal.iterations = 6;
    b->thermal.talus_deg = 30.0f;
    b->hydraulic.droplets = 300;
    b->material = 3;
}

static brush_dab seam_dab(const brush *b, const layer_grid *g, double cx, double cz, double r,
                          uint64_t seed) {
    brush_dab d = {.brush = b,
                   .cx = cx,
                   .cz = cz,
                   .radius = r,
                   .strength = (float)b->strength,
                   .spacing = g->spacing,
                   .target = (float)b->height,
                   .seed = seed};
    if (b->tool == BRUSH_RAMP) {
        d.ax = cx - 0.6 * r, d.az = cz - 0.3 * r;
        d.bx = cx + 0.7 * r, d.bz = cz + 0.4 * r;
        d.ha = 5.0f, d.hb = 60.0f;
    }
    return d;
}

// Applies the dab to the world within edit e and to ref (the samples of area), then
// compares area (the edit's tiles are read as they are now, before its commit).
// start: ref's samples as the edit began (paint measures a stroke's coverage from it).
static void dab_both(edit *e, const layer_grid *g, const brush_dab *d, void *ref, const void *start,
                     grid_rect area, const char *what) {
    og_error err;
    if (brush_dab_apply_array_since(d, g->layer, ref, start, area, &err) != 0)
        fail_msg("%s: brush_dab_apply_array: %s", what, err.msg);
    if (brush_dab_apply(e, g, d, &err) != 0) fail_msg("%s: brush_dab_apply: %s", what, err.msg);
    void *got = read_area(edit_world(e), g->layer, g->face, 0, area);
    expect_same_samples(ref, got, area, g->layer, what);
    free(got);
}

typedef struct dab_place {
    double cx, cz, r; // samples
} dab_place;

// Bounded world: straddling tile corners, on the edge and corner (clamping), and a
// radius covering many tiles; the whole layer is compared after every dab.
static void seams_bounded(tile_layer layer, const brush_tool *only, size_t only_count) {
    // Detail: a 300-sample world is 1197 detail samples, 5 x 5 detail tiles.
    world_params p = flat_params(layer == TILE_LAYER_DETAIL ? 300 : 700, 1.0);
    world *w = open_world(&p);
    layer_grid g = grid_of(w, layer, 0);
    double e = (double)g.extent - 1, mid = e / 2;
    const dab_place places[] = {
        {256, 256, 40}, {512, 255, 37}, {0, 0, 30}, {e, mid, 30}, {e, e, 25}, {mid, mid, 200},
    };
    if (layer == TILE_LAYER_DETAIL) { // give the (zero) detail layer some relief first
        brush nb;
        brush_defaults(&nb, BRUSH_NOISE);
        nb.target = TILE_LAYER_DETAIL;
        nb.amount = 3.0;
        nb.noise_scale = 7.0;
        nb.noise_octaves = 2;
        nb.falloff = FALLOFF_CONSTANT;
        nb.strength = 1.0;
        brush_dab d = seam_dab(&nb, &g, g.extent / 2, g.extent / 2, g.extent, 0);
        dab_world(w, &g, &d);
    }
    grid_rect area = {0, 0, g.extent, g.extent};
    void *ref = read_area(w, layer, 0, 0, area);
    uint64_t seed = 1;
    for (size_t i = 0; i < TOOL_CASES; i++) {
        int wanted = only_count == 0;
        for (size_t o = 0; o < only_count; o++)
            wanted |= only[o] == all_tools[i];
        if (!wanted || (all_tools[i] == BRUSH_PAINT) != (layer == TILE_LAYER_MATERIAL)) continue;
        brush b;
        seam_brush(&b, i);
        og_error err;
        edit *e = edit_begin(w, brush_tool_name(b.tool), &err); // one step per tool
        assert_non_null(e);
        void *start = read_area(w, layer, 0, 0, area);
        for (size_t q = 0; q < sizeof places / sizeof places[0]; q++) {
            brush_dab d = seam_dab(&b, &g, places[q].cx, places[q].cz, places[q].r, seed++);
            char what[128];
            snprintf(what, sizeof what, "%s%s on %s at (%g, %g) r=%g", b.invert ? "inverted " : "",
                     brush_tool_name(b.tool), tile_layer_name(layer), d.cx, d.cz, d.radius);
            dab_both(e, &g, &d, ref, start, area, what);
        }
        free(start);
        if (edit_commit(e, &err) != 0) fail_msg("edit_commit: %s", err.msg);
    }
    free(ref);
    world_close(w);
}

static void test_seams_bounded_coarse(void **state) {
    (void)state;
    seams_bounded(TILE_LAYER_COARSE, NULL, 0);
}

static void test_seams_bounded_material(void **state) {
    (void)state;
    seams_bounded(TILE_LAYER_MATERIAL, NULL, 0);
}

static void test_seams_bounded_detail(void **state) {
    (void)state;
    const brush_tool tools[] = {BRUSH_RAISE, BRUSH_SMOOTH};
    seams_bounded(TILE_LAYER_DETAIL, tools, 2);
}

// Unbounded world: a window holding the dab's rect plus a halo, around negative
// coordinates and across tile -1/0; each dab gets a fresh window from the world.
static void seams_unbounded(tile_layer layer, const brush_tool *only, size_t only_count) {
    world_params p = flat_params(0, 1.0);
    p.octaves = 2; // cheap mip tiles: every dab here reaches 12 new mip levels
    world *w = open_world(&p);
    layer_grid g = grid_of(w, layer, 0);
    const dab_place places[] = {
        {0, -3, 40}, {-256, -256, 50}, {255, -1, 30}, {-1, 256, 33}, {-600, 700, 200},
    };
    if (layer == TILE_LAYER_DETAIL) {
        brush nb;
        brush_defaults(&nb, BRUSH_NOISE);
        nb.target = TILE_LAYER_DETAIL;
        nb.amount = 3.0;
        nb.noise_scale = 7.0;
        nb.falloff = FALLOFF_CONSTANT;
        nb.strength = 1.0;
        for (size_t q = 0; q < sizeof places / sizeof places[0]; q++) {
            brush_dab d = seam_dab(&nb, &g, places[q].cx, places[q].cz, places[q].r + 80, 0);
            dab_world(w, &g, &d);
        }
    }
    uint64_t seed = 100;
    for (size_t i = 0; i < TOOL_CASES; i++) {
        int wanted = only_count == 0;
        for (size_t o = 0; o < only_count; o++)
            wanted |= only[o] == all_tools[i];
        if (!wanted || (all_tools[i] == BRUSH_PAINT) != (layer == TILE_LAYER_MATERIAL)) continue;
        brush b;
        seam_brush(&b, i);
        og_error err;
        // Each dab's window as the edit begins.
        enum { PLACES = sizeof places / sizeof places[0] };
        brush_dab dabs[PLACES];
        grid_rect areas[PLACES];
        void *starts[PLACES];
        for (size_t q = 0; q < PLACES; q++) {
            dabs[q] = seam_dab(&b, &g, places[q].cx, places[q].cz, places[q].r, seed++);
            grid_rect r = brush_dab_rect(&dabs[q]);
            int64_t margin = (int64_t)(dabs[q].radius / 4) + 12; // > every tool's halo
            areas[q] = (grid_rect){r.x0 - margin, r.z0 - margin, r.x1 + margin, r.z1 + margin};
            starts[q] = read_area(w, layer, 0, 0, areas[q]);
        }
        edit *e = edit_begin(w, brush_tool_name(b.tool), &err); // one step per tool
        assert_non_null(e);
        for (size_t q = 0; q < PLACES; q++) {
            brush_dab d = dabs[q];
            grid_rect area = areas[q];
            void *ref = read_area(w, layer, 0, 0, area);
            char what[128];
            snprintf(what, sizeof what, "%s%s on unbounded %s at (%g, %g) r=%g",
                     b.invert ? "inverted " : "", brush_tool_name(b.tool), tile_layer_name(layer),
                     d.cx, d.cz, d.radius);
            dab_both(e, &g, &d, ref, starts[q], area, what);
            free(ref);
            free(starts[q]);
        }
        if (edit_commit(e, &err) != 0) fail_msg("edit_commit: %s", err.msg);
    }
    world_close(w);
}

static void test_seams_unbounded_coarse(void **state) {
    (void)state;
    seams_unbounded(TILE_LAYER_COARSE, NULL, 0);
}

static void test_seams_unbounded_material(void **state) {
    (void)state;
    seams_unbounded(TILE_LAYER_MATERIAL, NULL, 0);
}

static void test_seams_unbounded_detail(void **state) {
    (void)state;
    const brush_tool tools[] = {BRUSH_RAISE, BRUSH_SMOOTH};
    seams_unbounded(TILE_LAYER_DETAIL, tools, 2);
}

// Strokes put dabs at fractional sample positions: the seams must hold there too.
static void test_seams_fractional_centre(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    const tile_layer layers[] = {TILE_LAYER_COARSE, TILE_LAYER_MATERIAL};
    for (size_t l = 0; l < 2; l++) {
        layer_grid g = grid_of(w, layers[l], 0);
        grid_rect area = {0, 0, g.extent, g.extent};
        void *ref = read_area(w, layers[l], 0, 0, area);
        for (size_t i = 0; i < TOOL_CASES; i++) {
            if ((all_tools[i] == BRUSH_PAINT) != (layers[l] == TILE_LAYER_MATERIAL)) continue;
            brush b;
            seam_brush(&b, i);
            og_error err;
            edit *e = edit_begin(w, brush_tool_name(b.tool), &err); // one step per tool
            assert_non_null(e);
            void *start = read_area(w, layers[l], 0, 0, area);
            // Spans starting at a tile edge near the centre and at the rect edge far
            // from it: the dx of the same sample is then rounded in different binades.
            const dab_place places[] = {{300.37, 255.61, 200.3}, {257.3, 511.9, 150.7}};
            for (size_t q = 0; q < 2; q++) {
                brush_dab d = seam_dab(&b, &g, places[q].cx, places[q].cz, places[q].r, 7);
                char what[128];
                snprintf(what, sizeof what, "%s%s at fractional centre (%g, %g) r=%g",
                         b.invert ? "inverted " : "", brush_tool_name(b.tool), d.cx, d.cz,
                         d.radius);
                dab_both(e, &g, &d, ref, start, area, what);
            }
            free(start);
            if (edit_commit(e, &err) != 0) fail_msg("edit_commit: %s", err.msg);
        }
        free(ref);
    }
    world_close(w);
}

// ---------------------------------------------------------------------------
// 2. Out of core
// ---------------------------------------------------------------------------

static void test_out_of_core_stroke(void **state) {
    (void)state;
    world_params p = flat_params(0, 1.0);
    p.octaves = 2;
    // Budget: 4 coarse tiles; the strokes below touch ~20 level-0 tiles plus mips.
    size_t small_budget = 4 * tile_layer_bytes(TILE_LAYER_COARSE);
    world *small = open_world_with(&p, small_budget, 0, NULL);
    world *big = open_world_with(&p, (size_t)512 << 20, 0, NULL);
    grid_rect area = {-110, -110, 1420, 720}; // the strokes' footprint
    uint64_t before = coarse_hash(big, 0, area);
    assert_true(coarse_hash(small, 0, area) == before);

    brush raise, smooth;
    brush_defaults(&raise, BRUSH_RAISE);
    raise.radius = 100;
    raise.amount = 4;
    raise.spacing = 0.5;
    brush_defaults(&smooth, BRUSH_SMOOTH);
    smooth.radius = 60;
    smooth.spacing = 1.0;
    const double path[] = {50, 50, 1300, 60, 1300, 600};
    const double back[] = {1250, 560, 100, 420};
    world *both[2] = {small, big};
    uint64_t after[2], mid[2];
    for (int i = 0; i < 2; i++) {
        stroke_world(both[i], &raise, path, 3);
        mid[i] = coarse_hash(both[i], 0, area);
        stroke_world(both[i], &smooth, back, 2);
        after[i] = coarse_hash(both[i], 0, area);
    }
    assert_true(mid[0] == mid[1]);
    assert_true(after[0] == after[1]);
    assert_true(after[0] != before && mid[0] != before);

    tile_cache_stats st;
    tile_cache_stats_get(world_cache(small), &st);
    assert_true(st.evicted > 20); // the edits really went through eviction
    assert_true(st.resident_bytes <= small_budget);

    undo(small);
    assert_true(coarse_hash(small, 0, area) == mid[0]);
    undo(small);
    assert_true(coarse_hash(small, 0, area) == before);
    redo(small);
    redo(small);
    assert_true(coarse_hash(small, 0, area) == after[0]);
    world_close(small);
    world_close(big);
}

// ---------------------------------------------------------------------------
// 3. Undo and redo, bit for bit, on every layer
// ---------------------------------------------------------------------------

typedef struct layer_hashes {
    uint64_t coarse, detail, material;
} layer_hashes;

static layer_hashes all_hashes(world *w) {
    layer_hashes h = {coarse_hash(w, 0, whole(w, TILE_LAYER_COARSE)),
                      layer_hash(w, TILE_LAYER_DETAIL, 0, whole(w, TILE_LAYER_DETAIL)),
                      layer_hash(w, TILE_LAYER_MATERIAL, 0, whole(w, TILE_LAYER_MATERIAL))};
    return h;
}

static int hashes_equal(layer_hashes a, layer_hashes b) {
    return a.coarse == b.coarse && a.detail == b.detail && a.material == b.material;
}

static void test_undo_redo_bit_exact(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    brush b[3];
    brush_defaults(&b[0], BRUSH_RAISE);
    b[0].radius = 45;
    brush_defaults(&b[1], BRUSH_PAINT);
    b[1].radius = 30;
    b[1].material = 5;
    brush_defaults(&b[2], BRUSH_NOISE);
    b[2].target = TILE_LAYER_DETAIL;
    b[2].radius = 12;
    b[2].noise_scale = 3;
    const double path[] = {240, 240, 530, 270, 500, 600};
    layer_hashes h[4];
    h[0] = all_hashes(w);
    for (int i = 0; i < 3; i++) {
        stroke_world(w, &b[i], path, 3);
        h[i + 1] = all_hashes(w);
    }
    assert_true(h[1].coarse != h[0].coarse && h[1].material == h[0].material);
    assert_true(h[2].material != h[1].material && h[2].coarse == h[1].coarse);
    assert_true(h[3].detail != h[2].detail && h[3].coarse == h[2].coarse);
    for (int i = 3; i > 0; i--) {
        undo(w);
        assert_true(hashes_equal(all_hashes(w), h[i - 1]));
    }
    og_error err;
    assert_int_equal(edit_undo(w, &err), 0);
    for (int i = 1; i <= 3; i++) {
        redo(w);
        assert_true(hashes_equal(all_hashes(w), h[i]));
    }
    assert_int_equal(edit_redo(w, &err), 0);
    // Undo then a new edit drops the redo step.
    undo(w);
    stroke_world(w, &b[0], path, 2);
    assert_int_equal(edit_redo(w, &err), 0);
    world_close(w);
}

// The engine's commands drive the same machinery.
static void test_commands_dab_undo(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    world_settings s = {.warn = silent};
    FILE *out = tmpfile();
    assert_non_null(out);
    cmd_context ctx;
    cmd_context_init(&ctx, w, &s, out, OROGEN_RESOURCE_DIR);
    og_error err;
    grid_rect all = whole(w, TILE_LAYER_COARSE);
    uint64_t h0 = coarse_hash(w, 0, all);
    double before, after;
    assert_int_equal(world_sample(w, 0, 100, 100, &before, &err), 0);
    const char *script = "tool lower radius=30 strength=1 amount=5; dab 100 100";
    if (cmd_run(&ctx, script, strlen(script), "-c", &err) != 0) fail_msg("%s", err.msg);
    assert_int_equal(world_sample(w, 0, 100, 100, &after, &err), 0);
    assert_true(fabs((before - after) - 5.0) < 1e-3);
    uint64_t h1 = coarse_hash(w, 0, all);
    assert_true(h1 != h0);
    const char *u = "undo";
    assert_int_equal(cmd_run(&ctx, u, strlen(u), "-c", &err), 0);
    assert_true(coarse_hash(w, 0, all) == h0);
    const char *r = "redo; history";
    assert_int_equal(cmd_run(&ctx, r, strlen(r), "-c", &err), 0);
    assert_true(coarse_hash(w, 0, all) == h1);
    const char *bad = "tool raise radius=nan";
    assert_int_equal(cmd_run(&ctx, bad, strlen(bad), "-c", &err), -1);
    assert_non_null(strstr(err.msg, "radius"));
    assert_true(ctx.brush.invert == 1 && ctx.brush.radius == 30.0); // the brush stayed
    const char *twice = "undo; undo";
    assert_int_equal(cmd_run(&ctx, twice, strlen(twice), "-c", &err), -1);
    assert_non_null(strstr(err.msg, "nothing to undo"));
    assert_true(coarse_hash(w, 0, all) == h0);
    fclose(out);
    world_close(w);
}

// ---------------------------------------------------------------------------
// 4. Property: random edits and a generate, all undone, all redone
// ---------------------------------------------------------------------------

static void random_stroke(world *w, uint64_t *rng) {
    brush b;
    brush_tool tool = (brush_tool)(rng_next(rng) % BRUSH_TOOL_COUNT);
    brush_defaults(&b, tool);
    b.radius = rng_uniform(rng, 4, 40);
    b.strength = rng_uniform(rng, 0.2, 1.0);
    b.falloff = (brush_falloff)(rng_next(rng) % FALLOFF_CURVE);
    b.spacing = rng_uniform(rng, 0.2, 0.8);
    b.amount = rng_uniform(rng, 0.5, 6);
    b.seed = (uint32_t)rng_next(rng);
    b.hydraulic.seed = b.seed;
    b.hydraulic.droplets = 60;
    b.thermal.iterations = 4;
    b.terrace_step = rng_uniform(rng, 2, 12);
    if (tool == BRUSH_SET || (tool == BRUSH_FLATTEN && rng_next(rng) % 2)) {
        b.has_height = 1;
        b.height = rng_uniform(rng, -100, 100);
    }
    if (tool == BRUSH_RAISE || tool == BRUSH_SMOOTH || tool == BRUSH_NOISE || tool == BRUSH_PAINT)
        b.invert = rng_next(rng) % 3 == 0;
    if ((tool == BRUSH_RAISE || tool == BRUSH_SMOOTH || tool == BRUSH_NOISE) &&
        rng_next(rng) % 4 == 0) {
        b.target = TILE_LAYER_DETAIL;
        b.radius = fmin(b.radius, 15);
    }
    b.material = (int)(rng_next(rng) % TILE_MATERIALS);
    og_error err;
    if (brush_tool_is_volume(tool)) { // 3D points around the ground; coarse and material stay
        double pts[3][3], ground = 0;
        int n = 1 + (int)(rng_next(rng) % 3);
        for (int i = 0; i < n; i++) {
            pts[i][0] = rng_uniform(rng, 50, 650);
            pts[i][2] = rng_uniform(rng, 50, 650);
            if (world_sample(w, 0, pts[i][0], pts[i][2], &ground, &err) != 0)
                fail_msg("world_sample: %s", err.msg);
            pts[i][1] = ground + rng_uniform(rng, -10, 10);
        }
        b.radius = fmin(b.radius, 12);
        if (volume_brush_apply(w, &b, (const double(*)[3])pts, NULL, (size_t)n, &err) != 0)
            fail_msg("volume_brush_apply: %s", err.msg);
        return;
    }
    stroke *s = stroke_begin(w, &b, &err);
    if (!s) fail_msg("stroke_begin: %s", err.msg);
    int points = 1 + (int)(rng_next(rng) % 4);
    double x = rng_uniform(rng, 0, 699), z = rng_uniform(rng, 0, 699);
    for (int i = 0; i < points; i++) {
        if (i) {
            x = fmin(699, fmax(0, x + rng_uniform(rng, -50, 50)));
            z = fmin(699, fmax(0, z + rng_uniform(rng, -50, 50)));
        }
        if (stroke_to(s, x, z, rng_uniform(rng, 0.3, 1.0), &err) != 0) {
            stroke_cancel(s);
            fail_msg("stroke_to: %s", err.msg);
        }
    }
    if (stroke_end(s, &err) != 0) fail_msg("stroke_end: %s", err.msg);
}

#define PROPERTY_OPS 44

static void test_property_random_edits_undo_redo(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    history *h = world_history(w);
    uint64_t rng = 0x0badc0ffee;
    grid_rect cr = whole(w, TILE_LAYER_COARSE), mr = whole(w, TILE_LAYER_MATERIAL);
    // Hashes of the coarse and material layers after each applied step.
    uint64_t coarse[PROPERTY_OPS + 2], material[PROPERTY_OPS + 2];
    coarse[0] = coarse_hash(w, 0, cr);
    material[0] = layer_hash(w, TILE_LAYER_MATERIAL, 0, mr);
    uint64_t detail0 = layer_hash(w, TILE_LAYER_DETAIL, 0, whole(w, TILE_LAYER_DETAIL));
    og_error err;
    for (int op = 0; op < PROPERTY_OPS; op++) {
        if (op == PROPERTY_OPS / 2) {
            world_params np = *world_get_params(w);
            np.seed += 17;
            np.octaves = 3;
            if (edit_generate(w, &np, &err) != 0) fail_msg("edit_generate: %s", err.msg);
        } else {
            random_stroke(w, &rng);
        }
        size_t at = history_position(h);
        assert_true(at <= PROPERTY_OPS + 1);
        coarse[at] = coarse_hash(w, 0, cr);
        material[at] = layer_hash(w, TILE_LAYER_MATERIAL, 0, mr);
    }
    size_t steps = history_position(h);
    assert_true(steps >= PROPERTY_OPS / 2); // most strokes changed something
    assert_true(coarse[steps] != coarse[0]);
    uint64_t detail_end = layer_hash(w, TILE_LAYER_DETAIL, 0, whole(w, TILE_LAYER_DETAIL));
    for (size_t i = steps; i > 0; i--) {
        undo(w);
        if (coarse_hash(w, 0, cr) != coarse[i - 1])
            fail_msg("coarse layer differs after undoing step %zu (%s)", i,
                     history_at(h, i - 1)->label);
        if (layer_hash(w, TILE_LAYER_MATERIAL, 0, mr) != material[i - 1])
            fail_msg("material layer differs after undoing step %zu (%s)", i,
                     history_at(h, i - 1)->label);
    }
    assert_int_equal(edit_undo(w, &err), 0);
    assert_true(layer_hash(w, TILE_LAYER_DETAIL, 0, whole(w, TILE_LAYER_DETAIL)) == detail0);
    assert_true(world_get_params(w)->seed == p.seed);
    assert_int_equal(world_is_modified(w), 0);
    for (size_t i = 1; i <= steps; i++) {
        redo(w);
        if (coarse_hash(w, 0, cr) != coarse[i])
            fail_msg("coarse layer differs after redoing step %zu (%s)", i,
                     history_at(h, i - 1)->label);
        if (layer_hash(w, TILE_LAYER_MATERIAL, 0, mr) != material[i])
            fail_msg("material layer differs after redoing step %zu (%s)", i,
                     history_at(h, i - 1)->label);
    }
    assert_true(layer_hash(w, TILE_LAYER_DETAIL, 0, whole(w, TILE_LAYER_DETAIL)) == detail_end);
    world_close(w);
}

// ---------------------------------------------------------------------------
// 5. History budget
// ---------------------------------------------------------------------------

static void test_history_budget_drops_oldest(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    warn_log log = {.lock = PTHREAD_MUTEX_INITIALIZER};
    world *w = open_world_with(&p, (size_t)256 << 20, (size_t)600 << 10, &log);
    history *h = world_history(w);
    assert_int_equal(history_budget(h), (size_t)600 << 10);
    grid_rect all = whole(w, TILE_LAYER_COARSE);
    brush b;
    brush_defaults(&b, BRUSH_NOISE); // noise: deltas that compress poorly
    b.radius = 70;
    b.noise_scale = 4;
    uint64_t hashes[41];
    hashes[0] = coarse_hash(w, 0, all);
    int strokes = 0;
    uint64_t rng = 5;
    while (strokes < 40 && history_dropped_total(h) < 3) {
        b.seed = (uint32_t)rng_next(&rng);
        double x = rng_uniform(&rng, 100, 600), z = rng_uniform(&rng, 100, 600);
        double path[] = {x, z, x + 60, z + 30};
        stroke_world(w, &b, path, 2);
        hashes[++strokes] = coarse_hash(w, 0, all);
    }
    uint64_t dropped = history_dropped_total(h);
    assert_true(dropped >= 3);
    size_t held = history_count(h);
    assert_int_equal(held + dropped, (size_t)strokes);
    assert_true(history_bytes(h) <= history_budget(h) || held == 1);
    assert_true(log.mentions_dropped > 0);
    assert_non_null(strstr(log.last, "dropped"));
    og_error err;
    // The newest step undoes to the state before it; undo stops at the floor.
    undo(w);
    assert_true(coarse_hash(w, 0, all) == hashes[strokes - 1]);
    for (size_t i = 1; i < held; i++)
        undo(w);
    assert_int_equal(edit_undo(w, &err), 0);
    assert_true(coarse_hash(w, 0, all) == hashes[dropped]);
    assert_int_equal(world_is_modified(w), 1); // the floor is not the created state
    while (edit_redo(w, &err) == 1) {
    }
    assert_true(coarse_hash(w, 0, all) == hashes[strokes]);
    // Shrinking the budget keeps the newest step.
    size_t now = history_count(h);
    assert_int_equal(history_set_budget(h, 1), now - 1);
    assert_int_equal(history_count(h), 1);
    undo(w);
    assert_true(coarse_hash(w, 0, all) == hashes[strokes - 1]);
    assert_int_equal(edit_undo(w, &err), 0);
    world_close(w);
}

// ---------------------------------------------------------------------------
// 6. Per-tool invariants
// ---------------------------------------------------------------------------

// Sample (x, z) of an array holding the samples of r.
static float at(const float *a, grid_rect r, int64_t x, int64_t z) {
    return a[(z - r.z0) * (r.x1 - r.x0) + (x - r.x0)];
}

static int inside(double cx, double cz, double radius, int64_t x, int64_t z) {
    double dx = (double)x - cx, dz = (double)z - cz;
    return dx * dx + dz * dz < radius * radius;
}

static grid_rect around(int64_t cx, int64_t cz, int64_t r) {
    return (grid_rect){cx - r, cz - r, cx + r + 1, cz + r + 1};
}

static void mean_var(const float *a, grid_rect r, double cx, double cz, double radius, double *mean,
                     double *var) {
    double s = 0, s2 = 0;
    long n = 0;
    for (int64_t z = r.z0; z < r.z1; z++)
        for (int64_t x = r.x0; x < r.x1; x++)
            if (inside(cx, cz, radius, x, z)) {
                double v = at(a, r, x, z);
                s += v, s2 += v * v, n++;
            }
    *mean = s / (double)n;
    *var = s2 / (double)n - *mean * *mean;
}

// Sum of squared discrete Laplacians inside the disc: the high-frequency energy.
static double roughness(const float *a, grid_rect r, double cx, double cz, double radius) {
    double e = 0;
    for (int64_t z = r.z0 + 1; z < r.z1 - 1; z++)
        for (int64_t x = r.x0 + 1; x < r.x1 - 1; x++)
            if (inside(cx, cz, radius, x, z)) {
                double l = at(a, r, x - 1, z) + at(a, r, x + 1, z) + at(a, r, x, z - 1) +
                           at(a, r, x, z + 1) - 4.0 * at(a, r, x, z);
                e += l * l;
            }
    return e;
}

static void test_invariant_smooth(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    grid_rect r = around(350, 350, 70);
    float *before = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    brush b;
    brush_defaults(&b, BRUSH_SMOOTH);
    b.radius = 64;
    b.strength = 1;
    b.falloff = FALLOFF_CONSTANT;
    dab_at(w, &b, 350, 350);
    float *after = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    double m0, v0, m1, v1;
    mean_var(before, r, 350, 350, 60, &m0, &v0);
    mean_var(after, r, 350, 350, 60, &m1, &v1);
    assert_true(v1 < v0);
    double e0 = roughness(before, r, 350, 350, 60), e1 = roughness(after, r, 350, 350, 60);
    print_message("smooth: variance %g -> %g, roughness %g -> %g\n", v0, v1, e0, e1);
    assert_true(e1 < 0.5 * e0);
    // Samples beyond the radius stay.
    for (int64_t z = r.z0; z < r.z1; z++)
        for (int64_t x = r.x0; x < r.x1; x++)
            if (!inside(350, 350, 64, x, z)) assert_true(at(before, r, x, z) == at(after, r, x, z));
    // Inverted (sharpen) adds high-frequency energy back.
    undo(w);
    b.invert = 1;
    b.strength = 0.5;
    dab_at(w, &b, 350, 350);
    float *sharp = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    assert_true(roughness(sharp, r, 350, 350, 60) > e0);
    free(before);
    free(after);
    free(sharp);
    world_close(w);
}

// The smooth dab against the blur written plainly: two box means of radius r/8 along
// rows, then two along columns, summed in double, the dab's samples moved toward them
// by the falloff. Radii whose box lengths take one, two and three power-of-two runs.
static void test_smooth_matches_plain_blur(void **state) {
    (void)state;
    enum { N = 240 };
    float *heights = malloc(N * N * sizeof *heights);
    double *a = malloc(N * N * sizeof *a), *c = malloc(N * N * sizeof *c);
    const double radii[] = {12, 40, 64, 64};
    double worst = 0;
    for (size_t t = 0; t < 4; t++) {
        for (int z = 0; z < N; z++) // relief of hundreds of metres with a rough part
            for (int x = 0; x < N; x++)
                heights[z * N + x] = (float)(900.0 + 120.0 * sin(x * 0.05) * cos(z * 0.07) +
                                             (double)((x * 7 + z * 13) % 17) - 0.01 * x * z);
        for (int i = 0; i < N * N; i++)
            a[i] = heights[i];
        brush b;
        brush_defaults(&b, BRUSH_SMOOTH);
        b.strength = 0.8;
        b.invert = t == 3;
        brush_dab d = {.brush = &b,
                       .cx = 120.3,
                       .cz = 119.6,
                       .radius = radii[t],
                       .strength = (float)b.strength,
                       .spacing = 1.0};
        og_error err;
        assert_int_equal(
            brush_dab_apply_array(&d, TILE_LAYER_COARSE, heights, (grid_rect){0, 0, N, N}, &err),
            0);
        int k = (int)fmax(1.0, floor(d.radius / 8.0));
        for (int pass = 0; pass < 4; pass++) { // the dab stays 4k inside the array
            int step = pass < 2 ? 1 : N;
            for (int z = 2 * k; z < N - 2 * k; z++)
                for (int x = 2 * k; x < N - 2 * k; x++) {
                    double sum = 0;
                    for (int j = -k; j <= k; j++)
                        sum += a[z * N + x + j * step];
                    c[z * N + x] = sum / (2 * k + 1);
                }
            memcpy(a, c, N * N * sizeof *a);
        }
        grid_rect r = brush_dab_rect(&d);
        for (int64_t z = r.z0; z < r.z1; z++)
            for (int64_t x = r.x0; x < r.x1; x++) {
                double dx = x - d.cx, dz = z - d.cz,
                       u = fmin(1.0, sqrt(dx * dx + dz * dz) / d.radius);
                double w = (1.0 - u * u * (3.0 - 2.0 * u)) * d.strength * (b.invert ? -1 : 1);
                double old = 900.0 + 120.0 * sin(x * 0.05) * cos(z * 0.07) +
                             (double)((x * 7 + z * 13) % 17) - 0.01 * x * z;
                old = (float)old;
                double want = old + w * (a[z * N + x] - old);
                double off = fabs(heights[z * N + x] - want);
                worst = fmax(worst, off);
                if (off > 2e-4)
                    fail_msg("radius %g, sample (%lld, %lld): %.6f, the plain blur gives %.6f",
                             d.radius, (long long)x, (long long)z, heights[z * N + x], want);
            }
    }
    print_message("smooth vs plain blur: largest difference %.3g m (heights ~900 m)\n", worst);
    free(heights);
    free(a);
    free(c);
}

static void test_invariant_flatten_converges(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    brush b;
    brush_defaults(&b, BRUSH_FLATTEN); // strength 0.5, smooth falloff
    b.radius = 30;
    b.has_height = 1;
    b.height = 37.0;
    grid_rect r = around(300, 420, 30);
    double last = INFINITY;
    for (int i = 1; i <= 60; i++) {
        dab_at(w, &b, 300, 420);
        if (i % 10) continue;
        float *a = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
        double worst = 0;
        for (int64_t z = r.z0; z < r.z1; z++)
            for (int64_t x = r.x0; x < r.x1; x++)
                if (inside(300, 420, 15, x, z)) worst = fmax(worst, fabs(at(a, r, x, z) - 37.0));
        free(a);
        assert_true(worst <= last);
        last = worst;
    }
    assert_true(last < 1e-3);
    // mode=raise never lowers; no height: the target is the height under the start.
    world_close(w);
    w = open_world(&p);
    grid_rect big = around(420, 300, 45);
    float *before = read_area(w, TILE_LAYER_COARSE, 0, 0, big);
    og_error err;
    brush_defaults(&b, BRUSH_FLATTEN);
    assert_int_equal(brush_set(&b, "mode", "raise", &err), 0);
    b.radius = 40;
    b.strength = 1;
    double start;
    assert_int_equal(world_sample(w, 0, 420, 300, &start, &err), 0);
    for (int i = 0; i < 20; i++)
        dab_at(w, &b, 420, 300);
    float *after = read_area(w, TILE_LAYER_COARSE, 0, 0, big);
    int raised = 0;
    for (size_t i = 0; i < rect_samples(big); i++) {
        assert_true(after[i] >= before[i]);
        raised += after[i] > before[i];
        if (after[i] > before[i]) assert_true(after[i] <= (float)start + 1e-3f);
    }
    assert_true(raised > 0);
    free(before);
    free(after);
    world_close(w);
}

static void test_invariant_thermal_talus(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    p.feature_size = 64; // steep: slopes well beyond 35 degrees
    world *w = open_world(&p);
    const double cx = 400, cz = 300, radius = 24;
    grid_rect r = around(400, 300, 26);
    float *before = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    const double limit = tan(35.0 * M_PI / 180.0);
    double steepest = 0;
    for (int64_t z = r.z0; z < r.z1; z++)
        for (int64_t x = r.x0 + 1; x < r.x1; x++)
            steepest = fmax(steepest, fabs(at(before, r, x, z) - at(before, r, x - 1, z)));
    assert_true(steepest > 2 * limit);
    brush b;
    brush_defaults(&b, BRUSH_THERMAL);
    b.radius = radius;
    b.strength = 1;
    b.falloff = FALLOFF_CONSTANT;
    b.thermal = (thermal_params){.talus_deg = 35.0f, .iterations = 4000, .rate = 1.0f};
    dab_at(w, &b, cx, cz);
    float *after = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    // Every pair of weighted neighbours (both inside the disc), axis and diagonal.
    const int dx[4] = {1, 0, 1, 1}, dz[4] = {0, 1, 1, -1};
    double worst = 0;
    for (int64_t z = r.z0 + 1; z < r.z1 - 1; z++)
        for (int64_t x = r.x0; x < r.x1 - 1; x++)
            for (int k = 0; k < 4; k++) {
                if (!inside(cx, cz, radius, x, z) || !inside(cx, cz, radius, x + dx[k], z + dz[k]))
                    continue;
                double dist = (dx[k] && dz[k]) ? sqrt(2.0) : 1.0;
                double s = fabs(at(after, r, x + dx[k], z + dz[k]) - at(after, r, x, z)) / dist;
                worst = fmax(worst, s);
            }
    if (worst > limit + 1e-3)
        fail_msg("thermal left a slope of %g inside the brush (talus %g)", worst, limit);
    // Mass moves, it is not made: the disc's sum stays (1e-5 relative).
    double s0 = 0, s1 = 0, moved = 0;
    for (size_t i = 0; i < rect_samples(r); i++) {
        s0 += before[i], s1 += after[i];
        moved += fabs((double)after[i] - before[i]);
    }
    assert_true(moved > 0);
    assert_true(fabs(s1 - s0) <= 1e-5 * fmax(fabs(s0), moved));
    free(before);
    free(after);
    world_close(w);
}

static void test_invariant_hydraulic_mass(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    brush b;
    brush_defaults(&b, BRUSH_HYDRAULIC);
    b.radius = 40;
    b.strength = 1;
    b.falloff = FALLOFF_CONSTANT;
    b.hydraulic.droplets = 3000;
    grid_rect r = around(350, 350, 40 + 8); // footprint and halo
    float *before = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    dab_at(w, &b, 350, 350);
    float *after = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    double s0 = 0, s1 = 0, change = 0;
    for (size_t i = 0; i < rect_samples(r); i++) {
        s0 += before[i], s1 += after[i];
        change += fabs((double)after[i] - before[i]);
        assert_true(isfinite(after[i]));
    }
    assert_true(change > 1.0);
    if (fabs(s1 - s0) > 1e-4 * change)
        fail_msg("hydraulic mass: sum changed by %g, total |change| %g", s1 - s0, change);
    // Beyond the brush nothing moves.
    for (int64_t z = r.z0; z < r.z1; z++)
        for (int64_t x = r.x0; x < r.x1; x++)
            if (!inside(350, 350, 40, x, z)) assert_true(at(before, r, x, z) == at(after, r, x, z));
    free(before);
    free(after);
    world_close(w);
}

static void test_invariant_paint(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    grid_rect all = whole(w, TILE_LAYER_MATERIAL);
    brush b;
    brush_defaults(&b, BRUSH_PAINT);
    b.radius = 40;
    b.strength = 0.7;
    b.material = 3;
    const double path[] = {250, 250, 520, 270};
    stroke_world(w, &b, path, 2);
    b.material = 6;
    b.falloff = FALLOFF_LINEAR;
    const double cross[] = {380, 150, 390, 400};
    stroke_world(w, &b, cross, 2);
    uint8_t *m = read_area(w, TILE_LAYER_MATERIAL, 0, 0, all);
    size_t centre = (size_t)(250 * 700 + 300) * TILE_MATERIALS;
    assert_true(m[centre + 3] > 200); // painted, from 0
    size_t mixed = (size_t)(262 * 700 + 385) * TILE_MATERIALS;
    assert_true(m[mixed + 6] > 100);
    uint8_t was = m[centre + 3];
    free(m);
    // Inverted: removes material 3 in proportion (0.3 at the centre).
    b.material = 3;
    b.invert = 1;
    b.strength = 0.3;
    b.falloff = FALLOFF_CONSTANT;
    dab_at(w, &b, 300, 250);
    m = read_area(w, TILE_LAYER_MATERIAL, 0, 0, all);
    for (size_t i = 0; i < rect_samples(all); i++) {
        int sum = 0;
        for (int c = 0; c < TILE_MATERIALS; c++)
            sum += m[i * TILE_MATERIALS + c];
        if (sum != 255) fail_msg("sample %zu: weights sum to %d", i, sum);
    }
    assert_true(abs((int)m[centre + 3] - (int)(0.7 * was + 0.5)) <= 1);
    size_t far = (size_t)(600 * 700 + 100) * TILE_MATERIALS;
    assert_int_equal(m[far], 255);
    free(m);
    world_close(w);
}

// Material 4's weight (0-255) at samples (x, z0 + k), k < n, at a mip level.
static void weights_down(world *w, int level, int64_t x, int64_t z0, int n, int *out) {
    uint8_t *m = read_area(w, TILE_LAYER_MATERIAL, 0, level, (grid_rect){x, z0, x + 1, z0 + n});
    for (int k = 0; k < n; k++) {
        int sum = 0;
        for (int c = 0; c < TILE_MATERIALS; c++)
            sum += m[k * TILE_MATERIALS + c];
        if (sum != 255)
            fail_msg("level %d (%lld, %lld): weights sum to %d", level, (long long)x,
                     (long long)(z0 + k), sum);
        out[k] = m[k * TILE_MATERIALS + 4];
    }
    free(m);
}

// Paint's edge follows the brush's falloff however many dabs a stroke lays (issue 26:
// repeated dabs used to pile up into a hard edge): across a straight stroke the weight
// is 255 x falloff(distance / radius); a brush held still never spreads past it; a
// second stroke lays its paint over the first; the mip levels carry the paint, and
// undo takes it from them too.
static void test_paint_soft_edge(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    brush b;
    brush_defaults(&b, BRUSH_PAINT);
    b.radius = 40;
    b.strength = 0.5;
    b.material = 4;
    b.spacing = 0.05; // a dab every 2 samples: ~40 dabs reach each sample
    const double line[] = {150, 350, 550, 350};
    stroke_world(w, &b, line, 2);
    enum { N = 101 };
    int got[N];
    weights_down(w, 0, 350, 300, N, got); // 50 samples either side of the stroke
    for (int k = 0; k < N; k++) {
        double t = fabs((double)(k - 50)) / b.radius;
        double want = 255.0 * brush_falloff_weight(&b, (float)t);
        // Never past the falloff; at half strength the dabs close in on it (within 3%).
        if (got[k] > want + 1.0 || got[k] < want - 8.0)
            fail_msg("%d samples from the stroke: weight %d, the falloff says %.1f", k - 50, got[k],
                     want);
    }
    // Held still for five seconds on fresh ground: the edge stays where the falloff puts it.
    stroke *s = stroke_begin(w, &b, &(og_error){0});
    og_error err;
    assert_non_null(s);
    if (stroke_to(s, 350, 150, 1.0, &err) != 0 || stroke_hold(s, 5.0, &err) != 0 ||
        stroke_end(s, &err) != 0)
        fail_msg("held stroke: %s", err.msg);
    int held[N];
    weights_down(w, 0, 350, 100, N, held);
    for (int k = 0; k < N; k++) {
        double t = fabs((double)(k - 50)) / b.radius;
        double want = 255.0 * brush_falloff_weight(&b, (float)t);
        if (t >= 1.0) assert_int_equal(held[k], 0);
        if (held[k] > want + 1.0 || held[k] < want - 1.0)
            fail_msg("held: %d samples from the centre: weight %d, the falloff says %.1f", k - 50,
                     held[k], want);
    }
    // A second stroke over the first: half way out (falloff 0.5) 0.5 + 0.5 x 0.5.
    b.strength = 1.0;
    stroke_world(w, &b, line, 2);
    weights_down(w, 0, 350, 300, N, got);
    assert_true(abs(got[50 + 20] - 191) <= 3);
    assert_int_equal(got[50], 255);

    // A patch of constant falloff: its middle reads full at every mip level that has
    // samples inside it, and undo restores them.
    b.falloff = FALLOFF_CONSTANT;
    b.radius = 120;
    dab_at(w, &b, 350, 500);
    int level_at[5];
    weights_down(w, 0, 350, 500, 1, &level_at[0]);
    assert_int_equal(level_at[0], 255);
    for (int level = 1; level <= 4; level++) {
        weights_down(w, level, 350 >> level, 500 >> level, 1, &level_at[level]);
        assert_int_equal(level_at[level], 255);
    }
    int outside;
    weights_down(w, 3, 100 >> 3, 650 >> 3, 1, &outside);
    assert_int_equal(outside, 0);
    undo(w);
    for (int level = 1; level <= 4; level++) {
        weights_down(w, level, 350 >> level, 500 >> level, 1, &level_at[level]);
        assert_int_equal(level_at[level], 0);
    }
    redo(w);
    weights_down(w, 4, 350 >> 4, 500 >> 4, 1, &level_at[4]);
    assert_int_equal(level_at[4], 255);
    world_close(w);
}

static float terrace_of(double h, double step, double sharpness) {
    double k = floor(h / step), f = h / step - k, pw = 1.0 + 15.0 * sharpness * sharpness;
    return (float)((k + pow(f, pw)) * step);
}

static double near_multiple(double h, double step) {
    double f = h / step - floor(h / step);
    return fmin(f, 1.0 - f) * step;
}

static void test_invariant_terrace(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    grid_rect r = around(330, 330, 60);
    float *before = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    brush b;
    brush_defaults(&b, BRUSH_TERRACE);
    b.radius = 60;
    b.strength = 1;
    b.falloff = FALLOFF_CONSTANT;
    b.terrace_step = 10;
    b.terrace_sharpness = 1;
    dab_at(w, &b, 330, 330);
    float *after = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    long n = 0, near0 = 0, near1 = 0;
    for (int64_t z = r.z0; z < r.z1; z++)
        for (int64_t x = r.x0; x < r.x1; x++) {
            if (!inside(330, 330, 60, x, z)) continue;
            float h0 = at(before, r, x, z), h1 = at(after, r, x, z);
            assert_true(fabsf(h1 - terrace_of(h0, 10, 1)) < 1e-3f);
            n++;
            near0 += near_multiple(h0, 10) < 1.0;
            near1 += near_multiple(h1, 10) < 1.0;
        }
    assert_true(near0 < 0.4 * n);
    assert_true(near1 > 0.8 * n);
    free(before);
    free(after);
    world_close(w);
}

static void test_invariant_ramp(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    grid_rect r = {80, 280, 421, 321};
    float *before = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    float ha = at(before, r, 100, 300), hb = at(before, r, 400, 300);
    brush b;
    brush_defaults(&b, BRUSH_RAMP);
    b.radius = 12;
    b.strength = 1;
    b.falloff = FALLOFF_CONSTANT;
    const double path[] = {100, 300, 250, 310, 400, 300}; // ramp: first to last point only
    stroke_world(w, &b, path, 3);
    float *after = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    for (int64_t x = 100; x <= 400; x++) {
        double t = (double)(x - 100) / 300.0, want = ha + t * (hb - ha);
        for (int64_t dz = -8; dz <= 8; dz++) { // across the ramp it is level
            double got = at(after, r, x, 300 + dz);
            if (fabs(got - want) > 1e-3)
                fail_msg("ramp at (%lld, %lld): %g, expected %g", (long long)x,
                         (long long)(300 + dz), got, want);
        }
    }
    // Beyond the radius of the segment nothing changed.
    for (int64_t x = r.x0; x < r.x1; x++) {
        assert_true(at(after, r, x, 280) == at(before, r, x, 280));
        assert_true(at(after, r, x, 320) == at(before, r, x, 320));
    }
    free(before);
    free(after);
    world_close(w);
}

static void test_invariant_set(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    grid_rect r = around(200, 500, 35);
    float *before = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    brush b;
    brush_defaults(&b, BRUSH_SET);
    og_error err;
    stroke *s = stroke_begin(w, &b, &err); // set needs its height
    assert_null(s);
    assert_non_null(strstr(err.msg, "height"));
    assert_int_equal(brush_set(&b, "height", "-42.5", &err), 0);
    b.radius = 30;
    b.strength = 1;
    b.falloff = FALLOFF_CONSTANT;
    dab_at(w, &b, 200, 500);
    float *after = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    for (int64_t z = r.z0; z < r.z1; z++)
        for (int64_t x = r.x0; x < r.x1; x++) {
            if (inside(200, 500, 30, x, z))
                assert_true(fabsf(at(after, r, x, z) + 42.5f) < 1e-4f);
            else
                assert_true(at(after, r, x, z) == at(before, r, x, z));
        }
    free(before);
    free(after);
    world_close(w);
}

// ---------------------------------------------------------------------------
// 7. Hostile input
// ---------------------------------------------------------------------------

static void test_brush_set_rejects_bad_values(void **state) {
    (void)state;
    static const char *bad[][2] = {
        {"radius", "nan"},    {"radius", "inf"},      {"radius", "1e999"}, {"radius", "-5"},
        {"radius", ""},       {"radius", "10abc"},    {"radius", "0"},     {"strength", "2"},
        {"strength", "-0.1"}, {"strength", "nan"},    {"amount", "inf"},   {"height", "nan"},
        {"height", "1e999"},  {"height", "-2e6"},     {"spacing", "0"},    {"falloff", "wobbly"},
        {"falloff", "curve"}, {"curve", "0:nan,1:0"}, {"curve", "0:1"},    {"curve", "0.5:1,0.2:0"},
        {"invert", "maybe"},  {"target", "volume"},   {"face", "1.5"},     {"face", "6"},
        {"seed", "-1"},       {"iterations", "0"},    {"droplets", "1e9"}, {"material", "8"},
        {"talus", "90"},      {"mode", "sideways"},   {"octaves", "inf"},  {"scale", "-nan"},
    };
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    b.radius = 33;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        brush copy = b;
        og_error err = {{0}};
        if (brush_set(&copy, bad[i][0], bad[i][1], &err) != -1)
            fail_msg("brush_set accepted %s=%s", bad[i][0], bad[i][1]);
        assert_memory_equal(&copy, &b, sizeof b);
        if (!strstr(err.msg, bad[i][0]))
            fail_msg("the message for %s=%s does not name the key: %s", bad[i][0], bad[i][1],
                     err.msg);
    }
    og_error err = {{0}};
    brush copy = b;
    assert_int_equal(brush_set(&copy, "radiuss", "10", &err), -1);
    assert_non_null(strstr(err.msg, "radiuss"));
    assert_memory_equal(&copy, &b, sizeof b);
    // Good values still go in.
    assert_int_equal(brush_set(&copy, "radius", "12.5", &err), 0);
    assert_true(copy.radius == 12.5);
}

// Thermal erosion at its defaults shows from the first view of the default world (issue
// 26): held still for a second where the window's first view looks, with the radius the
// window gives at that distance, it moves the ground metres, as a hydraulic stroke does.
// The old defaults (talus 25, 50 iterations, the kernel at the grid's spacing only)
// moved it at most 0.9 m there (0.06 m on average).
static void test_thermal_defaults_visible(void **state) {
    (void)state;
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    og_error err = {{0}};
    int errors = 0;
    if (world_params_load(OROGEN_RESOURCE_DIR "/default.world", &p, &errors, NULL, NULL, &err) !=
            0 ||
        errors)
        fail_msg("default.world: %s", err.msg);
    world *w = open_world(&p);
    viewport *v = viewport_create(OROGEN_RESOURCE_DIR);
    assert_non_null(v);
    if (viewport_camera_on_land(v, w, &err) != 0) fail_msg("first view: %s", err.msg);
    // The ground under the view's centre, marching along its ray.
    double dir[3], hit[3] = {0, 0, 0}, t = 0, g = 0;
    camera_ray(&v->cam, 16.0 / 10.0, 0.5, 0.5, dir);
    for (; t < 20000; t += 1.0) {
        for (int a = 0; a < 3; a++)
            hit[a] = v->cam.pos[a] + dir[a] * t;
        if (world_sample(w, 0, hit[0], hit[2], &g, &err) != 0) fail_msg("sample: %s", err.msg);
        if (hit[1] <= g) break;
    }
    assert_true(t < 20000);
    viewport_destroy(v);
    const double radius = 0.08 * t; // the window's radius until one is chosen
    enum { N = 81 };                // samples 2 m apart over the brush
    static double before[N * N];
    for (int pass = 0; pass < 2; pass++) {
        double most = 0, sum = 0;
        int inside = 0;
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                double x = hit[0] + (i - N / 2) * radius / (N / 2),
                       z = hit[2] + (j - N / 2) * radius / (N / 2), h;
                if (world_sample(w, 0, x, z, &h, &err) != 0) fail_msg("sample: %s", err.msg);
                if (pass == 0) {
                    before[j * N + i] = h;
                    continue;
                }
                double d = fabs(h - before[j * N + i]);
                most = fmax(most, d);
                if (hypot(x - hit[0], z - hit[2]) < radius) sum += d, inside++;
            }
        if (pass == 1) {
            printf(
                "thermal at its defaults, held 1 s at the first view (%.1f, %.1f, radius %.0f m): "
                "moved the ground up to %.2f m, %.2f m on average over the brush\n",
                hit[0], hit[2], radius, most, sum / inside);
            assert_true(most > 4.0);
            assert_true(sum / inside > 1.0);
            break;
        }
        cmd_context ctx;
        cmd_context_init(&ctx, w, NULL, stdout, OROGEN_RESOURCE_DIR);
        char script[256];
        snprintf(script, sizeof script,
                 "tool thermal radius=%.17g; stroke_begin; stroke_to %.17g %.17g; "
                 "stroke_hold 1; stroke_end",
                 radius, hit[0], hit[2]);
        if (cmd_run(&ctx, script, strlen(script), "test", &err) != 0)
            fail_msg("%s: %s", script, err.msg);
    }
    world_close(w);
}

// A brush held still keeps applying: 2 / spacing dabs a second, fractions carried, none
// with hold=0; the dabs raise the ground under it.
static void test_stroke_hold(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    assert_int_equal(b.hold, 1);
    og_error err;
    stroke *s = stroke_begin(w, &b, &err);
    assert_non_null(s);
    assert_int_equal(stroke_hold(s, 1.0, &err), 0); // before the first point: nothing
    assert_int_equal(stroke_dab_count(s), 0);
    assert_int_equal(stroke_to(s, 300, 300, 1, &err), 0);
    assert_int_equal(stroke_dab_count(s), 1);
    double before, after;
    assert_int_equal(world_sample(w, 0, 300, 300, &before, &err), 0);
    assert_int_equal(stroke_hold(s, 1.0, &err), 0); // spacing 0.25: 8 a second
    assert_int_equal(stroke_dab_count(s), 9);
    for (int i = 0; i < 10; i++) // 10 x 0.05 s: 4 dabs, the fractions carried
        assert_int_equal(stroke_hold(s, 0.05, &err), 0);
    assert_int_equal(stroke_dab_count(s), 13);
    assert_int_equal(world_sample(w, 0, 300, 300, &after, &err), 0);
    assert_true(after > before + 5 * 0.5 * 0.9); // 12 dabs of up to 0.5 m at the centre
    assert_int_equal(stroke_hold(s, -1, &err), -1);
    assert_non_null(strstr(err.msg, "seconds"));
    assert_int_equal(stroke_hold(s, NAN, &err), -1);
    assert_int_equal(stroke_end(s, &err), 0);
    assert_int_equal(brush_set(&b, "hold", "0", &err), 0);
    s = stroke_begin(w, &b, &err);
    assert_int_equal(stroke_to(s, 300, 300, 1, &err), 0);
    assert_int_equal(stroke_hold(s, 2.0, &err), 0);
    assert_int_equal(stroke_dab_count(s), 1);
    assert_int_equal(stroke_end(s, &err), 0);
    assert_int_equal(brush_set(&b, "hold", "maybe", &err), -1);
    world_close(w);
}

// A ramp lays its dab at the end: a drag (stroke_begin, stroke_to..., stroke_end, as the
// window runs it) counts it before, so the window's end of a drag keeps the ramp (it
// dropped drags that had "laid no dab"); one point is no ramp.
static void test_ramp_counts_its_dab(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    brush b;
    brush_defaults(&b, BRUSH_RAMP);
    og_error err;
    stroke *s = stroke_begin(w, &b, &err);
    assert_non_null(s);
    assert_int_equal(stroke_to(s, 300, 300, 1, &err), 0);
    assert_int_equal(stroke_dab_count(s), 0);
    assert_int_equal(stroke_to(s, 340, 300, 1, &err), 0);
    assert_int_equal(stroke_dab_count(s), 1);
    assert_int_equal(stroke_end(s, &err), 0);
    assert_int_equal(history_count(world_history(w)), 1);
    world_close(w);
}

static void test_stroke_rejects_bad_points(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    history *h = world_history(w);
    grid_rect all = whole(w, TILE_LAYER_COARSE);
    uint64_t h0 = coarse_hash(w, 0, all);
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    const double points[][3] = {
        {NAN, 100, 1},   {100, NAN, 1},        {INFINITY, 100, 1}, {100, -INFINITY, 1},
        {100, 100, NAN}, {100, 100, INFINITY}, {100, 100, 1.5},    {100, 100, -0.1},
        {-1, 100, 1},    {100, 700, 1},        {1e300, 1e300, 1},
    };
    og_error err;
    for (size_t i = 0; i < sizeof points / sizeof points[0]; i++) {
        stroke *s = stroke_begin(w, &b, &err);
        assert_non_null(s);
        err.msg[0] = 0;
        assert_int_equal(stroke_to(s, points[i][0], points[i][1], points[i][2], &err), -1);
        assert_true(strlen(err.msg) > 10);
        int is_pressure = i >= 4 && i < 8;
        assert_non_null(strstr(err.msg, is_pressure ? "pressure" : "position"));
        assert_int_equal(stroke_dab_count(s), 0);
        assert_int_equal(stroke_end(s, &err), 0); // an empty stroke: no step
        assert_int_equal(history_count(h), 0);
        assert_true(coarse_hash(w, 0, all) == h0);
    }
    // A bad point mid-stroke changes nothing more; cancelling undoes the rest.
    stroke *s = stroke_begin(w, &b, &err);
    assert_int_equal(stroke_to(s, 300, 300, 1, &err), 0);
    uint64_t h1 = coarse_hash(w, 0, all);
    assert_true(h1 != h0);
    assert_int_equal(stroke_to(s, NAN, 310, 1, &err), -1);
    assert_int_equal(stroke_to(s, 310, 310, NAN, &err), -1);
    assert_true(coarse_hash(w, 0, all) == h1);
    stroke_cancel(s);
    assert_true(coarse_hash(w, 0, all) == h0);
    assert_int_equal(history_count(h), 0);
    assert_int_equal(world_is_modified(w), 0);
    // A radius beyond the sample limit and a face that does not exist are refused.
    b.radius = 1e6;
    assert_null(stroke_begin(w, &b, &err));
    assert_non_null(strstr(err.msg, "radius"));
    b.radius = 20;
    b.face = 3;
    assert_null(stroke_begin(w, &b, &err));
    assert_non_null(strstr(err.msg, "face"));
    world_close(w);
}

static void expect_finite_area(world *w, grid_rect r, float lo, float hi) {
    float *a = read_area(w, TILE_LAYER_COARSE, 0, 0, r);
    for (size_t i = 0; i < rect_samples(r); i++)
        if (!(isfinite(a[i]) && a[i] >= lo && a[i] <= hi))
            fail_msg("sample %zu is %g, outside [%g, %g]", i, (double)a[i], (double)lo, (double)hi);
    free(a);
    // The mips too.
    grid_rect m = {r.x0 / 2, r.z0 / 2, (r.x1 + 1) / 2, (r.z1 + 1) / 2};
    a = read_area(w, TILE_LAYER_COARSE, 0, 1, m);
    for (size_t i = 0; i < rect_samples(m); i++)
        assert_true(isfinite(a[i]));
    free(a);
}

static void test_huge_values_stay_finite(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    const float lim = (float)BRUSH_HEIGHT_LIMIT;
    og_error err;
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    assert_int_equal(brush_set(&b, "amount", "10000", &err), 0);
    b.strength = 1;
    b.falloff = FALLOFF_CONSTANT;
    b.radius = 10;
    b.spacing = 0.01; // many dabs per metre
    // 9 segments of 2 m, a dab every 0.25 m: 73 dabs of 1e4 m per stroke.
    const double path[] = {200, 200, 202, 200, 200, 200, 202, 200, 200, 200,
                           202, 200, 200, 200, 202, 200, 200, 200, 202, 200};
    for (int i = 0; i < 2; i++)
        stroke_world(w, &b, path, 10);
    grid_rect r = around(201, 200, 14);
    expect_finite_area(w, r, -lim, lim);
    double top;
    assert_int_equal(world_sample(w, 0, 201, 200, &top, &err), 0);
    assert_true(top == BRUSH_HEIGHT_LIMIT);
    b.invert = 1;
    for (int i = 0; i < 4; i++)
        stroke_world(w, &b, path, 10);
    expect_finite_area(w, r, -lim, lim);
    assert_int_equal(world_sample(w, 0, 201, 200, &top, &err), 0);
    assert_true(top == -BRUSH_HEIGHT_LIMIT);
    // Noise, smooth, terrace, thermal and hydraulic on that cliff stay finite.
    const brush_tool tools[] = {BRUSH_NOISE, BRUSH_SMOOTH, BRUSH_TERRACE, BRUSH_THERMAL,
                                BRUSH_HYDRAULIC};
    for (size_t t = 0; t < 5; t++) {
        brush o;
        brush_defaults(&o, tools[t]);
        o.amount = 1e4;
        o.strength = 1;
        o.radius = 14;
        o.hydraulic.droplets = 200;
        o.terrace_step = 1e-3;
        for (int i = 0; i < 4; i++)
            dab_at(w, &o, 201 + i, 200);
        expect_finite_area(w, r, -lim, lim);
    }
    brush s;
    brush_defaults(&s, BRUSH_SET);
    assert_int_equal(brush_set(&s, "height", "1e6", &err), 0);
    s.strength = 1;
    s.falloff = FALLOFF_CONSTANT;
    dab_at(w, &s, 500, 500);
    expect_finite_area(w, around(500, 500, 20), -lim, lim);
    assert_int_equal(world_sample(w, 0, 500, 500, &top, &err), 0);
    assert_true(top == 1e6);
    world_close(w);
}

// ---------------------------------------------------------------------------
// 8. The detail layer and its PD map
// ---------------------------------------------------------------------------

static void test_detail_layer_and_pd(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0); // detail: 2797 samples, 0.25 m apart
    world *w = open_world(&p);
    layer_grid dg = grid_of(w, TILE_LAYER_DETAIL, 0);
    assert_int_equal(dg.extent, 2797);
    assert_true(dg.spacing == 0.25);
    grid_rect all = {0, 0, dg.extent, dg.extent};
    uint64_t d0 = layer_hash(w, TILE_LAYER_DETAIL, 0, all);
    uint64_t pd0 = layer_hash(w, TILE_LAYER_DETAIL_PD, 0, all);
    // Coarse edits leave the detail layer and its PD map alone.
    brush c;
    brush_defaults(&c, BRUSH_RAISE);
    c.radius = 80;
    dab_at(w, &c, 256, 256);
    brush_defaults(&c, BRUSH_SMOOTH);
    c.radius = 50;
    dab_at(w, &c, 300, 260);
    assert_true(layer_hash(w, TILE_LAYER_DETAIL, 0, all) == d0);
    assert_true(layer_hash(w, TILE_LAYER_DETAIL_PD, 0, all) == pd0);

    // A detail edit straddling detail tiles (detail sample 1024 = coarse 256).
    brush b;
    brush_defaults(&b, BRUSH_NOISE);
    b.target = TILE_LAYER_DETAIL;
    b.radius = 10;  // 40 detail samples
    b.amount = 0.5; // slopes stay within the PD range (+-8)
    b.noise_scale = 2;
    dab_at(w, &b, 256, 256);
    brush_defaults(&b, BRUSH_RAISE);
    b.target = TILE_LAYER_DETAIL;
    b.radius = 6;
    dab_at(w, &b, 262, 250);
    assert_true(layer_hash(w, TILE_LAYER_DETAIL, 0, all) != d0);

    grid_rect r = {1024 - 48, 1024 - 48, 1024 + 48, 1024 + 48};
    grid_rect src = {r.x0 - 2, r.z0 - 2, r.x1 + 2, r.z1 + 2};
    int64_t sw = src.x1 - src.x0;
    float *h = malloc(rect_samples(src) * sizeof *h);
    og_error err;
    assert_int_equal(layer_grid_read(w, &dg, src, h, &err), 0);
    int16_t *pd = read_area(w, TILE_LAYER_DETAIL_PD, 0, 0, r);
    long nonzero = 0;
    for (int64_t z = r.z0; z < r.z1; z++)
        for (int64_t x = r.x0; x < r.x1; x++) {
            const float *c0 = h + (z - src.z0) * sw + (x - src.x0);
            float row[5] = {c0[-2], c0[-1], c0[0], c0[1], c0[2]};
            float col[5] = {c0[-2 * sw], c0[-sw], c0[0], c0[sw], c0[2 * sw]};
            int16_t want[2];
            detail_pd_encode(row, col, dg.spacing, want);
            const int16_t *got = pd + 2 * ((z - r.z0) * (r.x1 - r.x0) + (x - r.x0));
            if (got[0] != want[0] || got[1] != want[1])
                fail_msg("PD at detail (%lld, %lld): %d %d, expected %d %d", (long long)x,
                         (long long)z, got[0], got[1], want[0], want[1]);
            nonzero += got[0] != 0 || got[1] != 0;
        }
    assert_true(nonzero > 1000);
    // A few samples by hand: f'(x) = (f(x-2) - 8 f(x-1) + 8 f(x+1) - f(x+2)) / (12 h).
    const int64_t probes[][2] = {{1024, 1024}, {1023, 1030}, {1040, 1000}, {1049, 1013}};
    for (size_t i = 0; i < 4; i++) {
        int64_t x = probes[i][0], z = probes[i][1];
        const float *c0 = h + (z - src.z0) * sw + (x - src.x0);
        double fx = ((double)c0[-2] - 8.0 * c0[-1] + 8.0 * c0[1] - c0[2]) / (12.0 * 0.25);
        double fz = ((double)c0[-2 * sw] - 8.0 * c0[-sw] + 8.0 * c0[sw] - c0[2 * sw]) / 3.0;
        const int16_t *got = pd + 2 * ((z - r.z0) * (r.x1 - r.x0) + (x - r.x0));
        assert_true(fabs(got[0] - fx * 4096.0) <= 0.5 + 1e-6);
        assert_true(fabs(got[1] - fz * 4096.0) <= 0.5 + 1e-6);
    }
    free(h);
    free(pd);
    // Undo both detail steps: offsets and their PD map go back to zero.
    undo(w);
    undo(w);
    assert_true(layer_hash(w, TILE_LAYER_DETAIL, 0, all) == d0);
    int16_t *back = read_area(w, TILE_LAYER_DETAIL_PD, 0, 0, r);
    for (size_t i = 0; i < 2 * rect_samples(r); i++)
        assert_int_equal(back[i], 0);
    free(back);
    assert_true(layer_hash(w, TILE_LAYER_DETAIL_PD, 0, all) == pd0);
    world_close(w);
}

// ---------------------------------------------------------------------------
// 9. Mip upkeep
// ---------------------------------------------------------------------------

// Level-1 change on a flat world: the tent (1/4, 1/2, 1/4)^2 of the level-0 change
// around sample (2i, 2j), computed in the engine's order.
static float tent_delta(const float *d0, grid_rect r, int64_t i, int64_t j) {
    float rows[3];
    for (int b = -1; b <= 1; b++) {
        int64_t z = 2 * j + b;
        rows[b + 1] = 0.25f * at(d0, r, 2 * i - 1, z) + 0.5f * at(d0, r, 2 * i, z) +
                      0.25f * at(d0, r, 2 * i + 1, z);
    }
    return 0.25f * rows[0] + 0.5f * rows[1] + 0.25f * rows[2];
}

// Checks level `level` over the parent samples pr against the tent of the change of
// level - 1 between before and after (level-(level-1) samples 2*pr - 1 .. 2*pr + 1).
// Returns how many parent samples changed.
typedef struct mip_snapshot {
    grid_rect child, parent;
    float *child_before, *parent_before;
} mip_snapshot;

static mip_snapshot mip_snap(world *w, int level, grid_rect pr) {
    mip_snapshot m = {.parent = pr};
    m.child = (grid_rect){2 * pr.x0 - 1, 2 * pr.z0 - 1, 2 * pr.x1, 2 * pr.z1};
    m.child_before = read_area(w, TILE_LAYER_COARSE, 0, level - 1, m.child);
    m.parent_before = read_area(w, TILE_LAYER_COARSE, 0, level, pr);
    return m;
}

static long mip_check(world *w, int level, const mip_snapshot *m) {
    float *ca = read_area(w, TILE_LAYER_COARSE, 0, level - 1, m->child);
    float *pa = read_area(w, TILE_LAYER_COARSE, 0, level, m->parent);
    float *delta = malloc(rect_samples(m->child) * sizeof *delta);
    for (size_t i = 0; i < rect_samples(m->child); i++)
        delta[i] = ca[i] - m->child_before[i];
    long changed = 0;
    grid_rect pr = m->parent;
    for (int64_t j = pr.z0; j < pr.z1; j++)
        for (int64_t i = pr.x0; i < pr.x1; i++) {
            float before = at(m->parent_before, pr, i, j);
            float want = before + tent_delta(delta, m->child, i, j);
            float got = at(pa, pr, i, j);
            if (fabsf(got - want) > 1e-4f)
                fail_msg("level-%d sample (%lld, %lld): %.9g, expected %.9g", level, (long long)i,
                         (long long)j, (double)got, (double)want);
            changed += got != before;
        }
    free(ca), free(pa), free(delta);
    return changed;
}

static void mip_free(mip_snapshot *m) {
    free(m->child_before), free(m->parent_before);
}

static void test_mips_follow_level0(void **state) {
    (void)state;
    world_params p = flat_params(0, 1.0);
    p.octaves = 3;
    world *w = open_world(&p);
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    b.radius = 45;
    b.amount = 8;
    // Across level-0 tiles 0/1, then across -1/0 in both directions (negative parents).
    const double spots[][2] = {{255, 301}, {-3, 2}};
    const grid_rect l1[] = {{0, 0, 256, 256}, {-256, -256, 256, 256}};
    const grid_rect l2[] = {{0, 0, 256, 256}, {-256, -256, 256, 256}};
    for (int s = 0; s < 2; s++) {
        mip_snapshot m1 = mip_snap(w, 1, l1[s]), m2 = mip_snap(w, 2, l2[s]);
        dab_at(w, &b, spots[s][0], spots[s][1]);
        assert_true(mip_check(w, 1, &m1) > 1000);
        assert_true(mip_check(w, 2, &m2) > 200);
        if (s == 0) { // one sample by hand: delta1(i,j) = sum w_a w_b delta0(2i+a, 2j+b)
            const double wt[3] = {0.25, 0.5, 0.25};
            const int64_t ci = 128, cj = 150;
            float *after = read_area(w, TILE_LAYER_COARSE, 0, 0, m1.child);
            float *pa = read_area(w, TILE_LAYER_COARSE, 0, 1, m1.parent);
            double d1 = 0;
            for (int a = -1; a <= 1; a++)
                for (int c = -1; c <= 1; c++)
                    d1 += wt[a + 1] * wt[c + 1] *
                          ((double)at(after, m1.child, 2 * ci + a, 2 * cj + c) -
                           at(m1.child_before, m1.child, 2 * ci + a, 2 * cj + c));
            assert_true(d1 > 1.0);
            double got =
                (double)at(pa, m1.parent, ci, cj) - at(m1.parent_before, m1.parent, ci, cj);
            assert_true(fabs(got - d1) < 1e-4);
            free(after), free(pa);
        }
        undo(w); // the mip tiles come back bit for bit
        float *u1 = read_area(w, TILE_LAYER_COARSE, 0, 1, l1[s]);
        float *u2 = read_area(w, TILE_LAYER_COARSE, 0, 2, l2[s]);
        assert_memory_equal(u1, m1.parent_before, rect_samples(l1[s]) * sizeof(float));
        assert_memory_equal(u2, m2.parent_before, rect_samples(l2[s]) * sizeof(float));
        free(u1), free(u2);
        mip_free(&m1), mip_free(&m2);
    }
    world_close(w);
}

// A raise of a whole bounded world by 100 m raises every mip sample by 100 m,
// including the first row and column (the tent's child -1 lies outside the world), and
// so does every level the viewport's clipmap reads, past the one where a tile covers
// the world (a small world seen from afar was drawn flat from the generator's mips).
static void test_mips_bounded_edge(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    assert_int_equal(edit_mips_top_level(&p), EDIT_MIP_LEVELS_UNBOUNDED);
    grid_rect l1 = {0, 0, 350, 350}, l2 = {0, 0, 175, 175}, far = {0, 0, 1, 1};
    float *b1 = read_area(w, TILE_LAYER_COARSE, 0, 1, l1);
    float *b2 = read_area(w, TILE_LAYER_COARSE, 0, 2, l2);
    float before[EDIT_MIP_LEVELS_UNBOUNDED + 1];
    for (int level = 3; level <= EDIT_MIP_LEVELS_UNBOUNDED; level++) {
        float *v = read_area(w, TILE_LAYER_COARSE, 0, level, far);
        before[level] = v[0];
        free(v);
    }
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    b.radius = 2000;
    b.strength = 1;
    b.falloff = FALLOFF_CONSTANT;
    b.amount = 100;
    dab_at(w, &b, 350, 350);
    float *a1 = read_area(w, TILE_LAYER_COARSE, 0, 1, l1);
    float *a2 = read_area(w, TILE_LAYER_COARSE, 0, 2, l2);
    const int64_t probes[][2] = {{0, 0}, {0, 100}, {100, 0}, {100, 100}, {174, 174}};
    for (size_t k = 0; k < 5; k++) {
        int64_t i = probes[k][0], j = probes[k][1];
        double d1 = (double)at(a1, l1, i, j) - at(b1, l1, i, j);
        double d2 = (double)at(a2, l2, i, j) - at(b2, l2, i, j);
        if (fabs(d1 - 100.0) > 0.01 || fabs(d2 - 100.0) > 0.01)
            fail_msg("mip samples (%lld, %lld) rose by %g (level 1) and %g (level 2), not 100 m",
                     (long long)i, (long long)j, d1, d2);
    }
    for (int level = 3; level <= EDIT_MIP_LEVELS_UNBOUNDED; level++) {
        float *v = read_area(w, TILE_LAYER_COARSE, 0, level, far);
        double d = (double)v[0] - before[level];
        free(v);
        if (fabs(d - 100.0) > 0.01)
            fail_msg("level %d's first sample rose by %g, not 100 m", level, d);
    }
    free(b1), free(b2), free(a1), free(a2);
    world_close(w);
}

// ---------------------------------------------------------------------------
// 10. Unsaved changes
// ---------------------------------------------------------------------------

static void file_stat(const char *path, struct stat *st) {
    if (stat(path, st) != 0) fail_msg("cannot stat %s", path);
}

static void test_unsaved_changes(void **state) {
    (void)state;
    char dir[4096], path[4200], tiles[4200];
    snprintf(dir, sizeof dir, "%s", test_tmpdir("edit-save"));
    snprintf(path, sizeof path, "%s/w.world", dir);
    snprintf(tiles, sizeof tiles, "%s/w.tiles", dir);
    world_params p = flat_params(700, 1.0);
    // A small cache: edits after the save get evicted (written somewhere) too.
    world *w = open_world_with(&p, 6 * tile_layer_bytes(TILE_LAYER_COARSE), 0, NULL);
    grid_rect all = whole(w, TILE_LAYER_COARSE);
    uint64_t h0 = coarse_hash(w, 0, all);
    assert_int_equal(world_is_modified(w), 0);
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    b.radius = 50;
    dab_at(w, &b, 200, 200);
    assert_int_equal(world_is_modified(w), 1);
    undo(w);
    assert_int_equal(world_is_modified(w), 0);
    redo(w);
    assert_int_equal(world_is_modified(w), 1);
    const double path2[] = {300, 500, 600, 520};
    stroke_world(w, &b, path2, 2);
    uint64_t saved = coarse_hash(w, 0, all);
    og_error err;
    if (world_save(w, path, 0, &err) != 0) fail_msg("world_save: %s", err.msg);
    assert_int_equal(world_is_modified(w), 0);
    assert_non_null(world_store(w));
    int64_t stored = tile_store_count(world_store(w), -1);
    assert_true(stored > 0);
    struct stat st0;
    file_stat(tiles, &st0);

    // Edits after the save stay out of the saved tile store until the next save.
    b.radius = 120;
    const double path3[] = {100, 600, 650, 100};
    stroke_world(w, &b, path3, 2);
    assert_int_equal(world_is_modified(w), 1);
    uint64_t unsaved = coarse_hash(w, 0, all);
    assert_true(unsaved != saved);
    assert_int_equal(tile_cache_flush(world_cache(w), &err), 0);
    assert_int_equal(tile_store_count(world_store(w), -1), stored);
    struct stat st1;
    file_stat(tiles, &st1);
    assert_true(st1.st_size == st0.st_size);
    assert_true(st1.st_mtim.tv_sec == st0.st_mtim.tv_sec &&
                st1.st_mtim.tv_nsec == st0.st_mtim.tv_nsec);
    world_close(w); // without saving

    world_settings s = {.cache_budget_bytes = (size_t)64 << 20, .warn = silent};
    int errors = 0;
    w = world_load(path, &s, &errors, &err);
    if (!w) fail_msg("world_load: %s", err.msg);
    assert_int_equal(errors, 0);
    assert_int_equal(world_is_modified(w), 0);
    assert_true(coarse_hash(w, 0, all) == saved); // the unsaved stroke is gone
    assert_true(coarse_hash(w, 0, all) != h0);
    assert_int_equal(edit_undo(w, &err), 0); // history is not saved
    // A dab on the loaded world, saved again, reloads.
    dab_at(w, &b, 350, 350);
    assert_int_equal(world_is_modified(w), 1);
    uint64_t again = coarse_hash(w, 0, all);
    assert_int_equal(world_save(w, NULL, 0, &err), 0);
    world_close(w);
    w = world_load(path, &s, &errors, &err);
    assert_non_null(w);
    assert_true(coarse_hash(w, 0, all) == again);
    world_close(w);
    test_rmtree(dir);
}

// Paint saved before the material layer had mip levels (issue 26): the world's store
// holds level-0 material tiles only. Loaded, the missing levels are built, the same bytes
// a stroke would have made, without an undo step or an unsaved change.
typedef struct stored_tiles {
    tile_key keys[512];
    int count;
} stored_tiles;

static int material_mip_key(void *user, tile_key key) {
    stored_tiles *t = user;
    if (tile_key_kind(key) == TILE_LAYER_MATERIAL && key.level > 0 && t->count < 512)
        t->keys[t->count++] = key;
    return 0;
}

static void test_material_mips_filled_on_load(void **state) {
    (void)state;
    char dir[4096], path[4200];
    snprintf(dir, sizeof dir, "%s", test_tmpdir("edit-material-mips"));
    snprintf(path, sizeof path, "%s/old.world", dir);
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    brush b;
    brush_defaults(&b, BRUSH_PAINT);
    b.radius = 80;
    b.material = 3;
    const double path1[] = {150, 150, 600, 500};
    stroke_world(w, &b, path1, 2);
    og_error err = {{0}};
    if (world_save(w, path, 0, &err) != 0) fail_msg("world_save: %s", err.msg);
    // What a stroke made: every material mip tile, kept to compare.
    stored_tiles t = {.count = 0};
    if (tile_store_each(world_store(w), material_mip_key, &t, &err) != 0)
        fail_msg("tile_store_each: %s", err.msg);
    assert_true(t.count >= 3 && t.count < 512);
    size_t bytes = tile_layer_bytes(TILE_LAYER_MATERIAL);
    uint8_t *want = malloc((size_t)t.count * bytes), *got = malloc(bytes);
    tile_store_write *drop = calloc((size_t)t.count, sizeof *drop);
    assert_true(want && got && drop);
    for (int i = 0; i < t.count; i++) {
        if (tile_store_get(world_store(w), t.keys[i], want + i * bytes, bytes, &err) !=
            TILE_STORE_OK)
            fail_msg("tile_store_get: %s", err.msg);
        drop[i].key = t.keys[i];
    }
    // The file as an older Orogen wrote it: no material mips, and the world file counts
    // the tiles left (else the load takes the store for damaged and opens it read-only).
    if (tile_store_put_batch(world_store(w), drop, (size_t)t.count, &err) != 0)
        fail_msg("deleting the mips: %s", err.msg);
    int64_t left = tile_store_count(world_store(w), -1);
    world_close(w);
    world_params saved;
    world_params_default(&saved, WORLD_FLAT);
    int errors = 0;
    if (world_params_load(path, &saved, &errors, NULL, NULL, &err) != 0 || errors)
        fail_msg("world_params_load: %s", err.msg);
    assert_true(saved.tiles_saved == left + t.count);
    saved.tiles_saved = left;
    if (world_params_save(path, &saved, &err) != 0) fail_msg("world_params_save: %s", err.msg);

    world_settings s = {.cache_budget_bytes = (size_t)64 << 20, .warn = silent};
    w = world_load(path, &s, &errors, &err);
    if (!w) fail_msg("world_load: %s", err.msg);
    assert_int_equal(world_read_only(w)[0], 0);
    assert_true(material_mips_fill_missing(w) > 0); // the painted tiles
    assert_int_equal(world_is_modified(w), 0);
    assert_int_equal(history_count(world_history(w)), 0);
    for (int i = 0; i < t.count; i++) {
        tile_view v;
        if (tile_cache_acquire(world_cache(w), t.keys[i], &v, &err) != 0)
            fail_msg("tile_cache_acquire: %s", err.msg);
        memcpy(got, v.data, bytes);
        tile_cache_release(world_cache(w), &v);
        char name[96];
        if (memcmp(got, want + i * bytes, bytes) != 0)
            fail_msg("%s differs from the one the stroke made",
                     tile_key_describe(t.keys[i], name, sizeof name));
    }
    // Saved, the file has them; loaded again, nothing is missing.
    if (world_save(w, NULL, 0, &err) != 0) fail_msg("world_save: %s", err.msg);
    world_close(w);
    w = world_load(path, &s, &errors, &err);
    if (!w) fail_msg("world_load: %s", err.msg);
    assert_int_equal(material_mips_fill_missing(w), 0);
    world_close(w);
    free(want);
    free(got);
    free(drop);
    test_rmtree(dir);
}

// Undo after a save must still reach the state before the undone edit.
static void test_undo_after_save(void **state) {
    (void)state;
    char dir[4096], path[4200];
    snprintf(dir, sizeof dir, "%s", test_tmpdir("edit-undo-save"));
    snprintf(path, sizeof path, "%s/w.world", dir);
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    grid_rect all = whole(w, TILE_LAYER_COARSE);
    uint64_t h0 = coarse_hash(w, 0, all);
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    b.radius = 50;
    dab_at(w, &b, 200, 200);
    uint64_t h1 = coarse_hash(w, 0, all);
    og_error err;
    assert_int_equal(world_save(w, path, 0, &err), 0);
    undo(w);
    assert_int_equal(world_is_modified(w), 1);
    uint64_t undone = coarse_hash(w, 0, all);
    if (undone != h0)
        fail_msg("undo after save: the world hashes %s the edited state, not the state before "
                 "the edit",
                 undone == h1 ? "as" : "unlike both the original and");
    redo(w);
    assert_true(coarse_hash(w, 0, all) == h1);
    assert_int_equal(world_is_modified(w), 0);
    world_close(w);
    test_rmtree(dir);
}

// ---------------------------------------------------------------------------
// 11. Dirty rectangles
// ---------------------------------------------------------------------------

// The changed areas a subscriber to the world's change notifications hears (the
// renderer's view); other kinds of events (history changed) are skipped.
static world_subscription *changes;

static size_t take_dirty(world *w, dirty_rect *out, size_t max) {
    (void)w;
    world_event e[64];
    size_t n = 0, got;
    while (n < max && (got = world_subscription_take(changes, e, 1)) > 0)
        for (size_t i = 0; i < got; i++)
            if (e[i].kind == WORLD_EVENT_AREA) {
                assert_int_equal(e[i].level, 0);
                out[n++] = (dirty_rect){e[i].layer, e[i].face, e[i].rect};
            }
    return n;
}

static void drain_dirty(world *w) {
    world_events_unsubscribe(changes);
    changes = world_events_subscribe(world_event_hub(w), NULL, NULL);
    assert_non_null(changes);
}

static int covers(grid_rect outer, grid_rect inner) {
    return outer.x0 <= inner.x0 && outer.z0 <= inner.z0 && outer.x1 >= inner.x1 &&
           outer.z1 >= inner.z1;
}

static void expect_dirty(world *w, tile_layer layer, grid_rect want) {
    dirty_rect d[64];
    size_t n = take_dirty(w, d, 64);
    int found = 0;
    for (size_t i = 0; i < n; i++) {
        if (d[i].layer == layer && d[i].face == 0 && covers(d[i].rect, want)) found = 1;
        assert_true(d[i].layer == layer); // nothing else was reported
    }
    if (!found)
        fail_msg("no dirty rect of the %s layer covers [%lld, %lld) x [%lld, %lld)",
                 tile_layer_name(layer), (long long)want.x0, (long long)want.x1, (long long)want.z0,
                 (long long)want.z1);
    assert_int_equal(take_dirty(w, d, 64), 0);
}

static void test_dirty_rects(void **state) {
    (void)state;
    world_params p = flat_params(700, 1.0);
    world *w = open_world(&p);
    drain_dirty(w);
    const tile_layer layers[] = {TILE_LAYER_COARSE, TILE_LAYER_MATERIAL, TILE_LAYER_DETAIL};
    const brush_tool tools[] = {BRUSH_SMOOTH, BRUSH_PAINT, BRUSH_RAISE};
    for (int i = 0; i < 3; i++) {
        brush b;
        brush_defaults(&b, tools[i]);
        if (layers[i] == TILE_LAYER_DETAIL) b.target = TILE_LAYER_DETAIL;
        b.radius = 33;
        layer_grid g = grid_of(w, layers[i], 0);
        double x = 250 + 7 * i, z = 260;
        brush_dab d = {
            .brush = &b, .cx = x / g.spacing, .cz = z / g.spacing, .radius = b.radius / g.spacing};
        grid_rect want = brush_dab_rect(&d);
        dab_at(w, &b, x, z);
        expect_dirty(w, layers[i], want);
        undo(w); // undo reports the same area
        expect_dirty(w, layers[i], want);
        redo(w);
        expect_dirty(w, layers[i], want);
    }
    // Clipped to the world at its corner.
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    b.radius = 40;
    dab_at(w, &b, 699, 0);
    dirty_rect d[64];
    assert_int_equal(take_dirty(w, d, 64), 1);
    assert_true(d[0].rect.x0 == 659 && d[0].rect.x1 == 700 && d[0].rect.z0 == 0 &&
                d[0].rect.z1 == 41);
    world_close(w);
    world_events_unsubscribe(changes); // outlives its world: the hub stays until now
    changes = NULL;
}

// A stroke drawn move by move (as the window draws it) publishes each coarse area once,
// when its mip levels are current: the moves' areas as they come, nothing again at the
// end; and the mip levels it updated move by move are those of the whole change.
static void test_stroke_publishes_once(void **state) {
    (void)state;
    world_params p = flat_params(0, 1.0);
    p.octaves = 3;
    world *w = open_world(&p);
    drain_dirty(w);
    const grid_rect l1 = {0, 0, 256, 256}, l2 = {0, 0, 128, 128};
    mip_snapshot m1 = mip_snap(w, 1, l1), m2 = mip_snap(w, 2, l2);
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    b.radius = 20;
    b.amount = 5;
    og_error err;
    stroke *s = stroke_begin(w, &b, &err);
    assert_non_null(s);
    for (int i = 0; i < 12; i++) { // a zigzag: later moves cross earlier ones' areas
        double x = 100 + 20 * i, z = i % 2 ? 120 : 180;
        assert_int_equal(stroke_to(s, x, z, 1.0, &err), 0);
        dirty_rect d[64];
        size_t n = take_dirty(w, d, 64);
        assert_true(n >= 1);
        int covered = 0;
        for (size_t k = 0; k < n; k++) {
            assert_int_equal(d[k].layer, TILE_LAYER_COARSE);
            covered |= covers(d[k].rect, (grid_rect){(int64_t)x - 2, (int64_t)z - 2, (int64_t)x + 2,
                                                     (int64_t)z + 2});
        }
        assert_true(covered);
    }
    assert_int_equal(stroke_end(s, &err), 0);
    dirty_rect d[64];
    assert_int_equal(take_dirty(w, d, 64), 0); // all of it was published live
    assert_true(mip_check(w, 1, &m1) > 1000);
    assert_true(mip_check(w, 2, &m2) > 200);
    mip_free(&m1), mip_free(&m2);
    world_close(w);
    world_events_unsubscribe(changes);
    changes = NULL;
}

// Drawn move by move across the corner of four tiles at every level (the origin), the
// stroke's live updates leave each level equal to the tent of its child level's change:
// a level reads the tiles the level below it just wrote (kept pinned between them), and
// tiles it did not write this move (the negative ones, earlier moves' areas) as before.
static void test_stroke_moves_every_level(void **state) {
    (void)state;
    world_params p = flat_params(0, 1.0);
    p.octaves = 3;
    world *w = open_world(&p);
    enum { LEVELS = 9 };
    mip_snapshot m[LEVELS + 1];
    for (int level = 1; level <= LEVELS; level++) {
        int64_t r = (70 >> level) + 3;
        m[level] = mip_snap(w, level, (grid_rect){-r, -r, r + 1, r + 1});
    }
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    b.radius = 16;
    b.amount = 5;
    og_error err;
    stroke *s = stroke_begin(w, &b, &err);
    assert_non_null(s);
    for (int i = 0; i < 24; i++) { // a zigzag over the origin, back and forth
        double x = -48 + 4 * i, z = i % 2 ? -30 : 30;
        assert_int_equal(stroke_to(s, x, z, 1.0, &err), 0);
    }
    assert_int_equal(stroke_end(s, &err), 0);
    for (int level = 1; level <= LEVELS; level++) {
        assert_true(mip_check(w, level, &m[level]) > 0);
        mip_free(&m[level]);
    }
    world_close(w);
}

// ---------------------------------------------------------------------------
// 12. A planet
// ---------------------------------------------------------------------------

static void test_planet_face_edit(void **state) {
    (void)state;
    world_params p;
    world_params_default(&p, WORLD_PLANET);
    p.radius = 20000;         // a face of 314 cells at 100 m: 2 x 2 tiles
    p.ocean_level = p.radius; // a radius on planets: the sea at the datum
    p.octaves = 5;
    world *w = open_world(&p);
    int64_t n = world_grid_face_samples(&p);
    assert_int_equal(n, 512);
    assert_int_equal(edit_mips_top_level(&p), 9); // down to one sample a face
    grid_rect face = {0, 0, n, n};
    uint64_t f2 = coarse_hash(w, 2, face), f3 = coarse_hash(w, 3, face);
    grid_rect r1 = {0, 0, 256, 256};
    float *l0_before = read_area(w, TILE_LAYER_COARSE, 2, 0, face);
    float *l1_before = read_area(w, TILE_LAYER_COARSE, 2, 1, r1);
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    og_error err;
    assert_int_equal(brush_set(&b, "face", "2", &err), 0);
    b.radius = 3000; // 49 cells of 61.4 m (face-local metres are the datum's arc)
    b.amount = 50;
    const double sp = world_grid_sample_metres(&p);
    grid_rect root = {0, 0, 16, 16}; // level 5: the planet viewport's root chunk of the face
    float *l5_before = read_area(w, TILE_LAYER_COARSE, 2, 5, root);
    dab_at(w, &b, 256 * sp, 250 * sp); // the face centre, across all four tiles
    float *l5_after = read_area(w, TILE_LAYER_COARSE, 2, 5, root);
    // The face seen whole shows the dab too (level-5 sample (8, 7) covers (256, 250)).
    assert_true(at(l5_after, root, 8, 7) - at(l5_before, root, 8, 7) > 1.0f);
    free(l5_before), free(l5_after);
    uint64_t f2_after = coarse_hash(w, 2, face);
    assert_true(f2_after != f2);
    assert_true(coarse_hash(w, 3, face) == f3);
    float *l0_after = read_area(w, TILE_LAYER_COARSE, 2, 0, face);
    float *l1_after = read_area(w, TILE_LAYER_COARSE, 2, 1, r1);
    // Box filter: delta1(i,j) = mean of delta0 over children (2i..2i+1, 2j..2j+1).
    const int64_t probes[][2] = {{128, 125}, {127, 124}, {135, 130}};
    for (size_t k = 0; k < 3; k++) {
        int64_t i = probes[k][0], j = probes[k][1];
        double d1 = 0;
        for (int a = 0; a < 2; a++)
            for (int c = 0; c < 2; c++)
                d1 += 0.25 * ((double)at(l0_after, face, 2 * i + a, 2 * j + c) -
                              at(l0_before, face, 2 * i + a, 2 * j + c));
        assert_true(d1 > 1.0);
        double got = (double)at(l1_after, r1, i, j) - at(l1_before, r1, i, j);
        assert_true(fabs(got - d1) < 2e-3); // half an ulp of heights near 8 km
    }
    undo(w);
    assert_true(coarse_hash(w, 2, face) == f2);
    float *l1_undone = read_area(w, TILE_LAYER_COARSE, 2, 1, r1);
    assert_memory_equal(l1_undone, l1_before, rect_samples(r1) * sizeof(float));
    redo(w);
    assert_true(coarse_hash(w, 2, face) == f2_after);
    free(l0_before), free(l0_after), free(l1_before), free(l1_after), free(l1_undone);
    world_close(w);
}

// ---------------------------------------------------------------------------
// Undo deltas of a tile's part
// ---------------------------------------------------------------------------

static uint32_t xorshift(uint32_t *s) {
    *s ^= *s << 13, *s ^= *s >> 17, *s ^= *s << 5;
    return *s;
}

// A delta of any part (edges, single samples, the whole tile) turns before into after
// and back, on 4- and 8-byte samples, whatever mix of zero runs and noise the change
// is; a damaged delta is refused; a whole-tile zstd delta (older journals) still applies.
static void test_history_part_deltas(void **state) {
    (void)state;
    const tile_layer layers[] = {TILE_LAYER_COARSE, TILE_LAYER_MATERIAL};
    uint32_t seed = 12345;
    for (int li = 0; li < 2; li++) {
        tile_layer layer = layers[li];
        size_t bytes = tile_layer_bytes(layer), el = bytes / TILE_SAMPLES;
        uint8_t *before = malloc(bytes), *after = malloc(bytes), *t = malloc(bytes);
        assert_non_null(before), assert_non_null(after), assert_non_null(t);
        for (size_t i = 0; i < bytes; i++)
            before[i] = (uint8_t)xorshift(&seed);
        for (int round = 0; round < 40; round++) {
            memcpy(after, before, bytes);
            int64_t x0 = xorshift(&seed) % TILE_SIZE, z0 = xorshift(&seed) % TILE_SIZE;
            grid_rect part = {x0, z0, x0 + 1 + xorshift(&seed) % (TILE_SIZE - x0),
                              z0 + 1 + xorshift(&seed) % (TILE_SIZE - z0)};
            if (round == 0) part = (grid_rect){0, 0, TILE_SIZE, TILE_SIZE};
            // Round by round: sparse changes (zero runs), dense noise (stored raw), a
            // change in the high bytes only.
            for (int64_t z = part.z0; z < part.z1; z++)
                for (int64_t x = part.x0; x < part.x1; x++) {
                    uint8_t *s = after + ((size_t)z * TILE_SIZE + (size_t)x) * el;
                    int mode = round % 3;
                    if (mode == 0 && xorshift(&seed) % 7 == 0) s[0] ^= 1;
                    if (mode == 1)
                        for (size_t k = 0; k < el; k++)
                            s[k] = (uint8_t)xorshift(&seed);
                    if (mode == 2) s[el - 1] ^= 0x40;
                }
            void *delta;
            size_t size;
            assert_int_equal(history_delta_encode_part(layer, before, after, part, &delta, &size),
                             0);
            if (!memcmp(before, after, bytes)) {
                assert_null(delta);
                continue;
            }
            assert_non_null(delta);
            history_tile ht = {{layer, 0, 0, 0, 0}, 0, size, delta};
            memcpy(t, before, bytes);
            assert_int_equal(history_tile_apply(&ht, t), 0);
            assert_memory_equal(t, after, bytes);
            assert_int_equal(history_tile_apply(&ht, t), 0);
            assert_memory_equal(t, before, bytes);
            ht.bytes = size - 1; // cut short
            assert_int_equal(history_tile_apply(&ht, t), -1);
            free(delta);
        }
        // An older journal's delta: the whole tile's planes as one zstd frame.
        for (size_t i = 0; i < bytes; i++)
            after[i] = before[i] ^ (i % 5 == 0 ? (uint8_t)i : 0);
        size_t n = bytes / el;
        uint8_t *planes = malloc(bytes), *frame = malloc(ZSTD_compressBound(bytes));
        assert_non_null(planes), assert_non_null(frame);
        for (size_t i = 0; i < n; i++)
            for (size_t k = 0; k < el; k++)
                planes[k * n + i] = before[i * el + k] ^ after[i * el + k];
        size_t fs = ZSTD_compress(frame, ZSTD_compressBound(bytes), planes, bytes, 1);
        assert_false(ZSTD_isError(fs));
        history_tile old = {{layer, 0, 0, 0, 0}, 0, fs, frame};
        memcpy(t, before, bytes);
        assert_int_equal(history_tile_apply(&old, t), 0);
        assert_memory_equal(t, after, bytes);
        free(planes), free(frame);
        free(before), free(after), free(t);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_seams_bounded_coarse),
        cmocka_unit_test(test_seams_bounded_material),
        cmocka_unit_test(test_seams_bounded_detail),
        cmocka_unit_test(test_seams_unbounded_coarse),
        cmocka_unit_test(test_seams_unbounded_material),
        cmocka_unit_test(test_seams_unbounded_detail),
        cmocka_unit_test(test_seams_fractional_centre),
        cmocka_unit_test(test_out_of_core_stroke),
        cmocka_unit_test(test_undo_redo_bit_exact),
        cmocka_unit_test(test_commands_dab_undo),
        cmocka_unit_test(test_property_random_edits_undo_redo),
        cmocka_unit_test(test_history_budget_drops_oldest),
        cmocka_unit_test(test_invariant_smooth),
        cmocka_unit_test(test_smooth_matches_plain_blur),
        cmocka_unit_test(test_invariant_flatten_converges),
        cmocka_unit_test(test_invariant_thermal_talus),
        cmocka_unit_test(test_thermal_defaults_visible),
        cmocka_unit_test(test_material_mips_filled_on_load),
        cmocka_unit_test(test_stroke_hold),
        cmocka_unit_test(test_ramp_counts_its_dab),
        cmocka_unit_test(test_invariant_hydraulic_mass),
        cmocka_unit_test(test_invariant_paint),
        cmocka_unit_test(test_paint_soft_edge),
        cmocka_unit_test(test_invariant_terrace),
        cmocka_unit_test(test_invariant_ramp),
        cmocka_unit_test(test_invariant_set),
        cmocka_unit_test(test_brush_set_rejects_bad_values),
        cmocka_unit_test(test_stroke_rejects_bad_points),
        cmocka_unit_test(test_huge_values_stay_finite),
        cmocka_unit_test(test_detail_layer_and_pd),
        cmocka_unit_test(test_mips_follow_level0),
        cmocka_unit_test(test_mips_bounded_edge),
        cmocka_unit_test(test_unsaved_changes),
        cmocka_unit_test(test_undo_after_save),
        cmocka_unit_test(test_dirty_rects),
        cmocka_unit_test(test_stroke_publishes_once),
        cmocka_unit_test(test_stroke_moves_every_level),
        cmocka_unit_test(test_planet_face_edit),
        cmocka_unit_test(test_history_part_deltas),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
