// Edit layers: the composite of random stacks against the formulas on plain arrays
// (every blend, opacity, hidden layers, empty samples, across tile edges), each layer
// command undone and redone bit-exactly, tools on a layer against a single heightfield,
// and a world saved before layers opening as one layer with the same heights.
#include "editor/cmd/commands.h"
#include "editor/edit/edit_commit.h"
#include "editor/edit/layer_composite.h"
#include "editor/layers/layer_blend.h"
#include "editor/params/world_grid.h"
#include "editor/world/layer_grid.h"
#include "support/test_support.h"
#include "support/test_world.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static float *read_rect(world *w, int face, grid_rect r) {
    layer_grid g;
    og_error err;
    if (layer_grid_init(&g, world_get_params(w), TILE_LAYER_COARSE, face, &err) != 0)
        fail_msg("%s", err.msg);
    float *out = malloc(sizeof(float) * (size_t)((r.x1 - r.x0) * (r.z1 - r.z0)));
    if (layer_grid_read(w, &g, r, out, &err) != 0) fail_msg("%s", err.msg);
    return out;
}

// The blend formulas of editor/layers/layer_blend.h, written out again for the reference.
static float reference_blend(layer_blend b, float w, float below, float v) {
    if (v != v || w <= 0) return below;
    float top = b == LAYER_BLEND_ADD       ? below + v
                : b == LAYER_BLEND_REPLACE ? v
                : b == LAYER_BLEND_MAX     ? (v > below ? v : below)
                                           : (v < below ? v : below);
    if (w >= 1) return top;
    return b == LAYER_BLEND_ADD ? below + w * v : below + w * (top - below);
}

#define REF_MARGIN 72

// The stack over one big array (the area grown by REF_MARGIN): each masked layer's
// weights from layer_mask_evaluate over the composite below it on the big array, the
// valid part narrowing by its border. Returns the area's samples (malloc'd).
static float *reference_stack(const layer_table *t, const float *base, float *const *values,
                              grid_rect big, grid_rect area) {
    int bw = (int)(big.x1 - big.x0), bh = (int)(big.z1 - big.z0);
    float *acc = malloc(sizeof(float) * (size_t)bw * bh);
    float *mask = malloc(sizeof(float) * (size_t)bw * bh);
    memcpy(acc, base, sizeof(float) * (size_t)bw * bh);
    int margin = 0; // of the big array no longer valid
    for (int i = 0; i < t->count; i++) {
        const layer_info *l = &t->layers[i];
        if (!l->visible) continue;
        int masked = layer_mask_active(&l->mask), b = masked ? layer_mask_border(&l->mask, 1.0) : 0;
        int inner = margin + b, iw = bw - 2 * inner, ih = bh - 2 * inner;
        assert_true(iw > 0 && inner <= REF_MARGIN);
        if (masked) {
            int cw = bw - 2 * margin, ch = bh - 2 * margin;
            float *below = malloc(sizeof(float) * (size_t)cw * ch);
            for (int z = 0; z < ch; z++)
                memcpy(below + (size_t)z * cw, acc + (size_t)(z + margin) * bw + margin,
                       sizeof(float) * cw);
            layer_mask_evaluate(&l->mask, below, iw, ih, b, 1.0, NULL, mask);
            free(below);
        }
        for (int z = 0; z < ih; z++)
            for (int x = 0; x < iw; x++) {
                size_t k = (size_t)(z + inner) * bw + x + inner;
                float wgt = (float)l->opacity * (masked ? mask[(size_t)z * iw + x] : 1.0f);
                acc[k] = reference_blend(l->blend, wgt, acc[k], values[i][k]);
            }
        margin = inner;
    }
    int aw = (int)(area.x1 - area.x0), ah = (int)(area.z1 - area.z0);
    float *out = malloc(sizeof(float) * (size_t)aw * ah);
    for (int z = 0; z < ah; z++)
        memcpy(out + (size_t)z * aw, acc + (size_t)(z + area.z0 - big.z0) * bw + (area.x0 - big.x0),
               sizeof(float) * aw);
    free(acc);
    free(mask);
    return out;
}

// Writes random values (some NaN) into a layer's samples r through an edit, and the same
// into the reference array (area's layout).
static void fill_layer(edit *e, int32_t id, int face, grid_rect r, float *ref, grid_rect area,
                       uint64_t *seed, double nan_share) {
    for (int64_t tz = r.z0 >> 8; tz <= (r.z1 - 1) >> 8; tz++)
        for (int64_t tx = r.x0 >> 8; tx <= (r.x1 - 1) >> 8; tx++) {
            tile_key key = {.layer = tile_layer_in_slot(TILE_LAYER_COARSE, id),
                            .face = face,
                            .tx = (int32_t)tx,
                            .ty = (int32_t)tz};
            tile_view v;
            og_error err;
            if (edit_tile_acquire(e, key, &v, &err) != 0) fail_msg("%s", err.msg);
            float *f = v.data;
            for (int j = 0; j < TILE_SIZE; j++)
                for (int i = 0; i < TILE_SIZE; i++) {
                    int64_t x = tx * TILE_SIZE + i, z = tz * TILE_SIZE + j;
                    if (x < r.x0 || x >= r.x1 || z < r.z0 || z >= r.z1) continue;
                    float val = test_rng_unit(seed) < nan_share
                                    ? NAN
                                    : (float)(test_rng_unit(seed) * 400.0 - 200.0);
                    f[j * TILE_SIZE + i] = val;
                    ref[(z - area.z0) * (area.x1 - area.x0) + (x - area.x0)] = val;
                }
            edit_tile_release(e, &v);
        }
}

// Random stacks over an unbounded world, around negative tile coordinates: the composite
// equals the formula on one big array everywhere, across tile edges.
static void test_composite_matches_arrays(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(0);
    world *w = test_world_open(&p);
    grid_rect area = {-300, -280, 320, 290};
    size_t n = (size_t)((area.x1 - area.x0) * (area.z1 - area.z0));
    float *base = read_rect(w, 0, area);
    // The reference works on one big array around the area: masks read around it.
    grid_rect big = {area.x0 - REF_MARGIN, area.z0 - REF_MARGIN, area.x1 + REF_MARGIN,
                     area.z1 + REF_MARGIN};
    size_t nb = (size_t)((big.x1 - big.x0) * (big.z1 - big.z0));
    float *base_big = read_rect(w, 0, big);
    uint64_t seed = 77;
    for (int trial = 0; trial < 6; trial++) {
        world_params next = *world_get_params(w);
        layer_table *t = &next.layers;
        layer_table_default(t);
        int layers = 2 + trial % 4;
        float *values[LAYER_MAX];
        og_error err;
        for (int i = 1; i < layers; i++) {
            char name[16];
            snprintf(name, sizeof name, "L%d", i);
            layer_table_insert(t, i, name, (layer_blend)(test_rng_next(&seed) % LAYER_BLEND_COUNT),
                               test_rng_unit(&seed) < 0.4 ? 1.0 : test_rng_unit(&seed), &err);
        }
        for (int i = 0; i < layers; i++)
            t->layers[i].visible = test_rng_unit(&seed) > 0.2;
        // Masks on some layers. (Not flow: it counts upstream area within the window it is
        // given, so a tile's part reads it a little differently from one big array.)
        for (int i = 0; i < layers; i++) {
            if (test_rng_unit(&seed) < 0.4) continue;
            layer_mask *m = &t->layers[i].mask;
            char v[64];
            snprintf(v, sizeof v, "%.1f,%.1f", test_rng_unit(&seed) * 200 - 150,
                     test_rng_unit(&seed) * 200);
            if (test_rng_unit(&seed) < 0.6) layer_mask_set_option(m, "height", v, &err);
            if (test_rng_unit(&seed) < 0.5) layer_mask_set_option(m, "falloff", "15", &err);
            snprintf(v, sizeof v, "%.1f,%.1f,4", test_rng_unit(&seed) * 20,
                     20 + test_rng_unit(&seed) * 40);
            if (test_rng_unit(&seed) < 0.5) layer_mask_set_option(m, "slope", v, &err);
            if (test_rng_unit(&seed) < 0.3) layer_mask_set_option(m, "curvature", "-3,3,1", &err);
            if (test_rng_unit(&seed) < 0.3) layer_mask_set_option(m, "invert", "1", &err);
        }
        edit *e = edit_begin(w, "test layers", &err);
        edit_set_layer_mode(e, EDIT_LAYER_COMPOSED);
        if (edit_set_params(e, &next, &err) != 0) fail_msg("%s", err.msg);
        for (int i = 0; i < layers; i++) {
            values[i] = malloc(sizeof(float) * nb);
            for (size_t k = 0; k < nb; k++)
                values[i][k] = NAN;
            // Each layer covers a random part of the area (its other samples stay empty).
            int64_t x0 = area.x0 + (int64_t)(test_rng_unit(&seed) * 200),
                    z0 = area.z0 + (int64_t)(test_rng_unit(&seed) * 200);
            int64_t x1 = area.x1 - (int64_t)(test_rng_unit(&seed) * 200),
                    z1 = area.z1 - (int64_t)(test_rng_unit(&seed) * 200);
            fill_layer(e, t->layers[i].id, 0, (grid_rect){x0, z0, x1, z1}, values[i], big, &seed,
                       0.1);
        }
        if (layer_recompose(e, 0, area, &err) != 0) fail_msg("%s", err.msg);
        if (edit_commit(e, &err) != 0) fail_msg("%s", err.msg);
        float *got = read_rect(w, 0, area);
        float *want = reference_stack(t, base_big, values, big, area);
        size_t wrong = 0;
        for (size_t k = 0; k < n; k++)
            if (memcmp(&want[k], &got[k], sizeof want[k]) != 0 && wrong++ < 3)
                print_error("trial %d sample %zu: formula %.9g, composite %.9g\n", trial, k,
                            want[k], got[k]);
        free(want);
        assert_int_equal(wrong, 0);
        free(got);
        for (int i = 0; i < layers; i++)
            free(values[i]);
        // Undo puts the terrain back exactly.
        assert_int_equal(edit_undo(w, &err), 1);
        got = read_rect(w, 0, area);
        assert_memory_equal(got, base, sizeof(float) * n);
        free(got);
    }
    free(base);
    free(base_big);
    world_close(w);
}

// Solving for a layer's value gives the target back exactly wherever floats allow.
static void test_solve_round_trips(void **state) {
    (void)state;
    uint64_t seed = 5;
    size_t exact = 0, total = 0;
    for (int i = 0; i < 200000; i++) {
        layer_blend b = (layer_blend)(test_rng_next(&seed) % LAYER_BLEND_COUNT);
        float w = test_rng_unit(&seed) < 0.5 ? 1.0f : (float)(0.05 + test_rng_unit(&seed));
        float below = (float)(test_rng_unit(&seed) * 2000 - 1000);
        float target = below + (float)(test_rng_unit(&seed) * 100 - 50);
        float v = layer_blend_solve(b, w, below, NAN, target);
        float got = layer_blend_sample(b, w, below, v);
        if ((b == LAYER_BLEND_MAX && target < below) || (b == LAYER_BLEND_MIN && target > below)) {
            assert_true(got == below); // the nearest such a layer can show
            continue;
        }
        total++;
        exact += got == target;
        assert_true(fabsf(got - target) <= 1e-4f * (1 + fabsf(target)) / (w < 1 ? w : 1));
    }
    // Weight 1 is exact but for the rare sums no float hits; below it, rounding of w*v.
    assert_true(exact > total * 8 / 10);
}

typedef struct session {
    world *w;
    cmd_context ctx;
    FILE *out;
} session;

static void open_session(session *s, world *w) {
    world_settings set = {.warn = test_silent};
    s->w = w;
    s->out = tmpfile();
    cmd_context_init(&s->ctx, w, &set, s->out, OROGEN_RESOURCE_DIR);
}

static void run(session *s, const char *script) {
    og_error err;
    if (cmd_run(&s->ctx, script, strlen(script), "-c", &err) != 0)
        fail_msg("%s: %s", script, err.msg);
}

static void run_fails(session *s, const char *script, const char *expect) {
    og_error err;
    assert_int_equal(cmd_run(&s->ctx, script, strlen(script), "-c", &err), -1);
    if (!strstr(err.msg, expect))
        fail_msg("'%s' said '%s', expected '%s'", script, err.msg, expect);
}

static uint64_t hash_all(session *s) {
    uint64_t d, c;
    og_error err;
    if (world_hash(s->ctx.world, 0, 0, 0, 599, 599, &d, &c, &err) != 0) fail_msg("%s", err.msg);
    return d;
}

// What `layers` prints.
static char *listing(session *s) {
    static char text[4096];
    long at = ftell(s->out);
    run(s, "layers");
    long end = ftell(s->out);
    fseek(s->out, at, SEEK_SET);
    size_t n = fread(text, 1, (size_t)(end - at), s->out);
    text[n] = 0;
    fseek(s->out, end, SEEK_SET);
    return text;
}

// Every layer command is one undo step: undo gives back the terrain and the table bit
// for bit, redo the state after it.
static void test_commands_undo_redo(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(600);
    session s;
    open_session(&s, test_world_open(&p));
    run(&s, "tool raise radius=80 strength=0.6; stroke 100 100 400 300");
    const char *steps[] = {
        "layer new Hills blend=add opacity=0.7",
        "stroke 150 400 450 120",
        "layer new Cap blend=max",
        "tool flatten radius=90 strength=1; stroke 300 300 320 310",
        "layer set Hills opacity=0.25",
        "layer mask Hills height=-inf,40 falloff=10 slope=0,30,5",
        "layer select Hills",
        "tool raise radius=60 strength=0.5; stroke 100 300 500 300",
        "layer set Hills visible=0",
        "layer set Hills visible=1 name=Hills2 blend=min",
        "layer mask Hills2 curvature=-5,5,2 invert=1",
        "layer mask Hills2 clear",
        "layer move Cap bottom",
        "layer move Cap to=2",
        "layer select Sculpt",
        "layer duplicate Hills2",
        "layer set Hills2 locked=1",
        "layer set Hills2 locked=0",
        "layer merge Hills2_copy",
        "layer merge Hills2",
        "layer clear Cap",
        "layer delete Cap",
    };
    enum { N = sizeof steps / sizeof steps[0] };
    uint64_t hashes[N + 1];
    static char lists[N + 1][4096];
    hashes[0] = hash_all(&s);
    snprintf(lists[0], sizeof lists[0], "%s", listing(&s));
    for (int i = 0; i < N; i++) {
        run(&s, steps[i]);
        hashes[i + 1] = hash_all(&s);
        snprintf(lists[i + 1], sizeof lists[i + 1], "%s", listing(&s));
        if (!strncmp(steps[i], "layer set Hills visible=0", 25) ||
            !strncmp(steps[i], "layer move", 10) || !strncmp(steps[i], "stroke", 6) ||
            !strncmp(steps[i], "tool", 4))
            assert_true(hashes[i + 1] != hashes[i]);
    }
    for (int i = N; i > 0; i--) {
        run(&s, "undo");
        assert_true(hashes[i - 1] == hash_all(&s));
        assert_string_equal(lists[i - 1], listing(&s));
    }
    for (int i = 0; i < N; i++) {
        run(&s, "redo");
        assert_true(hashes[i + 1] == hash_all(&s));
        assert_string_equal(lists[i + 1], listing(&s));
    }
    // Hiding a layer and showing it again gives the same heights back.
    // (The first time up to rounding: a tool's result is kept bit for bit, and base plus
    // layers may round a sample an ulp of a layer's value away from it; then exactly.)
    run(&s, "layer new Hills3; stroke 100 500 500 100");
    grid_rect all = {0, 0, 600, 600};
    float *stroked = read_rect(s.ctx.world, 0, all);
    uint64_t stroked_hash = hash_all(&s);
    run(&s, "layer set Hills3 visible=0");
    assert_true(hash_all(&s) != stroked_hash);
    run(&s, "layer set Hills3 visible=1");
    float *shown = read_rect(s.ctx.world, 0, all);
    for (size_t k = 0; k < 600 * 600; k++)
        assert_true(fabsf(stroked[k] - shown[k]) <= 1e-4f);
    free(stroked);
    free(shown);
    uint64_t shown_hash = hash_all(&s);
    run(&s, "layer set Hills3 visible=0; layer set Hills3 visible=1");
    assert_true(hash_all(&s) == shown_hash);
    // Bad input is refused with what was wrong, and changes nothing.
    run_fails(&s, "layer new Hills3", "exists already");
    run_fails(&s, "layer new bad/name", "not allowed");
    run_fails(&s, "layer set Nope visible=0", "no layer named 'Nope'");
    run_fails(&s, "layer set Hills3 opacity=2", "opacity");
    run_fails(&s, "layer set Hills3 colour=red", "unknown setting 'colour'");
    run_fails(&s, "layer move Hills3 sideways", "expected up, down");
    run_fails(&s, "layer move Hills3 up", "already at the top");
    run_fails(&s, "layer merge Sculpt", "bottom layer");
    run_fails(&s, "layer new K kind=volume", "expected height or paint");
    run_fails(&s, "layer new K kind=paint blend=max", "blend is for height layers");
    run(&s, "layer set Hills3 locked=1");
    run_fails(&s, "stroke 10 10 50 50", "locked");
    run_fails(&s, "layer clear Hills3", "locked");
    run_fails(&s, "layer delete Hills3", "locked");
    run(&s, "layer set Hills3 locked=0; layer set Sculpt visible=0; layer select Sculpt");
    run_fails(&s, "stroke 10 10 50 50", "hidden");
    run_fails(&s, "layer merge Hills3", "hidden");
    run(&s, "layer delete Hills3");
    run_fails(&s, "layer delete Sculpt", "only layer");
    fclose(s.out);
    world_close(s.ctx.world);
}

static double max_difference(session *x, session *y) {
    grid_rect all = {0, 0, 600, 600};
    float *a = read_rect(x->ctx.world, 0, all), *b = read_rect(y->ctx.world, 0, all);
    double worst = 0;
    size_t differ = 0;
    for (size_t k = 0; k < 600 * 600; k++) {
        worst = fmax(worst, fabs((double)a[k] - b[k]));
        differ += a[k] != b[k];
    }
    print_message("    %zu samples differ, by %g m at most\n", differ, worst);
    free(a);
    free(b);
    return worst;
}

// Smooth, flatten and erosion on a top layer give the same composite as on a single
// heightfield holding the same heights; on a layer under another add layer, the same up
// to rounding.
// A result tool on a faint layer (opacity 0.1): the change it stores is at most four times
// the tool's (not ten), so the composite shows 0.1 / 0.25 of the tool's change.
static void test_faint_layer_takes_bounded_change(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(600);
    session single, faint;
    open_session(&single, test_world_open(&p));
    open_session(&faint, test_world_open(&p));
    const char *setup = "tool raise radius=120 strength=0.8; stroke 100 200 500 260";
    run(&single, setup);
    run(&faint, setup);
    grid_rect all = {0, 0, 600, 600};
    float *before = read_rect(faint.ctx.world, 0, all);
    const char *smooth = "tool smooth radius=90 strength=1; stroke 150 150 450 350";
    run(&single, smooth);
    run(&faint, "layer new Faint opacity=0.1");
    run(&faint, smooth);
    float *a = read_rect(single.ctx.world, 0, all), *b = read_rect(faint.ctx.world, 0, all);
    double worst = 0, moved = 0;
    for (size_t k = 0; k < 600 * 600; k++) {
        double want = before[k] + 0.4 * ((double)a[k] - before[k]);
        worst = fmax(worst, fabs(b[k] - want));
        moved = fmax(moved, fabs((double)a[k] - before[k]));
    }
    assert_true(moved > 1.0); // the smooth did something
    if (worst > 1e-3 + 1e-4 * moved) fail_msg("faint layer: %g m from 0.4 of the change", worst);
    free(before);
    free(a);
    free(b);
    fclose(single.out);
    fclose(faint.out);
    world_close(single.ctx.world);
    world_close(faint.ctx.world);
}

static void test_tools_on_layer_match_single_heightfield(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(600);
    const char *setup = "tool raise radius=120 strength=0.8; stroke 100 200 500 260; "
                        "tool lower radius=60 strength=0.5; stroke 300 80 320 500";
    const char *tools[] = {"tool smooth radius=90 strength=1; stroke 150 150 450 350",
                           "tool flatten radius=70 strength=0.8; stroke 200 300 400 320",
                           "tool thermal radius=120 strength=1; stroke 250 250 350 260",
                           "tool hydraulic radius=120 strength=1; stroke 250 250 350 260",
                           "tool raise radius=50 strength=0.5; stroke 100 100 200 500"};
    for (size_t t = 0; t < sizeof tools / sizeof tools[0]; t++) {
        session single, layered;
        open_session(&single, test_world_open(&p));
        open_session(&layered, test_world_open(&p));
        run(&single, setup);
        run(&layered, setup);
        run(&layered, "layer new Work");
        run(&single, tools[t]);
        run(&layered, tools[t]);
        assert_true(hash_all(&single) == hash_all(&layered));
        // The change lives in Work: hiding it gives the heights before the tool back.
        // (Recomposed, base + Sculpt may round a sample an ulp of Sculpt's value away
        // from the tool's own result the composite kept: floats cannot always hold both.)
        session before;
        open_session(&before, test_world_open(&p));
        run(&before, setup);
        run(&layered, "layer set Work visible=0");
        assert_true(max_difference(&before, &layered) <= 1e-4);
        // Under an add layer: the same tool on the lower layer.
        run(&layered,
            "layer set Work visible=1; undo; undo; undo; layer new Top; "
            "tool raise radius=100 strength=0.5; stroke 200 100 400 500; layer select Work");
        run(&single, "undo; tool raise radius=100 strength=0.5; stroke 200 100 400 500");
        run(&single, tools[t]);
        run(&layered, tools[t]);
        double worst = max_difference(&single, &layered);
        if (worst > 1e-3) fail_msg("%s under a layer: differs by %g m", tools[t], worst);
        for (session *s = &single; s; s = s == &single    ? &layered
                                          : s == &layered ? &before
                                                          : NULL) {
            fclose(s->out);
            world_close(s->ctx.world);
        }
    }
}

// A layer holding ground set near 0 m over the base's hundreds of metres: where a tool
// then changes the composite, the layer's value is layer_blend_solve's (the take decides
// most such samples inline, for the sums around a result this fine miss it), and the
// layer's value is kept where the composite is.
static void test_take_fine_results_over_deep_base(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(600);
    session s;
    open_session(&s, test_world_open(&p));
    run(&s, "tool set height=0.37 radius=200 strength=1; dab 300 300");
    grid_rect r = {180, 180, 420, 420};
    size_t n = (size_t)((r.x1 - r.x0) * (r.z1 - r.z0));
    const layer_table *t = &world_get_params(s.ctx.world)->layers;
    int32_t slot = t->layers[t->active].id;
    float *base = test_read_slot(s.ctx.world, TILE_SLOT_BASE, r);
    float *was = test_read_slot(s.ctx.world, slot, r), *shown = read_rect(s.ctx.world, 0, r);
    run(&s, "tool raise radius=100 strength=0.2; dab 300 300");
    float *now = test_read_slot(s.ctx.world, slot, r), *comp = read_rect(s.ctx.world, 0, r);
    size_t missed = 0, changed = 0;
    for (size_t k = 0; k < n; k++) {
        float b = base[k], v = was[k], target = comp[k];
        int keep = !memcmp(&comp[k], &shown[k], sizeof target) ||
                   (v == v && (target != target || b + v == target)) || (v != v && target == b);
        float want = keep ? v : layer_blend_solve(LAYER_BLEND_ADD, 1.0f, b, v, target);
        if (memcmp(&want, &now[k], sizeof want) != 0)
            fail_msg("sample %zu: base %a layer %a composite %a: took %a, the solve %a", k,
                     (double)b, (double)v, (double)target, (double)now[k], (double)want);
        changed += !keep;
        missed += !keep && b + (target - b) != target;
    }
    assert_true(changed > 10000);
    assert_true(missed > 1000); // the sums around a result missed it: the inline search ran
    free(base), free(was), free(shown), free(now), free(comp);
    fclose(s.out);
    world_close(s.ctx.world);
}

static world *load_world(const char *path, int expect_errors) {
    world_settings set = {
        .cache_budget_bytes = (size_t)256 << 20, .workers = 2, .warn = test_silent};
    og_error err;
    int errors = 0;
    world *w = world_load(path, &set, &errors, &err);
    if (!w) fail_msg("world_load: %s", err.msg);
    if (!expect_errors) assert_int_equal(errors, 0);
    return w;
}

static void save_world(session *s, const char *path) {
    og_error err;
    if (world_save(s->ctx.world, path, 0, &err) != 0) fail_msg("world_save: %s", err.msg);
}

// Save and load keep the stack (names, order, blends, flags, the active layer, the
// tiles): the same listing, the same heights, and a layer still switches off after.
// Opened read-only (another process has the files) it is the same.
static void test_saved_stack(void **state) {
    (void)state;
    const char *dir = test_tmpdir("layers_saved");
    char path[512];
    snprintf(path, sizeof path, "%s/stack.world", dir);
    world_params p = test_flat_fbm_params(600);
    session a;
    open_session(&a, test_world_open(&p));
    run(&a, "tool raise radius=80 strength=0.6; stroke 100 100 400 300; layer new Roads "
            "blend=replace opacity=0.75; tool set radius=30 height=50; stroke 50 500 550 450; "
            "layer new Snow blend=max; tool raise; stroke 300 50 300 550; layer set Roads "
            "locked=1; layer select Snow; layer set Snow visible=0");
    char listed[4096];
    snprintf(listed, sizeof listed, "%s", listing(&a));
    uint64_t h = hash_all(&a);
    save_world(&a, path);
    fclose(a.out);
    world_close(a.ctx.world);
    // While another process has the files open: read-only, the same stack.
    int ready[2];
    assert_int_equal(pipe(ready), 0);
    pid_t holder = fork();
    if (holder == 0) {
        world *held = load_world(path, 0);
        (void)held;
        if (write(ready[1], "x", 1) != 1) _exit(1);
        pause();
        _exit(0);
    }
    char byte;
    assert_int_equal(read(ready[0], &byte, 1), 1);
    session c;
    open_session(&c, load_world(path, 1));
    kill(holder, SIGKILL);
    waitpid(holder, NULL, 0);
    close(ready[0]);
    close(ready[1]);
    assert_true(world_read_only(c.ctx.world)[0] != 0);
    assert_string_equal(listing(&c), listed);
    assert_true(hash_all(&c) == h);
    session b; // and once that process is gone, writable
    open_session(&b, load_world(path, 0));
    assert_true(world_read_only(b.ctx.world)[0] == 0);
    assert_string_equal(listing(&b), listed);
    assert_true(hash_all(&b) == h);
    // The layers' tiles came back: switching one off and on changes the heights and
    // brings them back, in both.
    for (session *s = &b; s; s = s == &b ? &c : NULL) {
        run(s, "layer set Roads visible=0");
        assert_true(hash_all(s) != h);
        run(s, "layer set Roads visible=1");
        uint64_t again = hash_all(s);
        run(s, "layer set Roads visible=0; layer set Roads visible=1");
        assert_true(hash_all(s) == again);
        run(s, "layer set Snow visible=1");
        assert_true(hash_all(s) != again);
    }
    for (session *s = &b; s; s = s == &b ? &c : NULL) {
        fclose(s->out);
        world_close(s->ctx.world);
    }
    test_rmtree(dir);
}

static int collect_layer_keys(void *user, tile_key key) {
    tile_key *keys = user;
    if (tile_key_slot(key) >= LAYER_FIRST_ID && keys[0].tx < 4000) keys[++keys[0].tx] = key;
    return 0;
}

// A world saved before layers (a parameter file without layer lines, coarse tiles only)
// opens as one layer named Sculpt holding its edits, with the same heights; hiding it
// shows the generated terrain.
static void test_world_from_before_layers(void **state) {
    (void)state;
    const char *dir = test_tmpdir("layers_legacy");
    char path[512], tiles[512];
    snprintf(path, sizeof path, "%s/old.world", dir);
    snprintf(tiles, sizeof tiles, "%s/old.tiles", dir);
    world_params p = test_flat_fbm_params(600);
    session a;
    open_session(&a, test_world_open(&p));
    uint64_t generated = hash_all(&a);
    run(&a, "tool raise radius=90 strength=0.8; stroke 50 50 550 500; tool smooth radius=60; "
            "stroke 100 400 500 100; tool hydraulic radius=150; stroke 300 300 310 300");
    uint64_t edited = hash_all(&a);
    save_world(&a, path);
    fclose(a.out);
    world_close(a.ctx.world);
    // Make the files what an Orogen from before layers wrote: no layer lines, no layer tiles.
    og_error err;
    tile_store *store = tile_store_open(tiles, &err);
    if (!store) fail_msg("%s", err.msg);
    static tile_key keys[4001];
    keys[0].tx = 0;
    assert_int_equal(tile_store_each(store, collect_layer_keys, keys, &err), 0);
    assert_true(keys[0].tx > 0);
    for (int i = 1; i <= keys[0].tx; i++)
        assert_int_equal(tile_store_put(store, keys[i], NULL, &err), 0);
    assert_true(tile_store_count(store, TILE_LAYER_COARSE) > 0);
    int64_t kept = tile_store_count(store, -1);
    tile_store_close(store);
    world_params old;
    int errors;
    assert_int_equal(world_params_load(path, &old, &errors, NULL, NULL, &err), 0);
    assert_int_equal(old.layers.count, 3 - 2); // Sculpt, as saved
    memset(&old.layers, 0, sizeof old.layers);
    old.tiles_saved = kept; // what the store holds now (else the world opens read-only)
    assert_int_equal(world_params_save(path, &old, &err), 0);
    char *text = test_read_file(path, NULL);
    assert_null(strstr(text, "layer"));
    free(text);

    session b;
    open_session(&b, load_world(path, 0));
    assert_true(hash_all(&b) == edited);
    const char *l = listing(&b);
    if (!strstr(l, "* 0 Sculpt kind=height blend=add opacity=1 visible=1 locked=0 tiles="))
        fail_msg("listing: %s", l);
    assert_true(atoi(strstr(l, "tiles=") + 6) > 0);
    run(&b, "layer set Sculpt visible=0");
    assert_true(hash_all(&b) == generated);
    run(&b, "layer set Sculpt visible=1");
    // Base plus the solved layer gives the saved heights back (exactly but where a float
    // sum cannot: an ulp of the layer's value).
    session saved;
    open_session(&saved, load_world(path, 1));
    assert_true(max_difference(&saved, &b) <= 1e-4);
    fclose(saved.out);
    world_close(saved.ctx.world);
    run(&b, "undo; undo");
    assert_true(hash_all(&b) == edited);
    fclose(b.out);
    world_close(b.ctx.world);
    test_rmtree(dir);
}

// A planet: a layer's dab at a cube corner reaches three faces; hiding the layer gives
// the generated terrain back on all six, showing it the dab again (up to rounding), and
// undo of each is exact.
static float *read_faces(world *w, int n) {
    float *h = malloc(sizeof(float) * 6 * (size_t)n * n);
    og_error err;
    for (int f = 0; f < 6; f++) {
        layer_grid g;
        assert_int_equal(layer_grid_init(&g, world_get_params(w), TILE_LAYER_COARSE, f, &err), 0);
        assert_int_equal(
            layer_grid_read(w, &g, (grid_rect){0, 0, n, n}, h + (size_t)f * n * n, &err), 0);
    }
    return h;
}

static void test_planet_layers(void **state) {
    (void)state;
    world_params p;
    world_params_default(&p, WORLD_PLANET);
    p.radius = 20000;
    p.ocean_level = 20000;
    p.octaves = 5;
    int n = (int)world_grid_face_samples(&p);
    session s;
    open_session(&s, test_world_open(&p));
    size_t all = 6 * (size_t)n * n;
    float *generated = read_faces(s.ctx.world, n);
    run(&s, "layer new Top; tool raise radius=4000 strength=1; dab 0 0");
    float *dabbed = read_faces(s.ctx.world, n);
    int faces_changed = 0;
    for (int f = 0; f < 6; f++)
        faces_changed += memcmp(generated + (size_t)f * n * n, dabbed + (size_t)f * n * n,
                                sizeof(float) * n * n) != 0;
    assert_true(faces_changed >= 3);
    run(&s, "layer set Top visible=0");
    float *hidden = read_faces(s.ctx.world, n);
    assert_memory_equal(hidden, generated, sizeof(float) * all);
    run(&s, "layer set Top visible=1");
    float *shown = read_faces(s.ctx.world, n);
    for (size_t k = 0; k < all; k++)
        assert_true(fabsf(shown[k] - dabbed[k]) <= 1e-3f);
    run(&s, "undo; undo");
    float *back = read_faces(s.ctx.world, n);
    assert_memory_equal(back, dabbed, sizeof(float) * all);
    // A masked layer on a planet: only where the ground below is low.
    run(&s, "layer mask Top height=-inf,0 falloff=50");
    float *masked = read_faces(s.ctx.world, n);
    for (size_t k = 0; k < all; k++) {
        assert_true(isfinite(masked[k]));
        if (generated[k] > 50.0f) assert_true(masked[k] == generated[k]);
    }
    run(&s, "undo");
    free(back);
    back = read_faces(s.ctx.world, n);
    assert_memory_equal(back, dabbed, sizeof(float) * all);
    free(generated);
    free(dabbed);
    free(hidden);
    free(shown);
    free(back);
    free(masked);
    fclose(s.out);
    world_close(s.ctx.world);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_solve_round_trips),
        cmocka_unit_test(test_composite_matches_arrays),
        cmocka_unit_test(test_commands_undo_redo),
        cmocka_unit_test(test_tools_on_layer_match_single_heightfield),
        cmocka_unit_test(test_take_fine_results_over_deep_base),
        cmocka_unit_test(test_faint_layer_takes_bounded_change),
        cmocka_unit_test(test_saved_stack),
        cmocka_unit_test(test_world_from_before_layers),
        cmocka_unit_test(test_planet_layers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
