#include "editor/world/history.h"

#include <stdlib.h>
#include <string.h>
#include <zstd.h>

// zstd level 1: deltas are mostly zero bytes; higher levels gain little here and
// the encode sits on the release of every stroke.
#define DELTA_ZSTD_LEVEL 1

struct history {
    history_step **steps;
    size_t count, cap, position;
    size_t bytes, budget;
    uint64_t next_id;
    uint64_t floor_id; // the state reached by the dropped steps (0: the loaded state)
    uint64_t saved_id; // the state that was saved last
    uint64_t dropped_total;
};

history *history_create(size_t budget_bytes) {
    history *h = calloc(1, sizeof *h);
    if (!h) return NULL;
    h->budget = budget_bytes ? budget_bytes : (size_t)512 << 20;
    h->next_id = 1;
    return h;
}

void history_destroy(history *h) {
    if (!h) return;
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

void history_step_free(history_step *s) {
    if (!s) return;
    for (size_t i = 0; i < s->tile_count; i++)
        free(s->tiles[i].delta);
    free(s->tiles);
    free(s->dirty);
    free(s);
}

// Element size of a layer's samples: its bytes are split into that many planes
// so the always-equal high bytes of a small change line up for zstd.
static size_t element_bytes(tile_layer layer) {
    switch (tile_layer_format(layer)) {
    case TILE_FORMAT_U8X8:
        return TILE_MATERIALS;
    default:
        return 4;
    }
}

int history_delta_encode(tile_layer layer, const void *before, const void *after, void **delta,
                         size_t *bytes) {
    *delta = NULL;
    *bytes = 0;
    size_t raw = tile_layer_bytes(layer);
    if (memcmp(before, after, raw) == 0) return 0;
    size_t el = element_bytes(layer), n = raw / el;
    uint8_t *planes = malloc(raw);
    size_t cap = ZSTD_compressBound(raw);
    uint8_t *out = malloc(cap);
    if (!planes || !out) {
        free(planes);
        free(out);
        return -1;
    }
    const uint8_t *a = before, *b = after;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    if (el == 4) { // float and int16x2 layers: one word per element, split into 4 planes
        uint8_t *p0 = planes, *p1 = planes + n, *p2 = planes + 2 * n, *p3 = planes + 3 * n;
        for (size_t i = 0; i < n; i++) {
            uint32_t x, y;
            memcpy(&x, a + 4 * i, 4);
            memcpy(&y, b + 4 * i, 4);
            x ^= y;
            p0[i] = (uint8_t)x, p1[i] = (uint8_t)(x >> 8), p2[i] = (uint8_t)(x >> 16);
            p3[i] = (uint8_t)(x >> 24);
        }
    } else
#endif
        for (size_t i = 0; i < n; i++)
            for (size_t k = 0; k < el; k++)
                planes[k * n + i] = a[i * el + k] ^ b[i * el + k];
    size_t comp = ZSTD_compress(out, cap, planes, raw, DELTA_ZSTD_LEVEL);
    free(planes);
    if (ZSTD_isError(comp)) {
        free(out);
        return -1;
    }
    uint8_t *fit = realloc(out, comp);
    *delta = fit ? fit : out;
    *bytes = comp;
    return 0;
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

int history_tile_apply(const history_tile *t, void *data) {
    tile_layer layer = (tile_layer)t->key.layer;
    size_t raw = tile_layer_bytes(layer), el = element_bytes(layer), n = raw / el;
    uint8_t *planes = malloc(raw);
    if (!planes) return -1;
    size_t got = ZSTD_decompress(planes, raw, t->delta, t->bytes);
    if (ZSTD_isError(got) || got != raw) {
        free(planes);
        return -1;
    }
    uint8_t *d = data;
    for (size_t i = 0; i < n; i++)
        for (size_t k = 0; k < el; k++)
            d[i * el + k] ^= planes[k * n + i];
    free(planes);
    return 0;
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
    return enforce_budget(h);
}

history_step *history_undo_peek(history *h) {
    return h->position ? h->steps[h->position - 1] : NULL;
}
void history_undo_done(history *h) {
    if (h->position) h->position--;
}
history_step *history_redo_peek(history *h) {
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
