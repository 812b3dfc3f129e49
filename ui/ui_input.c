// The input queue (ui.h): events in arrival order, handed out a frame's share at a time
// so that a slow frame neither drops a press nor sees a key twice.
#include "ui/ui.h"

#include <math.h>
#include <string.h>

#define DOUBLE_CLICK_SECONDS 0.35
#define DOUBLE_CLICK_PIXELS 4.0f

void ui_input_queue_init(ui_input_queue *q) {
    memset(q, 0, sizeof *q);
    q->state.mouse_x = q->state.mouse_y = -1e6f; // nowhere until the pointer comes in
    q->last_press_time = -1e9;
}

static ui_event *queued(ui_input_queue *q, size_t i) {
    return &q->events[(q->head + i) % UI_QUEUE_MAX];
}

void ui_input_queue_push(ui_input_queue *q, const ui_event *e) {
    if (q->count == UI_QUEUE_MAX) {
        // Full (no frame for thousands of events): a move only moves the pointer on from
        // the last queued move; anything else makes room by merging two queued moves.
        ui_event *last = queued(q, q->count - 1);
        if (e->kind == UI_EVENT_MOVE && last->kind == UI_EVENT_MOVE) {
            *last = *e;
            q->merged++;
            return;
        }
        for (size_t i = q->count - 1; i > 0; i--) {
            if (queued(q, i)->kind != UI_EVENT_MOVE || queued(q, i - 1)->kind != UI_EVENT_MOVE)
                continue;
            for (size_t k = i - 1; k + 1 < q->count; k++) // the later move replaces the earlier
                *queued(q, k) = *queued(q, k + 1);
            q->count--;
            q->merged++;
            break;
        }
        if (q->count == UI_QUEUE_MAX) return; // nothing to merge: cannot happen in practice
    }
    *queued(q, q->count++) = *e;
}

// What the frame holds so far, for deciding whether the next event still fits in it.
typedef struct frame_has {
    int button, ui_key, app_key, text;
} frame_has;

// Whether e may join a frame holding has (see ui.h for the rules).
static int fits(const ui_event *e, const frame_has *has, int typing) {
    switch (e->kind) {
    case UI_EVENT_MOVE:
    case UI_EVENT_WHEEL:
        return !has->button;
    case UI_EVENT_BUTTON:
        return !has->button && !has->ui_key && !has->app_key && !has->text;
    case UI_EVENT_KEY:
        if (!e->down) return 1; // a release only updates what is held
        if (e->key < 0 && typing) return !has->button && !has->ui_key; // plain typing
        return !has->button && !has->ui_key && !has->app_key && !has->text;
    case UI_EVENT_TEXT:
        return !has->button && !has->ui_key;
    }
    return 1;
}

size_t ui_input_queue_frame(ui_input_queue *q, int typing, ui_input *in) {
    ui_input *st = &q->state;
    memset(st->mouse_pressed, 0, sizeof st->mouse_pressed);
    memset(st->mouse_released, 0, sizeof st->mouse_released);
    memset(st->key_pressed, 0, sizeof st->key_pressed);
    st->double_click = 0;
    st->wheel = 0;
    st->text[0] = 0;
    st->event_count = 0;
    frame_has has = {0};
    while (q->count > 0 && st->event_count < UI_FRAME_EVENTS_MAX) {
        const ui_event *e = queued(q, 0);
        if (st->event_count > 0 && !fits(e, &has, typing)) break;
        if (e->kind == UI_EVENT_TEXT && strlen(st->text) + strlen(e->text) >= sizeof st->text)
            break;
        switch (e->kind) {
        case UI_EVENT_MOVE:
            st->mouse_x = e->x, st->mouse_y = e->y;
            break;
        case UI_EVENT_WHEEL:
            st->wheel += e->wheel;
            break;
        case UI_EVENT_BUTTON:
            has.button = 1;
            st->mouse_x = e->x, st->mouse_y = e->y;
            st->mods = e->mods;
            if (e->button < 0 || e->button > 2) break;
            st->mouse_down[e->button] = e->down;
            if (!e->down) {
                st->mouse_released[e->button] = 1;
                break;
            }
            st->mouse_pressed[e->button] = 1;
            if (e->button == 0) { // a second press soon and near the first: a double click
                st->double_click = e->time - q->last_press_time < DOUBLE_CLICK_SECONDS &&
                                   fabsf(e->x - q->last_press_x) <= DOUBLE_CLICK_PIXELS &&
                                   fabsf(e->y - q->last_press_y) <= DOUBLE_CLICK_PIXELS;
                // A third press is not a second double click.
                q->last_press_time = st->double_click ? -1e9 : e->time;
                q->last_press_x = e->x, q->last_press_y = e->y;
            }
            break;
        case UI_EVENT_KEY:
            st->mods = e->mods;
            if (!e->down) break;
            if (e->key >= 0 && e->key < UI_KEY_COUNT)
                st->key_pressed[e->key] = 1, has.ui_key = 1;
            else
                has.app_key = 1;
            break;
        case UI_EVENT_TEXT:
            strcat(st->text, e->text);
            has.text = 1;
            break;
        }
        st->time = e->time;
        st->events[st->event_count++] = *e;
        q->head = (q->head + 1) % UI_QUEUE_MAX;
        q->count--;
    }
    *in = *st;
    return q->count;
}
