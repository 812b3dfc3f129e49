// Tests of the tile store: bit-exact round trips, compression, atomic batches,
// survival of SIGKILL at any instant, corrupt blobs, and refusing foreign files.
#include "io/tile_store.h"
#include "support/test_support.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#define F32_BYTES ((size_t)TILE_SAMPLES * sizeof(float))
#define U8X8_BYTES ((size_t)TILE_SAMPLES * TILE_MATERIALS)

// ---------------------------------------------------------------------------
// Data generators
// ---------------------------------------------------------------------------

static uint64_t rng_next(uint64_t *s) {
    // splitmix64: deterministic, good enough for test data.
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// Smooth terrain-like heights: a few octaves of sines, in metres.
static void fill_terrain(float *t, int seed) {
    for (int y = 0; y < TILE_SIZE; y++)
        for (int x = 0; x < TILE_SIZE; x++) {
            double fx = x + seed * 256.0, fy = y;
            double h = 800.0 + 400.0 * sin(fx * 0.011) * cos(fy * 0.013) +
                       120.0 * sin(fx * 0.041 + 1.3) * sin(fy * 0.037 + 0.4) +
                       25.0 * sin(fx * 0.13 + fy * 0.11) + 4.0 * cos(fx * 0.47 - fy * 0.39);
            t[y * TILE_SIZE + x] = (float)h;
        }
}

static void fill_noise_bits(void *t, size_t bytes, uint64_t seed) {
    uint8_t *p = t;
    for (size_t i = 0; i < bytes; i += 8) {
        uint64_t v = rng_next(&seed);
        memcpy(p + i, &v, bytes - i < 8 ? bytes - i : 8);
    }
}

// Special values: signed zeros, denormals, extremes, infinities, and NaNs with
// payloads (the store must keep any bit pattern), mixed into smooth data.
static void fill_special(float *t) {
    static const uint32_t bits[] = {0x00000000, 0x80000000, 0x00000001, 0x80000001, 0x007FFFFF,
                                    0x807FFFFF, 0x00800000, 0x7F7FFFFF, 0xFF7FFFFF, 0x7F800000,
                                    0xFF800000, 0x7FC00000, 0x7FA00001, 0xFFFFFFFF, 0x3F800000};
    fill_terrain(t, 7);
    uint64_t s = 99;
    for (int i = 0; i < TILE_SAMPLES; i++) {
        uint64_t r = rng_next(&s);
        if (r % 5 == 0) memcpy(&t[i], &bits[(r >> 8) % (sizeof bits / sizeof bits[0])], 4);
    }
    for (int i = 0; i < 15; i++)
        memcpy(&t[i], &bits[i], 4);
}

static void fill_material(uint8_t *m, int seed) {
    // Painted weights: a few soft regions, weights summing to 255 per sample.
    for (int y = 0; y < TILE_SIZE; y++)
        for (int x = 0; x < TILE_SIZE; x++) {
            uint8_t *w = m + ((size_t)y * TILE_SIZE + (size_t)x) * TILE_MATERIALS;
            memset(w, 0, TILE_MATERIALS);
            int a = (x + y + seed) / 40 % TILE_MATERIALS;
            int blend = (x * 3 + seed) % 80 < 20 ? (x * 3 + seed) % 80 * 12 : 255;
            if (blend > 255) blend = 255;
            w[a] = (uint8_t)blend;
            w[(a + 1) % TILE_MATERIALS] = (uint8_t)(255 - blend);
        }
}

static tile_key key_of(tile_layer layer, int tx, int ty) {
    return (tile_key){.layer = layer, .face = 0, .level = 0, .tx = tx, .ty = ty};
}

static char *join(const char *dir, const char *name) {
    static char buf[4][4096];
    static int next;
    char *out = buf[next++ & 3];
    int n = snprintf(out, sizeof buf[0], "%s/%s", dir, name);
    assert_true(n > 0 && (size_t)n < sizeof buf[0]);
    return out;
}

static void assert_round_trip(tile_store *s, tile_key key, const void *data, size_t bytes) {
    og_error err = {{0}};
    assert_int_equal(tile_store_put(s, key, data, &err), 0);
    void *back = malloc(bytes);
    memset(back, 0xAB, bytes);
    assert_int_equal(tile_store_get(s, key, back, bytes, &err), TILE_STORE_OK);
    assert_memory_equal(back, data, bytes);
    free(back);
}

// Bitwise CRC32C, independent of the store's table-driven one: used to check
// it and to forge blob headers with valid checksums but hostile fields.
static uint32_t ref_crc32c(const void *data, size_t n) {
    const uint8_t *p = data;
    uint32_t c = 0xFFFFFFFFu;
    while (n--) {
        c ^= *p++;
        for (int k = 0; k < 8; k++)
            c = (c >> 1) ^ (0x82F63B78u & (0u - (c & 1)));
    }
    return ~c;
}

static void put_u32le(uint8_t *p, uint32_t v) {
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

static void reseal_header(uint8_t *blob) {
    put_u32le(blob + 20, ref_crc32c(blob, 20));
}

// ---------------------------------------------------------------------------
// Round trips and compression
// ---------------------------------------------------------------------------

static void test_round_trip_layers(void **state) {
    (void)state;
    const char *dir = test_tmpdir("store-rt");
    og_error err = {{0}};
    tile_store *s = tile_store_open(join(dir, "w.tiles"), &err);
    assert_non_null(s);
    assert_string_equal(tile_store_path(s), join(dir, "w.tiles"));

    float *f = malloc(F32_BYTES);
    uint8_t *m = malloc(U8X8_BYTES);

    fill_terrain(f, 1);
    assert_round_trip(s, key_of(TILE_LAYER_COARSE, 0, 0), f, F32_BYTES);
    fill_special(f);
    assert_round_trip(s, key_of(TILE_LAYER_COARSE, -1, 5), f, F32_BYTES);
    fill_noise_bits(f, F32_BYTES, 1234);
    assert_round_trip(s, key_of(TILE_LAYER_DETAIL, 2147483647, -2147483647 - 1), f, F32_BYTES);
    for (int i = 0; i < TILE_SAMPLES; i++)
        f[i] = (i & 1) ? -0.0f : 1e-45f; // denormal min
    assert_round_trip(s, key_of(TILE_LAYER_DETAIL, 3, 3), f, F32_BYTES);
    for (int i = 0; i < TILE_SAMPLES; i++)
        f[i] = (i % 3) ? 3.4e38f : -3.4e38f;
    assert_round_trip(s, key_of(TILE_LAYER_DETAIL, 4, 3), f, F32_BYTES);
    memset(f, 0, F32_BYTES);
    assert_round_trip(s, key_of(TILE_LAYER_COARSE, 9, 9), f, F32_BYTES);

    fill_material(m, 3);
    assert_round_trip(s, key_of(TILE_LAYER_MATERIAL, 0, 0), m, U8X8_BYTES);
    fill_noise_bits(m, U8X8_BYTES, 77);
    assert_round_trip(s, key_of(TILE_LAYER_MATERIAL, 1, 0), m, U8X8_BYTES);
    // Volume bricks name their vertical index in `level`, below zero too.
    fill_noise_bits(f, F32_BYTES, 78);
    tile_key brick = {TILE_LAYER_VOLUME, 0, -3, 5, -2};
    assert_round_trip(s, brick, f, F32_BYTES);
    brick.level = 3;
    assert_false(tile_store_has(s, brick));

    // Planet faces and mip levels are distinct keys.
    tile_key k = {TILE_LAYER_COARSE, 5, TILE_MAX_LEVEL, 1, 1};
    fill_terrain(f, 2);
    assert_round_trip(s, k, f, F32_BYTES);
    k.face = 4;
    assert_false(tile_store_has(s, k));

    // Overwrite replaces; the count does not grow.
    int64_t before = tile_store_count(s, -1);
    fill_terrain(f, 3);
    assert_round_trip(s, key_of(TILE_LAYER_COARSE, 0, 0), f, F32_BYTES);
    assert_int_equal(tile_store_count(s, -1), before);
    assert_int_equal(before, 10);
    assert_int_equal(tile_store_count(s, TILE_LAYER_COARSE), 4);
    assert_int_equal(tile_store_count(s, TILE_LAYER_DETAIL), 3);
    assert_int_equal(tile_store_count(s, TILE_LAYER_MATERIAL), 2);
    assert_int_equal(tile_store_count(s, TILE_LAYER_VOLUME), 1);

    // Persisted across close/reopen.
    tile_store_close(s);
    s = tile_store_open(join(dir, "w.tiles"), &err);
    assert_non_null(s);
    float *back = malloc(F32_BYTES);
    assert_int_equal(tile_store_get(s, key_of(TILE_LAYER_COARSE, 0, 0), back, F32_BYTES, &err),
                     TILE_STORE_OK);
    assert_memory_equal(back, f, F32_BYTES);

    // Absent tile, deletion, wrong buffer size, volume layer.
    assert_int_equal(tile_store_get(s, key_of(TILE_LAYER_COARSE, 50, 50), back, F32_BYTES, &err),
                     TILE_STORE_NOT_FOUND);
    assert_true(tile_store_has(s, key_of(TILE_LAYER_COARSE, 0, 0)));
    assert_int_equal(tile_store_put(s, key_of(TILE_LAYER_COARSE, 0, 0), NULL, &err), 0);
    assert_false(tile_store_has(s, key_of(TILE_LAYER_COARSE, 0, 0)));
    assert_int_equal(tile_store_get(s, key_of(TILE_LAYER_COARSE, 0, 0), back, F32_BYTES, &err),
                     TILE_STORE_NOT_FOUND);
    assert_int_equal(tile_store_get(s, key_of(TILE_LAYER_COARSE, 9, 9), back, 100, &err),
                     TILE_STORE_ERROR);
    assert_non_null(strstr(err.msg, "buffer"));
    tile_key no_layer = {TILE_LAYER_COUNT, 0, 0, 0, 0};
    assert_int_equal(tile_store_put(s, no_layer, f, &err), -1);
    assert_non_null(strstr(err.msg, "not a tile layer"));
    tile_key bad_face = {TILE_LAYER_COARSE, 6, 0, 0, 0};
    assert_int_equal(tile_store_put(s, bad_face, f, &err), -1);
    assert_int_equal(tile_store_count(s, -1), 9);

    tile_store_close(s);
    free(f);
    free(m);
    free(back);
    test_rmtree(dir);
}

static int collect_key(void *user, tile_key key) {
    int *seen = user;
    assert_int_equal(key.layer, TILE_LAYER_COARSE);
    assert_true(key.tx >= 0 && key.tx < 16 && key.ty == -key.tx);
    seen[key.tx]++;
    return 0;
}

static int stop_after_three(void *user, tile_key key) {
    (void)key;
    return ++*(int *)user == 3;
}

static void test_each_and_count(void **state) {
    (void)state;
    const char *dir = test_tmpdir("store-each");
    og_error err = {{0}};
    tile_store *s = tile_store_open(join(dir, "w.tiles"), &err);
    assert_non_null(s);
    float *f = calloc(TILE_SAMPLES, sizeof(float));
    tile_store_write w[16];
    for (int i = 0; i < 16; i++)
        w[i] = (tile_store_write){key_of(TILE_LAYER_COARSE, i, -i), f};
    assert_int_equal(tile_store_put_batch(s, w, 16, &err), 0);
    int seen[16] = {0};
    assert_int_equal(tile_store_each(s, collect_key, seen, &err), 0);
    for (int i = 0; i < 16; i++)
        assert_int_equal(seen[i], 1);
    int calls = 0;
    assert_int_equal(tile_store_each(s, stop_after_three, &calls, &err), 0);
    assert_int_equal(calls, 3);
    assert_int_equal(tile_store_count(s, -1), 16);
    tile_store_close(s);
    free(f);
    test_rmtree(dir);
}

static void test_compression_ratio(void **state) {
    (void)state;
    float *f = malloc(F32_BYTES);
    uint8_t *m = malloc(U8X8_BYTES);
    void *blob = NULL;
    og_error err = {{0}};

    fill_terrain(f, 0);
    size_t n = tile_blob_encode(TILE_LAYER_COARSE, f, &blob);
    assert_true(n > 0);
    print_message("smooth terrain: %zu -> %zu bytes (%.3f)\n", F32_BYTES, n,
                  (double)n / (double)F32_BYTES);
    assert_true(n < F32_BYTES * 7 / 10);
    float *back = malloc(F32_BYTES);
    assert_int_equal(tile_blob_decode(TILE_LAYER_COARSE, blob, n, back, &err), 0);
    assert_memory_equal(back, f, F32_BYTES);
    // Wrong layer for the blob.
    assert_int_equal(tile_blob_decode(TILE_LAYER_DETAIL, blob, n, back, &err), -1);
    free(blob);

    memset(f, 0, F32_BYTES);
    n = tile_blob_encode(TILE_LAYER_DETAIL, f, &blob);
    assert_true(n > 0 && n < 1024);
    free(blob);

    fill_material(m, 1);
    n = tile_blob_encode(TILE_LAYER_MATERIAL, m, &blob);
    print_message("painted material: %zu -> %zu bytes (%.3f)\n", U8X8_BYTES, n,
                  (double)n / (double)U8X8_BYTES);
    assert_true(n > 0 && n < U8X8_BYTES / 10);
    free(blob);

    // Incompressible data must still round-trip (and not blow up much).
    fill_noise_bits(f, F32_BYTES, 5);
    n = tile_blob_encode(TILE_LAYER_COARSE, f, &blob);
    assert_true(n > 0 && n < F32_BYTES + F32_BYTES / 50);
    assert_int_equal(tile_blob_decode(TILE_LAYER_COARSE, blob, n, back, &err), 0);
    assert_memory_equal(back, f, F32_BYTES);
    free(blob);

    // A volume brick: two int16 distances per voxel, mostly "no edit" (INT16_MAX).
    int16_t *v = (int16_t *)f;
    for (size_t k = 0; k < 2 * (size_t)TILE_SAMPLES; k++)
        v[k] = k % 2 == 0 && k < 4000 ? (int16_t)(k * 7 % 2001 - 1000) : INT16_MAX;
    n = tile_blob_encode(TILE_LAYER_VOLUME, f, &blob);
    assert_true(n > 0 && n < F32_BYTES / 20);
    assert_int_equal(tile_blob_decode(TILE_LAYER_VOLUME, blob, n, back, &err), 0);
    assert_memory_equal(back, f, F32_BYTES);
    free(blob);
    free(f);
    free(m);
    free(back);
}

// ---------------------------------------------------------------------------
// Hostile blobs through the decoder directly
// ---------------------------------------------------------------------------

static void test_decode_hostile(void **state) {
    (void)state;
    float *f = malloc(F32_BYTES), *out = malloc(F32_BYTES);
    og_error err = {{0}};
    void *blob_v = NULL;
    fill_terrain(f, 4);
    size_t n = tile_blob_encode(TILE_LAYER_COARSE, f, &blob_v);
    assert_true(n > 64);
    const uint8_t *blob = blob_v;
    uint8_t *copy = malloc(n);

    // Header layout is the documented format; check the checksum is CRC32C.
    assert_int_equal(ref_crc32c("123456789", 9), 0xE3069283u);
    assert_memory_equal(blob, "OGTB", 4);
    uint32_t stored = (uint32_t)blob[20] | (uint32_t)blob[21] << 8 | (uint32_t)blob[22] << 16 |
                      (uint32_t)blob[23] << 24;
    uint8_t keyed[36] = {0}; // header bytes 0..19, then face, level, tx, ty (all 0 here)
    memcpy(keyed, blob, 20);
    assert_int_equal(stored, ref_crc32c(keyed, sizeof keyed));

    // Every truncation, at the heap's exact size so ASan sees any over-read.
    for (size_t len = 0; len < n; len += (len < 64 ? 1 : 97)) {
        uint8_t *t = malloc(len ? len : 1);
        memcpy(t, blob, len);
        assert_int_equal(tile_blob_decode(TILE_LAYER_COARSE, t, len, out, &err), -1);
        free(t);
    }
    assert_int_equal(tile_blob_decode(TILE_LAYER_COARSE, NULL, 0, out, &err), -1);

    // Single-bit flips anywhere.
    uint64_t s = 42;
    for (int i = 0; i < 400; i++) {
        memcpy(copy, blob, n);
        size_t pos = i < 24 * 8 ? (size_t)i / 8 : rng_next(&s) % n;
        copy[pos] ^= (uint8_t)(1u << (i % 8));
        assert_int_equal(tile_blob_decode(TILE_LAYER_COARSE, copy, n, out, &err), -1);
    }

    // A valid header over garbage, and garbage over everything.
    for (int i = 0; i < 50; i++) {
        memcpy(copy, blob, n);
        fill_noise_bits(copy + 24, n - 24, (uint64_t)i);
        assert_int_equal(tile_blob_decode(TILE_LAYER_COARSE, copy, n, out, &err), -1);
        fill_noise_bits(copy, n, (uint64_t)i + 1000);
        assert_int_equal(tile_blob_decode(TILE_LAYER_COARSE, copy, n, out, &err), -1);
    }

    // Forged headers with valid checksums but lying fields.
    struct {
        size_t off;
        uint32_t value;
        int width;
    } lies[] = {
        {4, 2, 1},
        {5, TILE_LAYER_MATERIAL, 1},
        {6, 2, 1},
        {6, 0, 1},
        {8, 0xFFFFFFFF, 4},
        {8, 1024, 4},
        {12, 0xFFFFFFFF, 4},
        {12, 0, 4},
        {12, (uint32_t)n, 4},
        {16, 0x12345678, 4},
    };
    for (size_t i = 0; i < sizeof lies / sizeof lies[0]; i++) {
        memcpy(copy, blob, n);
        if (lies[i].width == 1)
            copy[lies[i].off] = (uint8_t)lies[i].value;
        else
            put_u32le(copy + lies[i].off, lies[i].value);
        reseal_header(copy);
        assert_int_equal(tile_blob_decode(TILE_LAYER_COARSE, copy, n, out, &err), -1);
        assert_true(strlen(err.msg) > 0);
    }
    // Payload checksum mismatch is named as such.
    memcpy(copy, blob, n);
    put_u32le(copy + 16, 0xDEADBEEF);
    reseal_header(copy);
    assert_int_equal(tile_blob_decode(TILE_LAYER_COARSE, copy, n, out, &err), -1);
    assert_non_null(strstr(err.msg, "checksum"));

    // Untouched blob still decodes after all that.
    assert_int_equal(tile_blob_decode(TILE_LAYER_COARSE, blob, n, out, &err), 0);
    assert_memory_equal(out, f, F32_BYTES);
    free(copy);
    free(blob_v);
    free(f);
    free(out);
}

// ---------------------------------------------------------------------------
// Corrupt rows in a real store
// ---------------------------------------------------------------------------

static void set_row(const char *path, tile_key k, const void *data, int bytes, int as_int) {
    sqlite3 *db = NULL;
    assert_int_equal(sqlite3_open(path, &db), SQLITE_OK);
    sqlite3_stmt *st = NULL;
    assert_int_equal(sqlite3_prepare_v2(db,
                                        "UPDATE tiles SET data=?6 WHERE layer=?1 AND face=?2 "
                                        "AND level=?3 AND tx=?4 AND ty=?5",
                                        -1, &st, NULL),
                     SQLITE_OK);
    sqlite3_bind_int(st, 1, k.layer);
    sqlite3_bind_int(st, 2, k.face);
    sqlite3_bind_int(st, 3, k.level);
    sqlite3_bind_int(st, 4, k.tx);
    sqlite3_bind_int(st, 5, k.ty);
    if (as_int)
        sqlite3_bind_int(st, 6, 42);
    else
        sqlite3_bind_blob(st, 6, data, bytes, SQLITE_TRANSIENT);
    assert_int_equal(sqlite3_step(st), SQLITE_DONE);
    assert_int_equal(sqlite3_changes(db), 1);
    sqlite3_finalize(st);
    sqlite3_close(db);
}

static void test_corrupt_rows(void **state) {
    (void)state;
    const char *dir = test_tmpdir("store-corrupt");
    char path[4096];
    if (snprintf(path, sizeof path, "%s/w.tiles", dir) >= (int)sizeof path) abort();
    og_error err = {{0}};
    float *f = malloc(F32_BYTES), *out = malloc(F32_BYTES);
    uint8_t *m = malloc(U8X8_BYTES), *mout = malloc(U8X8_BYTES);
    fill_terrain(f, 5);
    fill_material(m, 5);
    tile_key victim = {TILE_LAYER_COARSE, 2, 3, -4, 5}, other = key_of(TILE_LAYER_COARSE, 1, 1);
    tile_key mat = key_of(TILE_LAYER_MATERIAL, 1, 1);

    tile_store *s = tile_store_open(path, &err);
    assert_non_null(s);
    tile_store_write w[] = {{victim, f}, {other, f}, {mat, m}};
    assert_int_equal(tile_store_put_batch(s, w, 3, &err), 0);
    void *good = NULL, *good_mat = NULL;
    size_t n = tile_blob_encode(TILE_LAYER_COARSE, f, &good);
    size_t nm = tile_blob_encode(TILE_LAYER_MATERIAL, m, &good_mat);
    uint8_t *bad = malloc(n);

    char desc[128];
    tile_key_describe(victim, desc, sizeof desc);
    uint64_t seed = 7;
    for (int variant = 0; variant < 9; variant++) {
        memcpy(bad, good, n);
        int len = (int)n, as_int = 0;
        const void *data = bad;
        switch (variant) {
        case 0:
            bad[n / 2] ^= 0x55;
            break; // flipped compressed byte
        case 1:
            bad[9] ^= 0x01;
            break; // flipped header byte
        case 2:
            len = (int)n / 2;
            break; // truncated
        case 3:
            len = 10;
            break; // truncated inside the header
        case 4:
            fill_noise_bits(bad, n, seed++);
            break; // garbage
        case 5:
            len = 1;
            bad[0] = 0;
            break; // almost empty
        case 6:
            as_int = 1;
            break; // not a blob at all
        case 7:
            data = good_mat;
            len = (int)nm;
            break; // another layer's blob
        case 8:
            bad[n - 1] ^= 0x80;
            break; // last byte (zstd epilogue)
        }
        set_row(path, victim, data, len, as_int);
        memset(&err, 0, sizeof err);
        assert_int_equal(tile_store_get(s, victim, out, F32_BYTES, &err), TILE_STORE_CORRUPT);
        assert_non_null(strstr(err.msg, desc));
        assert_non_null(strstr(err.msg, "corrupt"));
        assert_non_null(strstr(err.msg, path));
        // Other tiles are untouched and still read.
        assert_int_equal(tile_store_get(s, other, out, F32_BYTES, &err), TILE_STORE_OK);
        assert_memory_equal(out, f, F32_BYTES);
        assert_int_equal(tile_store_get(s, mat, mout, U8X8_BYTES, &err), TILE_STORE_OK);
        assert_memory_equal(mout, m, U8X8_BYTES);
        assert_true(tile_store_has(s, victim));
    }
    // Rewriting the corrupt tile heals it.
    assert_int_equal(tile_store_put(s, victim, f, &err), 0);
    assert_int_equal(tile_store_get(s, victim, out, F32_BYTES, &err), TILE_STORE_OK);
    assert_memory_equal(out, f, F32_BYTES);
    tile_store_close(s);
    free(good);
    free(good_mat);
    free(bad);
    free(f);
    free(out);
    free(m);
    free(mout);
    test_rmtree(dir);
}

// ---------------------------------------------------------------------------
// Atomic batches
// ---------------------------------------------------------------------------

static void test_batch_atomicity(void **state) {
    (void)state;
    const char *dir = test_tmpdir("store-batch");
    og_error err = {{0}};
    tile_store *s = tile_store_open(join(dir, "w.tiles"), &err);
    assert_non_null(s);
    float *a = malloc(F32_BYTES), *b = malloc(F32_BYTES), *out = malloc(F32_BYTES);
    fill_terrain(a, 1);
    fill_terrain(b, 2);
    assert_int_equal(tile_store_put(s, key_of(TILE_LAYER_COARSE, 0, 0), a, &err), 0);

    // A batch that fails on its last write (no face 6) changes nothing,
    // neither the overwrite nor the new tiles nor the deletion before it.
    tile_store_write w[] = {
        {key_of(TILE_LAYER_COARSE, 0, 0), b}, {key_of(TILE_LAYER_COARSE, 1, 0), b},
        {key_of(TILE_LAYER_DETAIL, 2, 0), a}, {key_of(TILE_LAYER_COARSE, 0, 0), NULL},
        {{TILE_LAYER_COARSE, 6, 0, 3, 0}, b},
    };
    memset(&err, 0, sizeof err);
    assert_int_equal(tile_store_put_batch(s, w, 5, &err), -1);
    assert_non_null(strstr(err.msg, "face must be"));
    assert_int_equal(tile_store_count(s, -1), 1);
    assert_int_equal(tile_store_get(s, key_of(TILE_LAYER_COARSE, 0, 0), out, F32_BYTES, &err),
                     TILE_STORE_OK);
    assert_memory_equal(out, a, F32_BYTES);

    // A batch failing inside the transaction (a trigger aborts the 3rd insert)
    // is rolled back: earlier rows of the same batch are gone too.
    sqlite3 *db = NULL;
    assert_int_equal(sqlite3_open(join(dir, "w.tiles"), &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db,
                                  "CREATE TRIGGER no_tx7 BEFORE INSERT ON tiles WHEN NEW.tx=7 "
                                  "BEGIN SELECT RAISE(ABORT, 'tx 7 refused'); END;",
                                  NULL, NULL, NULL),
                     SQLITE_OK);
    sqlite3_close(db);
    tile_store_close(s);
    s = tile_store_open(join(dir, "w.tiles"), &err);
    assert_non_null(s);
    tile_store_write w2[] = {
        {key_of(TILE_LAYER_COARSE, 0, 0), b},
        {key_of(TILE_LAYER_COARSE, 5, 0), b},
        {key_of(TILE_LAYER_COARSE, 7, 0), b},
        {key_of(TILE_LAYER_COARSE, 8, 0), b},
    };
    assert_int_equal(tile_store_put_batch(s, w2, 4, &err), -1);
    assert_non_null(strstr(err.msg, "tx 7 refused"));
    assert_non_null(strstr(err.msg, "(7,0)"));
    assert_int_equal(tile_store_count(s, -1), 1);
    assert_false(tile_store_has(s, key_of(TILE_LAYER_COARSE, 5, 0)));
    assert_int_equal(tile_store_get(s, key_of(TILE_LAYER_COARSE, 0, 0), out, F32_BYTES, &err),
                     TILE_STORE_OK);
    assert_memory_equal(out, a, F32_BYTES);
    // The connection is usable after the rollback.
    assert_int_equal(tile_store_put_batch(s, w2, 2, &err), 0);
    assert_int_equal(tile_store_count(s, -1), 2);
    assert_int_equal(tile_store_get(s, key_of(TILE_LAYER_COARSE, 0, 0), out, F32_BYTES, &err),
                     TILE_STORE_OK);
    assert_memory_equal(out, b, F32_BYTES);

    tile_store_close(s);
    free(a);
    free(b);
    free(out);
    test_rmtree(dir);
}

// ---------------------------------------------------------------------------
// SIGKILL at random instants: old or new state, never a mix
// ---------------------------------------------------------------------------

#define KILL_TILES 6

// Tile i of version v: every sample derived from v, so a tile's version can
// be read back and checked against the whole payload.
static void fill_version(tile_layer layer, int i, uint32_t v, void *out) {
    if (layer == TILE_LAYER_MATERIAL) {
        uint8_t *m = out;
        for (size_t j = 0; j < U8X8_BYTES; j++)
            m[j] = (uint8_t)(v * 7 + (uint32_t)(j % 13));
        memcpy(m, &v, sizeof v); // the full version in the first 4 bytes
        return;
    }
    float *f = out;
    for (int j = 0; j < TILE_SAMPLES; j++)
        f[j] = (float)v + (float)((j + i) % 64) * 0.25f; // exact for v < 2^16
}

static tile_layer kill_layer(int i) {
    return i == KILL_TILES - 1 ? TILE_LAYER_MATERIAL
           : i % 2             ? TILE_LAYER_DETAIL
                               : TILE_LAYER_COARSE;
}

// Reads every tile of the set; returns the common version, or fails the test.
static uint32_t verify_versions(const char *path) {
    og_error err = {{0}};
    tile_store *s = tile_store_open(path, &err);
    if (!s) fail_msg("reopen after kill: %s", err.msg);
    void *buf = malloc(U8X8_BYTES > F32_BYTES ? U8X8_BYTES : F32_BYTES);
    void *expect = malloc(U8X8_BYTES > F32_BYTES ? U8X8_BYTES : F32_BYTES);
    int64_t count = tile_store_count(s, -1);
    uint32_t version = 0;
    for (int i = 0; i < KILL_TILES; i++) {
        tile_key k = key_of(kill_layer(i), i, -i);
        size_t bytes = tile_layer_bytes(kill_layer(i));
        tile_store_status st = tile_store_get(s, k, buf, bytes, &err);
        if (count == 0) {
            assert_int_equal(st, TILE_STORE_NOT_FOUND);
            continue;
        }
        if (st != TILE_STORE_OK) fail_msg("tile %d after kill: status %d: %s", i, st, err.msg);
        uint32_t v;
        if (kill_layer(i) == TILE_LAYER_MATERIAL)
            memcpy(&v, buf, sizeof v);
        else // sample 0 of tile i is v + (i % 64) * 0.25, exactly
            v = (uint32_t)(((const float *)buf)[0] - (float)(i % 64) * 0.25f);
        if (i == 0) version = v;
        if (v != version)
            fail_msg("mixed versions after kill: tile 0 has %u, tile %d has %u", version, i, v);
        fill_version(kill_layer(i), i, v, expect);
        assert_memory_equal(buf, expect, bytes);
    }
    assert_true(count == 0 || count == KILL_TILES);
    tile_store_close(s);

    sqlite3 *db = NULL;
    assert_int_equal(sqlite3_open(path, &db), SQLITE_OK);
    sqlite3_stmt *st = NULL;
    assert_int_equal(sqlite3_prepare_v2(db, "PRAGMA integrity_check", -1, &st, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(st), SQLITE_ROW);
    assert_string_equal((const char *)sqlite3_column_text(st, 0), "ok");
    sqlite3_finalize(st);
    sqlite3_close(db);
    free(buf);
    free(expect);
    return version;
}

static void fill_kill_batch(uint32_t v, void *data[KILL_TILES], tile_store_write *w) {
    for (int i = 0; i < KILL_TILES; i++) {
        fill_version(kill_layer(i), i, v, data[i]);
        w[i] = (tile_store_write){key_of(kill_layer(i), i, -i), data[i]};
    }
}

// The child: write the whole set at version v, v+1, ... until killed. It
// writes one byte to ready_fd once the store is open.
static void kill_child(const char *path, uint32_t start, int ready_fd) {
    og_error err;
    tile_store *s = tile_store_open(path, &err);
    if (!s) _exit(3);
    if (write(ready_fd, "r", 1) != 1) _exit(5);
    void *data[KILL_TILES];
    tile_store_write w[KILL_TILES];
    for (int i = 0; i < KILL_TILES; i++)
        data[i] = malloc(U8X8_BYTES);
    for (uint32_t v = start;; v++) {
        fill_kill_batch(v, data, w);
        if (tile_store_put_batch(s, w, KILL_TILES, &err)) _exit(4);
    }
}

static double now_us(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec * 1e-3;
}

static void test_kill_during_writes(void **state) {
    (void)state;
    const char *dir = test_tmpdir("store-kill");
    char path[4096], calib[4096];
    if (snprintf(path, sizeof path, "%s/w.tiles", dir) >= (int)sizeof path) abort();
    if (snprintf(calib, sizeof calib, "%s/calib.tiles", dir) >= (int)sizeof calib) abort();

    // How long one batch takes here (sanitizers, slow disks): kills are spread
    // over a few batches' time so they land before, during and after commits.
    og_error err = {{0}};
    tile_store *s = tile_store_open(calib, &err);
    assert_non_null(s);
    void *data[KILL_TILES];
    tile_store_write w[KILL_TILES];
    for (int i = 0; i < KILL_TILES; i++)
        data[i] = malloc(U8X8_BYTES);
    double t0 = now_us();
    for (uint32_t v = 1; v <= 4; v++) {
        fill_kill_batch(v, data, w);
        assert_int_equal(tile_store_put_batch(s, w, KILL_TILES, &err), 0);
    }
    double batch_us = (now_us() - t0) / 4;
    tile_store_close(s);
    for (int i = 0; i < KILL_TILES; i++)
        free(data[i]);
    int max_delay = (int)(batch_us * 4) + 2000;

    srand((unsigned)time(NULL));
    uint32_t version = 0, advanced = 0;
    // At least 60 kills, and on until a quarter of them landed after a commit: on a
    // loaded machine the child may not run for a while, so while fewer than a quarter
    // advanced, a kill that found nothing new committed widens the window (at most 240).
    const uint32_t min_advanced = 15;
    int iterations = 0;
    for (int it = 0; it < 240 && (it < 60 || advanced < min_advanced); it++) {
        iterations++;
        int ready[2];
        assert_int_equal(pipe(ready), 0);
        fflush(NULL);
        pid_t pid = fork();
        assert_true(pid >= 0);
        if (pid == 0) {
            close(ready[0]);
            kill_child(path, version + 1, ready[1]);
        }
        close(ready[1]);
        // Mostly: wait until the store is open, then kill within a few batches
        // (microseconds to tens of ms). Sometimes: kill while it is opening.
        useconds_t delay;
        if (it % 8 == 7) {
            delay = (useconds_t)(rand() % 1000);
        } else {
            char byte;
            assert_int_equal(read(ready[0], &byte, 1), 1);
            delay = (useconds_t)(rand() % max_delay);
        }
        usleep(delay);
        kill(pid, SIGKILL);
        close(ready[0]);
        int status = 0;
        assert_int_equal(waitpid(pid, &status, 0), pid);
        // Killed, not exited on an error of its own.
        if (!WIFSIGNALED(status)) fail_msg("writer child exited with %d", WEXITSTATUS(status));
        uint32_t v = verify_versions(path);
        assert_true(v >= version);
        if (v > version)
            advanced++;
        else if (advanced * 4 < (uint32_t)(it + 1) && max_delay < 2000000)
            max_delay += max_delay / 8;
        version = v;
    }
    print_message("kill test: %d kills within %d us of opening (one batch %.0f us), version "
                  "reached %u, advanced in %u iterations\n",
                  iterations, max_delay, batch_us, version, advanced);
    // The test only means something if kills landed while batches committed.
    assert_true(advanced >= min_advanced);
    test_rmtree(dir);
}

// ---------------------------------------------------------------------------
// Threads
// ---------------------------------------------------------------------------

typedef struct thread_job {
    tile_store *store;
    int id;
    int failures;
} thread_job;

static void *thread_main(void *arg) {
    thread_job *job = arg;
    float *f = malloc(F32_BYTES), *out = malloc(F32_BYTES);
    og_error err;
    for (int round = 0; round < 12; round++) {
        tile_key k = key_of(TILE_LAYER_COARSE, job->id, round);
        fill_terrain(f, job->id * 100 + round);
        if (tile_store_put(job->store, k, f, &err)) job->failures++;
        if (tile_store_get(job->store, k, out, F32_BYTES, &err) != TILE_STORE_OK ||
            memcmp(out, f, F32_BYTES) != 0)
            job->failures++;
        if (tile_store_count(job->store, -1) < round + 1) job->failures++;
    }
    free(f);
    free(out);
    return NULL;
}

static void test_threads(void **state) {
    (void)state;
    const char *dir = test_tmpdir("store-threads");
    og_error err = {{0}};
    tile_store *s = tile_store_open(join(dir, "w.tiles"), &err);
    assert_non_null(s);
    pthread_t th[4];
    thread_job jobs[4];
    for (int i = 0; i < 4; i++) {
        jobs[i] = (thread_job){s, i, 0};
        assert_int_equal(pthread_create(&th[i], NULL, thread_main, &jobs[i]), 0);
    }
    for (int i = 0; i < 4; i++) {
        pthread_join(th[i], NULL);
        assert_int_equal(jobs[i].failures, 0);
    }
    assert_int_equal(tile_store_count(s, -1), 48);
    tile_store_close(s);
    test_rmtree(dir);
}

// ---------------------------------------------------------------------------
// Foreign files, newer schemas, unwritable places, full disks
// ---------------------------------------------------------------------------

static void expect_open_fails(const char *path, const char *needle);

// Runs sql on the store file with SQLite directly (outside Orogen).
static void sql_on(const char *path, const char *sql) {
    sqlite3 *db = NULL;
    assert_int_equal(sqlite3_open(path, &db), SQLITE_OK);
    char *why = NULL;
    if (sqlite3_exec(db, sql, NULL, NULL, &why) != SQLITE_OK) fail_msg("%s: %s", sql, why);
    sqlite3_close(db);
}

// Issue 27: a tile blob copied under another key is that other tile's: corrupt there,
// never adopted (the blob's checksum covers its key).
static void test_moved_blob_is_corrupt(void **state) {
    (void)state;
    const char *dir = test_tmpdir("store-moved");
    char *path = join(dir, "w.tiles");
    og_error err = {{0}};
    float *f = malloc(F32_BYTES), *out = malloc(F32_BYTES);
    fill_terrain(f, 9);
    tile_store *s = tile_store_open(path, &err);
    assert_non_null(s);
    assert_int_equal(tile_store_put(s, key_of(TILE_LAYER_COARSE, 1, 2), f, &err), 0);
    tile_store_close(s);
    sql_on(path, "INSERT INTO tiles SELECT layer, face, level, 5, 2, data FROM tiles;"
                 "INSERT INTO tiles SELECT layer, 3, level, tx, ty, data FROM tiles WHERE tx=1;"
                 "INSERT INTO tiles SELECT layer, face, 1, tx, ty, data FROM tiles WHERE face=0 "
                 "AND tx=1;");
    assert_non_null(s = tile_store_open(path, &err));
    assert_int_equal(tile_store_get(s, key_of(TILE_LAYER_COARSE, 1, 2), out, F32_BYTES, &err),
                     TILE_STORE_OK);
    tile_key moved[] = {key_of(TILE_LAYER_COARSE, 5, 2),
                        {TILE_LAYER_COARSE, 3, 0, 1, 2},
                        {TILE_LAYER_COARSE, 0, 1, 1, 2}};
    for (size_t i = 0; i < 3; i++) {
        assert_int_equal(tile_store_get(s, moved[i], out, F32_BYTES, &err), TILE_STORE_CORRUPT);
        assert_non_null(strstr(err.msg, "another tile's blob"));
    }
    tile_store_close(s);
    free(f);
    free(out);
    test_rmtree(dir);
}

static char *file_bytes(const char *path, size_t *len) {
    return test_read_file(path, len);
}

// Issue 27: a store naming a format, schema or blob version this Orogen does not know
// is refused by name, and not written (its bytes stay as they were).
static void test_unknown_versions_refused(void **state) {
    (void)state;
    const char *dir = test_tmpdir("store-versions");
    static const char *const cases[][3] = {
        {"schema_version", "99", "schema_version '99'"},
        {"blob_version", "99", "blob_version '99'"},
        {"blob_version", "x", "blob_version 'x'"},
        {"format", "another store", "format is 'another store'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *path = join(dir, "v.tiles");
        og_error err = {{0}};
        float *f = malloc(F32_BYTES);
        fill_terrain(f, 3);
        tile_store *s = tile_store_open(path, &err);
        assert_non_null(s);
        assert_int_equal(tile_store_put(s, key_of(TILE_LAYER_COARSE, 0, 0), f, &err), 0);
        tile_store_close(s);
        char sql[256];
        snprintf(sql, sizeof sql, "UPDATE meta SET value='%s' WHERE key='%s'", cases[i][1],
                 cases[i][0]);
        sql_on(path, sql);
        size_t before_len = 0, after_len = 0;
        char *before = file_bytes(path, &before_len);
        expect_open_fails(path, cases[i][2]);
        assert_null(tile_store_open_readable(path, &err));
        char *after = file_bytes(path, &after_len);
        assert_int_equal(before_len, after_len);
        assert_memory_equal(before, after, before_len);
        free(before);
        free(after);
        free(f);
        unlink(path);
    }
    test_rmtree(dir);
}

// Commits sql on path in a child that then dies without closing (as a kill leaves it):
// the commit stays in path-wal, not checkpointed.
static void commit_and_die(const char *path, const char *sql) {
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        sqlite3 *db = NULL;
        if (sqlite3_open(path, &db) != SQLITE_OK ||
            sqlite3_exec(db, "PRAGMA wal_autocheckpoint=0", NULL, NULL, NULL) != SQLITE_OK ||
            sqlite3_exec(db, sql, NULL, NULL, NULL) != SQLITE_OK)
            _exit(1);
        _exit(0);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

// Issue 27, finding 4: a stray WAL of another database beside a store is moved aside
// as NAME-wal.foreign, never replayed; the store's own WAL (a kill after a commit)
// is replayed as always.
static void test_foreign_wal_moved_aside(void **state) {
    (void)state;
    const char *dir = test_tmpdir("store-wal");
    og_error err = {{0}};
    float *f = malloc(F32_BYTES);
    fill_terrain(f, 4);
    char a[4096], b[4096], wal[4200], foreign[4300];
    snprintf(a, sizeof a, "%s", join(dir, "a.tiles"));
    snprintf(b, sizeof b, "%s", join(dir, "b.tiles"));
    for (int i = 0; i < 2; i++) {
        tile_store *s = tile_store_open(i ? b : a, &err);
        assert_non_null(s);
        for (int t = 0; t < 6; t++)
            assert_int_equal(tile_store_put(s, key_of(TILE_LAYER_COARSE, t, i), f, &err), 0);
        assert_int_equal(tile_store_set_meta(s, "world_id", i ? "bbbb" : "aaaa", &err), 0);
        tile_store_close(s);
    }
    // Another store's WAL (an Orogen killed after clearing its tiles), copied beside a.
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        tile_store *other = tile_store_open(b, &err);
        _exit(other && tile_store_clear(other, &err) == 0 ? 0 : 1); // no close: the WAL stays
    }
    int status = 0;
    waitpid(pid, &status, 0);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    snprintf(wal, sizeof wal, "%s-wal", b);
    size_t len = 0;
    char *bytes = test_read_file(wal, &len);
    assert_true(len > 0);
    snprintf(wal, sizeof wal, "%s-wal", a);
    test_write_file(wal, bytes, len);
    free(bytes);
    tile_store *s = tile_store_open(a, &err);
    assert_non_null(s);
    assert_int_equal(tile_store_count(s, -1), 6);
    snprintf(foreign, sizeof foreign, "%s.foreign", wal);
    assert_non_null(strstr(tile_store_warning(s), foreign));
    tile_store_close(s);
    assert_int_equal(access(foreign, F_OK), 0);
    // A WAL that does not even read as a database's: the same.
    unlink(foreign);
    char junk[8192];
    for (size_t i = 0; i < sizeof junk; i++)
        junk[i] = (char)(i * 131 + 7);
    test_write_file(wal, junk, sizeof junk);
    assert_non_null(s = tile_store_open(a, &err));
    assert_int_equal(tile_store_count(s, -1), 6);
    tile_store_close(s);
    // Its own WAL (an Orogen killed after a commit): replayed. A WAL written by other
    // means (no frame of the store's meta page) is taken for a foreign one.
    commit_and_die(a, "DELETE FROM tiles WHERE tx=5");
    assert_non_null(s = tile_store_open(a, &err));
    assert_non_null(strstr(tile_store_warning(s), ".foreign"));
    assert_int_equal(tile_store_count(s, -1), 6);
    tile_store_close(s);
    pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        tile_store *own = tile_store_open(a, &err);
        _exit(own && tile_store_put(own, key_of(TILE_LAYER_COARSE, 0, 0), NULL, &err) == 0 ? 0 : 1);
    }
    waitpid(pid, &status, 0);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    assert_non_null(s = tile_store_open(a, &err));
    assert_string_equal(tile_store_warning(s), "");
    assert_int_equal(tile_store_count(s, -1), 5);
    tile_store_close(s);
    free(f);
    test_rmtree(dir);
}

static void expect_open_fails(const char *path, const char *needle) {
    og_error err = {{0}};
    tile_store *s = tile_store_open(path, &err);
    if (s) fail_msg("opening '%s' should fail", path);
    if (!strstr(err.msg, path)) fail_msg("message does not name the path: %s", err.msg);
    if (needle && !strstr(err.msg, needle)) fail_msg("message lacks '%s': %s", needle, err.msg);
}

static void test_refuses_foreign_files(void **state) {
    (void)state;
    const char *dir = test_tmpdir("store-foreign");
    char tmp[4096];
    if (snprintf(tmp, sizeof tmp, "%s", dir) >= (int)sizeof tmp) abort();

    uint8_t noise[8192];
    fill_noise_bits(noise, sizeof noise, 3);
    test_write_file(join(tmp, "noise.tiles"), noise, sizeof noise);
    expect_open_fails(join(tmp, "noise.tiles"), "not an Orogen tile store");

    const char text[] = "generator = fbm;\nseed = 7;\n# not a database at all, just text\n";
    char big[8192];
    for (size_t i = 0; i < sizeof big; i++)
        big[i] = text[i % (sizeof text - 1)];
    test_write_file(join(tmp, "text.tiles"), big, sizeof big);
    expect_open_fails(join(tmp, "text.tiles"), "not an Orogen tile store");
    // The file was left alone.
    size_t len = 0;
    char *again = test_read_file(join(tmp, "text.tiles"), &len);
    assert_int_equal(len, sizeof big);
    assert_memory_equal(again, big, sizeof big);
    free(again);

    // Some other application's SQLite database.
    sqlite3 *db = NULL;
    assert_int_equal(sqlite3_open(join(tmp, "other.db"), &db), SQLITE_OK);
    assert_int_equal(
        sqlite3_exec(db, "CREATE TABLE t(x); PRAGMA application_id=1234;", NULL, NULL, NULL),
        SQLITE_OK);
    sqlite3_close(db);
    expect_open_fails(join(tmp, "other.db"), "not an Orogen tile store");
    // A database with tables but no application id is also not ours.
    assert_int_equal(sqlite3_open(join(tmp, "plain.db"), &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "CREATE TABLE t(x);", NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);
    expect_open_fails(join(tmp, "plain.db"), "not an Orogen tile store");

    // A store from a newer Orogen.
    og_error err = {{0}};
    tile_store *s = tile_store_open(join(tmp, "new.tiles"), &err);
    assert_non_null(s);
    tile_store_close(s);
    assert_int_equal(sqlite3_open(join(tmp, "new.tiles"), &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "PRAGMA user_version=2;", NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);
    expect_open_fails(join(tmp, "new.tiles"), "newer");

    // Unopenable places: a missing folder, a file used as a folder.
    expect_open_fails(join(tmp, "missing/dir/w.tiles"), NULL);
    expect_open_fails(join(tmp, "noise.tiles/w.tiles"), NULL);
    test_rmtree(dir);
}

// Runs fn in a child process (for privilege drops and resource limits that
// must not leak into the test runner); the child reports by exit code.
static void run_in_child(int (*fn)(const char *dir), const char *dir) {
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) _exit(fn(dir));
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    if (WEXITSTATUS(status) != 0) fail_msg("child check failed at step %d", WEXITSTATUS(status));
}

static int unwritable_child(const char *dir) {
    // Root ignores permissions: become nobody for the check.
    if (geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0)) return 10;
    char path[4096];
    if (snprintf(path, sizeof path, "%s/ro/w.tiles", dir) >= (int)sizeof path) abort();
    og_error err = {{0}};
    tile_store *s = tile_store_open(path, &err);
    if (s) return 11;
    if (!strstr(err.msg, path)) return 12;
    // An existing store that is read-only for us.
    if (snprintf(path, sizeof path, "%s/rofile.tiles", dir) >= (int)sizeof path) abort();
    s = tile_store_open(path, &err);
    if (s) return 13;
    if (!strstr(err.msg, path)) return 14;
    return 0;
}

static void test_unwritable(void **state) {
    (void)state;
    const char *tmp = test_tmpdir("store-ro");
    char dir[4096], sub[4096];
    if (snprintf(dir, sizeof dir, "%s", tmp) >= (int)sizeof dir) abort();
    if (snprintf(sub, sizeof sub, "%s/ro", dir) >= (int)sizeof sub) abort();
    assert_int_equal(mkdir(sub, 0555), 0);
    assert_int_equal(chmod(sub, 0555), 0);
    og_error err = {{0}};
    tile_store *s = tile_store_open(join(dir, "rofile.tiles"), &err);
    assert_non_null(s);
    tile_store_close(s);
    assert_int_equal(chmod(join(dir, "rofile.tiles"), 0444), 0);
    assert_int_equal(chmod(dir, 0755), 0);
    run_in_child(unwritable_child, dir);
    test_rmtree(dir);
}

static int full_disk_child(const char *dir) {
    char path[4096];
    if (snprintf(path, sizeof path, "%s/full.tiles", dir) >= (int)sizeof path) abort();
    og_error err = {{0}};
    tile_store *s = tile_store_open(path, &err);
    if (!s) return 20;
    float *f = malloc(F32_BYTES), *out = malloc(F32_BYTES);
    fill_terrain(f, 1);
    if (tile_store_put(s, key_of(TILE_LAYER_COARSE, 0, 0), f, &err)) return 21;
    // Files may not grow past 1 MB from here: writes fail as on a full disk.
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit lim = {1 << 20, 1 << 20};
    if (setrlimit(RLIMIT_FSIZE, &lim)) return 22;
    int failed = 0;
    for (int i = 1; i < 64 && !failed; i++) {
        fill_noise_bits(f, F32_BYTES, (uint64_t)i); // incompressible, grows fast
        tile_store_write w[2] = {{key_of(TILE_LAYER_COARSE, i, 0), f},
                                 {key_of(TILE_LAYER_COARSE, i, 1), f}};
        failed = tile_store_put_batch(s, w, 2, &err) != 0;
    }
    if (!failed) return 23;
    if (!strstr(err.msg, path)) return 24;
    // The failed batch left nothing half-written; the first tile still reads.
    fill_terrain(f, 1);
    if (tile_store_get(s, key_of(TILE_LAYER_COARSE, 0, 0), out, F32_BYTES, &err) != TILE_STORE_OK)
        return 25;
    if (memcmp(out, f, F32_BYTES)) return 26;
    int64_t n = tile_store_count(s, -1);
    if (n < 1 || n % 2 != 1) return 27;
    tile_store_close(s);
    printf("full disk message: %s\n", err.msg);
    fflush(stdout);
    return 0;
}

static void test_full_disk(void **state) {
    (void)state;
    const char *tmp = test_tmpdir("store-full");
    char dir[4096];
    if (snprintf(dir, sizeof dir, "%s", tmp) >= (int)sizeof dir) abort();
    run_in_child(full_disk_child, dir);
    // And the store is sound for a process without the limit.
    og_error err = {{0}};
    tile_store *s = tile_store_open(join(dir, "full.tiles"), &err);
    assert_non_null(s);
    assert_true(tile_store_has(s, key_of(TILE_LAYER_COARSE, 0, 0)));
    tile_store_close(s);
    test_rmtree(dir);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip_layers),
        cmocka_unit_test(test_each_and_count),
        cmocka_unit_test(test_compression_ratio),
        cmocka_unit_test(test_decode_hostile),
        cmocka_unit_test(test_corrupt_rows),
        cmocka_unit_test(test_batch_atomicity),
        cmocka_unit_test(test_kill_during_writes),
        cmocka_unit_test(test_threads),
        cmocka_unit_test(test_refuses_foreign_files),
        cmocka_unit_test(test_unwritable),
        cmocka_unit_test(test_full_disk),
        cmocka_unit_test(test_moved_blob_is_corrupt),
        cmocka_unit_test(test_unknown_versions_refused),
        cmocka_unit_test(test_foreign_wal_moved_aside),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
