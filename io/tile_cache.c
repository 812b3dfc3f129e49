// Tile cache: one mutex guards the table, the LRU list and the work queue; the
// slow parts (store reads, generation, write-back) run with it released.
#include "io/tile_cache.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum entry_state { ENTRY_QUEUED, ENTRY_WORKING, ENTRY_READY } entry_state;

typedef struct entry {
    tile_key key;
    uint32_t hash;
    entry_state state;
    int pins;    // views, waiters and write-backs holding it resident
    int dirty;   // changed since last written to the store
    int edited;  // loaded from a store, or written since it was generated
    int invalid; // the source said the key lies outside the world
    int writing; // being written to the store with the lock released: writers wait
    void *data;
    struct entry *hnext;         // hash chain
    struct entry *lprev, *lnext; // LRU list of READY entries, most recent first
    struct entry *qprev, *qnext; // work queue of QUEUED entries
} entry;

struct tile_cache {
    tile_cache_desc desc;
    pthread_mutex_t lock;
    pthread_cond_t work; // queue gained an entry, or stopping
    pthread_cond_t done; // some entry became READY
    entry **buckets;
    size_t bucket_count, entry_count;
    entry *lru_head, *lru_tail;
    entry *queue_head, *queue_tail;
    size_t queue_depth;
    size_t resident_bytes, resident_tiles;
    tile_cache_stats counters;
    int stopping;
    int warned_no_store;
    pthread_t *threads;
    int thread_count;
};

static void warnf(tile_cache *c, const char *fmt, const char *a, const char *b) {
    if (!c->desc.warn) return;
    char msg[1400];
    snprintf(msg, sizeof msg, fmt, a, b);
    c->desc.warn(c->desc.warn_user, msg);
}

// ---- hash table ----------------------------------------------------------------

static entry *find(tile_cache *c, tile_key key, uint32_t h) {
    for (entry *e = c->buckets[h & (c->bucket_count - 1)]; e; e = e->hnext)
        if (e->hash == h && tile_key_equal(e->key, key)) return e;
    return NULL;
}

static void grow(tile_cache *c) {
    size_t n = c->bucket_count * 2;
    entry **b = calloc(n, sizeof *b);
    if (!b) return; // keep the old table: longer chains, still correct
    for (size_t i = 0; i < c->bucket_count; i++) {
        entry *e = c->buckets[i];
        while (e) {
            entry *next = e->hnext;
            e->hnext = b[e->hash & (n - 1)];
            b[e->hash & (n - 1)] = e;
            e = next;
        }
    }
    free(c->buckets);
    c->buckets = b;
    c->bucket_count = n;
}

static entry *insert(tile_cache *c, tile_key key, uint32_t h) {
    entry *e = calloc(1, sizeof *e);
    if (!e) return NULL;
    e->key = key;
    e->hash = h;
    e->hnext = c->buckets[h & (c->bucket_count - 1)];
    c->buckets[h & (c->bucket_count - 1)] = e;
    if (++c->entry_count > c->bucket_count) grow(c);
    return e;
}

static void unlink_hash(tile_cache *c, entry *e) {
    entry **p = &c->buckets[e->hash & (c->bucket_count - 1)];
    while (*p != e)
        p = &(*p)->hnext;
    *p = e->hnext;
    c->entry_count--;
}

// ---- LRU list and queue --------------------------------------------------------

static void lru_unlink(tile_cache *c, entry *e) {
    if (e->lprev)
        e->lprev->lnext = e->lnext;
    else
        c->lru_head = e->lnext;
    if (e->lnext)
        e->lnext->lprev = e->lprev;
    else
        c->lru_tail = e->lprev;
    e->lprev = e->lnext = NULL;
}

static void lru_push_front(tile_cache *c, entry *e) {
    e->lprev = NULL;
    e->lnext = c->lru_head;
    if (c->lru_head)
        c->lru_head->lprev = e;
    else
        c->lru_tail = e;
    c->lru_head = e;
}

static void queue_unlink(tile_cache *c, entry *e) {
    if (e->qprev)
        e->qprev->qnext = e->qnext;
    else
        c->queue_head = e->qnext;
    if (e->qnext)
        e->qnext->qprev = e->qprev;
    else
        c->queue_tail = e->qprev;
    e->qprev = e->qnext = NULL;
    c->queue_depth--;
}

// Newest requests first: what the camera or a command asked for last is what it
// needs now.
static void queue_push_front(tile_cache *c, entry *e) {
    e->qprev = NULL;
    e->qnext = c->queue_head;
    if (c->queue_head)
        c->queue_head->qprev = e;
    else
        c->queue_tail = e;
    c->queue_head = e;
    c->queue_depth++;
    pthread_cond_signal(&c->work);
}

// ---- eviction ------------------------------------------------------------------

static void free_entry(tile_cache *c, entry *e) {
    if (e->state == ENTRY_READY) lru_unlink(c, e);
    if (e->data) {
        c->resident_bytes -= tile_layer_bytes((tile_layer)e->key.layer);
        c->resident_tiles--;
        free(e->data);
    }
    unlink_hash(c, e);
    free(e);
}

// Writes one dirty entry back with the lock released. Returns 0 on success.
static int write_back(tile_cache *c, entry *e) {
    e->pins++;
    e->writing++; // the store reads the payload unlocked: no writer may touch it
    tile_key key = e->key;
    void *data = e->data;
    e->dirty = 0;
    pthread_mutex_unlock(&c->lock);
    og_error err = {{0}};
    int rc = tile_store_put(c->desc.store, key, data, &err);
    pthread_mutex_lock(&c->lock);
    e->pins--;
    e->writing--;
    pthread_cond_broadcast(&c->done);
    if (rc != 0) {
        e->dirty = 1;
        warnf(c, "tile cache: could not write back an edited tile, keeping it in memory: %s%s",
              err.msg, "");
        return -1;
    }
    c->counters.written++;
    return 0;
}

// Evicts least recently used unpinned tiles until `need` more bytes fit the budget.
// Pinned tiles are never evicted; if they alone exceed the budget, so be it.
static void make_room(tile_cache *c, size_t need) {
    entry *e = c->lru_tail;
    while (e && c->resident_bytes + need > c->desc.budget_bytes) {
        entry *prev = e->lprev;
        if (e->pins == 0) {
            if (e->dirty) {
                if (!c->desc.store) {
                    if (!c->warned_no_store) {
                        c->warned_no_store = 1;
                        warnf(c,
                              "tile cache: edited tiles exceed the budget and there is no "
                              "tile store to write them to; keeping them in memory%s%s",
                              "", "");
                    }
                } else {
                    // The lock is released during the write: the list may have changed,
                    // so start over from the tail. A failed write keeps the tile (and
                    // its edits) resident; stop evicting rather than retry forever.
                    if (write_back(c, e) != 0) return;
                    e = c->lru_tail;
                    continue;
                }
            } else {
                free_entry(c, e);
                c->counters.evicted++;
            }
        }
        e = prev;
    }
}

// ---- workers -------------------------------------------------------------------

// Fills buf for key: from the store when stored and readable, else from the source.
// Returns 1 if loaded, 0 if generated, -1 if the key lies outside the world.
static int produce(tile_cache *c, tile_key key, void *buf) {
    size_t bytes = tile_layer_bytes((tile_layer)key.layer);
    tile_store *stores[2] = {c->desc.store, c->desc.base_store};
    for (int s = 0; s < 2; s++) {
        if (!stores[s]) continue;
        og_error err = {{0}};
        tile_store_status st = tile_store_get(stores[s], key, buf, bytes, &err);
        if (st == TILE_STORE_OK) return 1;
        if (st != TILE_STORE_NOT_FOUND) {
            warnf(c, "warning: %s; using the generated terrain instead%s", err.msg, "");
            pthread_mutex_lock(&c->lock);
            c->counters.corrupt++;
            pthread_mutex_unlock(&c->lock);
            break;
        }
    }
    return c->desc.source(c->desc.source_user, key, buf) == 0 ? 0 : -1;
}

static void *worker_main(void *arg) {
    tile_cache *c = arg;
    pthread_mutex_lock(&c->lock);
    for (;;) {
        while (!c->stopping && !c->queue_head)
            pthread_cond_wait(&c->work, &c->lock);
        if (c->stopping) break;
        entry *e = c->queue_head;
        queue_unlink(c, e);
        e->state = ENTRY_WORKING;
        e->pins++; // nobody may free it while we fill it
        size_t bytes = tile_layer_bytes((tile_layer)e->key.layer);
        make_room(c, bytes);
        c->resident_bytes += bytes; // reserved before allocating: the budget holds
        c->resident_tiles++;
        tile_key key = e->key;
        pthread_mutex_unlock(&c->lock);

        void *buf = malloc(bytes);
        int how = buf ? produce(c, key, buf) : -1;

        pthread_mutex_lock(&c->lock);
        e->pins--;
        if (how < 0) {
            free(buf);
            c->resident_bytes -= bytes;
            c->resident_tiles--;
            e->invalid = 1;
        } else {
            e->data = buf;
            e->edited = how == 1;
            if (how == 1)
                c->counters.loaded++;
            else
                c->counters.generated++;
        }
        e->state = ENTRY_READY;
        lru_push_front(c, e);
        pthread_cond_broadcast(&c->done);
    }
    pthread_mutex_unlock(&c->lock);
    return NULL;
}

// ---- public API ----------------------------------------------------------------

tile_cache *tile_cache_create(const tile_cache_desc *desc, og_error *err) {
    if (!desc || !desc->source) {
        og_error_set(err, "tile cache: a tile source is required");
        return NULL;
    }
    tile_cache *c = calloc(1, sizeof *c);
    if (!c) {
        og_error_set(err, "tile cache: out of memory");
        return NULL;
    }
    c->desc = *desc;
    if (!c->desc.budget_bytes) c->desc.budget_bytes = (size_t)1 << 30;
    if (c->desc.workers <= 0) c->desc.workers = 2;
    c->bucket_count = 1024;
    c->buckets = calloc(c->bucket_count, sizeof *c->buckets);
    c->threads = calloc((size_t)c->desc.workers, sizeof *c->threads);
    if (!c->buckets || !c->threads) {
        free(c->buckets), free(c->threads), free(c);
        og_error_set(err, "tile cache: out of memory");
        return NULL;
    }
    pthread_mutex_init(&c->lock, NULL);
    pthread_cond_init(&c->work, NULL);
    pthread_cond_init(&c->done, NULL);
    for (int i = 0; i < c->desc.workers; i++) {
        if (pthread_create(&c->threads[i], NULL, worker_main, c) != 0) break;
        c->thread_count++;
    }
    if (c->thread_count == 0) {
        og_error_set(err, "tile cache: could not start a worker thread");
        tile_cache_destroy(c, NULL);
        return NULL;
    }
    return c;
}

static int destroy(tile_cache *c, int flush, og_error *err) {
    if (!c) return 0;
    pthread_mutex_lock(&c->lock);
    c->stopping = 1;
    pthread_cond_broadcast(&c->work);
    pthread_mutex_unlock(&c->lock);
    for (int i = 0; i < c->thread_count; i++)
        pthread_join(c->threads[i], NULL);
    int rc = flush && c->desc.store ? tile_cache_flush(c, err) : 0;
    for (size_t i = 0; i < c->bucket_count; i++) {
        entry *e = c->buckets[i];
        while (e) {
            entry *next = e->hnext;
            free(e->data);
            free(e);
            e = next;
        }
    }
    pthread_cond_destroy(&c->done);
    pthread_cond_destroy(&c->work);
    pthread_mutex_destroy(&c->lock);
    free(c->buckets);
    free(c->threads);
    free(c);
    return rc;
}

int tile_cache_destroy(tile_cache *c, og_error *err) {
    return destroy(c, 1, err);
}

void tile_cache_destroy_discarding(tile_cache *c) {
    destroy(c, 0, NULL);
}

static void pin_into(entry *e, tile_view *view) {
    e->pins++;
    view->key = e->key;
    view->data = e->data;
    view->handle_ = e;
    view->edited = e->edited;
}

static int32_t floor_shift(int32_t v, int d) {
    int64_t s = (int64_t)1 << d;
    int64_t q = (int64_t)v / s;
    if ((int64_t)v % s != 0 && v < 0) q--;
    return (int32_t)q;
}

// Finds or queues key. Caller holds the lock.
static entry *find_or_queue(tile_cache *c, tile_key key, int *hit) {
    uint32_t h = (uint32_t)tile_key_hash(key);
    entry *e = find(c, key, h);
    *hit = e && e->state == ENTRY_READY;
    if (*hit) {
        c->counters.hits++;
        lru_unlink(c, e);
        lru_push_front(c, e);
        return e;
    }
    c->counters.misses++;
    if (!e) {
        e = insert(c, key, h);
        if (!e) return NULL;
        e->state = ENTRY_QUEUED;
        queue_push_front(c, e);
    } else if (e->state == ENTRY_QUEUED) {
        queue_unlink(c, e); // asked again: move it to the front
        queue_push_front(c, e);
    }
    return e;
}

tile_status tile_cache_request(tile_cache *c, tile_key key, tile_view *view) {
    memset(view, 0, sizeof *view);
    view->key = key;
    pthread_mutex_lock(&c->lock);
    int hit;
    entry *e = find_or_queue(c, key, &hit);
    tile_status st = TILE_PENDING;
    if (e && hit) {
        if (e->invalid) {
            st = TILE_INVALID;
        } else {
            pin_into(e, view);
            st = TILE_READY;
        }
    } else {
        for (int d = 1; tile_key_has_mips(key) && key.level + d <= TILE_MAX_LEVEL; d++) {
            tile_key k = key;
            k.level += d;
            k.tx = floor_shift(key.tx, d);
            k.ty = floor_shift(key.ty, d);
            entry *f = find(c, k, (uint32_t)tile_key_hash(k));
            if (f && f->state == ENTRY_READY && f->data) {
                pin_into(f, view);
                break;
            }
        }
    }
    pthread_mutex_unlock(&c->lock);
    return st;
}

static int acquire(tile_cache *c, tile_key key, tile_view *view, int write, og_error *err) {
    memset(view, 0, sizeof *view);
    pthread_mutex_lock(&c->lock);
    int hit;
    entry *e = find_or_queue(c, key, &hit);
    if (!e) {
        pthread_mutex_unlock(&c->lock);
        return og_error_set(err, "tile cache: out of memory");
    }
    e->pins++; // a waiter: it must not be evicted between READY and our wake-up
    while (e->state != ENTRY_READY || (write && e->writing))
        pthread_cond_wait(&c->done, &c->lock);
    e->pins--;
    int rc = 0;
    if (e->invalid) {
        char what[128];
        rc = og_error_set(err, "%s lies outside the world",
                          tile_key_describe(key, what, sizeof what));
    } else {
        pin_into(e, view);
        if (write) e->dirty = e->edited = 1;
    }
    pthread_mutex_unlock(&c->lock);
    return rc;
}

int tile_cache_acquire(tile_cache *c, tile_key key, tile_view *view, og_error *err) {
    return acquire(c, key, view, 0, err);
}

int tile_cache_acquire_write(tile_cache *c, tile_key key, tile_view *view, og_error *err) {
    return acquire(c, key, view, 1, err);
}

int tile_cache_mark_generated(tile_cache *c, tile_key key) {
    pthread_mutex_lock(&c->lock);
    entry *e = find(c, key, (uint32_t)tile_key_hash(key));
    int rc = e ? -1 : 0; // not resident: the next request loads or generates it
    if (e && e->state == ENTRY_READY && e->pins == 0 && e->data) {
        e->dirty = e->edited = 0;
        rc = 0;
    }
    pthread_mutex_unlock(&c->lock);
    return rc;
}

void tile_cache_release(tile_cache *c, tile_view *view) {
    if (!view || !view->handle_) return;
    pthread_mutex_lock(&c->lock);
    entry *e = view->handle_;
    e->pins--;
    pthread_mutex_unlock(&c->lock);
    view->handle_ = NULL;
    view->data = NULL;
}

size_t tile_cache_edited_keys(tile_cache *c, int layer, tile_key *out, size_t max) {
    size_t n = 0;
    pthread_mutex_lock(&c->lock);
    for (size_t b = 0; b < c->bucket_count; b++)
        for (entry *e = c->buckets[b]; e; e = e->hnext)
            if (e->key.layer == layer && e->state == ENTRY_READY && e->edited && e->data) {
                if (n < max) out[n] = e->key;
                n++;
            }
    pthread_mutex_unlock(&c->lock);
    return n;
}

int tile_cache_flush(tile_cache *c, og_error *err) {
    if (!c->desc.store) return 0;
    pthread_mutex_lock(&c->lock);
    size_t n = 0;
    for (entry *e = c->lru_head; e; e = e->lnext)
        n += e->dirty != 0;
    if (n == 0) {
        pthread_mutex_unlock(&c->lock);
        return 0;
    }
    tile_store_write *writes = malloc(n * sizeof *writes);
    entry **pinned = malloc(n * sizeof *pinned);
    if (!writes || !pinned) {
        pthread_mutex_unlock(&c->lock);
        free(writes), free(pinned);
        return og_error_set(err, "tile cache: out of memory while saving");
    }
    size_t k = 0;
    for (entry *e = c->lru_head; e; e = e->lnext) {
        if (!e->dirty) continue;
        e->pins++;
        e->writing++;
        e->dirty = 0;
        pinned[k] = e;
        writes[k++] = (tile_store_write){e->key, e->data};
    }
    pthread_mutex_unlock(&c->lock);
    int rc = tile_store_put_batch(c->desc.store, writes, n, err);
    pthread_mutex_lock(&c->lock);
    for (size_t i = 0; i < n; i++) {
        pinned[i]->pins--;
        pinned[i]->writing--;
        if (rc != 0) pinned[i]->dirty = 1; // nothing landed: still unsaved
    }
    pthread_cond_broadcast(&c->done);
    if (rc == 0) c->counters.written += n;
    pthread_mutex_unlock(&c->lock);
    free(writes);
    free(pinned);
    return rc;
}

int tile_cache_has_dirty(tile_cache *c) {
    pthread_mutex_lock(&c->lock);
    int any = 0;
    for (entry *e = c->lru_head; e && !any; e = e->lnext)
        any = e->dirty;
    pthread_mutex_unlock(&c->lock);
    return any;
}

void tile_cache_stats_get(tile_cache *c, tile_cache_stats *out) {
    pthread_mutex_lock(&c->lock);
    *out = c->counters;
    out->resident_bytes = c->resident_bytes;
    out->resident_tiles = c->resident_tiles;
    out->budget_bytes = c->desc.budget_bytes;
    out->queue_depth = c->queue_depth;
    out->overhead_bytes = sizeof *c + c->entry_count * sizeof(entry) +
                          c->bucket_count * sizeof(entry *) +
                          (size_t)c->thread_count * sizeof(pthread_t);
    out->workers = c->thread_count;
    pthread_mutex_unlock(&c->lock);
}
