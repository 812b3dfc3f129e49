#include "editor/world/world_events.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#define QUEUE_MAX 256 // past this, areas collapse to bounding rectangles

struct world_subscription {
    world_events *hub;
    world_subscription *next;
    void (*notify)(void *user);
    void *user;
    world_event queue[QUEUE_MAX];
    size_t count;
};

struct world_events {
    pthread_mutex_t lock;
    world_subscription *subs;
    int refs; // the creator's, plus one per subscription: a subscription outlives its world
};

world_events *world_events_create(void) {
    world_events *hub = calloc(1, sizeof *hub);
    if (!hub) return NULL;
    pthread_mutex_init(&hub->lock, NULL);
    hub->refs = 1;
    return hub;
}

static void release(world_events *hub) {
    pthread_mutex_lock(&hub->lock);
    int last = --hub->refs == 0;
    pthread_mutex_unlock(&hub->lock);
    if (!last) return;
    pthread_mutex_destroy(&hub->lock);
    free(hub);
}

void world_events_release(world_events *hub) {
    if (hub) release(hub);
}

world_subscription *world_events_subscribe(world_events *hub, void (*notify)(void *user),
                                           void *user) {
    world_subscription *s = calloc(1, sizeof *s);
    if (!s) return NULL;
    s->hub = hub;
    s->notify = notify;
    s->user = user;
    pthread_mutex_lock(&hub->lock);
    s->next = hub->subs;
    hub->subs = s;
    hub->refs++;
    pthread_mutex_unlock(&hub->lock);
    return s;
}

void world_events_unsubscribe(world_subscription *s) {
    if (!s) return;
    world_events *hub = s->hub;
    pthread_mutex_lock(&hub->lock);
    for (world_subscription **p = &hub->subs; *p; p = &(*p)->next)
        if (*p == s) {
            *p = s->next;
            break;
        }
    pthread_mutex_unlock(&hub->lock);
    free(s);
    release(hub);
}

static int same_area_grid(const world_event *a, const world_event *b) {
    return a->layer == b->layer && a->face == b->face && a->level == b->level;
}

// Rectangles that overlap or share an edge.
static int touches(grid_rect a, grid_rect b) {
    return a.x0 <= b.x1 && b.x0 <= a.x1 && a.z0 <= b.z1 && b.z0 <= a.z1;
}

// Full: one bounding rectangle per layer, face and level (other kinds stay).
static void collapse(world_subscription *s) {
    size_t n = 0;
    for (size_t i = 0; i < s->count; i++) {
        world_event e = s->queue[i];
        size_t k = 0;
        if (e.kind == WORLD_EVENT_AREA)
            while (k < n &&
                   !(s->queue[k].kind == WORLD_EVENT_AREA && same_area_grid(&s->queue[k], &e)))
                k++;
        else
            k = n;
        if (k < n)
            s->queue[k].rect = grid_rect_union(s->queue[k].rect, e.rect);
        else
            s->queue[n++] = e;
    }
    s->count = n;
}

// Merges e with every touching queued area of its grid until none is left.
static void merge_area(world_subscription *s, world_event *e) {
    for (size_t i = 0; i < s->count;) {
        world_event *q = &s->queue[i];
        if (q->kind == WORLD_EVENT_AREA && same_area_grid(q, e) && touches(q->rect, e->rect)) {
            e->rect = grid_rect_union(e->rect, q->rect);
            memmove(q, q + 1, (s->count - i - 1) * sizeof *q); // keep the order
            s->count--;
            i = 0;
        } else {
            i++;
        }
    }
}

static void enqueue(world_subscription *s, world_event e) {
    if (e.kind != WORLD_EVENT_AREA) {
        for (size_t i = 0; i < s->count; i++)
            if (s->queue[i].kind == e.kind) return;
    } else {
        merge_area(s, &e);
    }
    if (s->count == QUEUE_MAX) {
        collapse(s);
        // The bounding rectangles now touch more: merge the new area into its grid's.
        if (e.kind == WORLD_EVENT_AREA) merge_area(s, &e);
    }
    if (s->count == QUEUE_MAX) {
        // Still full (areas on very many grids): "everything may differ" says it all.
        s->count = 0;
        e = (world_event){.kind = WORLD_EVENT_PARAMS};
    }
    s->queue[s->count++] = e;
}

void world_events_publish(world_events *hub, const world_event *e) {
    if (!hub) return;
    if (e->kind == WORLD_EVENT_AREA && grid_rect_empty(e->rect)) return;
    enum { NOTIFY_MAX = 64 }; // subscribers past this still get events, not wake-ups
    void (*fns[NOTIFY_MAX])(void *);
    void *users[NOTIFY_MAX];
    size_t n = 0;
    pthread_mutex_lock(&hub->lock);
    for (world_subscription *s = hub->subs; s; s = s->next) {
        enqueue(s, *e);
        if (s->notify && n < NOTIFY_MAX) fns[n] = s->notify, users[n++] = s->user;
    }
    pthread_mutex_unlock(&hub->lock);
    for (size_t i = 0; i < n; i++)
        fns[i](users[i]);
}

size_t world_subscription_take(world_subscription *s, world_event *out, size_t max) {
    pthread_mutex_lock(&s->hub->lock);
    size_t n = s->count < max ? s->count : max;
    memcpy(out, s->queue, n * sizeof *out);
    memmove(s->queue, s->queue + n, (s->count - n) * sizeof *out);
    s->count -= n;
    pthread_mutex_unlock(&s->hub->lock);
    return n;
}

world_events *world_subscription_hub(const world_subscription *s) {
    return s->hub;
}
