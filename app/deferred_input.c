// The queue of input held while a job runs (deferred_input.h).
#include "app/deferred_input.h"

int deferred_input_push(deferred_input *d, deferred_event e) {
    if (d->count == DEFERRED_INPUT_MAX) {
        deferred_event *last = &d->events[d->count - 1];
        if (e.kind != DEFERRED_CURSOR || last->kind != DEFERRED_CURSOR) {
            d->lost++;
            return -1;
        }
        *last = e; // a move after a move: only where the pointer ended up matters
        return 0;
    }
    d->events[d->count++] = e;
    return 0;
}
