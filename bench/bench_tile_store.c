// Tile store benchmark: cold loading of compressed tiles from the store against
// the physical limit of reading the same raw bytes from a plain file, in the
// same run. Also reports the compression ratio and in-memory encode/decode speed.
//
//   bench_tile_store [tiles] [runs]     (defaults: 512 tiles, 5 runs)
#include "io/tile_store.h"

#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include "bench/bench_timing.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define TILE_BYTES ((size_t)TILE_SAMPLES * sizeof(float))

// Lattice value noise with smoothstep interpolation; fBm of it gives
// terrain-like heights continuous across tile edges.
static double lattice(int64_t x, int64_t y, uint32_t seed) {
    uint64_t h = (uint64_t)x * 0x9E3779B97F4A7C15ull ^ (uint64_t)y * 0xC2B2AE3D27D4EB4Full ^ seed;
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 29;
    return (double)(h >> 11) / (double)(1ull << 53);
}

static double value_noise(double x, double y, uint32_t seed) {
    double fx = floor(x), fy = floor(y);
    int64_t ix = (int64_t)fx, iy = (int64_t)fy;
    double u = x - fx, v = y - fy;
    u = u * u * (3 - 2 * u);
    v = v * v * (3 - 2 * v);
    double a = lattice(ix, iy, seed), b = lattice(ix + 1, iy, seed);
    double c = lattice(ix, iy + 1, seed), d = lattice(ix + 1, iy + 1, seed);
    return (a + (b - a) * u) + ((c + (d - c) * u) - (a + (b - a) * u)) * v;
}

// Heights in metres (about 0-2500 m): 8 octaves, gain 0.5, lacunarity 2.
static void fill_fbm_tile(float *t, int tx, int ty) {
    for (int y = 0; y < TILE_SIZE; y++)
        for (int x = 0; x < TILE_SIZE; x++) {
            double px = (tx * TILE_SIZE + x) / 512.0, py = (ty * TILE_SIZE + y) / 512.0;
            double h = 0, amp = 1, freq = 1;
            for (int o = 0; o < 8; o++) {
                h += amp * value_noise(px * freq, py * freq, (uint32_t)o * 1013u);
                amp *= 0.5;
                freq *= 2.0;
            }
            t[y * TILE_SIZE + x] = (float)(h * 1300.0 - 100.0);
        }
}

// One loader thread: gets tiles first, first + step, ... (as tile cache
// workers would share a request queue).
typedef struct loader {
    tile_store *store;
    int first, step, ntiles, failed;
} loader;

static void *load_tiles(void *arg) {
    loader *l = arg;
    float *out = malloc(TILE_BYTES);
    og_error err;
    for (int i = l->first; out && i < l->ntiles; i += l->step) {
        tile_key k = {TILE_LAYER_COARSE, 0, 0, i % 32, i / 32};
        if (tile_store_get(l->store, k, out, TILE_BYTES, &err) != TILE_STORE_OK) l->failed = 1;
    }
    free(out);
    return NULL;
}

// Opens the store and loads every tile with nthreads threads; returns MB/s.
static double load_store(const char *path, int ntiles, int nthreads) {
    og_error err;
    double t0 = bench_now();
    tile_store *s = tile_store_open(path, &err);
    if (!s) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    pthread_t th[16];
    loader l[16];
    for (int t = 0; t < nthreads; t++) {
        l[t] = (loader){s, t, nthreads, ntiles, 0};
        pthread_create(&th[t], NULL, load_tiles, &l[t]);
    }
    for (int t = 0; t < nthreads; t++) {
        pthread_join(th[t], NULL);
        if (l[t].failed) {
            fprintf(stderr, "tile load failed\n");
            exit(1);
        }
    }
    tile_store_close(s);
    return (double)ntiles * (double)TILE_BYTES / 1e6 / (bench_now() - t0);
}

// Empties the OS page cache: globally when allowed (root), otherwise by
// asking the kernel to drop the given files' pages. Returns how it was done.
static const char *drop_caches(const char *const *files, int nfiles) {
    sync();
    FILE *f = fopen("/proc/sys/vm/drop_caches", "w");
    if (f) {
        int ok = fputs("3\n", f) >= 0;
        ok = (fclose(f) == 0) && ok;
        if (ok) return "drop_caches";
    }
    for (int i = 0; i < nfiles; i++) {
        int fd = open(files[i], O_RDONLY);
        if (fd < 0) continue;
        fdatasync(fd);
        posix_fadvise(fd, 0, 0, POSIX_FADV_DONTNEED);
        close(fd);
    }
    return "posix_fadvise(DONTNEED) (drop_caches not writable)";
}

int main(int argc, char **argv) {
    int ntiles = argc > 1 ? atoi(argv[1]) : 512;
    int runs = argc > 2 ? atoi(argv[2]) : 5;
    if (ntiles < 1 || runs < 1 || runs > 64) {
        fprintf(stderr, "usage: %s [tiles >= 1] [runs 1-64]\n", argv[0]);
        return 2;
    }
    const double raw_mb = (double)ntiles * (double)TILE_BYTES / 1e6;

    char dir[] = "/tmp/orogen-bench-store-XXXXXX";
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    char store_path[256], raw_path[256];
    snprintf(store_path, sizeof store_path, "%s/bench.tiles", dir);
    snprintf(raw_path, sizeof raw_path, "%s/bench.raw", dir);

    printf("generating %d fBm tiles (%.1f MB raw float32)...\n", ntiles, raw_mb);
    float *tiles = malloc((size_t)ntiles * TILE_BYTES);
    float *out = malloc(TILE_BYTES);
    void **blobs = calloc((size_t)ntiles, sizeof *blobs);
    size_t *sizes = calloc((size_t)ntiles, sizeof *sizes);
    if (!tiles || !out || !blobs || !sizes) {
        fprintf(stderr, "out of memory\n");
        return 1;
    }
    for (int i = 0; i < ntiles; i++)
        fill_fbm_tile(tiles + (size_t)i * TILE_SAMPLES, i % 32, i / 32);

    // In memory: encode and decode every tile, several runs.
    double enc[64], dec[64];
    size_t blob_total = 0;
    og_error err = {{0}};
    for (int r = 0; r < runs; r++) {
        double t0 = bench_now();
        blob_total = 0;
        for (int i = 0; i < ntiles; i++) {
            free(blobs[i]);
            sizes[i] =
                tile_blob_encode(TILE_LAYER_COARSE, tiles + (size_t)i * TILE_SAMPLES, &blobs[i]);
            if (!sizes[i]) {
                fprintf(stderr, "encode failed\n");
                return 1;
            }
            blob_total += sizes[i];
        }
        double t1 = bench_now();
        for (int i = 0; i < ntiles; i++)
            if (tile_blob_decode(TILE_LAYER_COARSE, blobs[i], sizes[i], out, &err) ||
                memcmp(out, tiles + (size_t)i * TILE_SAMPLES, TILE_BYTES)) {
                fprintf(stderr, "decode mismatch: %s\n", err.msg);
                return 1;
            }
        double t2 = bench_now();
        enc[r] = raw_mb / (t1 - t0);
        dec[r] = raw_mb / (t2 - t1);
    }

    // Write the store in batches of 32 tiles, then close it so the WAL is
    // checkpointed into the main file.
    tile_store *s = tile_store_open(store_path, &err);
    if (!s) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    double t0 = bench_now();
    for (int i = 0; i < ntiles; i += 32) {
        tile_store_write w[32];
        int n = ntiles - i < 32 ? ntiles - i : 32;
        for (int j = 0; j < n; j++)
            w[j] = (tile_store_write){{TILE_LAYER_COARSE, 0, 0, (i + j) % 32, (i + j) / 32},
                                      tiles + (size_t)(i + j) * TILE_SAMPLES};
        if (tile_store_put_batch(s, w, (size_t)n, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            return 1;
        }
    }
    double write_s = bench_now() - t0;
    tile_store_close(s);

    // The peer: the same raw bytes in a plain file.
    FILE *rf = fopen(raw_path, "wb");
    if (!rf || fwrite(tiles, TILE_BYTES, (size_t)ntiles, rf) != (size_t)ntiles || fflush(rf) ||
        fsync(fileno(rf)) || fclose(rf)) {
        perror(raw_path);
        return 1;
    }
    struct stat st;
    stat(store_path, &st);
    const char *files[] = {store_path, raw_path};

    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    int nthreads = cpus < 2 ? 1 : cpus > 16 ? 16 : (int)cpus;
    double cold[64], cold_mt[64], raw[64], warm[64];
    const char *how = "";
    for (int r = 0; r < runs; r++) {
        how = drop_caches(files, 2);
        cold[r] = load_store(store_path, ntiles, 1);
        warm[r] = load_store(store_path, ntiles, 1); // now in the page cache
        drop_caches(files, 2);
        cold_mt[r] = load_store(store_path, ntiles, nthreads);

        drop_caches(files, 2);
        t0 = bench_now();
        int fd = open(raw_path, O_RDONLY);
        size_t got = 0;
        ssize_t n;
        while (fd >= 0 && (n = read(fd, out, TILE_BYTES)) > 0)
            got += (size_t)n;
        if (fd >= 0) close(fd);
        if (got != (size_t)ntiles * TILE_BYTES) {
            fprintf(stderr, "short read of %s\n", raw_path);
            return 1;
        }
        raw[r] = raw_mb / (bench_now() - t0);
    }

    double c = bench_median(cold, runs), p = bench_median(raw, runs);
    printf("tiles: %d x %zu bytes, %d runs (medians); cache dropped with %s\n", ntiles, TILE_BYTES,
           runs, how);
    printf("compression: %.1f MB -> %.1f MB blobs (%.3f of raw, %.2fx); store file %.1f MB\n",
           raw_mb, (double)blob_total / 1e6, (double)blob_total / (raw_mb * 1e6),
           raw_mb * 1e6 / (double)blob_total, (double)st.st_size / 1e6);
    printf("in memory: encode %.0f MB/s, decode %.0f MB/s (decompressed bytes)\n",
           bench_median(enc, runs), bench_median(dec, runs));
    printf("store write (batches of 32, fsync per commit): %.0f MB/s\n", raw_mb / write_s);
    printf("store warm load: %.0f MB/s decompressed (1 thread)\n", bench_median(warm, runs));
    printf("store cold load, %d threads: %.0f MB/s decompressed; raw file read: %.0f MB/s; "
           "ratio %.2f\n",
           nthreads, bench_median(cold_mt, runs), p, bench_median(cold_mt, runs) / p);
    printf(
        "store cold load, 1 thread: %.0f MB/s decompressed; raw file read: %.0f MB/s; ratio %.2f\n",
        c, p, c / p);

    for (int i = 0; i < ntiles; i++)
        free(blobs[i]);
    free(blobs);
    free(sizes);
    free(tiles);
    free(out);
    unlink(store_path);
    unlink(raw_path);
    rmdir(dir);
    return 0;
}
