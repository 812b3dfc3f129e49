// Change notifications (editor/world/world_events.c): every subscriber gets every
// event; touching areas of one grid merge into their bounding rectangle, disjoint ones
// and other layers, faces and levels stay apart; other kinds are queued once while
// pending; take hands out the oldest first; empty areas are dropped; a flooded queue
// stays bounded and still covers everything; notify callbacks; unsubscribing;
// subscriptions that outlive their hub; and a world publishing its dabs, history,
// parameters and saves.
#include "editor/edit/edit.h"
#include "editor/tools/brush.h"
#include "editor/tools/stroke.h"
#include "editor/world/world.h"
#include "editor/world/world_events.h"
#include "support/test_support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

// ---- helpers -----------------------------------------------------------------------

static world_event area(tile_layer layer, int face, int level, int64_t x0, int64_t z0, int64_t x1,
                        int64_t z1) {
    return (world_event){.kind = WORLD_EVENT_AREA,
                         .layer = layer,
                         .face = face,
                         .level = level,
                         .rect = {x0, z0, x1, z1}};
}

static world_event coarse(int64_t x0, int64_t z0, int64_t x1, int64_t z1) {
    return area(TILE_LAYER_COARSE, 0, 0, x0, z0, x1, z1);
}

static world_event of_kind(world_event_kind kind) {
    return (world_event){.kind = kind};
}

static void publish(world_events *hub, world_event e) {
    world_events_publish(hub, &e);
}

static int rect_is(grid_rect r, int64_t x0, int64_t z0, int64_t x1, int64_t z1) {
    return r.x0 == x0 && r.z0 == z0 && r.x1 == x1 && r.z1 == z1;
}

static void assert_rect(grid_rect r, int64_t x0, int64_t z0, int64_t x1, int64_t z1) {
    if (!rect_is(r, x0, z0, x1, z1))
        fail_msg("rect [%lld,%lld)x[%lld,%lld), wanted [%lld,%lld)x[%lld,%lld)", (long long)r.x0,
                 (long long)r.x1, (long long)r.z0, (long long)r.z1, (long long)x0, (long long)x1,
                 (long long)z0, (long long)z1);
}

static int same_event(const world_event *a, const world_event *b) {
    if (a->kind != b->kind) return 0;
    if (a->kind != WORLD_EVENT_AREA) return 1;
    return a->layer == b->layer && a->face == b->face && a->level == b->level &&
           rect_is(a->rect, b->rect.x0, b->rect.z0, b->rect.x1, b->rect.z1);
}

// Rectangles that overlap or share an edge or a corner (what the hub merges).
static int touch(grid_rect a, grid_rect b) {
    return a.x0 <= b.x1 && b.x0 <= a.x1 && a.z0 <= b.z1 && b.z0 <= a.z1;
}

static int contains(grid_rect outer, grid_rect inner) {
    return outer.x0 <= inner.x0 && outer.z0 <= inner.z0 && inner.x1 <= outer.x1 &&
           inner.z1 <= outer.z1;
}

// ---- the hub --------------------------------------------------------------------------

static void test_every_subscriber_gets_every_event(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    assert_non_null(hub);
    world_subscription *a = world_events_subscribe(hub, NULL, NULL);
    world_subscription *b = world_events_subscribe(hub, NULL, NULL);
    assert_non_null(a);
    assert_non_null(b);
    assert_ptr_equal(world_subscription_hub(a), hub);
    assert_ptr_equal(world_subscription_hub(b), hub);
    const world_event sent[] = {
        coarse(0, 0, 10, 10),
        of_kind(WORLD_EVENT_HISTORY),
        area(TILE_LAYER_DETAIL, 0, 0, 5, 5, 6, 6),
        of_kind(WORLD_EVENT_PARAMS),
        coarse(100, 100, 120, 130),
        of_kind(WORLD_EVENT_SAVED),
        area(TILE_LAYER_MATERIAL, 3, 2, -50, -50, -40, -45),
        of_kind(WORLD_EVENT_REPLACED),
    };
    size_t count = sizeof sent / sizeof sent[0];
    for (size_t i = 0; i < count; i++)
        world_events_publish(hub, &sent[i]);
    // A subscriber that joins now starts empty.
    world_subscription *late = world_events_subscribe(hub, NULL, NULL);
    world_event got[32];
    assert_int_equal(world_subscription_take(late, got, 32), 0);
    world_subscription *subs[] = {a, b};
    for (int s = 0; s < 2; s++) {
        memset(got, 0, sizeof got);
        assert_int_equal(world_subscription_take(subs[s], got, 32), count);
        for (size_t i = 0; i < count; i++)
            if (!same_event(&got[i], &sent[i])) fail_msg("subscriber %d: event %zu differs", s, i);
        assert_int_equal(world_subscription_take(subs[s], got, 32), 0); // taken: gone
    }
    // Taking from one queue leaves the others alone.
    publish(hub, of_kind(WORLD_EVENT_HISTORY));
    assert_int_equal(world_subscription_take(a, got, 32), 1);
    assert_int_equal(world_subscription_take(b, got, 32), 1);
    assert_int_equal(world_subscription_take(late, got, 32), 1);
    assert_int_equal(got[0].kind, WORLD_EVENT_HISTORY);
    world_events_unsubscribe(a);
    world_events_unsubscribe(b);
    world_events_unsubscribe(late);
    world_events_release(hub);
}

static void test_touching_areas_merge(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    world_subscription *s = world_events_subscribe(hub, NULL, NULL);
    world_event got[16];
    // Overlapping.
    publish(hub, coarse(0, 0, 10, 10));
    publish(hub, coarse(5, 5, 15, 12));
    assert_int_equal(world_subscription_take(s, got, 16), 1);
    assert_rect(got[0].rect, 0, 0, 15, 12);
    assert_int_equal(got[0].kind, WORLD_EVENT_AREA);
    assert_int_equal(got[0].layer, TILE_LAYER_COARSE);
    // Sharing an edge (half-open rects side by side), in x and in z.
    publish(hub, coarse(0, 0, 10, 10));
    publish(hub, coarse(10, 2, 20, 8));
    publish(hub, coarse(3, 10, 4, 30));
    assert_int_equal(world_subscription_take(s, got, 16), 1);
    assert_rect(got[0].rect, 0, 0, 20, 30);
    // Contained, and containing.
    publish(hub, coarse(0, 0, 100, 100));
    publish(hub, coarse(40, 40, 50, 50));
    assert_int_equal(world_subscription_take(s, got, 16), 1);
    assert_rect(got[0].rect, 0, 0, 100, 100);
    publish(hub, coarse(40, 40, 50, 50));
    publish(hub, coarse(-1, -1, 101, 101));
    assert_int_equal(world_subscription_take(s, got, 16), 1);
    assert_rect(got[0].rect, -1, -1, 101, 101);
    // Sharing only a corner counts as touching too.
    publish(hub, coarse(0, 0, 10, 10));
    publish(hub, coarse(10, 10, 20, 20));
    assert_int_equal(world_subscription_take(s, got, 16), 1);
    assert_rect(got[0].rect, 0, 0, 20, 20);
    // A bridge between two queued areas merges all three.
    publish(hub, coarse(0, 0, 10, 10));
    publish(hub, of_kind(WORLD_EVENT_HISTORY));
    publish(hub, coarse(50, 0, 60, 10));
    publish(hub, coarse(5, 3, 55, 6));
    size_t n = world_subscription_take(s, got, 16);
    assert_int_equal(n, 2);
    int areas = 0, history = 0;
    for (size_t i = 0; i < n; i++) {
        if (got[i].kind == WORLD_EVENT_AREA) {
            areas++;
            assert_rect(got[i].rect, 0, 0, 60, 10);
        }
        history += got[i].kind == WORLD_EVENT_HISTORY;
    }
    assert_int_equal(areas, 1);
    assert_int_equal(history, 1);
    // The merged union can reach an area that touched none of the parts: a chain.
    publish(hub, coarse(0, 0, 10, 10));
    publish(hub, coarse(30, 0, 40, 10));  // apart from the first
    publish(hub, coarse(0, 20, 40, 30));  // apart from both
    publish(hub, coarse(9, 0, 31, 10));   // joins the first two into [0,40)x[0,10)
    publish(hub, coarse(20, 10, 21, 20)); // touches that and the third
    assert_int_equal(world_subscription_take(s, got, 16), 1);
    assert_rect(got[0].rect, 0, 0, 40, 30);
    world_events_unsubscribe(s);
    world_events_release(hub);
}

static void test_apart_and_other_grids_stay_separate(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    world_subscription *s = world_events_subscribe(hub, NULL, NULL);
    world_event got[32];
    // One sample of gap, in x, in z, and diagonally.
    publish(hub, coarse(0, 0, 10, 10));
    publish(hub, coarse(11, 0, 20, 10));
    publish(hub, coarse(0, 11, 10, 20));
    publish(hub, coarse(11, 11, 20, 20));
    assert_int_equal(world_subscription_take(s, got, 32), 4);
    assert_rect(got[0].rect, 0, 0, 10, 10);
    assert_rect(got[1].rect, 11, 0, 20, 10);
    assert_rect(got[2].rect, 0, 11, 10, 20);
    assert_rect(got[3].rect, 11, 11, 20, 20);
    // The same rectangle on another layer, face or level is another area.
    const world_event same_rect[] = {
        area(TILE_LAYER_COARSE, 0, 0, 0, 0, 10, 10),
        area(TILE_LAYER_DETAIL, 0, 0, 0, 0, 10, 10),
        area(TILE_LAYER_MATERIAL, 0, 0, 0, 0, 10, 10),
        area(TILE_LAYER_DETAIL_PD, 0, 0, 0, 0, 10, 10),
        area(TILE_LAYER_COARSE, 1, 0, 0, 0, 10, 10),
        area(TILE_LAYER_COARSE, 5, 0, 0, 0, 10, 10),
        area(TILE_LAYER_COARSE, 0, 1, 0, 0, 10, 10),
        area(TILE_LAYER_COARSE, 0, 7, 0, 0, 10, 10),
        area(TILE_LAYER_DETAIL, 2, 3, 0, 0, 10, 10),
    };
    size_t count = sizeof same_rect / sizeof same_rect[0];
    for (int round = 0; round < 3; round++) // repeats merge into their own grid's area only
        for (size_t i = 0; i < count; i++)
            world_events_publish(hub, &same_rect[i]);
    assert_int_equal(world_subscription_take(s, got, 32), count);
    for (size_t i = 0; i < count; i++)
        if (!same_event(&got[i], &same_rect[i])) fail_msg("event %zu differs", i);
    world_events_unsubscribe(s);
    world_events_release(hub);
}

static void test_other_kinds_queued_once(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    world_subscription *s = world_events_subscribe(hub, NULL, NULL);
    world_event got[16];
    for (int i = 0; i < 5; i++)
        publish(hub, of_kind(WORLD_EVENT_HISTORY));
    assert_int_equal(world_subscription_take(s, got, 16), 1);
    assert_int_equal(got[0].kind, WORLD_EVENT_HISTORY);
    // Each kind once, in the order of its first publish.
    publish(hub, of_kind(WORLD_EVENT_PARAMS));
    publish(hub, of_kind(WORLD_EVENT_SAVED));
    publish(hub, of_kind(WORLD_EVENT_PARAMS));
    publish(hub, coarse(0, 0, 1, 1));
    publish(hub, of_kind(WORLD_EVENT_HISTORY));
    publish(hub, of_kind(WORLD_EVENT_SAVED));
    publish(hub, of_kind(WORLD_EVENT_REPLACED));
    publish(hub, of_kind(WORLD_EVENT_HISTORY));
    publish(hub, of_kind(WORLD_EVENT_REPLACED));
    assert_int_equal(world_subscription_take(s, got, 16), 5);
    assert_int_equal(got[0].kind, WORLD_EVENT_PARAMS);
    assert_int_equal(got[1].kind, WORLD_EVENT_SAVED);
    assert_int_equal(got[2].kind, WORLD_EVENT_AREA);
    assert_int_equal(got[3].kind, WORLD_EVENT_HISTORY);
    assert_int_equal(got[4].kind, WORLD_EVENT_REPLACED);
    // Once taken, the same kind is queued again.
    publish(hub, of_kind(WORLD_EVENT_PARAMS));
    assert_int_equal(world_subscription_take(s, got, 16), 1);
    assert_int_equal(got[0].kind, WORLD_EVENT_PARAMS);
    world_events_unsubscribe(s);
    world_events_release(hub);
}

static void test_take_oldest_first(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    world_subscription *s = world_events_subscribe(hub, NULL, NULL);
    for (int i = 0; i < 7; i++) // apart from each other
        publish(hub, coarse(i * 10, 0, i * 10 + 5, 5));
    world_event got[8];
    memset(got, 0xab, sizeof got);
    assert_int_equal(world_subscription_take(s, got, 0), 0); // nothing moved
    assert_int_equal(world_subscription_take(s, got, 2), 2);
    assert_rect(got[0].rect, 0, 0, 5, 5);
    assert_rect(got[1].rect, 10, 0, 15, 5);
    for (size_t i = 0; i < sizeof got[2]; i++) // nothing written past max
        assert_int_equal(((const unsigned char *)&got[2])[i], 0xab);
    assert_int_equal(world_subscription_take(s, got, 3), 3);
    assert_rect(got[0].rect, 20, 0, 25, 5);
    assert_rect(got[2].rect, 40, 0, 45, 5);
    // What stays keeps its order behind newer events.
    publish(hub, of_kind(WORLD_EVENT_SAVED));
    assert_int_equal(world_subscription_take(s, got, 1), 1);
    assert_rect(got[0].rect, 50, 0, 55, 5);
    assert_int_equal(world_subscription_take(s, got, 8), 2);
    assert_rect(got[0].rect, 60, 0, 65, 5);
    assert_int_equal(got[1].kind, WORLD_EVENT_SAVED);
    assert_int_equal(world_subscription_take(s, got, 8), 0);
    world_events_unsubscribe(s);
    world_events_release(hub);
}

static void count_call(void *user) {
    (*(int *)user)++;
}

static void test_empty_areas_dropped(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    int calls = 0;
    world_subscription *s = world_events_subscribe(hub, count_call, &calls);
    publish(hub, coarse(5, 5, 5, 10));   // no width
    publish(hub, coarse(5, 5, 10, 5));   // no depth
    publish(hub, coarse(10, 10, 5, 20)); // inverted
    publish(hub, coarse(0, 0, 0, 0));
    publish(hub, coarse(INT64_MAX, 0, INT64_MIN, 1));
    world_event got[8];
    assert_int_equal(world_subscription_take(s, got, 8), 0);
    assert_int_equal(calls, 0); // not an event at all: nobody is woken
    // An empty area never widens a queued one either.
    publish(hub, coarse(0, 0, 2, 2));
    publish(hub, coarse(1, 1, 1000, 1));
    assert_int_equal(world_subscription_take(s, got, 8), 1);
    assert_rect(got[0].rect, 0, 0, 2, 2);
    assert_int_equal(calls, 1);
    world_events_unsubscribe(s);
    world_events_release(hub);
}

static void test_flooded_queue_stays_bounded_and_covers(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    world_subscription *s = world_events_subscribe(hub, NULL, NULL);
    publish(hub, of_kind(WORLD_EVENT_HISTORY));
    enum { N = 10000 };
    static world_event sent[N];
    for (int i = 0; i < N; i++) { // disjoint: two samples apart, on two grids
        int64_t x = (i % 100) * 3, z = (i / 100) * 3;
        sent[i] = i % 3 ? coarse(x, z, x + 1 + i % 2, z + 1)
                        : area(TILE_LAYER_DETAIL, 2, 0, x * 10, z * 10, x * 10 + 1, z * 10 + 2);
        world_events_publish(hub, &sent[i]);
    }
    enum { CAP = 20000 };
    world_event *got = malloc(CAP * sizeof *got);
    size_t n = world_subscription_take(s, got, CAP);
    print_message("10,000 disjoint areas became %zu events\n", n);
    assert_true(n >= 1);
    assert_true(n <= 256); // bounded: the queue never held more than its bound
    int history = 0;
    for (size_t k = 0; k < n; k++)
        history += got[k].kind == WORLD_EVENT_HISTORY;
    assert_int_equal(history, 1); // other kinds survive the collapse
    // Every published area lies inside a taken area of its own grid (or a PARAMS
    // event says "everything").
    for (int i = 0; i < N; i++) {
        int covered = 0;
        for (size_t k = 0; k < n && !covered; k++)
            covered = got[k].kind == WORLD_EVENT_PARAMS ||
                      (got[k].kind == WORLD_EVENT_AREA && got[k].layer == sent[i].layer &&
                       got[k].face == sent[i].face && got[k].level == sent[i].level &&
                       contains(got[k].rect, sent[i].rect));
        if (!covered) fail_msg("area %d was lost", i);
    }
    assert_int_equal(world_subscription_take(s, got, CAP), 0);
    // And the queue works normally afterwards.
    publish(hub, coarse(7, 7, 8, 8));
    assert_int_equal(world_subscription_take(s, got, CAP), 1);
    assert_rect(got[0].rect, 7, 7, 8, 8);
    free(got);
    world_events_unsubscribe(s);
    world_events_release(hub);
}

// Cell k of a 30 x 30 layout of 1 x 1 areas two samples apart, in an order that puts
// the two far corners first, so every later area lies inside the bounding rectangle
// of the earlier ones (but touches none of them).
static world_event cell(int k) {
    int c = k == 0 ? 0 : k == 1 ? 899 : k - 1; // k < 900
    int64_t x = (c % 30) * 3, z = (c / 30) * 3;
    return coarse(x, z, x + 1, z + 1);
}

static void test_flooded_queue_merges_afterwards(void **state) {
    (void)state;
    // The publish that fills the queue merges into its grid's bounding rectangle after
    // the collapse (it was once left beside it).
    for (int count = 1; count <= 600; count++) {
        world_events *hub = world_events_create();
        world_subscription *s = world_events_subscribe(hub, NULL, NULL);
        for (int k = 0; k < count; k++)
            publish(hub, cell(k));
        world_event got[1024];
        size_t n = world_subscription_take(s, got, 1024);
        world_events_unsubscribe(s);
        world_events_release(hub);
        for (size_t a = 0; a < n; a++)
            for (size_t b = a + 1; b < n; b++)
                if (touch(got[a].rect, got[b].rect))
                    fail_msg("after %d publishes: taken areas %zu [%lld,%lld)x[%lld,%lld) and "
                             "%zu [%lld,%lld)x[%lld,%lld) (of %zu) touch but were not merged",
                             count, a, (long long)got[a].rect.x0, (long long)got[a].rect.x1,
                             (long long)got[a].rect.z0, (long long)got[a].rect.z1, b,
                             (long long)got[b].rect.x0, (long long)got[b].rect.x1,
                             (long long)got[b].rect.z0, (long long)got[b].rect.z1, n);
    }
}

static void test_areas_on_very_many_grids(void **state) {
    (void)state;
    // More grids than the queue can hold even collapsed: the queue becomes one
    // WORLD_EVENT_PARAMS ("refresh everything"), as the header says.
    world_events *hub = world_events_create();
    world_subscription *s = world_events_subscribe(hub, NULL, NULL);
    for (int level = 0; level < 1000; level++)
        publish(hub, area(TILE_LAYER_COARSE, 0, level, 0, 0, 4, 4));
    world_event got[512];
    size_t n = world_subscription_take(s, got, 512);
    print_message("areas on 1000 grids became %zu events\n", n);
    assert_true(n >= 1 && n <= 256);
    int params = 0;
    for (size_t k = 0; k < n; k++)
        params += got[k].kind == WORLD_EVENT_PARAMS;
    assert_int_equal(params, 1);
    world_events_unsubscribe(s);
    world_events_release(hub);
}

// A notify callback that takes what was queued (allowed: it runs under no lock of
// the hub) and remembers the last event it saw.
typedef struct taker {
    world_subscription *s;
    int calls;
    size_t taken;
    world_event last;
} taker;

static void take_on_notify(void *user) {
    taker *t = user;
    t->calls++;
    world_event got[4];
    size_t n = world_subscription_take(t->s, got, 4);
    t->taken += n;
    if (n) t->last = got[n - 1];
}

static void test_notify(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    int calls_a = 0, calls_b = 0;
    world_subscription *a = world_events_subscribe(hub, count_call, &calls_a);
    world_subscription *b = world_events_subscribe(hub, count_call, &calls_b);
    world_subscription *quiet = world_events_subscribe(hub, NULL, NULL); // no callback
    taker t = {0};
    t.s = world_events_subscribe(hub, take_on_notify, &t);
    // Once per publish per subscriber, even when the event merges or is a repeat.
    publish(hub, coarse(0, 0, 4, 4));
    publish(hub, coarse(2, 2, 6, 6)); // merges
    publish(hub, of_kind(WORLD_EVENT_HISTORY));
    publish(hub, of_kind(WORLD_EVENT_HISTORY)); // not queued twice, still a wake-up
    assert_int_equal(calls_a, 4);
    assert_int_equal(calls_b, 4);
    assert_int_equal(t.calls, 4);
    // The callback runs after the event is queued: it finds it there.
    assert_int_equal(t.taken, 4);
    assert_int_equal(t.last.kind, WORLD_EVENT_HISTORY);
    world_event got[8];
    assert_int_equal(world_subscription_take(a, got, 8), 2);
    assert_rect(got[0].rect, 0, 0, 6, 6);
    assert_int_equal(world_subscription_take(quiet, got, 8), 2);
    // Empty areas wake nobody (see test_empty_areas_dropped); unsubscribing stops both
    // the events and the wake-ups of that subscriber only.
    world_events_unsubscribe(b);
    publish(hub, of_kind(WORLD_EVENT_SAVED));
    assert_int_equal(calls_a, 5);
    assert_int_equal(calls_b, 4);
    assert_int_equal(t.calls, 5);
    assert_int_equal(t.last.kind, WORLD_EVENT_SAVED);
    world_events_unsubscribe(t.s);
    publish(hub, of_kind(WORLD_EVENT_PARAMS));
    assert_int_equal(t.calls, 5);
    assert_int_equal(calls_a, 6);
    assert_int_equal(world_subscription_take(a, got, 8), 2); // SAVED, PARAMS
    world_events_unsubscribe(a);
    publish(hub, of_kind(WORLD_EVENT_REPLACED));
    assert_int_equal(calls_a, 6);
    assert_int_equal(world_subscription_take(quiet, got, 8), 3);
    world_events_unsubscribe(quiet);
    publish(hub, of_kind(WORLD_EVENT_REPLACED)); // nobody listens: fine
    world_events_unsubscribe(NULL);              // a no-op
    world_events_release(hub);
}

static void test_lifetimes(void **state) {
    (void)state;
    // A hub nobody subscribed to.
    world_events *hub = world_events_create();
    publish(hub, coarse(0, 0, 1, 1));
    world_events_release(hub);
    world_events_release(NULL);                                              // a no-op
    world_events_publish(NULL, &(world_event){.kind = WORLD_EVENT_HISTORY}); // likewise
    // Subscriptions outlive the creator's hold on the hub (ASan checks the accesses,
    // LeakSanitizer that the last unsubscribe frees the hub).
    hub = world_events_create();
    world_subscription *a = world_events_subscribe(hub, NULL, NULL);
    world_subscription *b = world_events_subscribe(hub, NULL, NULL);
    publish(hub, of_kind(WORLD_EVENT_SAVED));
    world_events_release(hub);
    assert_ptr_equal(world_subscription_hub(a), hub);
    world_event got[4];
    assert_int_equal(world_subscription_take(a, got, 4), 1); // queued before the release
    assert_int_equal(got[0].kind, WORLD_EVENT_SAVED);
    assert_int_equal(world_subscription_take(a, got, 4), 0);
    world_events_unsubscribe(a);
    assert_int_equal(world_subscription_take(b, got, 4), 1);
    world_events_unsubscribe(b); // the last hold: the hub goes now
    // Unsubscribing before the release works the other way round.
    hub = world_events_create();
    a = world_events_subscribe(hub, NULL, NULL);
    world_events_unsubscribe(a);
    world_events_release(hub);
    // A world's private hub (settings.events NULL) outlives the world for its subscribers.
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    og_error err = {{0}};
    world *w = world_create(&p, NULL, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    a = world_events_subscribe(world_event_hub(w), NULL, NULL);
    world_publish(w, &(world_event){.kind = WORLD_EVENT_HISTORY});
    world_close(w);
    assert_int_equal(world_subscription_take(a, got, 4), 1);
    world_events_unsubscribe(a);
}

// ---- a world publishing ---------------------------------------------------------------

typedef struct seen {
    int area, params, saved, history, replaced, other;
    grid_rect coarse; // union of the coarse level-0 face-0 areas
    int coarse_count;
} seen;

static seen take_all(world_subscription *s) {
    seen r = {0};
    world_event got[512];
    size_t n;
    while ((n = world_subscription_take(s, got, 512)) > 0)
        for (size_t i = 0; i < n; i++) {
            switch (got[i].kind) {
            case WORLD_EVENT_AREA:
                r.area++;
                if (got[i].layer == TILE_LAYER_COARSE && got[i].face == 0 && got[i].level == 0) {
                    r.coarse =
                        r.coarse_count ? grid_rect_union(r.coarse, got[i].rect) : got[i].rect;
                    r.coarse_count++;
                }
                break;
            case WORLD_EVENT_PARAMS:
                r.params++;
                break;
            case WORLD_EVENT_SAVED:
                r.saved++;
                break;
            case WORLD_EVENT_HISTORY:
                r.history++;
                break;
            case WORLD_EVENT_REPLACED:
                r.replaced++;
                break;
            default:
                r.other++;
            }
        }
    return r;
}

static void test_world_publishes(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    int wakeups = 0;
    world_subscription *s = world_events_subscribe(hub, count_call, &wakeups);
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    world_settings settings = {.events = hub};
    og_error err = {{0}};
    world *w = world_create(&p, &settings, &err);
    if (!w) fail_msg("world_create: %s", err.msg);
    assert_ptr_equal(world_event_hub(w), hub);
    take_all(s); // whatever creation says
    // A dab publishes the area it changed at once (the viewport shows it live), and
    // no history change until the stroke ends. Flat default: 2 m between samples, so
    // a 20 m brush at (500, 500) m covers about samples 240-260.
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    stroke *st = stroke_begin(w, &b, &err);
    if (!st) fail_msg("stroke_begin: %s", err.msg);
    seen e = take_all(s);
    assert_int_equal(e.area + e.history + e.params + e.saved, 0); // nothing yet
    wakeups = 0;
    if (stroke_to(st, 500, 500, 1.0, &err) != 0) fail_msg("stroke_to: %s", err.msg);
    assert_true(wakeups >= 1);
    e = take_all(s);
    assert_true(e.coarse_count >= 1);
    assert_int_equal(e.history, 0);
    grid_rect dab = e.coarse;
    print_message("dab area [%lld,%lld)x[%lld,%lld)\n", (long long)dab.x0, (long long)dab.x1,
                  (long long)dab.z0, (long long)dab.z1);
    assert_true(contains(dab, (grid_rect){249, 249, 252, 252}));
    assert_true(contains((grid_rect){230, 230, 271, 271}, dab));
    // The stroke's end adds an undo step.
    if (stroke_end(st, &err) != 0) fail_msg("stroke_end: %s", err.msg);
    e = take_all(s);
    assert_int_equal(e.history, 1);
    assert_int_equal(e.params + e.saved + e.replaced + e.other, 0);
    // Undo changes the same area back and the history.
    assert_int_equal(edit_undo(w, &err), 1);
    e = take_all(s);
    assert_int_equal(e.history, 1);
    assert_true(e.coarse_count >= 1);
    assert_true(contains(e.coarse, (grid_rect){249, 249, 252, 252}));
    assert_true(contains((grid_rect){230, 230, 271, 271}, e.coarse));
    // Redo likewise.
    assert_int_equal(edit_redo(w, &err), 1);
    e = take_all(s);
    assert_int_equal(e.history, 1);
    assert_true(e.coarse_count >= 1);
    // Nothing to undo twice: no event.
    assert_int_equal(edit_undo(w, &err), 1);
    take_all(s);
    assert_int_equal(edit_undo(w, &err), 0);
    e = take_all(s);
    assert_int_equal(e.area + e.history, 0);
    // New parameters.
    world_params q = *world_get_params(w);
    q.seed = 4242;
    if (world_regenerate(w, &q, &err) != 0) fail_msg("world_regenerate: %s", err.msg);
    e = take_all(s);
    assert_int_equal(e.params, 1);
    assert_int_equal(e.saved + e.history, 0);
    // Refused parameters change nothing and publish nothing.
    q.spacing = -1;
    assert_int_equal(world_regenerate(w, &q, &err), -1);
    e = take_all(s);
    assert_int_equal(e.params + e.area + e.history + e.saved, 0);
    // Saving.
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", test_tmpdir("world-events"));
    char path[4200];
    snprintf(path, sizeof path, "%s/events.world", dir);
    if (world_save(w, path, 0, &err) != 0) fail_msg("world_save: %s", err.msg);
    e = take_all(s);
    assert_int_equal(e.saved, 1);
    assert_int_equal(e.params + e.history + e.area, 0);
    if (world_save(w, NULL, 0, &err) != 0) fail_msg("world_save again: %s", err.msg);
    e = take_all(s);
    assert_int_equal(e.saved, 1);
    world_close(w);
    // The shared hub outlives the world; the subscription is still good.
    world_events_unsubscribe(s);
    world_events_release(hub);
    test_rmtree(dir);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_subscriber_gets_every_event),
        cmocka_unit_test(test_touching_areas_merge),
        cmocka_unit_test(test_apart_and_other_grids_stay_separate),
        cmocka_unit_test(test_other_kinds_queued_once),
        cmocka_unit_test(test_take_oldest_first),
        cmocka_unit_test(test_empty_areas_dropped),
        cmocka_unit_test(test_flooded_queue_stays_bounded_and_covers),
        cmocka_unit_test(test_flooded_queue_merges_afterwards), // fails: a bug, see the test
        cmocka_unit_test(test_areas_on_very_many_grids),
        cmocka_unit_test(test_notify),
        cmocka_unit_test(test_lifetimes),
        cmocka_unit_test(test_world_publishes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
