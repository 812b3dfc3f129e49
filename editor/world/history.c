#include "editor/world/history.h"

#include "editor/world/thread_scratch.h"
#include "io/avx2_clone.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#include <zstd.h>

struct history {
    history_step **steps;
    size_t count, cap, position;
    size_t bytes, budget;
    uint64_t next_id;
    uint64_t floor_id; // the state reached by the dropped steps (0: the loaded state)
    uint64_t saved_id; // the state that was saved last
    uint64_t dropped_total;
    void (*reader_wait)(void *user); // history_set_reader
    void *reader;
};

static void squeeze_queue(history *h, history_step *s);
static void squeeze_collect(history *h);
static void squeeze_cancel(const history_step *s);

history *history_create(size_t budget_bytes) {
    history *h = calloc(1, sizeof *h);
    if (!h) return NULL;
    h->budget = budget_bytes ? budget_bytes : (size_t)512 << 20;
    h->next_id = 1;
    return h;
}

void history_set_reader(history *h, void (*wait)(void *user), void *user) {
    h->reader_wait = wait;
    h->reader = user;
}

// Before a step's delta is freed or replaced: the reader done with them.
static void reader_done(history *h) {
    if (h->reader_wait) h->reader_wait(h->reader);
}

void history_destroy(history *h) {
    if (!h) return;
    reader_done(h);
    for (size_t i = 0; i < h->count; i++)
        history_step_free(h->steps[i]);
    free(h->steps);
    free(h);
}

history_step *history_step_new(const char *label) {
    history_step *s = calloc(1, sizeof *s);
    if (!s) return NULL;
    size_t n = strlen(label);
    if (n >= sizeof s->label) n = sizeof s->label - 1;
    memcpy(s->label, label, n);
    s->bytes = sizeof *s;
    return s;
}

int history_step_set_params(history_step *s, const world_params *before,
                            const world_params *after) {
    if (!s->params) {
        if (!(s->params = malloc(sizeof *s->params))) return -1;
        s->bytes += sizeof *s->params;
    }
    s->params->before = *before;
    s->params->after = *after;
    s->has_params = 1;
    return 0;
}

void history_step_free(history_step *s) {
    if (!s) return;
    squeeze_cancel(s);
    free(s->params);
    for (size_t i = 0; i < s->tile_count; i++)
        free(s->tiles[i].delta);
    free(s->tiles);
    free(s->dirty);
    free(s);
}

// Element size of a layer's samples: its bytes are split into that many planes
// so the always-equal high bytes of a small change line up in zero runs.
static size_t element_bytes(tile_layer layer) {
    switch (tile_layer_format(layer)) {
    case TILE_FORMAT_U8X8:
        return TILE_MATERIALS;
    default:
        return 4;
    }
}

// A delta covers a part of its tile: PART_MAGIC, u16 x0 z0 x1 z1 (tile-local samples,
// little-endian), then the part's XOR split into planes (one per byte of an element,
// w x h bytes each, row by row), each as u8 codec, u32 size and its bytes: raw, as
// zero runs (zero_runs_encode), or as a zstd frame. Deltas of older journals are a
// bare zstd frame of the whole tile's planes (magic 28 B5 2F FD): history_tile_apply
// still reads them.
#define PART_MAGIC "OGp1"
#define PART_HEADER 12
#define PLANE_HEADER 5
enum { PLANE_RAW = 0, PLANE_ZERO_RUNS = 1, PLANE_ZSTD = 2 };
// zstd level 1 where it is tried (plane_wants_zstd).
#define PLANE_ZSTD_LEVEL 1

// ---- zero runs --------------------------------------------------------------------
// The XOR of a step is zero wherever it left a tile alone, and its high planes are
// mostly zero where it changed it; the low planes are noise no codec shrinks much.
// Every plane first drops its zero runs (8-byte words) at memory speed: zstd took 180
// us for one dab's 66 KB of planes (the whole commit's budget is 100 us), mostly on
// the noise. zstd then gets only the planes whose bytes say it will gain.
// Stream: tokens (varint zeros, varint literal count, the literal bytes) to the end.

static uint64_t word_at(const uint8_t *p) {
    uint64_t w;
    memcpy(&w, p, sizeof w);
    return w;
}

static uint8_t *put_varint(uint8_t *o, size_t v) {
    for (; v >= 0x80; v >>= 7)
        *o++ = (uint8_t)(v | 0x80);
    *o++ = (uint8_t)v;
    return o;
}

static int get_varint(const uint8_t **p, const uint8_t *end, size_t *v) {
    *v = 0;
    for (int shift = 0; shift < 64 && *p < end; shift += 7) {
        uint8_t b = *(*p)++;
        *v |= (size_t)(b & 0x7f) << shift;
        if (!(b & 0x80)) return 0;
    }
    return -1;
}

// Encodes in[0, n) into out (room for cap bytes); returns the size, or 0 when it
// would not fit (the caller stores the bytes raw).
AVX2_CLONE static size_t zero_runs_encode(const uint8_t *in, size_t n, uint8_t *out, size_t cap) {
    uint8_t *o = out, *end = out + cap;
    size_t i = 0;
    while (i < n) {
        size_t z = i;
        // Words are looked at four at a time first (a dab's noisy low planes are one
        // long literal), then one at a time: the same runs.
        while (z + 32 <= n && (word_at(in + z) | word_at(in + z + 8) | word_at(in + z + 16) |
                               word_at(in + z + 24)) == 0)
            z += 32;
        while (z + 8 <= n && word_at(in + z) == 0)
            z += 8;
        if (z + 8 > n)
            while (z < n && in[z] == 0)
                z++;
        size_t l = z;
        while (l + 32 <= n && ((word_at(in + l) != 0) & (word_at(in + l + 8) != 0) &
                               (word_at(in + l + 16) != 0) & (word_at(in + l + 24) != 0)))
            l += 32;
        while (l < n && !(l + 8 <= n && word_at(in + l) == 0))
            l += l + 8 <= n ? 8 : 1;
        if ((size_t)(end - o) < 20 + (l - z)) return 0;
        o = put_varint(o, z - i);
        o = put_varint(o, l - z);
        memcpy(o, in + z, l - z);
        o += l - z;
        i = l;
    }
    return (size_t)(o - out);
}

// Decodes into out[0, n) (zeroed first); -1 when the stream does not fill it exactly.
static int zero_runs_decode(const uint8_t *in, size_t bytes, uint8_t *out, size_t n) {
    const uint8_t *p = in, *end = in + bytes;
    size_t i = 0;
    memset(out, 0, n);
    while (p < end) {
        size_t z, l;
        if (get_varint(&p, end, &z) != 0 || get_varint(&p, end, &l) != 0) return -1;
        if (z > n - i || l > n - i - z || l > (size_t)(end - p)) return -1;
        i += z;
        memcpy(out + i, p, l);
        i += l, p += l;
    }
    return i == n ? 0 : -1;
}

// ---- part deltas ------------------------------------------------------------------

static void put_u16(uint8_t *p, int64_t v) {
    p[0] = (uint8_t)v, p[1] = (uint8_t)(v >> 8);
}

static int64_t get_u16(const uint8_t *p) {
    return p[0] | p[1] << 8;
}

// planes[k * n + i] = byte k of (a ^ b) at the part's i-th element (row by row).
AVX2_CLONE static void split_planes(const uint8_t *restrict a, const uint8_t *restrict b, size_t el,
                                    grid_rect part, uint8_t *restrict planes) {
    size_t w = (size_t)(part.x1 - part.x0), n = w * (size_t)(part.z1 - part.z0), i = 0;
    for (int64_t z = part.z0; z < part.z1; z++) {
        size_t at = ((size_t)z * TILE_SIZE + (size_t)part.x0) * el;
        const uint8_t *ra = a + at, *rb = b + at;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
        if (el == 4) { // float and int16x2 layers: one word per element, 4 planes
            uint8_t *p0 = planes + i, *p1 = p0 + n, *p2 = p1 + n, *p3 = p2 + n;
            size_t x = 0;
            // 16 elements at a time through words of its own: vectorised whatever the
            // planes' place (the loop below, vectorised with checks of where the planes
            // lie, ran a scalar fallback for some places, at 3x the time).
            for (; x + 16 <= w; x += 16) {
                uint32_t u[16];
                for (int k = 0; k < 16; k++) {
                    uint32_t va, vb;
                    memcpy(&va, ra + 4 * (x + k), 4);
                    memcpy(&vb, rb + 4 * (x + k), 4);
                    u[k] = va ^ vb;
                }
                for (int k = 0; k < 16; k++)
                    p0[x + k] = (uint8_t)u[k];
                for (int k = 0; k < 16; k++)
                    p1[x + k] = (uint8_t)(u[k] >> 8);
                for (int k = 0; k < 16; k++)
                    p2[x + k] = (uint8_t)(u[k] >> 16);
                for (int k = 0; k < 16; k++)
                    p3[x + k] = (uint8_t)(u[k] >> 24);
            }
            for (; x < w; x++) {
                uint32_t u, v;
                memcpy(&u, ra + 4 * x, 4);
                memcpy(&v, rb + 4 * x, 4);
                u ^= v;
                p0[x] = (uint8_t)u, p1[x] = (uint8_t)(u >> 8), p2[x] = (uint8_t)(u >> 16);
                p3[x] = (uint8_t)(u >> 24);
            }
            i += w;
            continue;
        }
#endif
        for (size_t x = 0; x < w; x++, i++)
            for (size_t k = 0; k < el; k++)
                planes[k * n + i] = ra[x * el + k] ^ rb[x * el + k];
    }
}

// Whether the part's bytes differ between a and b.
static int part_differs(const uint8_t *a, const uint8_t *b, size_t el, grid_rect part) {
    size_t row = (size_t)(part.x1 - part.x0) * el;
    for (int64_t z = part.z0; z < part.z1; z++) {
        size_t at = ((size_t)z * TILE_SIZE + (size_t)part.x0) * el;
        if (memcmp(a + at, b + at, row) != 0) return 1;
    }
    return 0;
}

// A compression context per thread, kept for its life: making one per plane (as
// ZSTD_compress does) costs more than compressing a dab's plane.
static pthread_key_t cctx_key;
static pthread_once_t cctx_once = PTHREAD_ONCE_INIT;

static void free_cctx(void *c) {
    ZSTD_freeCCtx(c);
}

static void make_cctx_key(void) {
    pthread_key_create(&cctx_key, free_cctx);
}

static ZSTD_CCtx *thread_cctx(void) {
    pthread_once(&cctx_once, make_cctx_key);
    ZSTD_CCtx *c = pthread_getspecific(cctx_key);
    if (!c && (c = ZSTD_createCCtx()) != NULL && pthread_setspecific(cctx_key, c) != 0) {
        ZSTD_freeCCtx(c);
        c = NULL;
    }
    return c;
}

// Whether zstd should try a plane whose zero runs took `size` bytes (at runs): when
// the bytes' entropy, estimated from every 4th, is well under their count. Noise
// (a float's low bytes) is not worth zstd's time; a high plane's few values are.
// Nor is a plane whose runs already fit in 2 KB (a dab's coarser mip levels): zstd's
// setup per call cost about as much as encoding a dab's whole tile, to save a few
// hundred bytes.
static int plane_wants_zstd(const uint8_t *runs, size_t size) {
    if (size < 2048) return 0;
    uint32_t count[256] = {0};
    size_t n = 0;
    for (size_t i = 0; i < size; i += 4, n++)
        count[runs[i]]++;
    double bits = 0;
    for (int v = 0; v < 256; v++)
        if (count[v]) bits += count[v] * log2((double)n / count[v]);
    return bits < 0.7 * 8.0 * (double)n;
}

static void put_u32(uint8_t *p, size_t v) {
    p[0] = (uint8_t)v, p[1] = (uint8_t)(v >> 8), p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static size_t get_u32(const uint8_t *p) {
    return (size_t)p[0] | (size_t)p[1] << 8 | (size_t)p[2] << 16 | (size_t)p[3] << 24;
}

// Writes one plane of n bytes at o (room for PLANE_HEADER + n): the smallest of its
// encodings tried. Returns the bytes written.
static size_t encode_plane(const uint8_t *plane, size_t n, uint8_t *o, int zstd) {
    uint8_t *body = o + PLANE_HEADER;
    size_t size = zero_runs_encode(plane, n, body, n);
    o[0] = PLANE_ZERO_RUNS;
    if (!size) {
        memcpy(body, plane, size = n);
        o[0] = PLANE_RAW;
    }
    ZSTD_CCtx *c = zstd && size > 0 && plane_wants_zstd(body, size) ? thread_cctx() : NULL;
    uint8_t *frame = c ? malloc(ZSTD_compressBound(n)) : NULL;
    if (frame) {
        size_t comp =
            ZSTD_compressCCtx(c, frame, ZSTD_compressBound(n), plane, n, PLANE_ZSTD_LEVEL);
        if (!ZSTD_isError(comp) && comp < size) {
            memcpy(body, frame, size = comp);
            o[0] = PLANE_ZSTD;
        }
        free(frame);
    }
    put_u32(o + 1, size);
    return PLANE_HEADER + size;
}

static int encode_part(tile_layer layer, const void *before, const void *after, grid_rect part,
                       int zstd, void **delta, size_t *bytes) {
    *delta = NULL;
    *bytes = 0;
    part = grid_rect_intersect(part, (grid_rect){0, 0, TILE_SIZE, TILE_SIZE});
    size_t el = element_bytes(layer);
    if (grid_rect_empty(part) || !part_differs(before, after, el, part)) return 0;
    size_t n = (size_t)((part.x1 - part.x0) * (part.z1 - part.z0)), raw = n * el;
    uint8_t *planes =
        thread_scratch(SCRATCH_UNDO_ENCODE, 2 * raw + PART_HEADER + el * PLANE_HEADER);
    if (!planes) return -1;
    uint8_t *out = planes + raw;
    memcpy(out, PART_MAGIC, 4);
    put_u16(out + 4, part.x0), put_u16(out + 6, part.z0);
    put_u16(out + 8, part.x1), put_u16(out + 10, part.z1);
    split_planes(before, after, el, part, planes);
    size_t size = PART_HEADER;
    for (size_t k = 0; k < el; k++)
        size += encode_plane(planes + k * n, n, out + size, zstd);
    if (!(*delta = malloc(size))) return -1;
    memcpy(*delta, out, size);
    *bytes = size;
    return 0;
}

int history_delta_encode_part(tile_layer layer, const void *before, const void *after,
                              grid_rect part, void **delta, size_t *bytes) {
    return encode_part(layer, before, after, part, 1, delta, bytes);
}

int history_delta_encode_part_quick(tile_layer layer, const void *before, const void *after,
                                    grid_rect part, void **delta, size_t *bytes) {
    return encode_part(layer, before, after, part, 0, delta, bytes);
}

// A part delta with zstd tried on its planes as encode_plane tries it, or 0 when that
// gains nothing (or the delta is not a part delta): *out is then untouched.
static int squeeze_delta(tile_layer layer, const uint8_t *d, size_t bytes, void **out,
                         size_t *out_bytes) {
    size_t el = element_bytes(layer);
    if (bytes < PART_HEADER || memcmp(d, PART_MAGIC, 4) != 0) return 0;
    int64_t w = get_u16(d + 8) - get_u16(d + 4), h = get_u16(d + 10) - get_u16(d + 6);
    if (w <= 0 || h <= 0) return 0;
    size_t n = (size_t)(w * h);
    ZSTD_CCtx *c = thread_cctx();
    uint8_t *o = malloc(bytes), *plane = malloc(n), *frame = malloc(ZSTD_compressBound(n));
    int gained = 0;
    size_t at = PART_HEADER, size = PART_HEADER;
    if (!c || !o || !plane || !frame) goto done;
    memcpy(o, d, PART_HEADER);
    for (size_t k = 0; k < el; k++) {
        if (bytes - at < PLANE_HEADER) goto done;
        size_t len = get_u32(d + at + 1);
        const uint8_t *body = d + at + PLANE_HEADER;
        if (len > bytes - at - PLANE_HEADER) goto done;
        size_t keep = PLANE_HEADER + len; // as it is, unless zstd does better
        int decoded = -1;
        if (d[at] != PLANE_ZSTD && plane_wants_zstd(body, len)) {
            if (d[at] == PLANE_RAW && len == n)
                memcpy(plane, body, n), decoded = 0;
            else if (d[at] == PLANE_ZERO_RUNS)
                decoded = zero_runs_decode(body, len, plane, n);
        }
        if (decoded == 0) {
            size_t comp =
                ZSTD_compressCCtx(c, frame, ZSTD_compressBound(n), plane, n, PLANE_ZSTD_LEVEL);
            if (!ZSTD_isError(comp) && comp < len) {
                o[size] = PLANE_ZSTD;
                put_u32(o + size + 1, comp);
                memcpy(o + size + PLANE_HEADER, frame, comp);
                size += PLANE_HEADER + comp, at += keep, gained = 1;
                continue;
            }
        }
        memcpy(o + size, d + at, keep);
        size += keep, at += keep;
    }
    if (at != bytes) gained = 0;
done:
    free(plane);
    free(frame);
    if (!gained) {
        free(o);
        return 0;
    }
    uint8_t *fit = realloc(o, size);
    *out = fit ? fit : o;
    *out_bytes = size;
    return 1;
}

int history_delta_encode(tile_layer layer, const void *before, const void *after, void **delta,
                         size_t *bytes) {
    return history_delta_encode_part(layer, before, after, (grid_rect){0, 0, TILE_SIZE, TILE_SIZE},
                                     delta, bytes);
}

int history_step_add_delta(history_step *s, tile_key key, int was_pristine, void *delta,
                           size_t bytes) {
    history_tile *t = realloc(s->tiles, (s->tile_count + 1) * sizeof *t);
    if (!t) {
        free(delta);
        return -1;
    }
    s->tiles = t;
    s->tiles[s->tile_count++] = (history_tile){key, was_pristine, bytes, delta};
    s->bytes += bytes + sizeof *t;
    s->raw_bytes += tile_layer_bytes((tile_layer)key.layer);
    return 0;
}

// data's part ^= planes (split_planes' layout).
static void xor_planes(uint8_t *data, size_t el, grid_rect part, const uint8_t *planes) {
    size_t w = (size_t)(part.x1 - part.x0), n = w * (size_t)(part.z1 - part.z0), i = 0;
    for (int64_t z = part.z0; z < part.z1; z++) {
        uint8_t *row = data + ((size_t)z * TILE_SIZE + (size_t)part.x0) * el;
        for (size_t x = 0; x < w; x++, i++)
            for (size_t k = 0; k < el; k++)
                row[x * el + k] ^= planes[k * n + i];
    }
}

// Decodes a part delta's planes (after its header: bytes of them) into planes.
static int decode_planes(const uint8_t *d, size_t bytes, size_t el, size_t n, uint8_t *planes) {
    const uint8_t *end = d + bytes;
    for (size_t k = 0; k < el; k++) {
        if ((size_t)(end - d) < PLANE_HEADER) return -1;
        int codec = d[0];
        size_t size = get_u32(d + 1);
        d += PLANE_HEADER;
        if (size > (size_t)(end - d)) return -1;
        uint8_t *plane = planes + k * n;
        if (codec == PLANE_RAW) {
            if (size != n) return -1;
            memcpy(plane, d, n);
        } else if (codec == PLANE_ZERO_RUNS) {
            if (zero_runs_decode(d, size, plane, n) != 0) return -1;
        } else if (codec == PLANE_ZSTD) {
            size_t got = ZSTD_decompress(plane, n, d, size);
            if (ZSTD_isError(got) || got != n) return -1;
        } else {
            return -1;
        }
        d += size;
    }
    return d == end ? 0 : -1;
}

int history_tile_apply(const history_tile *t, void *data) {
    tile_layer layer = (tile_layer)t->key.layer;
    size_t el = element_bytes(layer);
    const uint8_t *d = t->delta;
    grid_rect part = {0, 0, TILE_SIZE, TILE_SIZE};
    int legacy = !(t->bytes >= PART_HEADER && memcmp(d, PART_MAGIC, 4) == 0);
    if (!legacy) {
        part = (grid_rect){get_u16(d + 4), get_u16(d + 6), get_u16(d + 8), get_u16(d + 10)};
        d += PART_HEADER;
        if (part.x1 > TILE_SIZE || part.z1 > TILE_SIZE || grid_rect_empty(part)) return -1;
    }
    size_t n = (size_t)((part.x1 - part.x0) * (part.z1 - part.z0)), raw = n * el;
    size_t have = t->bytes - (size_t)(d - (const uint8_t *)t->delta);
    uint8_t *planes = malloc(raw);
    if (!planes) return -1;
    int rc = 0;
    if (legacy) {
        size_t got = ZSTD_decompress(planes, raw, d, have);
        rc = ZSTD_isError(got) || got != raw ? -1 : 0;
    } else {
        rc = decode_planes(d, have, el, n, planes);
    }
    if (rc == 0) xor_planes(data, el, part, planes);
    free(planes);
    return rc;
}

int history_step_add_dirty(history_step *s, dirty_rect r) {
    dirty_rect *d = realloc(s->dirty, (s->dirty_count + 1) * sizeof *d);
    if (!d) return -1;
    s->dirty = d;
    s->dirty[s->dirty_count++] = r;
    s->bytes += sizeof *d;
    return 0;
}

static uint64_t state_id(const history *h) {
    return h->position ? h->steps[h->position - 1]->id : h->floor_id;
}

// Drops the oldest step. Its state becomes the floor: undo cannot go below it.
static void drop_oldest(history *h) {
    history_step *s = h->steps[0];
    h->floor_id = s->id;
    h->bytes -= s->bytes;
    history_step_free(s);
    memmove(h->steps, h->steps + 1, (h->count - 1) * sizeof *h->steps);
    h->count--;
    h->position--;
    h->dropped_total++;
}

static size_t enforce_budget(history *h) {
    size_t dropped = 0;
    // The newest applied step always stays, even alone over budget.
    while (h->bytes > h->budget && h->position > 1) {
        drop_oldest(h);
        dropped++;
    }
    return dropped;
}

size_t history_push(history *h, history_step *s) {
    reader_done(h); // a redo branch cut, the oldest steps dropped, deltas squeezed
    squeeze_collect(h);
    while (h->count > h->position) {
        history_step *r = h->steps[--h->count];
        h->bytes -= r->bytes;
        history_step_free(r);
    }
    if (h->count == h->cap) {
        size_t cap = h->cap ? h->cap * 2 : 64;
        history_step **grown = realloc(h->steps, cap * sizeof *grown);
        if (!grown) { // keep going without this step's undo rather than fail the edit
            history_step_free(s);
            h->floor_id = h->next_id++;
            while (h->count)
                drop_oldest(h);
            return 0;
        }
        h->steps = grown;
        h->cap = cap;
    }
    s->id = h->next_id++;
    h->steps[h->count++] = s;
    h->position = h->count;
    h->bytes += s->bytes;
    size_t dropped = enforce_budget(h);
    squeeze_queue(h, s);
    return dropped;
}

history_step *history_undo_peek(history *h) {
    reader_done(h);
    squeeze_collect(h);
    return h->position ? h->steps[h->position - 1] : NULL;
}
void history_undo_done(history *h) {
    if (h->position) h->position--;
}
history_step *history_redo_peek(history *h) {
    reader_done(h);
    squeeze_collect(h);
    return h->position < h->count ? h->steps[h->position] : NULL;
}
void history_redo_done(history *h) {
    if (h->position < h->count) h->position++;
}

size_t history_count(const history *h) {
    return h->count;
}
size_t history_position(const history *h) {
    return h->position;
}
const history_step *history_at(const history *h, size_t i) {
    return i < h->count ? h->steps[i] : NULL;
}
size_t history_bytes(const history *h) {
    return h->bytes;
}
size_t history_budget(const history *h) {
    return h->budget;
}
uint64_t history_dropped_total(const history *h) {
    return h->dropped_total;
}

size_t history_set_budget(history *h, size_t budget_bytes) {
    reader_done(h);
    squeeze_collect(h);
    h->budget = budget_bytes ? budget_bytes : (size_t)512 << 20;
    return enforce_budget(h);
}

void history_mark_saved(history *h) {
    h->saved_id = state_id(h);
}
long history_saved_position(const history *h) {
    if (h->saved_id == h->floor_id) return 0;
    for (size_t i = 0; i < h->count; i++)
        if (h->steps[i]->id == h->saved_id) return (long)i + 1;
    return -1;
}

int history_modified(const history *h) {
    return state_id(h) != h->saved_id;
}

// ---- squeezing in the background ------------------------------------------------------
// An edit's commit encodes its deltas with zero runs only (history_delta_encode_part_quick):
// zstd on a dab's planes was half the commit's time. history_push hands the new step's
// deltas to one background thread, which tries zstd on them as encode_plane
// does; a smaller delta replaces the step's at the next history_push, undo or redo peek
// or budget change, on the thread that edits (the only one that touches steps), after
// waiting for the ones still being squeezed, so budgets see the same sizes as before.
// A job reads the step's delta itself (the editing thread only reads it meanwhile, and
// replaces it only at collection): a step freed first (dropped, or a redo branch cut)
// cancels its work, waiting for a job that is running. The crash journal keeps what
// the commit wrote.

typedef struct squeeze_job {
    struct squeeze_job *next;
    history *h;
    history_step *step;
    size_t tile;
    const void *delta; // the step's delta it squeezes: swapped only while the tile holds it
    tile_layer layer;
    size_t in_bytes;
    void *out; // the squeezed delta, or NULL when zstd gained nothing
    size_t out_bytes;
    int running, done;
} squeeze_job;

// The squeeze thread's nice value (the editing threads keep the process's own).
#define SQUEEZE_NICE 10

// Work queued at once (bytes of deltas): past it, steps keep their zero-run deltas.
#define SQUEEZE_MAX_BYTES ((size_t)64 << 20)

static struct {
    pthread_once_t once;
    pthread_mutex_t lock;
    pthread_cond_t work, finished;
    int started;
    squeeze_job *head; // in order of queueing
    size_t bytes;
} squeeze = {.once = PTHREAD_ONCE_INIT,
             .lock = PTHREAD_MUTEX_INITIALIZER,
             .work = PTHREAD_COND_INITIALIZER,
             .finished = PTHREAD_COND_INITIALIZER};

// Unlinks j (under the lock) and frees it with what it holds.
static void squeeze_drop(squeeze_job *j) {
    for (squeeze_job **p = &squeeze.head; *p; p = &(*p)->next)
        if (*p == j) {
            *p = j->next;
            break;
        }
    squeeze.bytes -= j->in_bytes;
    free(j->out);
    free(j);
}

// The first job not taken yet (of h, unless NULL), or NULL.
static squeeze_job *squeeze_next(const history *h) {
    for (squeeze_job *j = squeeze.head; j; j = j->next)
        if (!j->running && !j->done && (!h || j->h == h)) return j;
    return NULL;
}

// Squeezes j (called and returning under the lock, which it lets go meanwhile).
static void squeeze_run(squeeze_job *j) {
    j->running = 1;
    pthread_mutex_unlock(&squeeze.lock);
    void *out = NULL;
    size_t out_bytes = 0;
    squeeze_delta(j->layer, j->delta, j->in_bytes, &out, &out_bytes);
    pthread_mutex_lock(&squeeze.lock);
    j->out = out, j->out_bytes = out_bytes;
    j->running = 0, j->done = 1;
    pthread_cond_broadcast(&squeeze.finished);
}

static void *squeeze_main(void *arg) {
    (void)arg;
    // Below the thread that edits: woken by a commit on a busy machine (no core free),
    // the squeeze at the same priority took the committing thread's core away for the
    // length of its zstd (150 us of a one-dab commit's 400), at its wake-up or later in
    // the step (SCHED_BATCH, which only stops the former, did not help). Its jobs are
    // one tile each: the editing thread waits for at most one it has begun. Linux: a
    // thread's own nice.
    setpriority(PRIO_PROCESS, (id_t)syscall(SYS_gettid), SQUEEZE_NICE);
    pthread_mutex_lock(&squeeze.lock);
    for (;;) {
        squeeze_job *j = squeeze_next(NULL);
        if (j)
            squeeze_run(j);
        else
            pthread_cond_wait(&squeeze.work, &squeeze.lock);
    }
    return NULL;
}

static void start_squeeze(void) {
    pthread_t t;
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
    squeeze.started = pthread_create(&t, &attr, squeeze_main, NULL) == 0;
    if (squeeze.started) pthread_setname_np(t, "orogen-squeeze"); // for top and perf
    pthread_attr_destroy(&attr);
}

// Whether a delta has a plane zstd was not tried on that it may shrink.
static int squeezable(const history_tile *t) {
    const uint8_t *d = t->delta;
    size_t el = element_bytes((tile_layer)t->key.layer), at = PART_HEADER;
    if (t->bytes < PART_HEADER || memcmp(d, PART_MAGIC, 4) != 0) return 0;
    for (size_t k = 0; k < el && t->bytes - at >= PLANE_HEADER; k++) {
        size_t len = get_u32(d + at + 1);
        if (d[at] != PLANE_ZSTD && len >= 2048) return 1;
        if (len > t->bytes - at - PLANE_HEADER) return 0;
        at += PLANE_HEADER + len;
    }
    return 0;
}

static void squeeze_queue(history *h, history_step *s) {
    pthread_once(&squeeze.once, start_squeeze);
    pthread_mutex_lock(&squeeze.lock);
    int queued = 0;
    for (size_t i = 0; squeeze.started && i < s->tile_count; i++) {
        const history_tile *t = &s->tiles[i];
        if (!squeezable(t) || squeeze.bytes + t->bytes > SQUEEZE_MAX_BYTES) continue;
        squeeze_job *j = calloc(1, sizeof *j);
        if (!j) continue; // out of memory: this delta stays as it is
        *j = (squeeze_job){.h = h,
                           .step = s,
                           .tile = i,
                           .delta = t->delta,
                           .layer = (tile_layer)t->key.layer,
                           .in_bytes = t->bytes};
        squeeze_job **end = &squeeze.head;
        while (*end)
            end = &(*end)->next;
        *end = j;
        squeeze.bytes += t->bytes;
        queued = 1;
    }
    pthread_mutex_unlock(&squeeze.lock);
    if (queued) pthread_cond_signal(&squeeze.work); // unlocked: it need not wait for the lock
}

// Finishes h's squeezing (taking a hand in what the thread has not started: a big
// step's tiles go twice as fast) and puts the smaller deltas into their steps.
static void squeeze_collect(history *h) {
    pthread_mutex_lock(&squeeze.lock);
    for (;;) {
        squeeze_job *mine = squeeze_next(h);
        if (mine) {
            squeeze_run(mine);
            continue;
        }
        int waiting = 0;
        for (squeeze_job *j = squeeze.head; j; j = j->next)
            waiting |= j->h == h && !j->done;
        if (!waiting) break;
        pthread_cond_wait(&squeeze.finished, &squeeze.lock);
    }
    squeeze_job *j = squeeze.head;
    while (j) {
        squeeze_job *next = j->next;
        if (j->h == h) {
            history_tile *t = &j->step->tiles[j->tile];
            if (j->out && t->delta == j->delta) {
                j->step->bytes -= t->bytes - j->out_bytes;
                h->bytes -= t->bytes - j->out_bytes;
                free(t->delta);
                t->delta = j->out, t->bytes = j->out_bytes;
                j->out = NULL;
            }
            squeeze_drop(j);
        }
        j = next;
    }
    pthread_mutex_unlock(&squeeze.lock);
}

// A step going away: its jobs are dropped (one being squeezed, when it is done).
static void squeeze_cancel(const history_step *s) {
    pthread_mutex_lock(&squeeze.lock);
    for (;;) {
        int running = 0;
        squeeze_job *j = squeeze.head;
        while (j) {
            squeeze_job *next = j->next;
            if (j->step == s && j->running)
                running = 1;
            else if (j->step == s)
                squeeze_drop(j);
            j = next;
        }
        if (!running) break;
        pthread_cond_wait(&squeeze.finished, &squeeze.lock); // it reads the step's delta
    }
    pthread_mutex_unlock(&squeeze.lock);
}
