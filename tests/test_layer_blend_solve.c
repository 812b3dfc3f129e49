// layer_blend_solve (editor/layers/layer_blend.c), which finds the layer value that
// shows a target height: the same values as its search with the library's nextafterf
// (its ulp steps are now taken by the float's bits) over random blends, weights,
// heights and targets, with zeros, subnormals, the largest floats, infinities and NaN.
#include "editor/layers/layer_blend.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

// The solve as it was written with nextafterf; reference_steps: the ulp steps it took.
static int reference_steps;

static float reference(layer_blend blend, float weight, float below, float value, float target) {
    reference_steps = 0;
    if (!(weight > 0.0f) || isnan(target)) return value;
    if (blend == LAYER_BLEND_MAX && target < below) return NAN;
    if (blend == LAYER_BLEND_MIN && target > below) return NAN;
    if (layer_blend_sample(blend, weight, below, value) == target) return value;
    float v;
    if (blend == LAYER_BLEND_ADD)
        v = weight >= 1.0f ? target - below : (target - below) / weight;
    else
        v = weight >= 1.0f ? target : below + (target - below) / weight;
    for (reference_steps = 0; reference_steps < 8; reference_steps++) {
        float got = layer_blend_sample(blend, weight, below, v);
        if (got == target || isnan(got)) break;
        float next = nextafterf(v, got < target ? INFINITY : -INFINITY);
        float again = layer_blend_sample(blend, weight, below, next);
        if (fabsf(again - target) > fabsf(got - target)) break;
        v = next;
    }
    return v;
}

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static uint32_t next_u32(void) {
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (uint32_t)(rng >> 16);
}

static float any_float(void) {
    static const float special[] = {0.0f,    -0.0f,    FLT_MIN,  -FLT_MIN,  1e-45f, -1e-45f,
                                    FLT_MAX, -FLT_MAX, INFINITY, -INFINITY, NAN,    1.0f};
    uint32_t r = next_u32() % 16;
    if (r < 2) return special[next_u32() % (sizeof special / sizeof *special)];
    if (r < 4) { // any bits
        uint32_t u = next_u32();
        float f;
        memcpy(&f, &u, sizeof f);
        return f;
    }
    return ((float)(next_u32() % 2000001) - 1e6f) * (r < 10 ? 1e-3f : 1.0f); // heights
}

static void test_solve_matches_the_nextafterf_search(void **state) {
    (void)state;
    static const float weights[] = {1.0f, 0.25f, 0.5f, 0.73f, 0.999f, 1.5f, 0.0f, -1.0f};
    long stepped = 0;
    for (int i = 0; i < 400000; i++) {
        layer_blend blend = (layer_blend)(next_u32() % 4);
        float w = i % 3 ? weights[next_u32() % 8] : (float)(next_u32() % 1000) / 999.0f;
        float below = any_float(), value = any_float();
        // Mostly targets near what the layer shows (the tool moved it a little).
        float target = next_u32() % 4 ? layer_blend_sample(blend, w, below, value) +
                                            ((float)(next_u32() % 2001) - 1000.0f) * 1e-3f
                                      : any_float();
        float want = reference(blend, w, below, value, target);
        float got = layer_blend_solve(blend, w, below, value, target);
        if (memcmp(&got, &want, sizeof got) != 0)
            fail_msg("blend %d weight %a below %a value %a target %a: %a, the search's %a",
                     (int)blend, (double)w, (double)below, (double)value, (double)target,
                     (double)got, (double)want);
        stepped += want != target - below;
    }
    assert_true(stepped > 1000);
}

// The row form (the take's common layer) gives layer_blend_solve's add values at full
// weight, bit for bit, over rows of every length (its chunks of 256 included), with
// targets near the sum, far from it, and the special floats; and a tall stroke's rows
// (a layer raised kilometres over a base of hundreds of metres), where the sum often
// cannot show the target and the search takes all its steps (an ulp up and down again).
static void test_add_row_matches_the_solve(void **state) {
    (void)state;
    static float below[700], value[700], target[700], out[700];
    long stepped = 0, samples = 0, searched = 0;
    for (int r = 0; r < 3000; r++) {
        int n = (int)(next_u32() % 700);
        float w = r % 2 ? 1.0f : 1.5f;
        for (int i = 0; i < n && r % 3 == 0; i++) {
            below[i] = 50.0f + (float)(next_u32() % 100000) / 100.0f;
            value[i] = next_u32() % 8 ? (float)(next_u32() % 500000) / 100.0f : NAN;
            target[i] = (below[i] + (value[i] == value[i] ? value[i] : 0.0f)) +
                        (float)(next_u32() % 1000) / 1000.0f;
        }
        for (int i = 0; i < n && r % 3 != 0; i++) {
            below[i] = any_float(), value[i] = any_float();
            float shown = layer_blend_sample(LAYER_BLEND_ADD, w, below[i], value[i]);
            target[i] = next_u32() % 4 ? shown + ((float)(next_u32() % 2001) - 1000.0f) * 1e-3f
                                       : any_float();
        }
        layer_blend_solve_add_row(below, value, target, out, n);
        for (int i = 0; i < n; i++, samples++) {
            float want = layer_blend_solve(LAYER_BLEND_ADD, w, below[i], value[i], target[i]);
            if (memcmp(&out[i], &want, sizeof want) != 0)
                fail_msg("weight %g below %a value %a target %a: %a, the solve's %a", (double)w,
                         (double)below[i], (double)value[i], (double)target[i], (double)out[i],
                         (double)want);
            stepped += want != target[i] - below[i];
            reference(LAYER_BLEND_ADD, w, below[i], value[i], target[i]);
            searched += reference_steps == 8;
        }
    }
    assert_true(samples > 500000);
    assert_true(searched > 1000);
    assert_true(stepped > 1000);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_solve_matches_the_nextafterf_search),
        cmocka_unit_test(test_add_row_matches_the_solve),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
