#include "io/progress.h"

static _Thread_local og_progress *installed;

void og_progress_init(og_progress *p) {
    atomic_init(&p->cancel, 0);
    atomic_init(&p->permille, 0);
    p->base = 0.0;
    p->width = 1.0;
}

void og_progress_install(og_progress *p) {
    installed = p;
}

og_progress *og_progress_current(void) {
    return installed;
}

void og_progress_cancel(og_progress *p) {
    atomic_store(&p->cancel, 1);
}

int og_progress_cancelled(const og_progress *p) {
    return p && atomic_load_explicit(&((og_progress *)p)->cancel, memory_order_relaxed);
}

double og_progress_fraction(const og_progress *p) {
    return atomic_load_explicit(&((og_progress *)p)->permille, memory_order_relaxed) / 1000.0;
}

int og_progress_report(og_progress *p, int64_t done, int64_t total) {
    if (!p) return 0;
    double f = total > 0 ? (double)done / (double)total : 0.0;
    f = f < 0.0 ? 0.0 : f > 1.0 ? 1.0 : f;
    int permille = (int)((p->base + p->width * f) * 1000.0);
    // Parts only move forward: a nested loop never makes the bar jump back.
    int seen = atomic_load_explicit(&p->permille, memory_order_relaxed);
    while (permille > seen &&
           !atomic_compare_exchange_weak_explicit(&p->permille, &seen, permille,
                                                  memory_order_relaxed, memory_order_relaxed)) {
    }
    return og_progress_cancelled(p) ? -1 : 0;
}

og_progress_part og_progress_enter(og_progress *p, int64_t index, int64_t count) {
    if (!p) return (og_progress_part){0.0, 1.0};
    og_progress_part outer = {p->base, p->width};
    if (count > 0) {
        p->width = outer.width / (double)count;
        p->base = outer.base + p->width * (double)index;
    }
    og_progress_report(p, 0, 1);
    return outer;
}

void og_progress_leave(og_progress *p, og_progress_part outer) {
    if (!p) return;
    p->base = outer.base;
    p->width = outer.width;
}
