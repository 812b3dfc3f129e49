#include "renderer/clip_window.h"

#include "editor/params/world_grid.h"

#include <stdlib.h>
#include <string.h>

// A 1024-sample window (renderer/clip_slopes.h) meets 5 x 5 tiles; a 256-sample ridge
// window 2 x 2 of its own level's and 5 x 5 of the finer one's (shift 2).
#define MAX_TILES 34

typedef struct sample_rect {
    int64_t x0, z0, x1, z1; // [x0, x1) x [z0, z1), sample indices at the window's level
} sample_rect;

int clip_window_init(clip_window *w, tile_layer layer, int face, int level, int size) {
    memset(w, 0, sizeof *w);
    w->layer = layer;
    w->face = face;
    w->level = level;
    w->size = size;
    w->texel_bytes = tile_layer_bytes(layer) / TILE_SAMPLES;
    w->mirror = calloc((size_t)size * size, w->texel_bytes);
    return w->mirror ? 0 : -1;
}

int clip_window_init_ridges(clip_window *w, int face, int level, int size, int shift) {
    if (clip_window_init(w, TILE_LAYER_COARSE, face, level, size) != 0) return -1;
    w->ridge_shift = shift;
    return 0;
}

void clip_window_free(clip_window *w) {
    free(w->mirror);
    w->mirror = NULL;
}

void clip_window_invalidate(clip_window *w) {
    w->has_data = 0;
    w->partial = 0;
}

int clip_window_current(const clip_window *w, const int64_t want[2]) {
    return w->has_data && w->have[0] == want[0] && w->have[1] == want[1];
}

static void add_upload(clip_window *w, int x, int z, int width, int height) {
    if (w->upload_all) return;
    if (w->upload_count == CLIP_WINDOW_MAX_RECTS) {
        w->upload_all = 1;
        return;
    }
    w->uploads[w->upload_count++] = (texel_rect){x, z, width, height};
}

// Splits a sample rect (at most size wide and high) at the texture's wrap seams.
static void queue_upload(clip_window *w, sample_rect r) {
    int mask = w->size - 1;
    int xs[2], xw[2], zs[2], zh[2], nx = 1, nz = 1;
    xs[0] = (int)(r.x0 & mask), xw[0] = (int)(r.x1 - r.x0);
    zs[0] = (int)(r.z0 & mask), zh[0] = (int)(r.z1 - r.z0);
    if (xs[0] + xw[0] > w->size) xs[1] = 0, xw[1] = xs[0] + xw[0] - w->size, xw[0] -= xw[1], nx = 2;
    if (zs[0] + zh[0] > w->size) zs[1] = 0, zh[1] = zs[0] + zh[0] - w->size, zh[0] -= zh[1], nz = 2;
    for (int j = 0; j < nz; j++)
        for (int i = 0; i < nx; i++)
            add_upload(w, xs[i], zs[j], xw[i], zh[j]);
}

typedef struct tile_pins {
    tile_key keys[MAX_TILES];
    tile_view views[MAX_TILES];
    int ready[MAX_TILES];
    int count;
} tile_pins;

static int collect_keys(const clip_window *w, const sample_rect *rects, int n, tile_pins *pins) {
    pins->count = 0;
    for (int k = 0; k < n * (w->ridge_shift > 0 ? 2 : 1); k++) {
        sample_rect r = rects[k % n];
        if (r.x0 >= r.x1 || r.z0 >= r.z1) continue;
        const int s = k < n ? 0 : w->ridge_shift; // the finer level's samples read
        const int64_t k = (int64_t)1 << s;        // a multiply: indices may be negative
        r = (sample_rect){r.x0 * k, r.z0 * k, (r.x1 - 1) * k + 1, (r.z1 - 1) * k + 1};
        for (int64_t ty = world_grid_floor_div(r.z0, TILE_SIZE);
             ty <= world_grid_floor_div(r.z1 - 1, TILE_SIZE); ty++)
            for (int64_t tx = world_grid_floor_div(r.x0, TILE_SIZE);
                 tx <= world_grid_floor_div(r.x1 - 1, TILE_SIZE); tx++) {
                tile_key key = {w->layer, w->face, w->level - s, (int32_t)tx, (int32_t)ty};
                int seen = 0;
                for (int i = 0; i < pins->count && !seen; i++)
                    seen = tile_key_equal(pins->keys[i], key);
                if (seen) continue;
                if (pins->count == MAX_TILES) return -1;
                pins->keys[pins->count++] = key;
            }
    }
    return 0;
}

static void release_pins(tile_cache *cache, tile_pins *pins) {
    for (int i = 0; i < pins->count; i++)
        if (pins->views[i].data) tile_cache_release(cache, &pins->views[i]);
}

// Pins every tile the rects need without waiting. Returns 1 when all are resident
// (pinned; release_pins after copying), 0 when some are still pending (none pinned).
static int pin_tiles(const clip_window *w, tile_cache *cache, const sample_rect *rects, int n,
                     tile_pins *pins) {
    if (collect_keys(w, rects, n, pins) != 0) return -1;
    int pending = 0;
    // Requested last = produced first (the cache's queue is LIFO): ask for the tile
    // nearest the window's centre last.
    for (int i = pins->count - 1; i >= 0; i--) {
        tile_status s = tile_cache_request(cache, pins->keys[i], &pins->views[i]);
        pins->ready[i] = s == TILE_READY;
        if (s == TILE_PENDING) {
            pending = 1;
            if (pins->views[i].data) tile_cache_release(cache, &pins->views[i]);
            pins->views[i].data = NULL;
        } else if (s == TILE_INVALID) {
            pins->views[i].data = NULL; // outside the world: zeros
        }
    }
    if (pending) {
        release_pins(cache, pins);
        return 0;
    }
    return 1;
}

static const unsigned char *pinned_tile(const tile_pins *pins, int level, int32_t tx, int32_t ty) {
    for (int i = 0; i < pins->count; i++)
        if (pins->keys[i].level == level && pins->keys[i].tx == tx && pins->keys[i].ty == ty)
            return pins->views[i].data;
    return NULL;
}

// A ridge window's samples in r (copied as the level's own first): each raised to the
// finer level's sample at its place where that is higher.
static void raise_to_finer(clip_window *w, const tile_pins *pins, sample_rect r) {
    const int mask = w->size - 1, s = w->ridge_shift, fine = w->level - s;
    const int64_t k = (int64_t)1 << s; // a multiply: indices may be negative
    float *mirror = (float *)w->mirror;
    for (int64_t z = r.z0; z < r.z1; z++) {
        const int64_t fz = z * k;
        const int32_t ty = (int32_t)world_grid_floor_div(fz, TILE_SIZE);
        const int row = (int)(fz - (int64_t)ty * TILE_SIZE);
        float *dst_row = mirror + (size_t)(z & mask) * w->size;
        const float *src = NULL;
        int32_t src_tx = 0;
        for (int64_t x = r.x0; x < r.x1; x++) {
            const int64_t fx = x * k;
            const int32_t tx = (int32_t)world_grid_floor_div(fx, TILE_SIZE);
            if (x == r.x0 || tx != src_tx)
                src = (const float *)pinned_tile(pins, fine, tx, ty), src_tx = tx;
            if (!src) continue; // outside the world: the level's own zeros
            const float h = src[(size_t)row * TILE_SIZE + (size_t)(fx - (int64_t)tx * TILE_SIZE)];
            float *d = dst_row + (x & mask);
            if (h > *d) *d = h;
        }
    }
}

static void copy_rect(clip_window *w, const tile_pins *pins, sample_rect r) {
    int mask = w->size - 1;
    size_t tb = w->texel_bytes;
    for (int64_t z = r.z0; z < r.z1; z++) {
        int32_t ty = (int32_t)world_grid_floor_div(z, TILE_SIZE);
        int row = (int)(z - (int64_t)ty * TILE_SIZE);
        unsigned char *dst_row = w->mirror + (size_t)(z & mask) * w->size * tb;
        for (int64_t x = r.x0; x < r.x1;) {
            int32_t tx = (int32_t)world_grid_floor_div(x, TILE_SIZE);
            int col = (int)(x - (int64_t)tx * TILE_SIZE);
            int run = TILE_SIZE - col;
            if (run > r.x1 - x) run = (int)(r.x1 - x);
            int dst = (int)(x & mask);
            if (run > w->size - dst) run = w->size - dst; // the wrap seam
            const unsigned char *src = pinned_tile(pins, w->level, tx, ty);
            if (src)
                memcpy(dst_row + (size_t)dst * tb, src + ((size_t)row * TILE_SIZE + col) * tb,
                       (size_t)run * tb);
            else
                memset(dst_row + (size_t)dst * tb, 0, (size_t)run * tb);
            x += run;
        }
    }
    if (w->ridge_shift > 0) raise_to_finer(w, pins, r);
    w->texels_copied += (uint64_t)(r.x1 - r.x0) * (uint64_t)(r.z1 - r.z0);
}

int clip_window_update(clip_window *w, tile_cache *cache, const int64_t want[2]) {
    if (clip_window_current(w, want)) return 1;
    w->partial = 0; // a whole refill below replaces one under way
    int64_t n = w->size;
    sample_rect rects[2];
    int count = 0;
    int64_t dx = want[0] - w->have[0], dz = want[1] - w->have[1];
    int full = !w->has_data || llabs(dx) >= n || llabs(dz) >= n;
    if (full) {
        rects[count++] = (sample_rect){want[0], want[1], want[0] + n, want[1] + n};
    } else {
        // Columns that entered (full height), then rows that entered (full width).
        if (dx > 0)
            rects[count++] = (sample_rect){w->have[0] + n, want[1], want[0] + n, want[1] + n};
        if (dx < 0) rects[count++] = (sample_rect){want[0], want[1], w->have[0], want[1] + n};
        if (dz > 0)
            rects[count++] = (sample_rect){want[0], w->have[1] + n, want[0] + n, want[1] + n};
        if (dz < 0) rects[count++] = (sample_rect){want[0], want[1], want[0] + n, w->have[1]};
    }
    tile_pins pins;
    int ok = pin_tiles(w, cache, rects, count, &pins);
    if (ok <= 0) return ok;
    for (int i = 0; i < count; i++) {
        copy_rect(w, &pins, rects[i]);
        if (full)
            w->upload_all = 1;
        else
            queue_upload(w, rects[i]);
    }
    release_pins(cache, &pins);
    w->have[0] = want[0], w->have[1] = want[1];
    w->has_data = 1;
    return 1;
}

static sample_rect intersect(sample_rect a, sample_rect b) {
    sample_rect r = {a.x0 > b.x0 ? a.x0 : b.x0, a.z0 > b.z0 ? a.z0 : b.z0,
                     a.x1 < b.x1 ? a.x1 : b.x1, a.z1 < b.z1 ? a.z1 : b.z1};
    if (r.x0 >= r.x1 || r.z0 >= r.z1) r.x1 = r.x0, r.z1 = r.z0;
    return r;
}

static int64_t area(sample_rect r) {
    return (r.x1 - r.x0) * (r.z1 - r.z0);
}

// What the mirror holds: a whole window, the part of one a budgeted fill reached, or nothing.
static sample_rect valid_rect(const clip_window *w) {
    if (w->has_data)
        return (sample_rect){w->have[0], w->have[1], w->have[0] + w->size, w->have[1] + w->size};
    if (w->partial) return (sample_rect){w->valid[0], w->valid[1], w->valid[2], w->valid[3]};
    return (sample_rect){0, 0, 0, 0};
}

// Copies r (pinning its tiles; 0 while some are pending) and queues its upload.
static int fill(clip_window *w, tile_cache *cache, sample_rect r) {
    if (area(r) == 0) return 1;
    tile_pins pins;
    int ok = pin_tiles(w, cache, &r, 1, &pins);
    if (ok <= 0) return ok;
    copy_rect(w, &pins, r);
    queue_upload(w, r);
    release_pins(cache, &pins);
    return 1;
}

int clip_window_update_within(clip_window *w, tile_cache *cache, const int64_t want[2],
                              int64_t *budget) {
    if (clip_window_current(w, want)) return 1;
    int64_t n = w->size;
    sample_rect t = {want[0], want[1], want[0] + n, want[1] + n};
    sample_rect v = intersect(valid_rect(w), t);
    if (area(v) == 0) { // nothing of it yet: grow from its first row
        v = (sample_rect){t.x0, t.z0, t.x1, t.z0};
        w->refill_started = 1;
    }
    // Columns beside what is held (over its rows), then whole rows above and below.
    int64_t left = v.x0 - t.x0, right = t.x1 - v.x1, above = v.z0 - t.z0, below = t.z1 - v.z1;
    int64_t missing = (left + right) * (v.z1 - v.z0) + (above + below) * n;
    int64_t allow = missing <= 32 * n ? missing : *budget;
    int ok = 1;
    for (int side = 0; side < 4 && ok == 1 && allow > 0; side++) {
        int64_t *gap = side == 0 ? &left : side == 1 ? &right : side == 2 ? &above : &below;
        if (*gap == 0) continue;
        if (side >= 2 && (left > 0 || right > 0)) break; // rows once the columns are whole
        int64_t across = side < 2 ? v.z1 - v.z0 : n, k = across > 0 ? allow / across : *gap;
        if (k > *gap) k = *gap;
        if (k == 0) break;
        sample_rect r = side == 0   ? (sample_rect){v.x0 - k, v.z0, v.x0, v.z1}
                        : side == 1 ? (sample_rect){v.x1, v.z0, v.x1 + k, v.z1}
                        : side == 2 ? (sample_rect){t.x0, v.z0 - k, t.x1, v.z0}
                                    : (sample_rect){t.x0, v.z1, t.x1, v.z1 + k};
        if ((ok = fill(w, cache, r)) != 1) break;
        if (side == 0) v.x0 -= k;
        if (side == 1) v.x1 += k;
        if (side == 2) v.z0 -= k;
        if (side == 3) v.z1 += k;
        *gap -= k;
        allow -= area(r);
        *budget -= area(r);
    }
    if (ok < 0) return -1;
    if (v.x0 == t.x0 && v.z0 == t.z0 && v.x1 == t.x1 && v.z1 == t.z1) {
        w->have[0] = want[0], w->have[1] = want[1];
        w->has_data = 1, w->partial = 0;
        return 1;
    }
    w->has_data = 0, w->partial = 1;
    w->valid[0] = v.x0, w->valid[1] = v.z0, w->valid[2] = v.x1, w->valid[3] = v.z1;
    return 0;
}

void clip_window_refresh(clip_window *w, tile_cache *cache, int64_t x0, int64_t z0, int64_t x1,
                         int64_t z1) {
    if (w->partial) { // a budgeted fill under way: re-read what it already holds
        sample_rect r = intersect(valid_rect(w), (sample_rect){x0, z0, x1, z1});
        if (area(r) > 0 && fill(w, cache, r) != 1) w->partial = 0; // tiles gone: start over
        return;
    }
    if (!w->has_data) return;
    int64_t n = w->size;
    sample_rect r = {x0 > w->have[0] ? x0 : w->have[0], z0 > w->have[1] ? z0 : w->have[1],
                     x1 < w->have[0] + n ? x1 : w->have[0] + n,
                     z1 < w->have[1] + n ? z1 : w->have[1] + n};
    if (r.x0 >= r.x1 || r.z0 >= r.z1) return;
    tile_pins pins;
    if (pin_tiles(w, cache, &r, 1, &pins) != 1) {
        w->has_data = 0; // refill everything once the tiles are back
        return;
    }
    copy_rect(w, &pins, r);
    queue_upload(w, r);
    release_pins(cache, &pins);
}
