// Change notifications (editor/world/world_events.c): every subscriber hears every
// change, touching areas merge, queues stay bounded without losing coverage, wake-up
// callbacks, unsubscribing, subscriptions that outlive their world; and a world
// publishing edits, history changes, new parameters and saves.
#include "editor/edit/edit.h"
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

static world_event area(tile_layer layer, int face, int level, int64_t x0, int64_t z0, int64_t x1,
                        int64_t z1) {
    return (world_event){.kind = WORLD_EVENT_AREA,
                         .layer = layer,
                         .face = face,
                         .level = level,
                         .rect = {x0, z0, x1, z1}};
}

static void test_fan_out_and_merging(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    world_subscription *a = world_events_subscribe(hub, NULL, NULL);
    world_subscription *b = world_events_subscribe(hub, NULL, NULL);
    world_event e = area(TILE_LAYER_COARSE, 0, 0, 0, 0, 10, 10);
    world_events_publish(hub, &e);
    e = area(TILE_LAYER_COARSE, 0, 0, 10, 5, 20, 8); // shares an edge: merges
    world_events_publish(hub, &e);
    e = area(TILE_LAYER_COARSE, 0, 0, 100, 100, 110, 110); // apart
    world_events_publish(hub, &e);
    e = area(TILE_LAYER_MATERIAL, 0, 0, 0, 0, 10, 10); // another layer never merges
    world_events_publish(hub, &e);
    e = area(TILE_LAYER_COARSE, 1, 0, 0, 0, 10, 10); // nor another face
    world_events_publish(hub, &e);
    e = area(TILE_LAYER_COARSE, 0, 0, 5, 5, 5, 9); // empty: dropped
    world_events_publish(hub, &e);
    world_event h = {.kind = WORLD_EVENT_HISTORY};
    world_events_publish(hub, &h);
    world_events_publish(hub, &h); // not queued twice
    world_event got[16];
    size_t n = world_subscription_take(a, got, 16);
    assert_int_equal(n, 5);
    assert_int_equal(got[0].kind, WORLD_EVENT_AREA);
    assert_true(got[0].rect.x0 == 0 && got[0].rect.z0 == 0 && got[0].rect.x1 == 20 &&
                got[0].rect.z1 == 10);
    assert_true(got[1].rect.x0 == 100);
    assert_int_equal(got[2].layer, TILE_LAYER_MATERIAL);
    assert_int_equal(got[3].face, 1);
    assert_int_equal(got[4].kind, WORLD_EVENT_HISTORY);
    assert_int_equal(world_subscription_take(a, got, 16), 0);
    // b has its own queue; take in small pieces, oldest first.
    assert_int_equal(world_subscription_take(b, got, 2), 2);
    assert_true(got[0].rect.x1 == 20 && got[1].rect.x0 == 100);
    assert_int_equal(world_subscription_take(b, got, 16), 3);
    world_events_unsubscribe(a);
    world_events_publish(hub, &h);
    assert_int_equal(world_subscription_take(b, got, 16), 1);
    world_events_unsubscribe(b);
    world_events_release(hub);
}

static void test_bounded_queue_keeps_coverage(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    world_subscription *s = world_events_subscribe(hub, NULL, NULL);
    for (int i = 0; i < 10000; i++) { // disjoint little areas
        world_event e =
            area(TILE_LAYER_COARSE, 0, 0, i * 3, (i % 7) * 3, i * 3 + 1, (i % 7) * 3 + 1);
        world_events_publish(hub, &e);
    }
    world_event got[1024];
    size_t n = world_subscription_take(s, got, 1024);
    assert_true(n >= 1 && n <= 512);
    for (int i = 0; i < 10000; i++) { // every published area is inside one taken
        int64_t x = i * 3, z = (i % 7) * 3;
        int covered = 0;
        for (size_t k = 0; k < n && !covered; k++)
            covered = got[k].kind == WORLD_EVENT_PARAMS ||
                      (got[k].rect.x0 <= x && got[k].rect.z0 <= z && got[k].rect.x1 >= x + 1 &&
                       got[k].rect.z1 >= z + 1);
        if (!covered) fail_msg("area %d was lost", i);
    }
    world_events_unsubscribe(s);
    world_events_release(hub);
}

static void count_call(void *user) {
    (*(int *)user)++;
}

static void test_notify_and_lifetime(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    int calls_a = 0, calls_b = 0;
    world_subscription *a = world_events_subscribe(hub, count_call, &calls_a);
    world_subscription *b = world_events_subscribe(hub, count_call, &calls_b);
    world_event h = {.kind = WORLD_EVENT_SAVED};
    world_events_publish(hub, &h);
    world_events_publish(hub, &h);
    assert_int_equal(calls_a, 2);
    assert_int_equal(calls_b, 2);
    world_events_unsubscribe(b);
    world_events_publish(hub, &h);
    assert_int_equal(calls_a, 3);
    assert_int_equal(calls_b, 2);
    // The creator lets go first: the subscription stays valid (ASan checks this).
    world_events_release(hub);
    world_event got[4];
    assert_int_equal(world_subscription_take(a, got, 4), 1);
    assert_ptr_equal(world_subscription_hub(a), hub);
    world_events_unsubscribe(a);
}

static int has(world_subscription *s, world_event_kind kind, tile_layer layer) {
    world_event got[256];
    size_t n = world_subscription_take(s, got, 256);
    int found = 0;
    for (size_t i = 0; i < n; i++)
        found |= got[i].kind == kind && (kind != WORLD_EVENT_AREA || got[i].layer == layer);
    return found;
}

static void test_world_publishes(void **state) {
    (void)state;
    world_events *hub = world_events_create();
    world_subscription *s = world_events_subscribe(hub, NULL, NULL);
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.size = 1024;
    world_settings settings = {.events = hub};
    og_error err = {{0}};
    world *w = world_create(&p, &settings, &err);
    assert_non_null(w);
    assert_ptr_equal(world_event_hub(w), hub);
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    stroke *st = stroke_begin(w, &b, &err);
    assert_non_null(st);
    assert_int_equal(stroke_to(st, 500, 500, 1.0, &err), 0);
    assert_true(has(s, WORLD_EVENT_AREA, TILE_LAYER_COARSE)); // live, during the stroke
    assert_int_equal(stroke_end(st, &err), 0);
    world_event got[256];
    size_t n = world_subscription_take(s, got, 256);
    int area_seen = 0, history_seen = 0;
    for (size_t i = 0; i < n; i++) {
        area_seen |= got[i].kind == WORLD_EVENT_AREA;
        history_seen |= got[i].kind == WORLD_EVENT_HISTORY;
    }
    assert_true(area_seen && history_seen);
    assert_int_equal(edit_undo(w, &err), 1);
    n = world_subscription_take(s, got, 256);
    area_seen = history_seen = 0;
    for (size_t i = 0; i < n; i++) {
        area_seen |= got[i].kind == WORLD_EVENT_AREA;
        history_seen |= got[i].kind == WORLD_EVENT_HISTORY;
    }
    assert_true(area_seen && history_seen);
    world_params q = *world_get_params(w);
    q.seed = 99;
    assert_int_equal(world_regenerate(w, &q, &err), 0);
    assert_true(has(s, WORLD_EVENT_PARAMS, 0));
    const char *dir = test_tmpdir("events");
    char path[4200];
    snprintf(path, sizeof path, "%s/e.world", dir);
    assert_int_equal(world_save(w, path, &err), 0);
    assert_true(has(s, WORLD_EVENT_SAVED, 0));
    world_close(w);
    world_events_unsubscribe(s);
    world_events_release(hub);
    test_rmtree(dir);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fan_out_and_merging),
        cmocka_unit_test(test_bounded_queue_keeps_coverage),
        cmocka_unit_test(test_notify_and_lifetime),
        cmocka_unit_test(test_world_publishes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
