// Change notifications: the world publishes what changed, and any number of
// subscribers (the renderer, the window, later the GUI's panels and the volume
// mesher) each take the changes from their own queue. Nobody polls the world or
// reads the undo history to learn what changed.
//
// Threads: publish from any thread (in practice the editor thread that runs
// commands; edits publish after their parallel work joins). take from any thread.
// A subscription's notify callback runs on the publishing thread right after the
// event is queued, under no lock of ours: keep it short (e.g. wake an event loop) and
// never publish from it. Subscribe and unsubscribe from the thread that owns the hub.
#ifndef OROGEN_EDITOR_WORLD_EVENTS_H
#define OROGEN_EDITOR_WORLD_EVENTS_H

#include "editor/params/world_grid.h"
#include "io/tile.h"

#include <stddef.h>

typedef enum world_event_kind {
    WORLD_EVENT_AREA,     // samples of a layer changed: layer, face, level, rect
    WORLD_EVENT_PARAMS,   // the generation parameters changed: any generated tile may differ
    WORLD_EVENT_SAVED,    // the world was written to its files (its path may be new)
    WORLD_EVENT_HISTORY,  // the undo history changed (a step added, undone, redone, dropped)
    WORLD_EVENT_REPLACED, // another world became the document (new, load)
    // Only the edit layer table changed (a layer command, its undo): generated tiles stay;
    // the composite's changes arrive as WORLD_EVENT_AREA.
    WORLD_EVENT_LAYERS,
} world_event_kind;

typedef struct world_event {
    world_event_kind kind;
    // WORLD_EVENT_AREA only: samples [rect) of that layer's level-`level` grid on face.
    tile_layer layer;
    int face;
    int level;
    grid_rect rect;
} world_event;

typedef struct world_events world_events;
typedef struct world_subscription world_subscription;

// A hub held by its creator. release drops the creator's hold; the hub is freed once
// its last subscription is gone too, so a subscriber may outlive the world it
// subscribed to (it simply hears nothing more) and unsubscribe later.
world_events *world_events_create(void);
void world_events_release(world_events *hub);

// Queues e for every subscriber, then calls their notify callbacks. Area events that
// touch a queued area of the same layer, face and level are merged into it; other
// kinds already queued are not queued twice. A queue that grows past its bound
// collapses its areas to one bounding rectangle per layer, face and level, so a
// subscriber that never takes costs bounded memory and loses nothing but precision
// (in the extreme, the queue becomes one WORLD_EVENT_PARAMS: refresh everything).
void world_events_publish(world_events *hub, const world_event *e);

// A new subscriber with an empty queue. notify (may be NULL) is called after each
// publish with user. NULL when out of memory.
world_subscription *world_events_subscribe(world_events *hub, void (*notify)(void *user),
                                           void *user);
void world_events_unsubscribe(world_subscription *s);
// The hub s listens to.
world_events *world_subscription_hub(const world_subscription *s);
// Moves up to max queued events to out, oldest first; returns how many.
size_t world_subscription_take(world_subscription *s, world_event *out, size_t max);

#endif
