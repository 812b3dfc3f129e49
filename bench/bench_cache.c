// Tile cache benchmarks, each figure beside its reference from the same run:
//  - warm lookup (request/release of a resident tile) against one read of the
//    tile's bytes (the least any user of the tile does with it);
//  - generation throughput with 1 and 2 worker threads (goal: >= 1.8x);
//  - cold loading of stored tiles through the cache (store read, checksum,
//    decompression) in decompressed MB/s, against reading the same number of raw
//    bytes from a plain file on disk, page cache dropped before each.
#include "editor/gen/gen.h"
#include "editor/world/world.h"
#include "io/tile_cache.h"

#include "bench/bench_journals.h"
#include "bench/bench_timing.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static void quiet(void *u, const char *m) {
    (void)u, (void)m;
}

static int drop_page_cache(void) {
    sync();
    FILE *f = fopen("/proc/sys/vm/drop_caches", "w");
    if (!f) return 0;
    int ok = fputs("3\n", f) >= 0;
    return fclose(f) == 0 && ok;
}

static void bench_warm_lookup(void) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    world_settings s = {.warn = quiet};
    og_error err;
    world *w = world_create(&p, &s, &err);
    tile_cache *c = world_cache(w);
    tile_key keys[64];
    for (int i = 0; i < 64; i++) {
        keys[i] = (tile_key){TILE_LAYER_COARSE, 0, 0, i % 8, i / 8};
        tile_view v;
        tile_cache_acquire(c, keys[i], &v, &err);
        tile_cache_release(c, &v);
    }
    const int n = 2000000;
    double lookup[5], touch[5];
    volatile float sink = 0;
    for (int r = 0; r < 5; r++) {
        double t0 = bench_now();
        for (int i = 0; i < n; i++) {
            tile_view v;
            tile_cache_request(c, keys[i & 63], &v);
            tile_cache_release(c, &v);
        }
        lookup[r] = (bench_now() - t0) / n * 1e9;
        t0 = bench_now();
        for (int i = 0; i < 256; i++) {
            tile_view v;
            tile_cache_request(c, keys[i & 63], &v);
            const float *h = v.data;
            float acc = 0;
            for (size_t k = 0; k < TILE_SAMPLES; k++)
                acc += h[k];
            sink += acc;
            tile_cache_release(c, &v);
        }
        touch[r] = (bench_now() - t0) / 256 * 1e9;
    }
    printf("cache warm lookup (request + release of a resident tile): %.0f ns; "
           "one pass over the tile's %zu KiB: %.0f ns; lookup = %.3f%% of the pass\n",
           bench_median(lookup, 5), tile_layer_bytes(TILE_LAYER_COARSE) >> 10,
           bench_median(touch, 5), 100.0 * bench_median(lookup, 5) / bench_median(touch, 5));
    world_close(w);
}

// Generates `count` fresh fBm tiles (8 octaves) through a cache with `workers` threads.
static double generate_rate(int workers, int count, int offset) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.generator = GEN_FBM;
    p.octaves = 8;
    world_settings s = {.workers = workers, .warn = quiet};
    og_error err;
    world *w = world_create(&p, &s, &err);
    tile_cache *c = world_cache(w);
    double t0 = bench_now();
    for (int i = 0; i < count; i++) {
        tile_view v;
        tile_cache_request(c, (tile_key){0, 0, 0, offset + i, 77}, &v);
        tile_cache_release(c, &v);
    }
    for (int i = 0; i < count; i++) {
        tile_view v;
        tile_cache_acquire(c, (tile_key){0, 0, 0, offset + i, 77}, &v, &err);
        tile_cache_release(c, &v);
    }
    double rate = count / (bench_now() - t0);
    world_close(w);
    return rate;
}

static void bench_generation_scaling(void) {
    double one[5], two[5];
    for (int r = 0; r < 5; r++) {
        one[r] = generate_rate(1, 96, r * 1000);
        two[r] = generate_rate(2, 96, r * 1000 + 500);
    }
    double a = bench_median(one, 5), b = bench_median(two, 5);
    printf("generation (fbm, 8 octaves, 256x256 tiles): 1 worker %.1f tiles/s (%.1f Msamples/s); "
           "2 workers %.1f tiles/s; scaling %.2fx (goal >= 1.8x)\n",
           a, a * TILE_SAMPLES / 1e6, b, b / a);
}

static int generated_source(void *user, tile_key key, void *out) {
    return gen_tile(user, key, out);
}

static void bench_cold_load(void) {
    const int count = 256; // 64 MiB of coarse tiles
    char dir[] = "/var/tmp/orogen-bench-XXXXXX";
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return;
    }
    char tiles[256], raw[256];
    snprintf(tiles, sizeof tiles, "%s/b.tiles", dir);
    snprintf(raw, sizeof raw, "%s/raw.bin", dir);
    og_error err;
    tile_store *store = tile_store_open(tiles, &err);
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    float *buf = malloc(tile_layer_bytes(TILE_LAYER_COARSE));
    FILE *rf = fopen(raw, "wb");
    for (int i = 0; i < count; i++) {
        tile_key k = {0, 0, 0, i % 16, i / 16};
        gen_tile(&p, k, buf);
        tile_store_put(store, k, buf, &err);
        fwrite(buf, 1, tile_layer_bytes(TILE_LAYER_COARSE), rf);
    }
    fclose(rf);
    int dropped = 1;
    double store_mbs[5], raw_mbs[5];
    double mb = count * (double)tile_layer_bytes(TILE_LAYER_COARSE) / 1e6;
    for (int r = 0; r < 5; r++) {
        dropped &= drop_page_cache();
        tile_cache *c = tile_cache_create(
            &(tile_cache_desc){
                .workers = 2, .source = generated_source, .source_user = &p, .store = store},
            &err);
        double t0 = bench_now();
        // Walk the tiles in order with a few queued ahead, as `hash` and a moving
        // camera do (queuing all first would read the file backwards: newest first).
        for (int i = 0; i < count; i++) {
            for (int a = i + 8; a > i; a--) {
                if (a >= count) continue;
                tile_view ahead;
                tile_cache_request(c, (tile_key){0, 0, 0, a % 16, a / 16}, &ahead);
                tile_cache_release(c, &ahead);
            }
            tile_view v;
            tile_cache_acquire(c, (tile_key){0, 0, 0, i % 16, i / 16}, &v, &err);
            tile_cache_release(c, &v);
        }
        store_mbs[r] = mb / (bench_now() - t0);
        tile_cache_stats st;
        tile_cache_stats_get(c, &st);
        if (st.loaded != (uint64_t)count)
            printf("  (warning: %llu of %d tiles loaded from the store)\n",
                   (unsigned long long)st.loaded, count);
        tile_cache_destroy(c, &err);

        dropped &= drop_page_cache();
        t0 = bench_now();
        rf = fopen(raw, "rb");
        size_t total = 0, got;
        while ((got = fread(buf, 1, tile_layer_bytes(TILE_LAYER_COARSE), rf)) > 0)
            total += got;
        fclose(rf);
        raw_mbs[r] = total / 1e6 / (bench_now() - t0);
    }
    printf("cold load through the cache (2 workers): %.0f MB/s decompressed; raw file read of the "
           "same bytes: %.0f MB/s; ratio %.2f%s\n",
           bench_median(store_mbs, 5), bench_median(raw_mbs, 5),
           bench_median(store_mbs, 5) / bench_median(raw_mbs, 5),
           dropped ? "" : " (page cache could not be dropped: not root? both sides warm)");
    tile_store_close(store);
    free(buf);
    unlink(tiles);
    unlink(raw);
    char wal[300];
    snprintf(wal, sizeof wal, "%s-wal", tiles);
    unlink(wal);
    snprintf(wal, sizeof wal, "%s-shm", tiles);
    unlink(wal);
    rmdir(dir);
}

int main(void) {
    bench_journals_private(); // no crash journals left in the user's folder
    bench_warm_lookup();
    bench_generation_scaling();
    bench_cold_load();
    return 0;
}
