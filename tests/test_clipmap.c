// Clipmap geometry and level windows: the pieces tile every level exactly once around
// the finer level for each of its four positions; the toroidal window holds exactly
// the samples of its origin after any move, copies only what entered, never blocks,
// and re-reads edited samples; its cells' height bounds hold every sample of a range.
// Refined pieces cover their quads at half the spacing and close their borders' T-junctions
// with zero-area triangles; the refinement cells bound every refined vertex and its move;
// the skyline is found at the far ridge, not on the nearer, lower ground.
#include "io/tile_cache.h"
#include "renderer/clip_cells.h"
#include "renderer/clip_refine.h"
#include "renderer/clip_refine_mesh.h"
#include "renderer/clip_skyline.h"
#include "renderer/clip_window.h"
#include "renderer/clipmap_mesh.h"

#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

// Marks the quad cells a piece's triangles cover (two triangles per cell); returns
// the number of triangles with zero area.
static int cover(const clipmap_mesh *m, const clip_piece *p, int *cells) {
    int n = m->n, degenerate = 0;
    for (uint32_t t = p->first; t < p->first + p->count; t += 3) {
        int x[3], z[3];
        for (int k = 0; k < 3; k++) {
            uint16_t v = m->indices[t + k];
            x[k] = m->vertices[2 * v], z[k] = m->vertices[2 * v + 1];
        }
        int area2 = (x[1] - x[0]) * (z[2] - z[0]) - (x[2] - x[0]) * (z[1] - z[0]);
        if (area2 == 0) {
            degenerate++;
            continue;
        }
        assert_int_equal(abs(area2), 1); // half a unit quad
        int cx = x[0] < x[1] ? x[0] : x[1], cz = z[0] < z[1] ? z[0] : z[1];
        cx = x[2] < cx ? x[2] : cx, cz = z[2] < cz ? z[2] : cz;
        cells[cz * (n - 1) + cx]++;
    }
    return degenerate;
}

static void check_level(const clipmap_mesh *m, int finest, int off_x, int off_z) {
    int n = m->n, q = n - 1;
    int *cells = calloc((size_t)q * q, sizeof *cells);
    clip_trim trims[2];
    clipmap_trims_for_offset(m->m, off_x, off_z, trims);
    for (size_t i = 0; i < m->piece_count; i++) {
        const clip_piece *p = &m->pieces[i];
        if (p->kind == CLIP_PIECE_INTERIOR && !finest) continue;
        if (p->kind == CLIP_PIECE_TRIM &&
            (finest || (p->trim != (int)trims[0] && p->trim != (int)trims[1])))
            continue;
        int degenerate = cover(m, p, cells);
        assert_int_equal(degenerate, p->kind == CLIP_PIECE_DEGENERATE ? (int)p->count / 3 : 0);
    }
    // The finer level: 2m-1 of this level's quads per side at the offset.
    int fine = 2 * m->m - 1;
    for (int z = 0; z < q; z++)
        for (int x = 0; x < q; x++) {
            int inside =
                !finest && x >= off_x && x < off_x + fine && z >= off_z && z < off_z + fine;
            assert_int_equal(cells[z * q + x], inside ? 0 : 2);
        }
    free(cells);
}

static void test_pieces_tile_each_level_once(void **state) {
    (void)state;
    int sizes[3] = {15, 63, 255};
    for (int s = 0; s < 3; s++) {
        clipmap_mesh m;
        assert_int_equal(clipmap_mesh_build(&m, sizes[s]), 0);
        assert_int_equal(m.m, (sizes[s] + 1) / 4);
        int kinds[5] = {0};
        long quads[5] = {0}; // blocks and the interior come in parts, for culling
        for (size_t i = 0; i < m.piece_count; i++) {
            const clip_piece *pc = &m.pieces[i];
            kinds[pc->kind]++;
            quads[pc->kind] += (long)(pc->x1 - pc->x0) * (pc->z1 - pc->z0);
            if (pc->kind == CLIP_PIECE_BLOCK || pc->kind == CLIP_PIECE_INTERIOR) {
                assert_true(pc->x1 - pc->x0 <= CLIPMAP_CULL_QUADS);
                assert_true(pc->z1 - pc->z0 <= CLIPMAP_CULL_QUADS);
                assert_int_equal(pc->count, 6u * (pc->x1 - pc->x0) * (pc->z1 - pc->z0));
            }
        }
        int parts = (m.m - 1 + CLIPMAP_CULL_QUADS - 1) / CLIPMAP_CULL_QUADS;
        assert_int_equal(kinds[CLIP_PIECE_BLOCK], 12 * parts * parts);
        assert_int_equal(quads[CLIP_PIECE_BLOCK], 12L * (m.m - 1) * (m.m - 1)); // m x m vertices
        assert_int_equal(kinds[CLIP_PIECE_FIXUP], 4);
        assert_int_equal(kinds[CLIP_PIECE_TRIM], CLIP_TRIM_COUNT);
        assert_int_equal(kinds[CLIP_PIECE_DEGENERATE], 1);
        assert_int_equal(quads[CLIP_PIECE_INTERIOR], 4L * m.m * m.m);
        check_level(&m, 1, 0, 0);
        for (int ox = m.m - 1; ox <= m.m; ox++)
            for (int oz = m.m - 1; oz <= m.m; oz++)
                check_level(&m, 0, ox, oz);
        clipmap_mesh_free(&m);
    }
}

static void test_bad_sizes_are_refused(void **state) {
    (void)state;
    clipmap_mesh m;
    int bad[5] = {0, 7, 100, 256, 511};
    for (int i = 0; i < 5; i++)
        assert_int_equal(clipmap_mesh_build(&m, bad[i]), -1);
}

// Sample (x, z) of level L holds a value that names it.
static float expected(int level, int64_t x, int64_t z) {
    return (float)(x * 1000 + z) + 0.25f * (float)level;
}

typedef struct slow_source {
    pthread_mutex_t lock;
    int open;
} slow_source;

static int named_source(void *user, tile_key key, void *out) {
    slow_source *g = user;
    for (;;) {
        pthread_mutex_lock(&g->lock);
        int open = g->open;
        pthread_mutex_unlock(&g->lock);
        if (open) break;
        usleep(1000);
    }
    float *h = out;
    for (int j = 0; j < TILE_SIZE; j++)
        for (int i = 0; i < TILE_SIZE; i++)
            h[j * TILE_SIZE + i] = expected(key.level, (int64_t)key.tx * TILE_SIZE + i,
                                            (int64_t)key.ty * TILE_SIZE + j);
    return 0;
}

static void check_window(const clip_window *w) {
    const float *m = (const float *)w->mirror;
    for (int64_t z = w->have[1]; z < w->have[1] + w->size; z++)
        for (int64_t x = w->have[0]; x < w->have[0] + w->size; x++) {
            float got = m[(size_t)(z & (w->size - 1)) * w->size + (size_t)(x & (w->size - 1))];
            if (got != expected(w->level, x, z))
                fail_msg("sample (%lld, %lld): %g, expected %g", (long long)x, (long long)z, got,
                         expected(w->level, x, z));
        }
}

static int settle(clip_window *w, tile_cache *c, int64_t x, int64_t z) {
    int64_t want[2] = {x, z};
    for (int i = 0; i < 20000; i++) {
        int rc = clip_window_update(w, c, want);
        if (rc != 0) return rc;
        usleep(500);
    }
    return 0;
}

// A cache whose tiles name their samples (expected()), made as g allows.
static tile_cache *named_cache(slow_source *g) {
    og_error err;
    tile_cache *c = tile_cache_create(
        &(tile_cache_desc){
            .budget_bytes = 64u << 20, .workers = 2, .source = named_source, .source_user = g},
        &err);
    assert_non_null(c);
    return c;
}

static void test_window_moves_toroidally(void **state) {
    (void)state;
    slow_source g = {PTHREAD_MUTEX_INITIALIZER, 0};
    og_error err;
    tile_cache *c = named_cache(&g);
    clip_window w;
    assert_int_equal(clip_window_init(&w, TILE_LAYER_COARSE, 0, 2, 256), 0);
    int64_t want[2] = {-300, 77};
    // Nothing resident: the update answers at once and the window stays empty.
    assert_int_equal(clip_window_update(&w, c, want), 0);
    assert_false(clip_window_current(&w, want));
    assert_int_equal(w.texels_copied, 0);
    pthread_mutex_lock(&g.lock);
    g.open = 1;
    pthread_mutex_unlock(&g.lock);
    assert_int_equal(settle(&w, c, -300, 77), 1);
    assert_true(w.upload_all);
    check_window(&w);
    w.upload_all = 0, w.upload_count = 0;

    // Small moves copy only the entering columns and rows (and say which texels).
    struct {
        int dx, dz;
    } moves[] = {{37, 0}, {0, -5}, {-64, 130}, {255, -255}, {1, 1}};
    for (size_t i = 0; i < sizeof moves / sizeof moves[0]; i++) {
        uint64_t before = w.texels_copied;
        int64_t x = w.have[0] + moves[i].dx, z = w.have[1] + moves[i].dz;
        assert_int_equal(settle(&w, c, x, z), 1);
        check_window(&w);
        uint64_t ax = (uint64_t)abs(moves[i].dx), az = (uint64_t)abs(moves[i].dz);
        assert_int_equal(w.texels_copied - before, ax * 256 + az * 256);
        uint64_t queued = 0;
        for (int k = 0; k < w.upload_count; k++) {
            assert_true(w.uploads[k].x >= 0 && w.uploads[k].x + w.uploads[k].w <= 256);
            assert_true(w.uploads[k].z >= 0 && w.uploads[k].z + w.uploads[k].h <= 256);
            queued += (uint64_t)w.uploads[k].w * w.uploads[k].h;
        }
        assert_false(w.upload_all);
        assert_int_equal(queued, ax * 256 + az * 256);
        w.upload_count = 0;
    }
    // A jump beyond the window refills it all.
    assert_int_equal(settle(&w, c, 100000, -100000), 1);
    assert_true(w.upload_all);
    check_window(&w);

    // An edit: change a resident tile, refresh the rectangle, see exactly that change.
    tile_view v;
    int64_t ex = w.have[0] + 10, ez = w.have[1] + 20; // a sample inside the window
    tile_key k2 = {TILE_LAYER_COARSE, 0, 2, (int32_t)(ex >> 8),
                   (int32_t)(ez >> 8)}; // floor division
    assert_int_equal(tile_cache_acquire_write(c, k2, &v, &err), 0);
    ((float *)v.data)[(ez & 255) * 256 + (ex & 255)] = -7.0f;
    tile_cache_release(c, &v);
    w.upload_all = 0, w.upload_count = 0;
    clip_window_refresh(&w, c, ex, ez, ex + 1, ez + 1);
    const float *m = (const float *)w.mirror;
    assert_true(m[(size_t)(ez & 255) * 256 + (size_t)(ex & 255)] == -7.0f);
    assert_int_equal(w.upload_count, 1);
    assert_int_equal(w.uploads[0].w * w.uploads[0].h, 1);

    clip_window_free(&w);
    assert_int_equal(tile_cache_destroy(c, &err), 0);
}

// Texels queued for upload since the last call (and forgets them).
static uint64_t take_queued(clip_window *w) {
    uint64_t queued = 0;
    for (int k = 0; k < w->upload_count; k++)
        queued += (uint64_t)w->uploads[k].w * w->uploads[k].h;
    if (w->upload_all) queued += (uint64_t)w->size * w->size;
    w->upload_count = 0, w->upload_all = 0;
    return queued;
}

// Budgeted updates: jumps and first fills spread over calls, never more than the budget
// a call (moves of up to 32 rows or columns excepted), the window growing from what it
// holds of the wanted one, edits during a fill kept, and the result the same samples.
static void test_window_fills_within_a_budget(void **state) {
    (void)state;
    slow_source g = {PTHREAD_MUTEX_INITIALIZER, 1};
    og_error err;
    tile_cache *c = named_cache(&g);
    clip_window w;
    assert_int_equal(clip_window_init(&w, TILE_LAYER_COARSE, 0, 1, 256), 0);
    struct {
        int64_t x, z; // where the window goes (absolute), one jump after another
    } goals[] = {{-300, 77}, {-290, 80}, {-100, 77}, {5000, 5000}, {5000 + 200, 5000 - 40}};
    const int64_t per_call = 40 * 256;
    int calls_total = 0, edited = 0;
    for (size_t i = 0; i < sizeof goals / sizeof goals[0]; i++) {
        int64_t want[2] = {goals[i].x, goals[i].z};
        int calls = 0, rc = 0;
        for (; calls < 20000 && rc != 1; calls++) {
            int64_t budget = per_call;
            rc = clip_window_update_within(&w, c, want, &budget);
            assert_true(rc >= 0);
            uint64_t queued = take_queued(&w);
            // Small moves (<= 32 rows or columns) may exceed it; nothing else does.
            assert_true(queued <= (uint64_t)per_call || queued <= 32 * 256);
            assert_int_equal(queued, (uint64_t)(per_call - budget));
            if (rc == 1) assert_true(clip_window_current(&w, want));
            if (rc != 1) {
                assert_false(clip_window_current(&w, want));
                usleep(200); // tiles still coming
            }
            if (i == 3 && w.partial && w.valid[3] > w.valid[1]) {
                // An edit inside what a fill already holds is re-read at once.
                int64_t ex = w.valid[0] + 3, ez = w.valid[1];
                tile_view v;
                tile_key k = {TILE_LAYER_COARSE, 0, 1, (int32_t)(ex >> 8), (int32_t)(ez >> 8)};
                const float *m = (const float *)w.mirror;
                for (int pass = 0; pass < 2; pass++) { // -7, then back
                    float value = pass == 0 ? -7.0f : expected(1, ex, ez);
                    assert_int_equal(tile_cache_acquire_write(c, k, &v, &err), 0);
                    ((float *)v.data)[(ez & 255) * 256 + (ex & 255)] = value;
                    tile_cache_release(c, &v);
                    clip_window_refresh(&w, c, ex, ez, ex + 1, ez + 1);
                    assert_true(w.partial);
                    assert_true(m[(size_t)(ez & 255) * 256 + (size_t)(ex & 255)] == value);
                    assert_int_equal(take_queued(&w), 1);
                }
                edited = 1;
            }
        }
        assert_int_equal(rc, 1);
        check_window(&w);
        calls_total += calls;
        if (i == 1) assert_int_equal(calls, 1);                 // a small move: at once
        if (i == 3) assert_true(calls >= 256 * 256 / per_call); // a jump: spread
    }
    assert_true(calls_total > 10);
    assert_true(edited);
    clip_window_free(&w);
    assert_int_equal(tile_cache_destroy(c, &err), 0);
}

// A shading-slopes window (renderer/clip_slopes.h: 1024 samples, 5 x 5 tiles when not
// aligned) fills at once, as headless renders fill.
static void test_large_window_fills_at_once(void **state) {
    (void)state;
    slow_source g = {PTHREAD_MUTEX_INITIALIZER, 1};
    og_error err;
    tile_cache *c = named_cache(&g);
    clip_window w;
    assert_int_equal(clip_window_init(&w, TILE_LAYER_COARSE, 0, 1, 1024), 0);
    assert_int_equal(settle(&w, c, -300, 77), 1);
    check_window(&w);
    clip_window_free(&w);
    assert_int_equal(tile_cache_destroy(c, &err), 0);
}

// A ridge window (level 3, shift 2: the clipmap's heights) holds at each sample the
// higher of its level's sample and level 1's at the same place (x 4): here level 1's
// where x * 1000 + z > 0, its own elsewhere, both in one window. Moves and an edit of a
// level-1 sample (above the level's, then below it) keep it so.
static void test_ridge_window_takes_the_higher(void **state) {
    (void)state;
    slow_source g = {PTHREAD_MUTEX_INITIALIZER, 1};
    og_error err;
    tile_cache *c = named_cache(&g);
    clip_window w;
    assert_int_equal(clip_window_init_ridges(&w, 0, 3, 256, 2), 0);
    int own = 0, finer = 0;
    const int64_t origins[][2] = {{-128, -100}, {-100, -90}, {-140, -60}};
    for (int k = 0; k < 3; k++) {
        assert_int_equal(settle(&w, c, origins[k][0], origins[k][1]), 1);
        const float *m = (const float *)w.mirror;
        for (int64_t z = w.have[1]; z < w.have[1] + 256; z++)
            for (int64_t x = w.have[0]; x < w.have[0] + 256; x++) {
                float a = expected(3, x, z), b = expected(1, 4 * x, 4 * z);
                float got = m[(size_t)(z & 255) * 256 + (size_t)(x & 255)];
                if (got != (a > b ? a : b))
                    fail_msg("sample (%lld, %lld): %g, expected max(%g, %g)", (long long)x,
                             (long long)z, got, a, b);
                own += a > b, finer += b > a;
            }
    }
    assert_true(own > 1000 && finer > 1000);
    // An edit of level 1 under sample (ex, ez): refreshed, the sample follows it.
    int64_t ex = w.have[0] + 10, ez = w.have[1] + 20, fx = 4 * ex, fz = 4 * ez;
    tile_key k1 = {TILE_LAYER_COARSE, 0, 1, (int32_t)(fx >> 8), (int32_t)(fz >> 8)};
    const float *m = (const float *)w.mirror;
    const float values[] = {1e9f, -1e9f};
    for (int pass = 0; pass < 2; pass++) {
        tile_view v;
        assert_int_equal(tile_cache_acquire_write(c, k1, &v, &err), 0);
        ((float *)v.data)[(fz & 255) * 256 + (fx & 255)] = values[pass];
        tile_cache_release(c, &v);
        clip_window_refresh(&w, c, ex, ez, ex + 1, ez + 1);
        float want = pass == 0 ? 1e9f : expected(3, ex, ez);
        assert_true(m[(size_t)(ez & 255) * 256 + (size_t)(ex & 255)] == want);
    }
    clip_window_free(&w);
    assert_int_equal(tile_cache_destroy(c, &err), 0);
}

// The cells' bounds of any range of samples are those of its samples (a window whose
// mirror is rotated by its origin, ranges partly outside it clamped to it).
static void test_cells_bound_every_range(void **state) {
    (void)state;
    clip_window w;
    assert_int_equal(clip_window_init(&w, TILE_LAYER_COARSE, 0, 3, 256), 0);
    const int n = w.size;
    w.have[0] = -1000 + 37, w.have[1] = 5 * 256 + 200; // not a multiple of the size
    float *m = (float *)w.mirror;
    uint32_t seed = 12345;
    for (int k = 0; k < n * n; k++) {
        seed = seed * 1664525u + 1013904223u;
        m[k] = (float)(seed >> 8) / 65536.0f - 128.0f;
    }
    clip_cells cells;
    w.has_data = 0;
    clip_cells_build(&cells, &w);
    float lo, hi;
    assert_int_equal(
        clip_cells_range(&cells, w.have[0], w.have[1], w.have[0] + 3, w.have[1] + 3, &lo, &hi),
        0); // not built from a window without its samples
    w.has_data = 1;
    clip_cells_build(&cells, &w);
    for (int t = 0; t < 2000; t++) {
        seed = seed * 1664525u + 1013904223u;
        int64_t i0 = w.have[0] - 20 + (int64_t)(seed >> 8) % (n + 10);
        int64_t j0 = w.have[1] - 20 + (int64_t)(seed >> 20) % (n + 10);
        seed = seed * 1664525u + 1013904223u;
        int64_t i1 = i0 + (int64_t)(seed >> 8) % 40, j1 = j0 + (int64_t)(seed >> 20) % 40;
        float want_lo = INFINITY, want_hi = -INFINITY;
        for (int64_t z = j0; z <= j1; z++)
            for (int64_t x = i0; x <= i1; x++) {
                if (x < w.have[0] || z < w.have[1] || x >= w.have[0] + n || z >= w.have[1] + n)
                    continue;
                float v = m[(size_t)(z & (n - 1)) * n + (size_t)(x & (n - 1))];
                want_lo = fminf(want_lo, v), want_hi = fmaxf(want_hi, v);
            }
        int got = clip_cells_range(&cells, i0, j0, i1, j1, &lo, &hi);
        if (want_lo > want_hi) { // wholly outside the window
            assert_int_equal(got, 0);
            continue;
        }
        assert_int_equal(got, 1);
        if (!(lo <= want_lo && hi >= want_hi))
            fail_msg("range [%lld, %lld] x [%lld, %lld]: bounds %g .. %g miss %g .. %g",
                     (long long)i0, (long long)i1, (long long)j0, (long long)j1, lo, hi, want_lo,
                     want_hi);
    }
    // And tight to the cells around a range: a spike shows only in ranges near it.
    memset(w.mirror, 0, (size_t)n * n * sizeof(float));
    int64_t sx = w.have[0] + 100, sz = w.have[1] + 60;
    m[(size_t)(sz & (n - 1)) * n + (size_t)(sx & (n - 1))] = 1000.0f;
    clip_cells_build(&cells, &w);
    assert_int_equal(clip_cells_range(&cells, sx, sz, sx, sz, &lo, &hi), 1);
    assert_true(hi == 1000.0f && lo == 0.0f);
    assert_int_equal(clip_cells_range(&cells, sx + 17, sz - 40, sx + 60, sz + 40, &lo, &hi), 1);
    assert_true(hi == 0.0f);
    assert_int_equal(clip_cells_range(&cells, sx - 40, sz + 17, sx + 40, sz + 50, &lo, &hi), 1);
    assert_true(hi == 0.0f);
    clip_window_free(&w);
}

// A part's refined ranges over base vertices [bx0, bx1] x [bz0, bz1]: its quads cover
// each quad with 2 x 2 fine quads (two triangles each, no on-line copy among them), its
// seams are one zero-area triangle per odd vertex of its border, through that vertex's
// on-line copy and its two neighbours along the border.
static void check_fine_range(const clip_refine_mesh *r, const clip_refine_part *q, int *cells) {
    const int side = r->side;
    const size_t grid = (size_t)side * side;
    const int x0 = 2 * q->x0, z0 = 2 * q->z0, x1 = 2 * q->x1, z1 = 2 * q->z1;
    memset(cells, 0, grid * sizeof *cells);
    int degenerate = 0;
    for (uint32_t at = 0; at < q->fine_count + q->seam_count; at += 3) {
        const int seam = at >= q->fine_count;
        const uint32_t t = seam ? q->seam_first + at - q->fine_count : q->fine_first + at;
        int x[3], z[3], on_line[3], lines = 0;
        for (int k = 0; k < 3; k++) {
            uint32_t v = r->indices[t + k];
            assert_true(v < r->vertex_count);
            on_line[k] = v >= grid;
            lines += on_line[k];
            x[k] = r->vertices[2 * v] & ~CLIP_REFINE_ON_LINE, z[k] = r->vertices[2 * v + 1];
            assert_int_equal(on_line[k], (r->vertices[2 * v] & CLIP_REFINE_ON_LINE) != 0);
            assert_true(x[k] >= x0 && x[k] <= x1 && z[k] >= z0 && z[k] <= z1);
        }
        int area2 = (x[1] - x[0]) * (z[2] - z[0]) - (x[2] - x[0]) * (z[1] - z[0]);
        assert_int_equal(area2 == 0, seam);
        if (area2 == 0) {
            assert_int_equal(lines, 1);
            int k = on_line[0] ? 0 : on_line[1] ? 1 : 2, a = (k + 1) % 3, b = (k + 2) % 3;
            // Odd along the border, between its two neighbours.
            int along_x = z[k] == z0 || z[k] == z1;
            assert_true(along_x ? (x[k] & 1) == 1 : (z[k] & 1) == 1);
            assert_true(along_x || x[k] == x0 || x[k] == x1);
            assert_int_equal(x[a] + x[b], 2 * x[k]);
            assert_int_equal(z[a] + z[b], 2 * z[k]);
            assert_int_equal(abs(x[a] - x[b]) + abs(z[a] - z[b]), 2);
            degenerate++;
            continue;
        }
        assert_int_equal(lines, 0);
        assert_int_equal(abs(area2), 1);
        int cx = x[0] < x[1] ? x[0] : x[1], cz = z[0] < z[1] ? z[0] : z[1];
        cx = x[2] < cx ? x[2] : cx, cz = z[2] < cz ? z[2] : cz;
        cells[cz * side + cx]++;
    }
    for (int z = z0; z < z1; z++)
        for (int x = x0; x < x1; x++)
            assert_int_equal(cells[z * side + x], 2);
    assert_int_equal(degenerate, (x1 - x0) + (z1 - z0));
}

// The same part at the level's density, after the base mesh's indices: two triangles
// per base quad through the base mesh's vertices, split along its diagonal; counts each
// base quad in `quads`.
static void check_coarse_range(const clip_refine_mesh *r, const clipmap_mesh *m, uint32_t first,
                               uint32_t count, int bx0, int bz0, int bx1, int bz1, int *quads) {
    const int n = m->n;
    assert_true(first >= m->index_count && first + count <= m->index_count + r->coarse_count);
    for (uint32_t t = first; t < first + count; t += 3) {
        int x[3], z[3];
        for (int k = 0; k < 3; k++) {
            uint32_t v = r->coarse[t - m->index_count + k];
            assert_true(v < m->vertex_count);
            x[k] = m->vertices[2 * v], z[k] = m->vertices[2 * v + 1];
            assert_true(x[k] >= bx0 && x[k] <= bx1 && z[k] >= bz0 && z[k] <= bz1);
        }
        int area2 = (x[1] - x[0]) * (z[2] - z[0]) - (x[2] - x[0]) * (z[1] - z[0]);
        assert_int_equal(abs(area2), 1);
        int cx = x[0] < x[1] ? x[0] : x[1], cz = z[0] < z[1] ? z[0] : z[1];
        cx = x[2] < cx ? x[2] : cx, cz = z[2] < cz ? z[2] : cz;
        // The base mesh's diagonal, from (x + 1, z) to (x, z + 1): no triangle holds
        // (x, z) and (x + 1, z + 1) both.
        int low = 0, high = 0;
        for (int k = 0; k < 3; k++)
            low |= x[k] == cx && z[k] == cz, high |= x[k] == cx + 1 && z[k] == cz + 1;
        assert_false(low && high);
        quads[cz * n + cx]++;
    }
}

// Every refinable piece's parts: they tile it, each at most CLIP_REFINE_PART quads a side,
// each in both forms; other kinds have none.
static void test_refined_pieces_cover_their_quads(void **state) {
    (void)state;
    const int sizes[] = {15, 255};
    for (int s = 0; s < 2; s++) {
        clipmap_mesh m;
        clip_refine_mesh r;
        assert_int_equal(clipmap_mesh_build(&m, sizes[s]), 0);
        assert_int_equal(clip_refine_mesh_build(&r, &m), 0);
        const int side = r.side, n = m.n;
        const size_t grid = (size_t)side * side;
        assert_int_equal(side, 2 * m.n - 1);
        assert_int_equal(r.vertex_count, 2 * grid);
        int *cells = calloc(grid, sizeof *cells), *quads = calloc((size_t)n * n, sizeof *quads);
        for (size_t i = 0; i < m.piece_count; i++) {
            const clip_piece *pc = &m.pieces[i];
            if (!clip_refine_piece_refinable(pc)) {
                assert_int_equal(r.part_count[i], 0);
                continue;
            }
            memset(quads, 0, (size_t)n * n * sizeof *quads);
            assert_true(r.part_count[i] >= 1 && r.part_count[i] <= CLIP_REFINE_PARTS_MAX);
            for (uint32_t k = 0; k < r.part_count[i]; k++) {
                const clip_refine_part *q = &r.parts[r.part_first[i] + k];
                assert_true(q->x0 >= pc->x0 && q->x1 <= pc->x1 && q->z0 >= pc->z0 &&
                            q->z1 <= pc->z1);
                assert_true(q->x1 > q->x0 && q->x1 - q->x0 <= CLIP_REFINE_PART);
                assert_true(q->z1 > q->z0 && q->z1 - q->z0 <= CLIP_REFINE_PART);
                check_fine_range(&r, q, cells);
                check_coarse_range(&r, &m, q->coarse_first, q->coarse_count, q->x0, q->z0, q->x1,
                                   q->z1, quads);
            }
            for (int z = 0; z < n; z++) // every quad of the piece twice, none outside it
                for (int x = 0; x < n; x++)
                    assert_int_equal(quads[z * n + x],
                                     x >= pc->x0 && x < pc->x1 && z >= pc->z0 && z < pc->z1 ? 2
                                                                                            : 0);
        }
        free(cells);
        free(quads);
        clip_refine_mesh_free(&r);
        clipmap_mesh_free(&m);
    }
}

// Four rows of cells seen from the front, 50 m up: the far row a ridge 100 m high, the
// others flat at 0. The far row is near the skyline; the nearer rows, far under it, are
// not; a level whose cells are not built is near nothing.
static void test_skyline_at_the_far_ridge(void **state) {
    (void)state;
    static clip_cells c;
    memset(&c, 0, sizeof c);
    c.cells = 4;
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++)
            c.lo[j * 4 + i] = 0.0f, c.hi[j * 4 + i] = j == 3 ? 100.0f : 0.0f;
    const double spacing = 10.0, eye[3] = {160, 50, -100}, forward[3] = {0, 0, 1},
                 right[3] = {-1, 0, 0}, up[3] = {0, 1, 0};
    clip_skyline k;
    clip_skyline_begin(&k, eye, forward, right, up, 1.0, 0.6);
    clip_skyline_add_level(&k, &c, spacing, 0, 0, 31, 31, 1, 1, 0, 0);
    const double band = 2.0 * 2.0 / 540.0;
    assert_true(clip_skyline_near(&k, &c, spacing, 8, 24, 16, 31, band));
    assert_false(clip_skyline_near(&k, &c, spacing, 8, 0, 16, 8, band));
    assert_false(clip_skyline_near(&k, &c, spacing, 8, 8, 16, 16, band));
    c.cells = 0;
    assert_false(clip_skyline_near(&k, &c, spacing, 8, 24, 16, 31, band));
}

static float fine_height(int64_t x, int64_t z) {
    return (float)(20.0 * sin(0.37 * (double)x) * cos(0.23 * (double)z) + 0.5 * (double)(x % 7));
}

// The refinement cells of a level window and its finer window (4 samples per level
// sample) bound, over any range, every refined vertex there and the level's samples, and
// their error is at least every refined vertex's move from the level's surface (and is
// reached); the weight is 0 up to the threshold, 1 from 1.5 times it, 0 when off.
static void test_refine_cells_bound_every_refined_vertex(void **state) {
    (void)state;
    clip_window level, fine;
    assert_int_equal(clip_window_init(&level, TILE_LAYER_COARSE, 0, 2, 16), 0);
    assert_int_equal(clip_window_init(&fine, TILE_LAYER_COARSE, 0, 0, 64), 0);
    const int k = 4, n = 16;
    level.have[0] = 10, level.have[1] = 20, level.has_data = 1;
    fine.have[0] = 10 * k - 2, fine.have[1] = 20 * k - 2, fine.has_data = 1;
    float *h = (float *)level.mirror, *f = (float *)fine.mirror;
    for (int64_t z = fine.have[1]; z < fine.have[1] + 64; z++)
        for (int64_t x = fine.have[0]; x < fine.have[0] + 64; x++)
            f[(z & 63) * 64 + (x & 63)] = fine_height(x, z);
    for (int64_t j = level.have[1]; j < level.have[1] + n; j++)
        for (int64_t i = level.have[0]; i < level.have[0] + n; i++) // its own mip: off a little
            h[(j & 15) * 16 + (i & 15)] = fine_height(i * k, j * k) + (float)((i + j) % 3) - 1.0f;
    clip_refine_cells c;
    clip_refine_cells_build(&c, &level, &fine, k);
    assert_int_equal(c.cells, 2);
#define H(i, j) h[(((j) + 20) & 15) * 16 + (((i) + 10) & 15)]
    float worst = 0.0f;
    for (int j = 0; j + 1 < n; j++)
        for (int i = 0; i + 1 < n; i++) {
            // The quad's refined vertices (corner, low edges' midpoints, centre) in
            // global fine samples, and the level's surface there.
            const int64_t fx = (i + 10) * k, fz = (j + 20) * k;
            const float a = H(i, j), b = H(i + 1, j), d = H(i, j + 1), e = H(i + 1, j + 1);
            const float v[4] = {fine_height(fx, fz), fine_height(fx + 2, fz),
                                fine_height(fx, fz + 2), fine_height(fx + 2, fz + 2)};
            const float surface[4] = {a, 0.5f * (a + b), 0.5f * (a + d), 0.5f * (b + d)};
            float lo, hi, error;
            assert_true(clip_refine_cells_range(&c, 10 + i, 20 + j, 10 + i + 1, 20 + j + 1, &lo,
                                                &hi, &error));
            for (int q = 0; q < 4; q++) {
                assert_true(v[q] >= lo && v[q] <= hi);
                assert_true(fabsf(v[q] - surface[q]) <= error + 1e-4f);
                worst = fmaxf(worst, fabsf(v[q] - surface[q]));
            }
            assert_true(a >= lo && a <= hi && e >= lo && e <= hi);
        }
#undef H
    float lo, hi, error;
    assert_true(clip_refine_cells_range(&c, 10, 20, 10 + n - 1, 20 + n - 1, &lo, &hi, &error));
    assert_true(fabsf(error - worst) < 1e-4f);
    assert_false(clip_refine_cells_range(&c, 100, 20, 110, 30, &lo, &hi, &error));
    // 1 m seen straight across from 500 m at 500 px per radian: 1 pixel.
    assert_true(clip_refine_weight(1.0, 500, 500, 500, 1.0) == 0.0f);
    assert_true(fabsf(clip_refine_weight(1.25, 500, 500, 500, 1.0) - 0.5f) < 1e-5f);
    assert_true(clip_refine_weight(1.5, 500, 500, 500, 1.0) == 1.0f);
    assert_true(clip_refine_weight(50, 500, 500, 500, 0.0) == 0.0f);
    assert_true(clip_refine_weight(50, 0, 500, 500, 1.0) == 0.0f); // straight down: no move seen
    clip_window_free(&level);
    clip_window_free(&fine);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_window_fills_within_a_budget),
        cmocka_unit_test(test_pieces_tile_each_level_once),
        cmocka_unit_test(test_bad_sizes_are_refused),
        cmocka_unit_test(test_window_moves_toroidally),
        cmocka_unit_test(test_cells_bound_every_range),
        cmocka_unit_test(test_large_window_fills_at_once),
        cmocka_unit_test(test_ridge_window_takes_the_higher),
        cmocka_unit_test(test_refined_pieces_cover_their_quads),
        cmocka_unit_test(test_refine_cells_bound_every_refined_vertex),
        cmocka_unit_test(test_skyline_at_the_far_ridge),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
