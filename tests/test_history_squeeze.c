// The history's background squeeze (editor/world/history.c): a commit's deltas are
// encoded with zero runs only and zstd is tried on them after history_push, off the
// editing thread. Checked: the squeezed deltas (put in at the next peek or push) are
// those the full encoder writes, byte for byte, and undo the same tiles; the step's and
// the history's byte counts follow them; steps cut from the history (a redo branch, the
// budget) while their squeeze runs are let go (many steps in a row, no crash or leak:
// ASan/TSan builds run this too); a step never pushed is freed as before. A reader of
// the deltas on another thread (the crash journal's writer) is waited for before any
// delta it may be reading is replaced (squeezed) or freed (budget, redo branch, end).
#include "editor/world/history.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

static uint64_t rng = 0x51ed2701a5u;

static uint32_t next_u32(void) {
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (uint32_t)(rng >> 16);
}

// A tile of smooth heights and the same after a raise over part (a dab): the high
// planes of their XOR are runs of few values, which zstd shrinks.
static void tiles(float *before, float *after, grid_rect part, float amount) {
    for (int z = 0; z < TILE_SIZE; z++)
        for (int x = 0; x < TILE_SIZE; x++) {
            float h =
                100.0f + 0.37f * (float)x - 0.21f * (float)z + (float)(next_u32() % 7) * 0.01f;
            before[z * TILE_SIZE + x] = h;
            int in = x >= part.x0 && x < part.x1 && z >= part.z0 && z < part.z1;
            after[z * TILE_SIZE + x] = in ? h + amount * (float)((x - part.x0) % 17) : h;
        }
}

static size_t step_sum(const history *h) {
    size_t sum = 0;
    for (size_t i = 0; i < history_count(h); i++)
        sum += history_at(h, i)->bytes;
    return sum;
}

static void test_squeezed_deltas_are_the_full_encoding(void **state) {
    (void)state;
    history *h = history_create(0);
    float *before = malloc(sizeof(float) * TILE_SAMPLES),
          *after = malloc(sizeof(float) * TILE_SAMPLES);
    float *undone = malloc(sizeof(float) * TILE_SAMPLES);
    assert_true(h && before && after && undone);
    grid_rect part = {40, 30, 200, 190};
    tiles(before, after, part, 0.5f);
    void *quick, *full;
    size_t quick_bytes, full_bytes;
    assert_int_equal(history_delta_encode_part_quick(TILE_LAYER_COARSE, before, after, part, &quick,
                                                     &quick_bytes),
                     0);
    assert_int_equal(
        history_delta_encode_part(TILE_LAYER_COARSE, before, after, part, &full, &full_bytes), 0);
    assert_true(full_bytes < quick_bytes); // zstd gains here: the squeeze has work to do
    history_step *s = history_step_new("dab");
    tile_key key = {.layer = TILE_LAYER_COARSE};
    assert_int_equal(history_step_add_delta(s, key, 0, quick, quick_bytes), 0);
    assert_int_equal(history_push(h, s), 0);
    size_t pushed = history_bytes(h);
    // The undo peek puts the squeezed delta in first.
    history_step *peek = history_undo_peek(h);
    assert_ptr_equal(peek, s);
    assert_int_equal(s->tiles[0].bytes, full_bytes);
    assert_memory_equal(s->tiles[0].delta, full, full_bytes);
    assert_int_equal(history_bytes(h), pushed - (quick_bytes - full_bytes));
    assert_int_equal(history_bytes(h), step_sum(h));
    memcpy(undone, after, sizeof(float) * TILE_SAMPLES);
    assert_int_equal(history_tile_apply(&s->tiles[0], undone), 0);
    assert_memory_equal(undone, before, sizeof(float) * TILE_SAMPLES);
    free(full);
    free(before);
    free(after);
    free(undone);
    history_destroy(h);
}

// Pushes a one-tile step of a random dab.
static history_step *push_dab(history *h, float *before, float *after) {
    grid_rect part = {(int64_t)(next_u32() % 100), (int64_t)(next_u32() % 100), 0, 0};
    part.x1 = part.x0 + 20 + next_u32() % 130, part.z1 = part.z0 + 20 + next_u32() % 130;
    tiles(before, after, part, 0.25f + (float)(next_u32() % 4));
    void *d;
    size_t bytes;
    assert_int_equal(
        history_delta_encode_part_quick(TILE_LAYER_COARSE, before, after, part, &d, &bytes), 0);
    history_step *s = history_step_new("dab");
    assert_non_null(s);
    assert_int_equal(history_step_add_delta(s, (tile_key){.layer = TILE_LAYER_COARSE}, 0, d, bytes),
                     0);
    history_push(h, s);
    return s;
}

static void test_steps_cut_while_squeezed(void **state) {
    (void)state;
    float *before = malloc(sizeof(float) * TILE_SAMPLES),
          *after = malloc(sizeof(float) * TILE_SAMPLES);
    assert_true(before && after);
    // A budget of a few steps: pushes drop the oldest while newer ones are squeezed.
    history *h = history_create((size_t)600 << 10);
    assert_non_null(h);
    for (int i = 0; i < 200; i++) {
        push_dab(h, before, after);
        if (next_u32() % 3 == 0) { // undo one or two: the next push cuts them
            int n = 1 + (int)(next_u32() % 2);
            for (int k = 0; k < n && history_undo_peek(h); k++)
                history_undo_done(h);
        }
        if (next_u32() % 7 == 0) history_redo_peek(h);
    }
    assert_true(history_dropped_total(h) > 0);
    history_undo_peek(h); // every squeeze in
    assert_int_equal(history_bytes(h), step_sum(h) + 0);
    assert_true(history_bytes(h) <= history_budget(h) || history_count(h) == 1);
    history_destroy(h); // with nothing squeezed left, and again with work queued:
    h = history_create(0);
    for (int i = 0; i < 20; i++)
        push_dab(h, before, after);
    history_destroy(h);
    // A step never pushed.
    history_step *alone = history_step_new("alone");
    history_step_free(alone);
    free(before);
    free(after);
}

// What the reader saw each time the history waited for it: the first step's delta as the
// commit gave it, still there (nothing replaced or freed before the wait).
typedef struct reader_log {
    history *h;
    const void *given; // the first step's delta as pushed
    int waits, intact; // waits, and those that found it
} reader_log;

static void reader_wait(void *user) {
    reader_log *r = user;
    r->waits++;
    const history_step *first = history_at(r->h, 0);
    r->intact += first && first->tile_count && first->tiles[0].delta == r->given;
}

static void test_reader_waited_for_before_deltas_change(void **state) {
    (void)state;
    history *h = history_create(0);
    float *before = malloc(sizeof(float) * TILE_SAMPLES),
          *after = malloc(sizeof(float) * TILE_SAMPLES);
    assert_true(h && before && after);
    reader_log log = {.h = h};
    history_set_reader(h, reader_wait, &log);
    grid_rect part = {40, 30, 200, 190};
    tiles(before, after, part, 0.5f);
    void *quick;
    size_t quick_bytes;
    assert_int_equal(history_delta_encode_part_quick(TILE_LAYER_COARSE, before, after, part, &quick,
                                                     &quick_bytes),
                     0);
    history_step *s = history_step_new("dab");
    tile_key key = {.layer = TILE_LAYER_COARSE};
    assert_int_equal(history_step_add_delta(s, key, 0, quick, quick_bytes), 0);
    log.given = quick;
    assert_int_equal(history_push(h, s), 0);
    // The peek squeezes the delta (a smaller one replaces it): the reader first.
    log.waits = log.intact = 0;
    assert_ptr_equal(history_undo_peek(h), s);
    assert_true(log.waits >= 1);
    assert_int_equal(log.intact, log.waits);
    assert_ptr_not_equal(s->tiles[0].delta, quick); // replaced, after the wait
    // A budget that drops the oldest step, then a redo branch cut by a new step, and
    // the history's end: each waits for the reader before it frees one.
    for (int i = 0; i < 2; i++) {
        history_step *n = history_step_new("dab");
        void *d = malloc(64);
        assert_true(n && d);
        memset(d, i + 1, 64);
        assert_int_equal(history_step_add_delta(n, key, 0, d, 64), 0);
        history_push(h, n);
    }
    log.given = history_at(h, 0)->tiles[0].delta;
    log.waits = log.intact = 0;
    history_set_budget(h, 1); // only the newest stays
    assert_int_equal(history_count(h), 1);
    assert_true(log.waits >= 1 && log.intact == log.waits);
    history_undo_peek(h);
    history_undo_done(h); // the newest undone: a redo branch
    log.given = history_at(h, 0)->tiles[0].delta;
    log.waits = log.intact = 0;
    history_step *n = history_step_new("dab");
    assert_non_null(n);
    history_push(h, n); // cuts the branch (frees its step)
    assert_true(log.waits >= 1 && log.intact >= 1);
    log.waits = 0;
    log.given = NULL;
    history_destroy(h);
    assert_int_equal(log.waits, 1);
    free(before);
    free(after);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_squeezed_deltas_are_the_full_encoding),
        cmocka_unit_test(test_steps_cut_while_squeezed),
        cmocka_unit_test(test_reader_waited_for_before_deltas_change),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
