// Tile cache: the budget holds over an area far larger than it, requests never
// block and offer coarser levels, dirty tiles survive eviction, corrupt stored
// tiles fall back to the generated terrain, edits made while tiles are written
// back are kept.
#include "editor/gen/gen.h"
#include "editor/world/world.h"
#include "io/tile_cache.h"
#include "support/test_support.h"

#include <pthread.h>
#include <sqlite3.h>
#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

static void silent(void *user, const char *m) {
    (void)user, (void)m;
}

// 16384 x 16384 samples = 64 x 64 tiles of 256 KiB (1 GiB) through a 64 MiB cache.
static void test_budget_holds_over_large_area(void **state) {
    (void)state;
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.octaves = 2.0; // cheap tiles: this test is about the cache, not the generator
    const size_t budget = (size_t)64 << 20;
    world_settings s = {.cache_budget_bytes = budget, .workers = 2, .warn = silent};
    og_error err;
    world *w = world_create(&p, &s, &err);
    assert_non_null(w);
    tile_cache *c = world_cache(w);
    const int across = 64;
    size_t peak = 0;
    float *expect = malloc(tile_layer_bytes(TILE_LAYER_COARSE));
    for (int t = 0; t < across * across; t++) {
        // Keep a few tiles queued ahead, as a viewer or a command would.
        for (int a = 1; a <= 4 && t + a < across * across; a++) {
            tile_view ahead;
            tile_key k = {TILE_LAYER_COARSE, 0, 0, (t + a) % across, (t + a) / across};
            tile_cache_request(c, k, &ahead);
            tile_cache_release(c, &ahead);
        }
        tile_key key = {TILE_LAYER_COARSE, 0, 0, t % across, t / across};
        tile_view v;
        assert_int_equal(tile_cache_acquire(c, key, &v, &err), 0);
        assert_true(tile_key_equal(v.key, key));
        if (t % 37 == 0) { // answers are right, not just present
            assert_int_equal(gen_tile(&p, key, expect), 0);
            assert_memory_equal(v.data, expect, tile_layer_bytes(TILE_LAYER_COARSE));
        }
        tile_cache_release(c, &v);
        tile_cache_stats st;
        tile_cache_stats_get(c, &st);
        if (st.resident_bytes > peak) peak = st.resident_bytes;
        assert_true(st.resident_bytes <= budget);
    }
    tile_cache_stats st;
    tile_cache_stats_get(c, &st);
    print_message("64x64 tiles through a 64 MiB budget: peak resident %zu bytes, evicted %llu, "
                  "bookkeeping outside the budget %zu bytes for %zu resident tiles\n",
                  peak, (unsigned long long)st.evicted, st.overhead_bytes, st.resident_tiles);
    assert_true(st.evicted >= (uint64_t)(across * across) - budget / tile_layer_bytes(0));
    assert_true(st.overhead_bytes < (size_t)1 << 20);
    // The digest of the whole area is the same through a roomy cache.
    uint64_t d_small, d_big, n;
    assert_int_equal(world_hash(w, 0, 0, 0, 2.0 * 16383, 2.0 * 16383, &d_small, &n, &err), 0);
    assert_int_equal(n, (uint64_t)16384 * 16384);
    world_close(w);
    s.cache_budget_bytes = (size_t)2 << 30;
    w = world_create(&p, &s, &err);
    assert_int_equal(world_hash(w, 0, 0, 0, 2.0 * 16383, 2.0 * 16383, &d_big, &n, &err), 0);
    assert_true(d_small == d_big);
    world_close(w);
    free(expect);
}

// A source the test holds closed, to prove requests return while generation waits.
typedef struct gate {
    pthread_mutex_t lock;
    pthread_cond_t cond;
    int open;
    int calls;
} gate;

static int gated_source(void *user, tile_key key, void *out) {
    gate *g = user;
    pthread_mutex_lock(&g->lock);
    g->calls++;
    while (!g->open)
        pthread_cond_wait(&g->cond, &g->lock);
    pthread_mutex_unlock(&g->lock);
    float *h = out;
    for (size_t k = 0; k < TILE_SAMPLES; k++)
        h[k] = (float)key.level;
    return key.face == 0 ? 0 : -1;
}

static void open_gate(gate *g) {
    pthread_mutex_lock(&g->lock);
    g->open = 1;
    pthread_cond_broadcast(&g->cond);
    pthread_mutex_unlock(&g->lock);
}

static void close_gate(gate *g) {
    pthread_mutex_lock(&g->lock);
    g->open = 0;
    pthread_mutex_unlock(&g->lock);
}

static int gate_calls(gate *g) {
    pthread_mutex_lock(&g->lock);
    int n = g->calls;
    pthread_mutex_unlock(&g->lock);
    return n;
}

static void test_request_never_blocks_and_falls_back(void **state) {
    (void)state;
    gate g = {PTHREAD_MUTEX_INITIALIZER, PTHREAD_COND_INITIALIZER, 0, 0};
    og_error err;
    tile_cache *c = tile_cache_create(
        &(tile_cache_desc){
            .budget_bytes = 16u << 20, .workers = 2, .source = gated_source, .source_user = &g},
        &err);
    assert_non_null(c);
    alarm(60); // if request blocked while the gate is shut, this kills the test
    tile_key fine = {TILE_LAYER_COARSE, 0, 0, 5, 6};
    tile_view v;
    assert_int_equal(tile_cache_request(c, fine, &v), TILE_PENDING);
    assert_null(v.data); // nothing coarser is resident either
    assert_int_equal(tile_cache_request(c, fine, &v), TILE_PENDING);
    tile_cache_stats st;
    tile_cache_stats_get(c, &st);
    assert_true(st.misses >= 2);
    open_gate(&g);
    // Make a coarse level resident: level 3 tile (0,0) covers level-0 tiles 0-7.
    tile_key coarse = {TILE_LAYER_COARSE, 0, 3, 0, 0};
    assert_int_equal(tile_cache_acquire(c, coarse, &v, &err), 0);
    tile_cache_release(c, &v);
    // Let the fine tile through, then shut the gate again: whatever is asked now waits
    // inside the source, so the fallback is seen every time (a gate, not a race).
    for (int i = 0; i < 2000 && tile_cache_request(c, fine, &v) != TILE_READY; i++)
        usleep(5000);
    tile_cache_release(c, &v);
    close_gate(&g);
    int calls = gate_calls(&g);
    tile_key other = {TILE_LAYER_COARSE, 0, 0, 7, 1};
    tile_status s = tile_cache_request(c, other, &v);
    assert_int_equal(s, TILE_PENDING);
    assert_non_null(v.data);
    assert_int_equal(v.key.level, 3); // the coarser level covering the same area
    assert_true(((float *)v.data)[0] == 3.0f);
    tile_cache_release(c, &v);
    for (int i = 0; i < 2000 && gate_calls(&g) == calls; i++)
        usleep(1000);
    assert_int_equal(tile_cache_request(c, other, &v), TILE_PENDING); // still held
    assert_int_equal(v.key.level, 3);
    tile_cache_release(c, &v);
    // Far away nothing coarser is resident: pending, with nothing offered.
    tile_key far = {TILE_LAYER_COARSE, 0, 0, 900, 900};
    assert_int_equal(tile_cache_request(c, far, &v), TILE_PENDING);
    assert_null(v.data);
    open_gate(&g);
    // Every request made while the gate was shut is served once it opens.
    assert_int_equal(tile_cache_acquire(c, other, &v, &err), 0);
    assert_true(tile_key_equal(v.key, other) && ((float *)v.data)[0] == 0.0f);
    tile_cache_release(c, &v);
    assert_int_equal(tile_cache_acquire(c, far, &v, &err), 0);
    assert_true(tile_key_equal(v.key, far));
    tile_cache_release(c, &v);
    // Eventually the fine tile is there.
    for (int i = 0; i < 2000 && tile_cache_request(c, fine, &v) != TILE_READY; i++)
        usleep(5000);
    assert_non_null(v.data);
    assert_true(tile_key_equal(v.key, fine));
    tile_cache_release(c, &v);
    // Keys the source refuses are reported, not cached as terrain.
    tile_key outside = {TILE_LAYER_COARSE, 1, 0, 0, 0};
    assert_int_equal(tile_cache_acquire(c, outside, &v, &err), -1);
    assert_non_null(strstr(err.msg, "outside the world"));
    assert_int_equal(tile_cache_request(c, outside, &v), TILE_INVALID);
    alarm(0);
    assert_int_equal(tile_cache_destroy(c, &err), 0);
}

static int plain_source(void *user, tile_key key, void *out) {
    (void)user;
    float *h = out;
    for (size_t k = 0; k < TILE_SAMPLES; k++)
        h[k] = (float)(key.tx * 1000 + key.ty);
    return 0;
}

static void test_dirty_tiles_written_back_before_eviction(void **state) {
    (void)state;
    const char *dir = test_tmpdir("cache");
    char path[4200];
    snprintf(path, sizeof path, "%s/w.tiles", dir);
    og_error err;
    tile_store *store = tile_store_open(path, &err);
    assert_non_null(store);
    // Room for two tiles only.
    tile_cache *c = tile_cache_create(
        &(tile_cache_desc){.budget_bytes = 2 * tile_layer_bytes(TILE_LAYER_COARSE),
                           .workers = 2,
                           .source = plain_source,
                           .store = store},
        &err);
    tile_key edited = {TILE_LAYER_COARSE, 0, 0, 1, 1};
    tile_view v;
    assert_int_equal(tile_cache_acquire_write(c, edited, &v, &err), 0);
    ((float *)v.data)[123] = 42.5f;
    tile_cache_release(c, &v);
    assert_true(tile_cache_has_dirty(c));
    for (int i = 2; i < 8; i++) {
        assert_int_equal(tile_cache_acquire(c, (tile_key){0, 0, 0, i, 0}, &v, &err), 0);
        tile_cache_release(c, &v);
    }
    tile_cache_stats st;
    tile_cache_stats_get(c, &st);
    assert_true(st.written >= 1);
    assert_true(tile_store_has(store, edited));
    assert_int_equal(tile_cache_acquire(c, edited, &v, &err), 0);
    assert_true(((float *)v.data)[123] == 42.5f);
    assert_true(((float *)v.data)[124] == 1001.0f);
    tile_cache_release(c, &v);
    tile_cache_stats_get(c, &st);
    assert_true(st.loaded >= 1);
    assert_int_equal(tile_cache_destroy(c, &err), 0);
    tile_store_close(store);
    test_rmtree(dir);
}

// Writers keep editing tiles while the workers evict them, writing each back to
// the store with the cache unlocked: a writer must never change a tile the store is
// reading (TSan watches this test), and no edit may be lost.
typedef struct writer_args {
    tile_cache *cache;
    int row, rounds;
    float last[4]; // what this writer last wrote into each tile of its row
} writer_args;

// Edits tiles of one row in a scrambled order, so a tile being evicted (written
// back) is often the next one asked for.
static void *edit_row_of_tiles(void *arg) {
    writer_args *a = arg;
    og_error err;
    uint32_t rng = 12345u + (uint32_t)a->row;
    for (int r = 1; r <= a->rounds; r++) {
        rng = rng * 1664525u + 1013904223u;
        int tx = (int)(rng >> 30);
        tile_view v;
        if (tile_cache_acquire_write(a->cache, (tile_key){0, 0, 0, tx, a->row}, &v, &err))
            return "acquire_write failed";
        float *h = v.data;
        for (size_t k = 0; k < TILE_SAMPLES; k++)
            h[k] = (float)r;
        a->last[tx] = (float)r;
        tile_cache_release(a->cache, &v);
    }
    return NULL;
}

static void test_edits_during_write_back_are_kept(void **state) {
    (void)state;
    const char *dir = test_tmpdir("cache");
    char path[4200];
    snprintf(path, sizeof path, "%s/w.tiles", dir);
    og_error err;
    tile_store *store = tile_store_open(path, &err);
    assert_non_null(store);
    // Room for three tiles: fewer than either writer's four, so evictions (and
    // write-backs) happen even when the threads happen not to overlap at all, as
    // under a slow sanitizer run where one finishes before the other starts.
    tile_cache *c = tile_cache_create(
        &(tile_cache_desc){.budget_bytes = 3 * tile_layer_bytes(TILE_LAYER_COARSE),
                           .workers = 2,
                           .source = plain_source,
                           .store = store},
        &err);
    assert_non_null(c);
    writer_args args[2] = {{c, 0, 150, {0}}, {c, 1, 150, {0}}};
    pthread_t th[2];
    for (int i = 0; i < 2; i++)
        assert_int_equal(pthread_create(&th[i], NULL, edit_row_of_tiles, &args[i]), 0);
    for (int i = 0; i < 2; i++) {
        void *failed;
        pthread_join(th[i], &failed);
        assert_null(failed);
    }
    tile_cache_stats st;
    tile_cache_stats_get(c, &st);
    assert_true(st.written >= 8);
    assert_int_equal(tile_cache_flush(c, &err), 0);
    assert_int_equal(tile_cache_destroy(c, &err), 0);
    // Every tile in the store holds its writer's last edit, whole.
    float *h = malloc(tile_layer_bytes(TILE_LAYER_COARSE));
    for (int row = 0; row < 2; row++)
        for (int tx = 0; tx < 4; tx++) {
            if (args[row].last[tx] == 0.0f) continue; // never picked
            assert_int_equal(tile_store_get(store, (tile_key){0, 0, 0, tx, row}, h,
                                            tile_layer_bytes(TILE_LAYER_COARSE), &err),
                             TILE_STORE_OK);
            for (size_t k = 0; k < TILE_SAMPLES; k += 997)
                assert_true(h[k] == args[row].last[tx]);
        }
    free(h);
    tile_store_close(store);
    test_rmtree(dir);
}

typedef struct warnings {
    char last[2048];
    int count;
} warnings;

static void collect(void *user, const char *m) {
    warnings *w = user;
    snprintf(w->last, sizeof w->last, "%s", m);
    w->count++;
}

static void test_corrupt_stored_tile_falls_back(void **state) {
    (void)state;
    const char *dir = test_tmpdir("cache-corrupt");
    char path[4200];
    snprintf(path, sizeof path, "%s/w.tiles", dir);
    og_error err;
    tile_store *store = tile_store_open(path, &err);
    float *data = malloc(tile_layer_bytes(TILE_LAYER_COARSE));
    for (size_t k = 0; k < TILE_SAMPLES; k++)
        data[k] = 7.0f;
    tile_key key = {TILE_LAYER_COARSE, 0, 0, 3, -4};
    assert_int_equal(tile_store_put(store, key, data, &err), 0);
    tile_store_close(store);
    sqlite3 *db;
    assert_int_equal(sqlite3_open(path, &db), SQLITE_OK);
    assert_int_equal(
        sqlite3_exec(db, "UPDATE tiles SET data = randomblob(length(data))", NULL, NULL, NULL),
        SQLITE_OK);
    sqlite3_close(db);
    store = tile_store_open(path, &err);
    assert_non_null(store);
    warnings warn = {{0}, 0};
    tile_cache *c = tile_cache_create(
        &(tile_cache_desc){
            .source = plain_source, .store = store, .warn = collect, .warn_user = &warn},
        &err);
    tile_view v;
    assert_int_equal(tile_cache_acquire(c, key, &v, &err), 0);
    assert_true(((float *)v.data)[0] == 3.0f * 1000 - 4); // the generated terrain
    tile_cache_release(c, &v);
    assert_int_equal(warn.count, 1);
    assert_non_null(strstr(warn.last, "(3,-4)"));
    tile_cache_stats st;
    tile_cache_stats_get(c, &st);
    assert_int_equal(st.corrupt, 1);
    tile_cache_destroy(c, &err);
    tile_store_close(store);
    free(data);
    test_rmtree(dir);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_budget_holds_over_large_area),
        cmocka_unit_test(test_request_never_blocks_and_falls_back),
        cmocka_unit_test(test_dirty_tiles_written_back_before_eviction),
        cmocka_unit_test(test_edits_during_write_back_are_kept),
        cmocka_unit_test(test_corrupt_stored_tile_falls_back),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
