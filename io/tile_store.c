#include "io/tile_store.h"

#include "io/crc32c.h"
#include "io/path_folder.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>
#include <zstd.h>

// ---------------------------------------------------------------------------
// Blob format (all numbers little-endian), version 2 (version 1, still read, differs
// only in that its header CRC does not cover the key):
//
//   offset size  field
//        0    4  magic "OGTB"
//        4    1  format version (1)
//        5    1  layer (tile_layer)
//        6    1  transform id (BLOB_TRANSFORM_*)
//        7    1  reserved, 0
//        8    4  raw size: bytes of the decoded tile payload
//       12    4  compressed size: bytes following the header
//       16    4  CRC32C of the raw payload (the tile's values as little-endian bytes)
//       20    4  CRC32C of header bytes 0..19 then the tile's face, level, tx, ty (u32)
//       24    .  zstd frame of the transformed payload
//
// The header CRC lets decode reject a damaged header before trusting any size
// in it, and a blob copied under another key (it is another tile's); the payload CRC
// catches anything zstd's own checks let through.
// ---------------------------------------------------------------------------

#define BLOB_MAGIC 0x4254474Fu // "OGTB" read as little-endian
#define BLOB_VERSION 2
#define BLOB_HEADER_BYTES 24

enum {
    // float32: bit patterns mapped to ordered integers, 2D Lorenzo predictor
    // (left + up - upleft) in wrapping integer arithmetic, zigzag residuals,
    // then the 4 residual bytes split into 4 planes (low bytes first).
    BLOB_TRANSFORM_F32_LORENZO_PLANES = 1,
    // uint8 x 8: the 8 channels split into planes, each plane delta-coded
    // against its left neighbour (the up neighbour in the first column).
    BLOB_TRANSFORM_U8X8_PLANES_DELTA = 2,
    // int16 x 2: each channel delta-coded against its left neighbour (up in the
    // first column) in wrapping 16-bit arithmetic, split into low/high byte planes.
    BLOB_TRANSFORM_S16X2_PLANES_DELTA = 3,
};

// zstd level 3 (zstd's default). Measured on 256x256 tiles: sculpted-like
// fBm heights give 0.48 of raw at every level 1-9 (the residuals' low bytes
// are noise no level can squeeze); integer-metre DEM imports and painted
// materials gain 5-10% at levels 5-9 but encode 3-4x slower. Level 1 gained no
// clear speed over 3. Decoding speed is the same at every level. The Lorenzo
// predictor beats a left-neighbour delta (0.48 vs 0.53 of raw on fBm).
#define BLOB_ZSTD_LEVEL 3

// Orogen tile store identification and schema version, stored in the SQLite
// header (PRAGMA application_id / user_version) so `file` and sqlite3 see them.
#define STORE_APPLICATION_ID 0x4F524F47 // "OROG"
#define STORE_SCHEMA_VERSION 1
#define STORE_BUSY_TIMEOUT_MS 10000

// ---------------------------------------------------------------------------
// Little-endian helpers
// ---------------------------------------------------------------------------

static void put_u32le(uint8_t *p, uint32_t v) {
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static uint32_t get_u32le(const uint8_t *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

// CRC of a tile payload as little-endian bytes, whatever the host's byte order.
static uint32_t payload_crc(tile_format format, const void *data, size_t n) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    if (format == TILE_FORMAT_F32) {
        uint8_t chunk[4096];
        const uint8_t *p = data;
        uint32_t crc = 0;
        for (size_t off = 0; off < n; off += sizeof chunk) {
            size_t len = n - off < sizeof chunk ? n - off : sizeof chunk;
            for (size_t i = 0; i + 4 <= len; i += 4) {
                uint32_t v;
                memcpy(&v, p + off + i, 4);
                put_u32le(chunk + i, v);
            }
            crc = crc32c_update(crc, chunk, len);
        }
        return crc;
    }
#endif
    (void)format;
    return crc32c_update(0, data, n);
}

// ---------------------------------------------------------------------------
// Transforms. Each maps a tile payload to a same-size buffer that zstd
// compresses well, and back, bit-exactly for every input (NaN payloads,
// -0.0, denormals included) because all arithmetic is on integers.
// ---------------------------------------------------------------------------

// Float bits -> unsigned integers in the same order as the floats, so close
// heights have close integers across the sign boundary.
static inline uint32_t f32_order(uint32_t u) {
    return (u & 0x80000000u) ? ~u : u | 0x80000000u;
}
static inline uint32_t f32_unorder(uint32_t m) {
    return (m & 0x80000000u) ? m & 0x7FFFFFFFu : ~m;
}
static inline uint32_t zigzag(uint32_t d) {
    return (d << 1) ^ (0u - (d >> 31));
}
static inline uint32_t unzigzag(uint32_t z) {
    return (z >> 1) ^ (0u - (z & 1));
}

// The 2D Lorenzo predictor (left + up - upleft) on ordered integers, with the
// left neighbour on the first row and the up neighbour in the first column.
// Written as row passes over two distinct arrays so everything but the
// running sum vectorises: decoding is on the tile cache's load path.
static void f32_forward(const void *src, uint8_t *planes) {
    const uint8_t *in = src;
    uint32_t cur[TILE_SIZE], prev[TILE_SIZE], res[TILE_SIZE];
    uint8_t *p0 = planes, *p1 = p0 + TILE_SAMPLES, *p2 = p1 + TILE_SAMPLES, *p3 = p2 + TILE_SAMPLES;
    memset(prev, 0, sizeof prev);
    for (int y = 0; y < TILE_SIZE; y++) {
        size_t row = (size_t)y * TILE_SIZE;
        for (int x = 0; x < TILE_SIZE; x++) {
            uint32_t u;
            memcpy(&u, in + (row + (size_t)x) * 4, 4);
            cur[x] = f32_order(u);
        }
        res[0] = cur[0] - prev[0]; // prev is all zero on the first row
        if (y)
            for (int x = 1; x < TILE_SIZE; x++)
                res[x] = cur[x] - cur[x - 1] - prev[x] + prev[x - 1];
        else
            for (int x = 1; x < TILE_SIZE; x++)
                res[x] = cur[x] - cur[x - 1];
        for (int x = 0; x < TILE_SIZE; x++) {
            uint32_t z = zigzag(res[x]);
            p0[row + (size_t)x] = (uint8_t)z;
            p1[row + (size_t)x] = (uint8_t)(z >> 8);
            p2[row + (size_t)x] = (uint8_t)(z >> 16);
            p3[row + (size_t)x] = (uint8_t)(z >> 24);
        }
        memcpy(prev, cur, sizeof prev);
    }
}

static void f32_inverse(const uint8_t *planes, void *dst) {
    uint8_t *out = dst;
    uint32_t cur[TILE_SIZE], prev[TILE_SIZE];
    const uint8_t *p0 = planes, *p1 = p0 + TILE_SAMPLES, *p2 = p1 + TILE_SAMPLES,
                  *p3 = p2 + TILE_SAMPLES;
    memset(prev, 0, sizeof prev);
    for (int y = 0; y < TILE_SIZE; y++) {
        size_t row = (size_t)y * TILE_SIZE;
        // cur[x] = cur[x-1] + (prev[x] - prev[x-1]) + residual: the residual
        // and gradient first, then one running sum along the row.
        for (int x = 0; x < TILE_SIZE; x++) {
            size_t i = row + (size_t)x;
            cur[x] = unzigzag((uint32_t)p0[i] | (uint32_t)p1[i] << 8 | (uint32_t)p2[i] << 16 |
                              (uint32_t)p3[i] << 24);
        }
        cur[0] += prev[0];
        if (y)
            for (int x = 1; x < TILE_SIZE; x++)
                cur[x] += prev[x] - prev[x - 1];
        uint32_t sum = 0;
        for (int x = 0; x < TILE_SIZE; x++)
            cur[x] = sum += cur[x];
        for (int x = 0; x < TILE_SIZE; x++) {
            uint32_t u = f32_unorder(cur[x]);
            memcpy(out + (row + (size_t)x) * 4, &u, 4);
        }
        memcpy(prev, cur, sizeof prev);
    }
}

static void u8x8_forward(const void *src, uint8_t *planes) {
    const uint8_t *in = src;
    for (int c = 0; c < TILE_MATERIALS; c++) {
        uint8_t *plane = planes + (size_t)c * TILE_SAMPLES;
        for (size_t i = 0; i < TILE_SAMPLES; i++) {
            uint8_t v = in[i * TILE_MATERIALS + (size_t)c];
            uint8_t pred = (i % TILE_SIZE) ? in[(i - 1) * TILE_MATERIALS + (size_t)c]
                           : i             ? in[(i - TILE_SIZE) * TILE_MATERIALS + (size_t)c]
                                           : 0;
            plane[i] = (uint8_t)(v - pred);
        }
    }
}

static void u8x8_inverse(const uint8_t *planes, void *dst) {
    uint8_t *out = dst;
    for (int c = 0; c < TILE_MATERIALS; c++) {
        const uint8_t *plane = planes + (size_t)c * TILE_SAMPLES;
        for (size_t i = 0; i < TILE_SAMPLES; i++) {
            uint8_t pred = (i % TILE_SIZE) ? out[(i - 1) * TILE_MATERIALS + (size_t)c]
                           : i             ? out[(i - TILE_SIZE) * TILE_MATERIALS + (size_t)c]
                                           : 0;
            out[i * TILE_MATERIALS + (size_t)c] = (uint8_t)(plane[i] + pred);
        }
    }
}

static uint16_t s16x2_at(const uint8_t *in, size_t i, int c) {
    uint16_t v;
    memcpy(&v, in + (i * 2 + (size_t)c) * 2, 2);
    return v;
}

static uint16_t s16x2_pred(const uint8_t *tile, size_t i, int c) {
    return (i % TILE_SIZE) ? s16x2_at(tile, i - 1, c) : i ? s16x2_at(tile, i - TILE_SIZE, c) : 0;
}

static void s16x2_forward(const void *src, uint8_t *planes) {
    const uint8_t *in = src;
    for (int c = 0; c < 2; c++) {
        uint8_t *lo = planes + (size_t)(2 * c) * TILE_SAMPLES, *hi = lo + TILE_SAMPLES;
        for (size_t i = 0; i < TILE_SAMPLES; i++) {
            uint16_t d = (uint16_t)(s16x2_at(in, i, c) - s16x2_pred(in, i, c));
            lo[i] = (uint8_t)d;
            hi[i] = (uint8_t)(d >> 8);
        }
    }
}

static void s16x2_inverse(const uint8_t *planes, void *dst) {
    uint8_t *out = dst;
    for (int c = 0; c < 2; c++) {
        const uint8_t *lo = planes + (size_t)(2 * c) * TILE_SAMPLES, *hi = lo + TILE_SAMPLES;
        for (size_t i = 0; i < TILE_SAMPLES; i++) {
            uint16_t v = (uint16_t)(s16x2_pred(out, i, c) + (uint16_t)(lo[i] | (hi[i] << 8)));
            memcpy(out + (i * 2 + (size_t)c) * 2, &v, 2);
        }
    }
}

static int layer_transform(tile_layer layer) {
    switch (tile_layer_format(layer)) {
    case TILE_FORMAT_U8X8:
        return BLOB_TRANSFORM_U8X8_PLANES_DELTA;
    case TILE_FORMAT_S16X2:
        return BLOB_TRANSFORM_S16X2_PLANES_DELTA;
    default:
        return BLOB_TRANSFORM_F32_LORENZO_PLANES;
    }
}

// ---------------------------------------------------------------------------
// Blob encode / decode
// ---------------------------------------------------------------------------

// The header checksum: bytes 0..19, and from version 2 the key they belong to.
static uint32_t header_crc(const uint8_t *b, tile_key key, int version) {
    uint32_t crc = crc32c_update(0, b, 20);
    if (version < 2) return crc;
    uint8_t k[16];
    put_u32le(k, (uint32_t)key.face);
    put_u32le(k + 4, (uint32_t)key.level);
    put_u32le(k + 8, (uint32_t)key.tx);
    put_u32le(k + 12, (uint32_t)key.ty);
    crc = crc32c_update(crc, k, sizeof k);
    // An edit layer's tile also answers for its slot (the composite's, slot 0, as before).
    if (tile_key_slot(key)) {
        put_u32le(k, (uint32_t)tile_key_slot(key));
        crc = crc32c_update(crc, k, 4);
    }
    return crc;
}

size_t tile_blob_encode(tile_layer layer, const void *data, void **blob) {
    return tile_blob_encode_key((tile_key){.layer = layer}, data, blob);
}

int tile_blob_decode(tile_layer layer, const void *blob, size_t blob_bytes, void *out,
                     og_error *err) {
    return tile_blob_decode_key((tile_key){.layer = layer}, blob, blob_bytes, out, err);
}

size_t tile_blob_encode_key(tile_key key, const void *data, void **blob) {
    tile_layer layer = (tile_layer)key.layer;
    *blob = NULL;
    size_t raw = tile_layer_bytes(layer);
    if (!raw || !data || raw > UINT32_MAX) return 0;
    int transform = layer_transform(layer);
    uint8_t *planes = malloc(raw);
    size_t cap = BLOB_HEADER_BYTES + ZSTD_compressBound(raw);
    uint8_t *out = malloc(cap);
    if (!planes || !out) {
        free(planes);
        free(out);
        return 0;
    }
    if (transform == BLOB_TRANSFORM_F32_LORENZO_PLANES)
        f32_forward(data, planes);
    else if (transform == BLOB_TRANSFORM_S16X2_PLANES_DELTA)
        s16x2_forward(data, planes);
    else
        u8x8_forward(data, planes);
    size_t comp = ZSTD_compress(out + BLOB_HEADER_BYTES, cap - BLOB_HEADER_BYTES, planes, raw,
                                BLOB_ZSTD_LEVEL);
    free(planes);
    if (ZSTD_isError(comp) || comp > UINT32_MAX) {
        free(out);
        return 0;
    }
    put_u32le(out, BLOB_MAGIC);
    out[4] = BLOB_VERSION;
    out[5] = (uint8_t)layer;
    out[6] = (uint8_t)transform;
    out[7] = 0;
    put_u32le(out + 8, (uint32_t)raw);
    put_u32le(out + 12, (uint32_t)comp);
    put_u32le(out + 16, payload_crc(tile_layer_format(layer), data, raw));
    put_u32le(out + 20, header_crc(out, key, BLOB_VERSION));
    *blob = out;
    return BLOB_HEADER_BYTES + comp;
}

int tile_blob_decode_key(tile_key key, const void *blob, size_t blob_bytes, void *out,
                         og_error *err) {
    tile_layer layer = (tile_layer)key.layer;
    const uint8_t *b = blob;
    size_t raw = tile_layer_bytes(layer);
    if (!raw) return og_error_set(err, "layer %d has no stored payload", (int)layer);
    if (!b || blob_bytes < BLOB_HEADER_BYTES)
        return og_error_set(err, "blob too short (%zu bytes, header needs %d)", blob_bytes,
                            BLOB_HEADER_BYTES);
    if (get_u32le(b) != BLOB_MAGIC) return og_error_set(err, "bad blob magic");
    if (b[4] < 1 || b[4] > BLOB_VERSION)
        return og_error_set(err, "blob format version %u (this Orogen reads 1 to %d)", b[4],
                            BLOB_VERSION);
    if (get_u32le(b + 20) != header_crc(b, key, b[4]))
        return og_error_set(err, "blob header checksum mismatch (damaged, or another tile's "
                                 "blob under this key)");
    if (b[5] != (uint8_t)layer)
        return og_error_set(err, "blob holds layer %u, expected %s", b[5], tile_layer_name(layer));
    if (b[6] != layer_transform(layer))
        return og_error_set(err, "blob transform %u does not fit layer %s", b[6],
                            tile_layer_name(layer));
    uint32_t raw_size = get_u32le(b + 8), comp_size = get_u32le(b + 12);
    if (raw_size != raw) return og_error_set(err, "blob raw size %u, expected %zu", raw_size, raw);
    if (comp_size != blob_bytes - BLOB_HEADER_BYTES)
        return og_error_set(err, "blob payload is %zu bytes, header says %u",
                            blob_bytes - BLOB_HEADER_BYTES, comp_size);
    unsigned long long frame = ZSTD_getFrameContentSize(b + BLOB_HEADER_BYTES, comp_size);
    if (frame != raw) return og_error_set(err, "compressed frame does not hold %zu bytes", raw);

    uint8_t *planes = malloc(raw);
    if (!planes) return og_error_set(err, "out of memory decoding a tile");
    size_t got = ZSTD_decompress(planes, raw, b + BLOB_HEADER_BYTES, comp_size);
    if (ZSTD_isError(got) || got != raw) {
        int rc = og_error_set(err, "decompression failed: %s",
                              ZSTD_isError(got) ? ZSTD_getErrorName(got) : "short output");
        free(planes);
        return rc;
    }
    if (b[6] == BLOB_TRANSFORM_F32_LORENZO_PLANES)
        f32_inverse(planes, out);
    else if (b[6] == BLOB_TRANSFORM_S16X2_PLANES_DELTA)
        s16x2_inverse(planes, out);
    else
        u8x8_inverse(planes, out);
    free(planes);
    if (payload_crc(tile_layer_format(layer), out, raw) != get_u32le(b + 16))
        return og_error_set(err, "payload checksum mismatch");
    return 0;
}

// ---------------------------------------------------------------------------
// The store
// ---------------------------------------------------------------------------

struct tile_store {
    pthread_mutex_t lock; // one connection, used by one thread at a time
    sqlite3 *db;
    char *path;
    int blob_version;     // the meta table's: raised to BLOB_VERSION by the first write
    char store_id[40];    // the meta table's store_id ("" until the first write makes it)
    char read_only[4600]; // opened for reading only, and why ("" when writable)
    char warning[9000];   // what opening it found and did (a foreign WAL moved aside), or
    sqlite3_stmt *get, *has, *put, *del, *count_all, *count_layer, *each;
    sqlite3_stmt *begin, *commit, *rollback;
};

const char *tile_store_path(const tile_store *store) {
    return store->path;
}

// Error naming the store's path, the operation and SQLite's reason.
static int db_fail(const tile_store *store, og_error *err, const char *what) {
    int code = sqlite3_extended_errcode(store->db);
    const char *hint = "";
    if ((code & 0xFF) == SQLITE_FULL) hint = " (disk full?)";
    if ((code & 0xFF) == SQLITE_READONLY || (code & 0xFF) == SQLITE_CANTOPEN ||
        (code & 0xFF) == SQLITE_PERM)
        hint = " (is the file or its folder writable?)";
    int sys = sqlite3_system_errno(store->db);
    return og_error_set(err, "tile store '%s': %s: %s%s%s%s", store->path, what,
                        sqlite3_errmsg(store->db), sys ? ": " : "", sys ? strerror(sys) : "", hint);
}

static int key_valid(tile_key key, og_error *err, const char *path) {
    char desc[128];
    if (key.layer < 0 || tile_key_kind(key) >= TILE_LAYER_COUNT)
        return og_error_set(err, "tile store '%s': layer %d is not a tile layer", path, key.layer);
    if (!tile_layer_bytes((tile_layer)key.layer))
        return og_error_set(err, "tile store '%s': %s: the %s layer has no payload to store", path,
                            tile_key_describe(key, desc, sizeof desc),
                            tile_layer_name((tile_layer)key.layer));
    if (key.face < 0 || key.face > 5 ||
        (tile_key_has_mips(key) && (key.level < 0 || key.level > TILE_MAX_LEVEL)))
        return og_error_set(err, "tile store '%s': %s: face must be 0-5 and level 0-%d", path,
                            tile_key_describe(key, desc, sizeof desc), TILE_MAX_LEVEL);
    return 0;
}

static void bind_key(sqlite3_stmt *st, tile_key key) {
    sqlite3_bind_int(st, 1, key.layer);
    sqlite3_bind_int(st, 2, key.face);
    sqlite3_bind_int(st, 3, key.level);
    sqlite3_bind_int(st, 4, key.tx);
    sqlite3_bind_int(st, 5, key.ty);
}

static int exec(tile_store *store, const char *sql, og_error *err, const char *what) {
    if (sqlite3_exec(store->db, sql, NULL, NULL, NULL) != SQLITE_OK)
        return db_fail(store, err, what);
    return 0;
}

static int pragma_int(tile_store *store, const char *sql, int *value, og_error *err) {
    sqlite3_stmt *st = NULL;
    int rc = sqlite3_prepare_v2(store->db, sql, -1, &st, NULL);
    if (rc == SQLITE_OK) rc = sqlite3_step(st);
    if (rc != SQLITE_ROW) {
        sqlite3_finalize(st);
        if (rc == SQLITE_NOTADB || sqlite3_errcode(store->db) == SQLITE_NOTADB)
            return og_error_set(err, "'%s' is not an Orogen tile store (not an SQLite database)",
                                store->path);
        return db_fail(store, err, "cannot read the file header");
    }
    *value = sqlite3_column_int(st, 0);
    sqlite3_finalize(st);
    return 0;
}

// Checks the identity and schema version; creates the schema in a fresh file.
static int store_init_schema(tile_store *store, og_error *err) {
    int app_id, version, objects;
    if (pragma_int(store, "PRAGMA application_id", &app_id, err)) return -1;
    if (pragma_int(store, "PRAGMA user_version", &version, err)) return -1;
    if (pragma_int(store, "SELECT count(*) FROM sqlite_master", &objects, err)) return -1;

    if (app_id == 0 && version == 0 && objects == 0) {
        // Fresh file. Create under a write lock and re-check, so two processes
        // creating the same store at once do not both build the schema.
        if (exec(store, "BEGIN IMMEDIATE", err, "cannot start creating the store")) return -1;
        if (pragma_int(store, "SELECT count(*) FROM sqlite_master", &objects, err)) {
            sqlite3_exec(store->db, "ROLLBACK", NULL, NULL, NULL);
            return -1;
        }
        if (objects == 0) {
            static const char schema[] =
                "CREATE TABLE meta(key TEXT PRIMARY KEY NOT NULL, value TEXT NOT NULL);"
                "INSERT INTO meta VALUES('format', 'orogen tile store');"
                "INSERT INTO meta VALUES('schema_version', '1');"
                "INSERT INTO meta VALUES('blob_version', '2');"
                // A rowid table (not WITHOUT ROWID): rows are ~100 KB blobs, which
                // SQLite stores best out of line from a small primary-key index.
                "CREATE TABLE tiles(layer INTEGER NOT NULL, face INTEGER NOT NULL,"
                " level INTEGER NOT NULL, tx INTEGER NOT NULL, ty INTEGER NOT NULL,"
                " data BLOB NOT NULL, PRIMARY KEY(layer, face, level, tx, ty));";
            char sql[128];
            snprintf(sql, sizeof sql, "PRAGMA application_id = %d; PRAGMA user_version = %d;",
                     STORE_APPLICATION_ID, STORE_SCHEMA_VERSION);
            if (exec(store, schema, err, "cannot create the schema") ||
                exec(store, sql, err, "cannot write the store identity")) {
                sqlite3_exec(store->db, "ROLLBACK", NULL, NULL, NULL);
                return -1;
            }
        }
        if (exec(store, "COMMIT", err, "cannot commit the new schema")) {
            sqlite3_exec(store->db, "ROLLBACK", NULL, NULL, NULL);
            return -1;
        }
        if (pragma_int(store, "PRAGMA application_id", &app_id, err)) return -1;
        if (pragma_int(store, "PRAGMA user_version", &version, err)) return -1;
    }
    if (app_id != STORE_APPLICATION_ID)
        return og_error_set(err,
                            "'%s' is not an Orogen tile store (SQLite application_id 0x%08X, "
                            "expected 0x%08X)",
                            store->path, (unsigned)app_id, (unsigned)STORE_APPLICATION_ID);
    if (version > STORE_SCHEMA_VERSION)
        return og_error_set(err,
                            "tile store '%s' has schema version %d, newer than this Orogen "
                            "supports (%d); open it with a newer Orogen",
                            store->path, version, STORE_SCHEMA_VERSION);
    if (version < 1)
        return og_error_set(err, "tile store '%s' has an invalid schema version %d", store->path,
                            version);
    return 0;
}

// The meta table's value of key into out ("" and 0 when it has none).
static int meta_text(tile_store *store, const char *key, char *out, size_t len) {
    sqlite3_stmt *st = NULL;
    out[0] = 0;
    int found = 0;
    if (sqlite3_prepare_v2(store->db, "SELECT value FROM meta WHERE key=?1", -1, &st, NULL) ==
        SQLITE_OK) {
        sqlite3_bind_text(st, 1, key, -1, SQLITE_STATIC);
        if (sqlite3_step(st) == SQLITE_ROW) {
            const unsigned char *v = sqlite3_column_text(st, 0);
            snprintf(out, len, "%s", v ? (const char *)v : "");
            found = 1;
        }
    }
    sqlite3_finalize(st);
    return found;
}

// Refuses a store whose meta table names a format, schema or blob version this Orogen
// does not know (before anything is written to it).
static int check_versions(tile_store *store, og_error *err) {
    char format[128], schema[64], blob[64];
    if (!meta_text(store, "format", format, sizeof format) || strcmp(format, "orogen tile store"))
        return og_error_set(err,
                            "tile store '%s': its meta table's format is '%s', not 'orogen "
                            "tile store': refused",
                            store->path, format);
    char *end;
    long v = 0;
    if (!meta_text(store, "schema_version", schema, sizeof schema) ||
        (v = strtol(schema, &end, 10), *end || v != STORE_SCHEMA_VERSION))
        return og_error_set(err,
                            "tile store '%s' has schema_version '%s' (this Orogen knows %d): "
                            "refused, nothing written",
                            store->path, schema, STORE_SCHEMA_VERSION);
    if (!meta_text(store, "blob_version", blob, sizeof blob) ||
        (v = strtol(blob, &end, 10), *end || v < 1 || v > BLOB_VERSION))
        return og_error_set(err,
                            "tile store '%s' has blob_version '%s' (this Orogen reads 1 to "
                            "%d): refused, nothing written",
                            store->path, blob, BLOB_VERSION);
    store->blob_version = (int)v;
    meta_text(store, "store_id", store->store_id, sizeof store->store_id);
    return 0;
}

// Within every write transaction: the meta table says which blob version the store
// holds, and its store_id (random, made by the first write) is written again, so every
// WAL this store writes carries its meta page: a WAL of another store is told by it.
static int mark_write(tile_store *store, og_error *err) {
    if (!store->store_id[0]) {
        uint8_t bits[16];
        if (getrandom(bits, sizeof bits, 0) != (ssize_t)sizeof bits)
            return og_error_set(err, "tile store '%s': cannot make a store id", store->path);
        for (size_t i = 0; i < sizeof bits; i++)
            snprintf(store->store_id + 2 * i, 3, "%02x", bits[i]);
    }
    char sql[256];
    snprintf(sql, sizeof sql,
             "INSERT OR REPLACE INTO main.meta VALUES('blob_version', '%d'), ('store_id', '%s')",
             BLOB_VERSION, store->store_id);
    return exec(store, sql, err, "cannot record the store's identity");
}

static int prepare(tile_store *store, sqlite3_stmt **st, const char *sql, og_error *err) {
    if (sqlite3_prepare_v3(store->db, sql, -1, SQLITE_PREPARE_PERSISTENT, st, NULL) != SQLITE_OK)
        return db_fail(store, err, "cannot prepare statements (damaged schema?)");
    return 0;
}

void tile_store_close(tile_store *store) {
    if (!store) return;
    sqlite3_stmt *all[] = {store->get,       store->has,         store->put,  store->del,
                           store->count_all, store->count_layer, store->each, store->begin,
                           store->commit,    store->rollback};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        sqlite3_finalize(all[i]);
    sqlite3_close(store->db);
    pthread_mutex_destroy(&store->lock);
    free(store->path);
    free(store);
}

// ---------------------------------------------------------------------------
// A WAL that is not the database's
// ---------------------------------------------------------------------------

// A connection to path: "immutable" reads the main file alone (its WAL ignored);
// otherwise read-only through the WAL, never checkpointing it into the file.
// path as an SQLite URI with the given query ("mode=ro").
static void file_uri(const char *path, const char *query, char *uri, size_t len) {
    size_t n = (size_t)snprintf(uri, len, "file:");
    for (const unsigned char *c = (const unsigned char *)path; *c && n + 40 < len; c++) {
        if (*c == '%' || *c == '?' || *c == '#' || *c < 0x20)
            n += (size_t)snprintf(uri + n, len - n, "%%%02X", *c);
        else
            uri[n++] = (char)*c;
    }
    snprintf(uri + n, len - n, "?%s", query);
}

enum { PROBE_READ_ONLY = 0, PROBE_IMMUTABLE = 1, PROBE_THROUGH_WAL = 2 };

// A connection that never writes the database file: immutable (the main file alone),
// read-only through the WAL, or through the WAL with its index (-shm) made if missing
// (a read-only connection cannot make it), queries only, never checkpointing.
static sqlite3 *open_probe(const char *path, int mode) {
    char uri[8400];
    file_uri(path,
             mode == PROBE_IMMUTABLE   ? "immutable=1"
             : mode == PROBE_READ_ONLY ? "mode=ro"
                                       : "",
             uri, sizeof uri);
    sqlite3 *db = NULL;
    int flags = (mode == PROBE_THROUGH_WAL ? SQLITE_OPEN_READWRITE : SQLITE_OPEN_READONLY) |
                SQLITE_OPEN_URI | SQLITE_OPEN_NOMUTEX;
    if (sqlite3_open_v2(uri, &db, flags, NULL) != SQLITE_OK) {
        sqlite3_close(db);
        return NULL;
    }
    sqlite3_db_config(db, SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 1, NULL);
    if (mode == PROBE_THROUGH_WAL) sqlite3_exec(db, "PRAGMA query_only=1", NULL, NULL, NULL);
    return db;
}

// The identity a connection sees: "application id/world id/store id".
// SQLITE_OK, or the error reading them gave.
static int probe_identity(sqlite3 *db, char *out, size_t len) {
    sqlite3_stmt *st = NULL;
    int rc =
        sqlite3_prepare_v2(db,
                           "SELECT (SELECT application_id FROM pragma_application_id) || '/' || "
                           "ifnull((SELECT value FROM meta WHERE key='world_id'), '') || '/' || "
                           "ifnull((SELECT value FROM meta WHERE key='store_id'), '')",
                           -1, &st, NULL);
    if (rc == SQLITE_OK) rc = sqlite3_step(st);
    if (rc == SQLITE_ROW) {
        const unsigned char *v = sqlite3_column_text(st, 0);
        snprintf(out, len, "%s", v ? (const char *)v : "");
        rc = SQLITE_OK;
    }
    if (rc != SQLITE_OK && db) rc = sqlite3_errcode(db);
    sqlite3_finalize(st);
    return rc;
}

static uint32_t get_u32be(const uint8_t *p) {
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

// Whether a valid frame of the WAL at path (its salts those of the WAL's header) holds
// the page numbered page.
static int wal_writes_page(const char *path, uint32_t page) {
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (fd < 0) return 0;
    uint8_t head[32], frame[24];
    int found = 0;
    if (pread(fd, head, sizeof head, 0) == (ssize_t)sizeof head &&
        (get_u32be(head) & 0xFFFFFFFEu) == 0x377F0682u) {
        uint32_t page_size = get_u32be(head + 8);
        if (page_size == 1) page_size = 65536;
        for (off_t at = 32; !found && pread(fd, frame, sizeof frame, at) == (ssize_t)sizeof frame;
             at += 24 + (off_t)page_size) {
            if (memcmp(frame + 8, head + 16, 8) != 0) break; // past the valid frames
            found = get_u32be(frame) == page;
        }
    }
    close(fd);
    return found;
}

// The root page of the meta table, or 0.
static uint32_t meta_root_page(sqlite3 *db) {
    sqlite3_stmt *st = NULL;
    uint32_t page = 0;
    if (db &&
        sqlite3_prepare_v2(db, "SELECT rootpage FROM sqlite_master WHERE name='meta'", -1, &st,
                           NULL) == SQLITE_OK &&
        sqlite3_step(st) == SQLITE_ROW)
        page = (uint32_t)sqlite3_column_int64(st, 0);
    sqlite3_finalize(st);
    return page;
}

// Whether SQLite's quick_check finds the database as a connection sees it consistent.
static int quick_ok(sqlite3 *db) {
    sqlite3_stmt *st = NULL;
    int ok = 0;
    if (db && sqlite3_prepare_v2(db, "PRAGMA quick_check(1)", -1, &st, NULL) == SQLITE_OK &&
        sqlite3_step(st) == SQLITE_ROW) {
        const unsigned char *v = sqlite3_column_text(st, 0);
        ok = v && !strcmp((const char *)v, "ok");
    }
    sqlite3_finalize(st);
    return ok;
}

// Whether a live connection has the database open (SQLite's shared lock on the -shm's
// "DMS" byte): its WAL is then in use, not left over, and is not touched.
static int wal_in_use(const char *shm) {
    int fd = open(shm, O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (fd < 0) return 0;
    struct flock l = {.l_type = F_WRLCK, .l_whence = SEEK_SET, .l_start = 128, .l_len = 1};
    int busy = fcntl(fd, F_GETLK, &l) == 0 && l.l_type != F_UNLCK;
    close(fd);
    return busy;
}

// SQLite replays a WAL beside the database into it on open, whatever database wrote
// it: a stray one (another store's, a copy's) would overwrite the tiles. Before the
// store is opened, a leftover WAL is checked against the main file: it is this store's
// when one of its frames is the meta page (each write transaction rewrites the store's
// row there), the view through it names the same application, world and store ids,
// and that view is as consistent as the file alone (quick_check). Otherwise it is moved
// aside as PATH-wal.foreign (its index, PATH-shm, removed) and never replayed. (A WAL
// left by an Orogen from before store ids, killed before its checkpoint, is also moved
// aside, not lost: renaming it back replays it.)
static void set_foreign_wal_aside(tile_store *store) {
    char wal[4200], shm[4200], aside[4300];
    snprintf(wal, sizeof wal, "%s-wal", store->path);
    snprintf(shm, sizeof shm, "%s-shm", store->path);
    struct stat st;
    if (lstat(wal, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size == 0 || wal_in_use(shm)) return;
    char main_id[256] = "", wal_id[256] = "";
    // Both views: their ids, and whether their pages make a consistent database (a WAL
    // of another database laid over this one's pages mostly does not, also when it does
    // not carry the meta page).
    sqlite3 *db = open_probe(store->path, PROBE_IMMUTABLE);
    int main_rc = db ? probe_identity(db, main_id, sizeof main_id) : SQLITE_CANTOPEN;
    int main_ok = main_rc == SQLITE_OK && quick_ok(db);
    uint32_t meta_page = meta_root_page(db);
    sqlite3_close(db);
    if (main_rc != SQLITE_OK) return; // not judged here: opening reports what the file is
    db = open_probe(store->path, PROBE_THROUGH_WAL);
    int wal_rc = db ? probe_identity(db, wal_id, sizeof wal_id) : SQLITE_CANTOPEN;
    if ((wal_rc & 0xFF) == SQLITE_CANTOPEN || (wal_rc & 0xFF) == SQLITE_READONLY) {
        sqlite3_close(db);
        db = open_probe(store->path, PROBE_READ_ONLY); // a read-only folder: an index exists?
        wal_rc = db ? probe_identity(db, wal_id, sizeof wal_id) : SQLITE_CANTOPEN;
    }
    int wal_ok = wal_rc == SQLITE_OK && quick_ok(db);
    sqlite3_close(db);
    int primary = wal_rc & 0xFF;
    if (primary == SQLITE_CANTOPEN || primary == SQLITE_BUSY || primary == SQLITE_READONLY ||
        primary == SQLITE_IOERR || primary == SQLITE_NOMEM || primary == SQLITE_PERM)
        return; // could not look: leave it (opening will say what fails)
    // The same store: the same application id, and the world and store ids the main
    // file names (the WAL of a store's first writes may name ids the file does not yet).
    char main_f[3][128] = {{0}}, wal_f[3][128] = {{0}};
    sscanf(main_id, "%127[^/]/%127[^/]/%127s", main_f[0], main_f[1], main_f[2]);
    sscanf(wal_id, "%127[^/]/%127[^/]/%127s", wal_f[0], wal_f[1], wal_f[2]);
    if (main_f[1][0] == 0) sscanf(main_id, "%127[^/]//%127s", main_f[0], main_f[2]);
    if (wal_f[1][0] == 0) sscanf(wal_id, "%127[^/]//%127s", wal_f[0], wal_f[2]);
    int ours = wal_rc == SQLITE_OK && !strcmp(main_f[0], wal_f[0]);
    for (int i = 1; i < 3 && ours; i++)
        if (main_f[i][0] && strcmp(main_f[i], wal_f[i]) != 0) ours = 0;
    if (ours && main_ok && !wal_ok) ours = 0, wal_rc = SQLITE_CORRUPT;
    // Every write transaction of a store rewrites its meta row (mark_write): a WAL none
    // of whose frames is the meta page was not written by this store.
    if (ours && meta_page && !wal_writes_page(wal, meta_page)) ours = 0;
    if (ours) return;
    for (int n = 1; n < 100; n++) {
        if (n == 1)
            snprintf(aside, sizeof aside, "%s.foreign", wal);
        else
            snprintf(aside, sizeof aside, "%s.foreign%d", wal, n);
        if (renameat2(AT_FDCWD, wal, AT_FDCWD, aside, RENAME_NOREPLACE) == 0 ||
            ((errno == EINVAL || errno == ENOSYS) && link(wal, aside) == 0 && unlink(wal) == 0)) {
            unlink(shm);
            snprintf(store->warning, sizeof store->warning,
                     "warning: %s is not this tile store's write-ahead log (%s): moved aside "
                     "as %s, not replayed",
                     wal,
                     wal_rc == SQLITE_OK ? "it holds another database's pages"
                                         : "the view "
                                           "through it is damaged",
                     aside);
            return;
        }
        if (errno != EEXIST) break;
    }
    snprintf(store->warning, sizeof store->warning,
             "warning: %s is not this tile store's write-ahead log and cannot be moved aside "
             "(%s)",
             wal, strerror(errno));
}

const char *tile_store_warning(const tile_store *store) {
    return store->warning;
}

// Why a store that exists cannot be written (for tile_store_open_readable): the file
// system, the folder's or the file's permissions, or a full disk; found without writing.
static void write_cause(const char *path, const char *sqlite_why, char *out, size_t len) {
    char dir[4200];
    path_folder(path, dir, sizeof dir);
    struct statvfs fs;
    int have_fs = statvfs(dir, &fs) == 0;
    if (have_fs && (fs.f_flag & ST_RDONLY))
        snprintf(out, len, "its folder %s is on a read-only file system", dir);
    else if (access(dir, W_OK) != 0)
        snprintf(out, len, "its folder %s is not writable (%s)", dir, strerror(errno));
    else if (access(path, W_OK) != 0)
        snprintf(out, len, "the file is not writable (%s)", strerror(errno));
    else if (have_fs && (unsigned long long)fs.f_bavail * fs.f_frsize < (1ull << 20))
        snprintf(out, len, "the disk is full (%llu KiB free)",
                 (unsigned long long)fs.f_bavail * fs.f_frsize / 1024);
    else
        snprintf(out, len, "%s", sqlite_why);
}

static tile_store *open_store(const char *path, int read_only, og_error *err);

tile_store *tile_store_open(const char *path, og_error *err) {
    return open_store(path, 0, err);
}

tile_store *tile_store_open_readable(const char *path, og_error *err) {
    tile_store *store = open_store(path, 0, err);
    struct stat st;
    if (store || stat(path, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size == 0) return store;
    og_error why = *err;
    // Only a store that cannot be written is opened for reading: not a damaged or
    // foreign one, nor an unknown version.
    if (strstr(why.msg, "refused") || strstr(why.msg, "not an Orogen tile store")) return NULL;
    if (!(store = open_store(path, 1, err))) {
        *err = why;
        return NULL;
    }
    write_cause(path, why.msg, store->read_only, sizeof store->read_only);
    return store;
}

const char *tile_store_read_only(const tile_store *store) {
    return store->read_only;
}

static tile_store *open_store(const char *path, int read_only, og_error *err) {
    tile_store *store = calloc(1, sizeof *store);
    if (!store || !(store->path = strdup(path))) {
        free(store);
        og_error_set(err, "tile store '%s': out of memory", path);
        return NULL;
    }
    pthread_mutex_init(&store->lock, NULL);
    set_foreign_wal_aside(store);
    int stuck = strstr(store->warning, "cannot be moved aside") != NULL;
    if (stuck && !read_only) {
        og_error_set(err, "tile store '%s': %s; not opened (it would be replayed into the store)",
                     path, store->warning + 9);
        tile_store_close(store);
        return NULL;
    }
    // NOMUTEX: our own lock serialises use of the connection. Read-only: through the
    // WAL when SQLite can (its index exists or can be made), else the main file alone
    // (immutable), which is also how a foreign WAL that could not be moved is ignored.
    char wal_path[4200];
    struct stat wst;
    snprintf(wal_path, sizeof wal_path, "%s-wal", path);
    int has_wal = lstat(wal_path, &wst) == 0 && wst.st_size > 0;
    int rc = SQLITE_CANTOPEN;
    if (!read_only) {
        // URI filenames on: save attaches its sources read-only ("file:...?mode=ro").
        char uri[8400];
        file_uri(path, "", uri, sizeof uri);
        rc = sqlite3_open_v2(uri, &store->db,
                             SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX |
                                 SQLITE_OPEN_URI,
                             NULL);
    } else {
        if (!has_wal && (store->db = open_probe(path, PROBE_IMMUTABLE))) // nothing to replay
            rc = SQLITE_OK;
        if (rc != SQLITE_OK && !stuck) {
            sqlite3 *db = open_probe(path, PROBE_READ_ONLY);
            if (db && sqlite3_exec(db, "SELECT count(*) FROM sqlite_master", NULL, NULL, NULL) ==
                          SQLITE_OK)
                store->db = db, rc = SQLITE_OK;
            else
                sqlite3_close(db);
        }
        if (rc != SQLITE_OK && (!has_wal || stuck) &&
            (store->db = open_probe(path, PROBE_IMMUTABLE)))
            rc = SQLITE_OK;
    }
    if (rc != SQLITE_OK) {
        if (!store->db) {
            og_error_set(err, "tile store '%s': cannot open: out of memory", path);
        } else {
            int e = sqlite3_system_errno(store->db);
            og_error_set(err, "cannot open tile store '%s': %s%s%s", path,
                         sqlite3_errmsg(store->db), e ? ": " : "", e ? strerror(e) : "");
        }
        tile_store_close(store);
        return NULL;
    }
    sqlite3_extended_result_codes(store->db, 1);
    sqlite3_busy_timeout(store->db, STORE_BUSY_TIMEOUT_MS);
    if (store_init_schema(store, err) || check_versions(store, err)) goto fail;
    if (read_only) goto statements;
    if (sqlite3_db_readonly(store->db, "main") == 1) {
        og_error_set(err, "tile store '%s' is read-only (check the file's permissions)", path);
        goto fail;
    }
    // WAL: readers never block the writer and a commit is one append. With
    // synchronous=FULL the WAL is synced at every commit, so a commit that
    // returned survives power loss, and a kill at any instant leaves the old
    // or the new state (NORMAL would keep atomicity but could lose the last
    // commits on power loss: not acceptable for a user's save).
    sqlite3_stmt *st = NULL;
    int wal = 0;
    if (sqlite3_prepare_v2(store->db, "PRAGMA journal_mode=WAL", -1, &st, NULL) == SQLITE_OK &&
        sqlite3_step(st) == SQLITE_ROW) {
        const unsigned char *mode = sqlite3_column_text(st, 0);
        wal = mode && strcmp((const char *)mode, "wal") == 0;
    }
    sqlite3_finalize(st);
    if (!wal) {
        db_fail(store, err, "cannot switch to WAL journal mode");
        goto fail;
    }
    if (exec(store, "PRAGMA synchronous=FULL", err, "cannot set synchronous mode")) goto fail;
statements:;

    if (prepare(store, &store->get,
                "SELECT data FROM tiles WHERE layer=?1 AND face=?2 AND level=?3 AND tx=?4 "
                "AND ty=?5",
                err) ||
        prepare(store, &store->has,
                "SELECT 1 FROM tiles WHERE layer=?1 AND face=?2 AND level=?3 AND tx=?4 AND ty=?5",
                err) ||
        prepare(store, &store->put,
                "INSERT INTO tiles(layer, face, level, tx, ty, data) VALUES(?1,?2,?3,?4,?5,?6) "
                "ON CONFLICT(layer, face, level, tx, ty) DO UPDATE SET data=excluded.data",
                err) ||
        prepare(store, &store->del,
                "DELETE FROM tiles WHERE layer=?1 AND face=?2 AND level=?3 AND tx=?4 AND ty=?5",
                err) ||
        prepare(store, &store->count_all, "SELECT count(*) FROM tiles", err) ||
        prepare(store, &store->count_layer, "SELECT count(*) FROM tiles WHERE layer=?1", err) ||
        prepare(store, &store->each, "SELECT layer, face, level, tx, ty FROM tiles", err) ||
        prepare(store, &store->begin, "BEGIN IMMEDIATE", err) ||
        prepare(store, &store->commit, "COMMIT", err) ||
        prepare(store, &store->rollback, "ROLLBACK", err))
        goto fail;
    return store;
fail:
    tile_store_close(store);
    return NULL;
}

// Runs a statement without result rows; on failure sets err (before the
// reset, while SQLite still holds the reason) and returns -1.
static int step_done(tile_store *store, sqlite3_stmt *st, og_error *err, const char *what) {
    int rc = sqlite3_step(st) == SQLITE_DONE ? 0 : db_fail(store, err, what);
    sqlite3_reset(st);
    return rc;
}

tile_store_status tile_store_get(tile_store *store, tile_key key, void *out, size_t bytes,
                                 og_error *err) {
    if (key_valid(key, err, store->path)) return TILE_STORE_ERROR;
    size_t want = tile_layer_bytes((tile_layer)key.layer);
    char desc[128];
    if (bytes != want) {
        og_error_set(err, "tile store '%s': %s: buffer is %zu bytes, the tile is %zu", store->path,
                     tile_key_describe(key, desc, sizeof desc), bytes, want);
        return TILE_STORE_ERROR;
    }

    // Copy the blob out under the lock; decompress after releasing it so other
    // threads can use the connection meanwhile.
    void *blob = NULL;
    size_t blob_bytes = 0;
    int kind = SQLITE_NULL;
    pthread_mutex_lock(&store->lock);
    bind_key(store->get, key);
    int rc = sqlite3_step(store->get);
    if (rc == SQLITE_ROW) {
        kind = sqlite3_column_type(store->get, 0);
        const void *data = sqlite3_column_blob(store->get, 0);
        int n = sqlite3_column_bytes(store->get, 0);
        if (data && n > 0 && (blob = malloc((size_t)n))) {
            memcpy(blob, data, (size_t)n);
            blob_bytes = (size_t)n;
        } else if (n > 0) {
            rc = SQLITE_NOMEM;
        }
    }
    tile_store_status status = TILE_STORE_OK;
    if (rc == SQLITE_DONE) {
        status = TILE_STORE_NOT_FOUND;
    } else if (rc != SQLITE_ROW) {
        db_fail(store, err, tile_key_describe(key, desc, sizeof desc));
        status = TILE_STORE_ERROR;
    }
    sqlite3_reset(store->get);
    pthread_mutex_unlock(&store->lock);
    if (status != TILE_STORE_OK) {
        free(blob);
        return status;
    }

    og_error why = {{0}};
    if (kind != SQLITE_BLOB) {
        og_error_set(&why, "stored value is not a blob");
    } else if (tile_blob_decode_key(key, blob, blob_bytes, out, &why) == 0) {
        free(blob);
        return TILE_STORE_OK;
    }
    free(blob);
    og_error_set(err, "tile store '%s': %s is corrupt: %s", store->path,
                 tile_key_describe(key, desc, sizeof desc), why.msg);
    return TILE_STORE_CORRUPT;
}

int tile_store_has(tile_store *store, tile_key key) {
    pthread_mutex_lock(&store->lock);
    bind_key(store->has, key);
    int found = sqlite3_step(store->has) == SQLITE_ROW;
    sqlite3_reset(store->has);
    pthread_mutex_unlock(&store->lock);
    return found;
}

int tile_store_put_batch(tile_store *store, const tile_store_write *writes, size_t count,
                         og_error *err) {
    if (!count) return 0;
    if (!writes) return og_error_set(err, "tile store '%s': no writes given", store->path);
    for (size_t i = 0; i < count; i++)
        if (key_valid(writes[i].key, err, store->path)) return -1;

    // Compress everything before taking the lock: encoding is the slow part
    // and must not hold up readers or other writers.
    void **blobs = calloc(count, sizeof *blobs);
    size_t *sizes = calloc(count, sizeof *sizes);
    int result = 0;
    char desc[128];
    if (!blobs || !sizes) {
        result = og_error_set(err, "tile store '%s': out of memory for a batch of %zu tiles",
                              store->path, count);
        goto done;
    }
    for (size_t i = 0; i < count; i++) {
        if (!writes[i].data) continue;
        sizes[i] = tile_blob_encode_key(writes[i].key, writes[i].data, &blobs[i]);
        if (!sizes[i] || sizes[i] > INT_MAX) {
            result = og_error_set(err, "tile store '%s': %s: cannot compress the tile", store->path,
                                  tile_key_describe(writes[i].key, desc, sizeof desc));
            goto done;
        }
    }

    pthread_mutex_lock(&store->lock);
    if (step_done(store, store->begin, err, "cannot start a write transaction")) {
        result = -1;
        pthread_mutex_unlock(&store->lock);
        goto done;
    }
    result = mark_write(store, err);
    for (size_t i = 0; i < count && result == 0; i++) {
        sqlite3_stmt *st = writes[i].data ? store->put : store->del;
        bind_key(st, writes[i].key);
        if (writes[i].data) sqlite3_bind_blob(st, 6, blobs[i], (int)sizes[i], SQLITE_STATIC);
        char what[192];
        snprintf(what, sizeof what, "cannot write %s",
                 tile_key_describe(writes[i].key, desc, sizeof desc));
        result = step_done(store, st, err, what);
        sqlite3_clear_bindings(st);
    }
    if (result == 0) result = step_done(store, store->commit, err, "cannot commit the write");
    if (result == 0) store->blob_version = BLOB_VERSION;
    if (result != 0 && !sqlite3_get_autocommit(store->db)) {
        og_error ignored; // keep the first failure's message
        step_done(store, store->rollback, &ignored, "cannot roll back");
    }
    pthread_mutex_unlock(&store->lock);

done:
    if (blobs)
        for (size_t i = 0; i < count; i++)
            free(blobs[i]);
    free(blobs);
    free(sizes);
    return result;
}

int64_t tile_store_count(tile_store *store, int layer) {
    pthread_mutex_lock(&store->lock);
    sqlite3_stmt *st = layer < 0 ? store->count_all : store->count_layer;
    if (layer >= 0) sqlite3_bind_int(st, 1, layer);
    int64_t n = sqlite3_step(st) == SQLITE_ROW ? sqlite3_column_int64(st, 0) : -1;
    sqlite3_reset(st);
    pthread_mutex_unlock(&store->lock);
    return n;
}

int tile_store_get_meta(tile_store *store, const char *key, char *value, size_t len,
                        og_error *err) {
    pthread_mutex_lock(&store->lock);
    sqlite3_stmt *st = NULL;
    int rc = sqlite3_prepare_v2(store->db, "SELECT value FROM meta WHERE key=?1", -1, &st, NULL);
    int result = 0;
    if (rc == SQLITE_OK) {
        sqlite3_bind_text(st, 1, key, -1, SQLITE_STATIC);
        rc = sqlite3_step(st);
    }
    if (rc == SQLITE_ROW) {
        const unsigned char *text = sqlite3_column_text(st, 0);
        snprintf(value, len, "%s", text ? (const char *)text : "");
        result = 1;
    } else if (rc != SQLITE_DONE) {
        result = db_fail(store, err, "cannot read the store's meta table");
    }
    sqlite3_finalize(st);
    pthread_mutex_unlock(&store->lock);
    return result;
}

int tile_store_set_meta(tile_store *store, const char *key, const char *value, og_error *err) {
    pthread_mutex_lock(&store->lock);
    sqlite3_stmt *st = NULL;
    int rc =
        sqlite3_prepare_v2(store->db, "INSERT OR REPLACE INTO meta VALUES(?1, ?2)", -1, &st, NULL);
    if (rc == SQLITE_OK) {
        sqlite3_bind_text(st, 1, key, -1, SQLITE_STATIC);
        sqlite3_bind_text(st, 2, value, -1, SQLITE_STATIC);
        rc = sqlite3_step(st);
    }
    int result = rc == SQLITE_DONE ? 0 : db_fail(store, err, "cannot write the store's meta table");
    sqlite3_finalize(st);
    pthread_mutex_unlock(&store->lock);
    return result;
}

int tile_store_each(tile_store *store, int (*fn)(void *user, tile_key key), void *user,
                    og_error *err) {
    // Collect the keys first and call fn without the lock, so fn may use the
    // store (typically to get the tile) without deadlocking.
    tile_key *keys = NULL;
    size_t n = 0, cap = 0;
    int rc, result = 0;
    pthread_mutex_lock(&store->lock);
    while ((rc = sqlite3_step(store->each)) == SQLITE_ROW) {
        if (n == cap) {
            size_t grown = cap ? cap * 2 : 256;
            tile_key *more = realloc(keys, grown * sizeof *keys);
            if (!more) {
                result =
                    og_error_set(err, "tile store '%s': out of memory listing tiles", store->path);
                break;
            }
            keys = more;
            cap = grown;
        }
        keys[n++] =
            (tile_key){sqlite3_column_int(store->each, 0), sqlite3_column_int(store->each, 1),
                       sqlite3_column_int(store->each, 2), sqlite3_column_int(store->each, 3),
                       sqlite3_column_int(store->each, 4)};
    }
    if (result == 0 && rc != SQLITE_DONE) result = db_fail(store, err, "cannot list tiles");
    sqlite3_reset(store->each);
    pthread_mutex_unlock(&store->lock);
    for (size_t i = 0; i < n && result == 0; i++)
        if (fn(user, keys[i])) break;
    free(keys);
    return result;
}

// Within the caller's transaction: meta state_id = id (nothing when id is NULL).
static int set_state_id(tile_store *store, const char *id, og_error *err) {
    if (!id) return 0;
    sqlite3_stmt *st = NULL;
    int rc = sqlite3_prepare_v2(
        store->db, "INSERT OR REPLACE INTO main.meta VALUES('state_id', ?1)", -1, &st, NULL);
    if (rc == SQLITE_OK) {
        sqlite3_bind_text(st, 1, id, -1, SQLITE_STATIC);
        rc = sqlite3_step(st);
    }
    sqlite3_finalize(st);
    return rc == SQLITE_DONE ? 0 : db_fail(store, err, "cannot record the saved state");
}

int tile_store_merge_from(tile_store *store, const char *const *sources, size_t count, int replace,
                          const char *state_id, og_error *err) {
    if (count > 4) return og_error_set(err, "tile store '%s': at most 4 sources", store->path);
    pthread_mutex_lock(&store->lock);
    int rc = 0;
    size_t attached = 0;
    for (; attached < count && rc == 0; attached++) {
        char sql[64];
        snprintf(sql, sizeof sql, "ATTACH DATABASE ?1 AS merge_source%zu", attached);
        sqlite3_stmt *st = NULL;
        if (sqlite3_prepare_v2(store->db, sql, -1, &st, NULL) != SQLITE_OK) {
            rc = db_fail(store, err, "cannot prepare attaching the tiles to save");
        } else {
            // Read-only: a source on a full disk or in a read-only folder is still read;
            // with no WAL to replay, as an immutable file (no index to write or lock).
            char uri[8400], wal[4200];
            struct stat wst;
            snprintf(wal, sizeof wal, "%s-wal", sources[attached]);
            int no_wal = lstat(wal, &wst) != 0 || wst.st_size == 0;
            file_uri(sources[attached], "mode=ro", uri, sizeof uri);
            sqlite3_bind_text(st, 1, uri, -1, SQLITE_TRANSIENT);
            int step = sqlite3_step(st);
            if (step != SQLITE_DONE && no_wal) {
                sqlite3_reset(st);
                file_uri(sources[attached], "immutable=1", uri, sizeof uri);
                sqlite3_bind_text(st, 1, uri, -1, SQLITE_TRANSIENT);
                step = sqlite3_step(st);
            }
            if (step != SQLITE_DONE) rc = db_fail(store, err, "cannot attach the tiles to save");
        }
        sqlite3_finalize(st);
        if (rc != 0) break;
    }
    // One transaction: the store has all of it, or is as it was (a full disk half-way
    // through a save-as must not leave it emptied).
    if (rc == 0 && exec(store, "BEGIN IMMEDIATE", err, "cannot start the merge") == 0) {
        if (replace) rc = exec(store, "DELETE FROM main.tiles", err, "cannot clear the tiles");
        for (size_t i = 0; i < count && rc == 0; i++) {
            // Blobs are copied as they are: both stores share the blob format.
            char sql[320];
            snprintf(
                sql, sizeof sql,
                "INSERT INTO main.tiles(layer, face, level, tx, ty, data) "
                "SELECT layer, face, level, tx, ty, data FROM merge_source%zu.tiles WHERE true "
                "ON CONFLICT(layer, face, level, tx, ty) DO UPDATE SET data=excluded.data",
                i);
            rc = exec(store, sql, err, "cannot merge the tiles to save");
        }
        if (rc == 0) rc = set_state_id(store, state_id, err);
        if (rc == 0) rc = mark_write(store, err);
        if (rc == 0) rc = exec(store, "COMMIT", err, "cannot commit the merge");
        if (rc == 0) store->blob_version = BLOB_VERSION;
        if (rc != 0 && !sqlite3_get_autocommit(store->db))
            sqlite3_exec(store->db, "ROLLBACK", NULL, NULL, NULL);
    } else if (rc == 0) {
        rc = -1;
    }
    for (size_t i = 0; i < attached; i++) {
        char sql[64];
        snprintf(sql, sizeof sql, "DETACH DATABASE merge_source%zu", i);
        sqlite3_exec(store->db, sql, NULL, NULL, NULL);
    }
    pthread_mutex_unlock(&store->lock);
    return rc;
}

int tile_store_clear(tile_store *store, og_error *err) {
    pthread_mutex_lock(&store->lock);
    int rc = exec(store, "BEGIN IMMEDIATE", err, "cannot start clearing the tiles");
    if (rc == 0) rc = mark_write(store, err);
    if (rc == 0) rc = exec(store, "DELETE FROM tiles", err, "cannot clear the tiles");
    if (rc == 0) rc = exec(store, "COMMIT", err, "cannot commit clearing the tiles");
    if (rc != 0 && !sqlite3_get_autocommit(store->db))
        sqlite3_exec(store->db, "ROLLBACK", NULL, NULL, NULL);
    pthread_mutex_unlock(&store->lock);
    return rc;
}

const char *tile_store_library_versions(void) {
    static char text[96];
    snprintf(text, sizeof text, "SQLite %s, zstd %s", sqlite3_libversion(), ZSTD_versionString());
    return text;
}
