// What input waits while a job runs, and its replay once the job has ended through the
// window's own handlers (the queue: deferred_input.h).
#include "app/window_internal.h"

#include <stdio.h>
#include <string.h>

static deferred_input *queue_of(window_state *st) {
    return &st->input.deferred;
}

// Where the pointer is as the events that wait leave it (the last motion event's, else).
static void pointer_after_queue(window_state *st, double *x, double *y) {
    deferred_input *d = queue_of(st);
    pointer_pos(st, x, y);
    for (int i = d->count - 1; i >= 0; i--)
        if (d->events[i].kind == DEFERRED_CURSOR || d->events[i].kind == DEFERRED_BUTTON) {
            *x = d->events[i].x, *y = d->events[i].y;
            return;
        }
}

int input_defer_button(window_state *st, int button, int action, int mods) {
    deferred_input *d = queue_of(st);
    if (button < 0 || button >= (int)sizeof d->held_live || !work_queue_busy(&st->work)) return 0;
    double x, y;
    pointer_after_queue(st, &x, &y);
    if (action == GLFW_RELEASE) {
        if (d->held_live[button]) { // its press went to Cancel: so does its release
            d->held_live[button] = 0;
            return 0;
        }
        if (!d->held_late[button] && d->count == 0) return 0; // a drag from before the job
        d->held_late[button] = 0;
    } else if (d->count == 0 && panels_busy_widget_at(st, ui_px(st, x), ui_px(st, y))) {
        d->held_live[button] = 1;
        return 0;
    } else {
        d->held_late[button] = 1;
    }
    deferred_input_push(d, (deferred_event){DEFERRED_BUTTON, button, action, mods, x, y});
    return 1;
}

int input_defer_cursor(window_state *st, double x, double y) {
    deferred_input *d = queue_of(st);
    if (!work_queue_busy(&st->work) || d->count == 0) return 0;
    deferred_input_push(d, (deferred_event){.kind = DEFERRED_CURSOR, .x = x, .y = y});
    return 1;
}

int input_defer_key(window_state *st, int key, int action, int mods) {
    deferred_input *d = queue_of(st);
    if (!work_queue_busy(&st->work)) return 0;
    if (key == GLFW_KEY_ESCAPE && action == GLFW_PRESS) return 0; // it cancels the work
    if (action == GLFW_RELEASE && d->count == 0) return 0;        // a key held from before
    deferred_input_push(d, (deferred_event){DEFERRED_KEY, key, action, mods, 0, 0});
    return 1;
}

int input_defer_char(window_state *st, unsigned codepoint) {
    if (!work_queue_busy(&st->work)) return 0;
    deferred_input_push(queue_of(st), (deferred_event){.kind = DEFERRED_CHAR, .a = (int)codepoint});
    return 1;
}

int input_defer_scroll(window_state *st, double dx, double dy) {
    if (!work_queue_busy(&st->work)) return 0;
    deferred_input_push(queue_of(st), (deferred_event){.kind = DEFERRED_SCROLL, .x = dx, .y = dy});
    return 1;
}

size_t input_waiting(const window_state *st) {
    return st->input.queue->count + (size_t)st->input.deferred.count + (size_t)st->work.count;
}

void input_replay_deferred(window_state *st) {
    deferred_input *d = queue_of(st);
    const deferred_handlers *h = &d->handlers;
    // No job runs during the replay (the handlers only queue work), so nothing waits again.
    for (int i = 0; i < d->count; i++) {
        const deferred_event *e = &d->events[i];
        switch (e->kind) {
        case DEFERRED_BUTTON:
            if (h->cursor) h->cursor(st->win, e->x, e->y); // the press where it was made
            if (h->button) h->button(st->win, e->a, e->b, e->c);
            break;
        case DEFERRED_CURSOR:
            if (h->cursor) h->cursor(st->win, e->x, e->y);
            break;
        case DEFERRED_KEY:
            if (h->key) h->key(st->win, e->a, 0, e->b, e->c);
            break;
        case DEFERRED_CHAR:
            if (h->character) h->character(st->win, (unsigned)e->a);
            break;
        case DEFERRED_SCROLL:
            if (h->scroll) h->scroll(st->win, e->x, e->y);
            break;
        }
    }
    d->count = 0;
    memset(d->held_late, 0, sizeof d->held_late);
    if (d->lost) {
        fprintf(stderr, "orogen: %ld input events came while work ran and the queue was full\n",
                d->lost);
        d->lost = 0;
    }
}
