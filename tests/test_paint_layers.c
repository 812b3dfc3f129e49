// Paint layers: the material composite of random paint stacks (opacity, hidden layers,
// masks reading the heights below, partial coverage, across tile edges at negative tile
// coordinates) against the formula on plain arrays; the paint tool on a paint layer
// against painting a world without layers; hiding, undo/redo, merging (masks and opacity
// baked in), masked height layers merged, save/load, and paint from before paint layers
// becoming the ground's own paint.
#include "editor/cmd/commands.h"
#include "editor/edit/edit_commit.h"
#include "editor/edit/layer_composite.h"
#include "editor/edit/paint_composite.h"
#include "editor/layers/paint_blend.h"
#include "editor/world/layer_grid.h"
#include "io/tile_store.h"
#include "support/test_support.h"
#include "support/test_world.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

static void *read_kind(world *w, tile_layer kind, grid_rect r) {
    layer_grid g;
    og_error err;
    if (layer_grid_init(&g, world_get_params(w), kind, 0, &err) != 0) fail_msg("%s", err.msg);
    void *out =
        malloc(tile_layer_bytes(kind) / TILE_SAMPLES * (size_t)((r.x1 - r.x0) * (r.z1 - r.z0)));
    if (layer_grid_read_samples(w, &g, r, out, &err) != 0) fail_msg("%s", err.msg);
    return out;
}

// The paint formula of editor/layers/paint_blend.h, written out again for the reference.
static void reference_paint(float *acc, float w, const uint8_t *l) {
    int sum = 0;
    for (int c = 0; c < TILE_MATERIALS; c++)
        sum += l[c];
    if (w <= 0 || !sum) return;
    for (int c = 0; c < TILE_MATERIALS; c++)
        acc[c] = acc[c] * (1.0f - w * ((float)sum / 255.0f)) + w * (float)l[c];
}

// Writes random weights (coverage 0..1, some samples empty) into slot's material tiles
// over r through an edit, and the same into ref (area's layout, 8 bytes a sample).
static void fill_paint(edit *e, int32_t slot, grid_rect r, uint8_t *ref, grid_rect area,
                       uint64_t *seed, int full) {
    for (int64_t tz = r.z0 >> 8; tz <= (r.z1 - 1) >> 8; tz++)
        for (int64_t tx = r.x0 >> 8; tx <= (r.x1 - 1) >> 8; tx++) {
            tile_key key = {.layer = tile_layer_in_slot(TILE_LAYER_MATERIAL, slot),
                            .tx = (int32_t)tx,
                            .ty = (int32_t)tz};
            tile_view v;
            og_error err;
            if (edit_tile_acquire(e, key, &v, &err) != 0) fail_msg("%s", err.msg);
            uint8_t *m = v.data;
            for (int j = 0; j < TILE_SIZE; j++)
                for (int i = 0; i < TILE_SIZE; i++) {
                    int64_t x = tx * TILE_SIZE + i, z = tz * TILE_SIZE + j;
                    if (x < r.x0 || x >= r.x1 || z < r.z0 || z >= r.z1) continue;
                    uint8_t *s = m + ((size_t)j * TILE_SIZE + i) * TILE_MATERIALS;
                    int total = full                        ? 255
                                : test_rng_unit(seed) < 0.2 ? 0
                                                            : (int)(test_rng_unit(seed) * 256);
                    memset(s, 0, TILE_MATERIALS);
                    for (int left = total; left > 0;) { // a few materials share the total
                        int c = (int)(test_rng_next(seed) % TILE_MATERIALS);
                        int give = left < 40 ? left : 1 + (int)(test_rng_unit(seed) * left);
                        s[c] = (uint8_t)(s[c] + give);
                        left -= give;
                    }
                    memcpy(ref + ((z - area.z0) * (area.x1 - area.x0) + (x - area.x0)) *
                                     TILE_MATERIALS,
                           s, TILE_MATERIALS);
                }
            edit_tile_release(e, &v);
        }
}

// Writes random coverage (some beyond 0..1, some NaN) into layer id's painted mask over r.
static void fill_coverage(edit *e, int32_t id, grid_rect r, float *ref, grid_rect area,
                          uint64_t *seed) {
    for (int64_t tz = r.z0 >> 8; tz <= (r.z1 - 1) >> 8; tz++)
        for (int64_t tx = r.x0 >> 8; tx <= (r.x1 - 1) >> 8; tx++) {
            tile_key key = {.layer = tile_layer_in_slot(TILE_LAYER_COARSE, layer_coverage_slot(id)),
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
                    float c =
                        test_rng_unit(seed) < 0.05 ? NAN : (float)(test_rng_unit(seed) * 1.5 - 0.2);
                    f[j * TILE_SIZE + i] = c;
                    if (x >= area.x0 && x < area.x1 && z >= area.z0 && z < area.z1)
                        ref[(z - area.z0) * (area.x1 - area.x0) + (x - area.x0)] = c;
                }
            edit_tile_release(e, &v);
        }
}

// Random paint stacks over an unbounded world around negative tile coordinates, over and
// under the height layer, with masks reading the heights: the material composite equals
// the formula on plain arrays everywhere, across tile edges.
static void test_paint_composite_matches_arrays(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(0);
    world *w = test_world_open(&p);
    grid_rect area = {-300, -280, 320, 290};
    int aw = (int)(area.x1 - area.x0), ah = (int)(area.z1 - area.z0);
    size_t n = (size_t)aw * ah;
    float *base_h = read_kind(w, TILE_LAYER_COARSE, area);
    uint8_t *base_m = read_kind(w, TILE_LAYER_MATERIAL, area);
    uint64_t seed = 91;
    int painted_masks = 0;
    for (int trial = 0; trial < 4; trial++) {
        world_params next = *world_get_params(w);
        layer_table *t = &next.layers;
        og_error err;
        layer_table_default(t); // Sculpt (height, empty: heights are the base's)
        int paints = 2 + trial % 3;
        for (int i = 0; i < paints; i++) {
            char name[16];
            snprintf(name, sizeof name, "P%d", i);
            int at =
                layer_table_insert(t, i == 0 ? 0 : t->count, name, LAYER_BLEND_ADD,
                                   test_rng_unit(&seed) < 0.4 ? 1.0 : test_rng_unit(&seed), &err);
            t->layers[at].kind = LAYER_KIND_PAINT;
            t->layers[at].visible = test_rng_unit(&seed) > 0.2;
            layer_mask *m = &t->layers[at].mask;
            if (test_rng_unit(&seed) < 0.5) {
                char v[64];
                snprintf(v, sizeof v, "%.1f,%.1f", test_rng_unit(&seed) * 100 - 50,
                         50 + test_rng_unit(&seed) * 100);
                layer_mask_set_option(m, "height", v, &err);
                layer_mask_set_option(m, "falloff", "12", &err);
                if (test_rng_unit(&seed) < 0.5) layer_mask_set_option(m, "slope", "0,20,4", &err);
                if (test_rng_unit(&seed) < 0.3) layer_mask_set_option(m, "invert", "1", &err);
            }
            if (test_rng_unit(&seed) < 0.4) layer_mask_set_option(m, "painted", "1", &err);
        }
        edit *e = edit_begin(w, "test paint", &err);
        edit_set_layer_mode(e, EDIT_LAYER_COMPOSED);
        if (edit_set_params(e, &next, &err) != 0) fail_msg("%s", err.msg);
        uint8_t *base = malloc(n * TILE_MATERIALS), *values[LAYER_MAX] = {0};
        float *coverage[LAYER_MAX] = {0};
        memcpy(base, base_m, n * TILE_MATERIALS);
        fill_paint(e, TILE_SLOT_BASE, (grid_rect){area.x0 + 50, area.z0, area.x1, area.z0 + 300},
                   base, area, &seed, 1);
        for (int i = 0; i < t->count; i++) {
            if (t->layers[i].kind != LAYER_KIND_PAINT) continue;
            values[i] = calloc(n, TILE_MATERIALS);
            int64_t x0 = area.x0 + (int64_t)(test_rng_unit(&seed) * 200),
                    z0 = area.z0 + (int64_t)(test_rng_unit(&seed) * 200);
            int64_t x1 = area.x1 - (int64_t)(test_rng_unit(&seed) * 200),
                    z1 = area.z1 - (int64_t)(test_rng_unit(&seed) * 200);
            fill_paint(e, t->layers[i].id, (grid_rect){x0, z0, x1, z1}, values[i], area, &seed, 0);
            if (t->layers[i].mask.painted) { // coverage (out of range and NaN too) over a part
                coverage[i] = calloc(n, sizeof(float));
                painted_masks += t->layers[i].visible;
                fill_coverage(e, t->layers[i].id, (grid_rect){x1 - 250, z1 - 250, x1 + 30, z1 + 10},
                              coverage[i], area, &seed);
            }
        }
        tile_parts parts = {0};
        tile_parts_add_rect(&parts, 0, area);
        if (paint_recompose(e, &parts, &err) != 0) fail_msg("%s", err.msg);
        tile_parts_free(&parts);
        if (edit_commit(e, &err) != 0) fail_msg("%s", err.msg);
        uint8_t *got = read_kind(w, TILE_LAYER_MATERIAL, area);
        // The reference: masks from the heights over the area (clamped at its edges, so
        // compare an inner window the masks' borders do not reach past).
        float *mask = malloc(sizeof(float) * n), *acc = malloc(sizeof(float) * TILE_MATERIALS);
        float *weights[LAYER_MAX] = {0};
        for (int i = 0; i < t->count; i++) {
            const layer_info *l = &t->layers[i];
            if (l->kind != LAYER_KIND_PAINT || !l->visible) continue;
            weights[i] = malloc(sizeof(float) * n);
            if (layer_mask_active(&l->mask)) {
                int b = 1;
                float *win = malloc(sizeof(float) * (size_t)(aw - 2 * b) * (ah - 2 * b));
                float *painted = NULL;
                if (coverage[i]) {
                    painted = malloc(sizeof(float) * (size_t)(aw - 2 * b) * (ah - 2 * b));
                    for (int z = 0; z < ah - 2 * b; z++)
                        memcpy(painted + (size_t)z * (aw - 2 * b),
                               coverage[i] + (size_t)(z + b) * aw + b,
                               sizeof(float) * (aw - 2 * b));
                }
                layer_mask_evaluate(&l->mask, base_h, aw - 2 * b, ah - 2 * b, b, 1.0, painted, win);
                free(painted);
                for (size_t k = 0; k < n; k++)
                    mask[k] = 0;
                for (int z = 0; z < ah - 2 * b; z++)
                    for (int x = 0; x < aw - 2 * b; x++)
                        mask[(size_t)(z + b) * aw + x + b] = win[(size_t)z * (aw - 2 * b) + x];
                free(win);
            }
            for (size_t k = 0; k < n; k++)
                weights[i][k] = (float)l->opacity * (layer_mask_active(&l->mask) ? mask[k] : 1.0f);
        }
        size_t wrong = 0, compared = 0;
        for (int z = 1; z < ah - 1; z++)
            for (int x = 1; x < aw - 1; x++) {
                size_t k = (size_t)z * aw + x;
                for (int c = 0; c < TILE_MATERIALS; c++)
                    acc[c] = base[k * TILE_MATERIALS + c];
                for (int i = 0; i < t->count; i++)
                    if (weights[i])
                        reference_paint(acc, weights[i][k], values[i] + k * TILE_MATERIALS);
                uint8_t want[TILE_MATERIALS];
                paint_blend_round(acc, want);
                compared++;
                if (memcmp(want, got + k * TILE_MATERIALS, TILE_MATERIALS) && wrong++ < 3)
                    print_error("trial %d sample (%d,%d): formula %d %d %d, composite %d %d %d\n",
                                trial, x, z, want[0], want[1], want[2], got[k * 8], got[k * 8 + 1],
                                got[k * 8 + 2]);
            }
        assert_int_equal(wrong, 0);
        assert_true(compared > n / 2);
        for (int i = 0; i < LAYER_MAX; i++) {
            free(values[i]);
            free(coverage[i]);
            free(weights[i]);
        }
        free(mask);
        free(acc);
        free(base);
        free(got);
        // Undo puts the materials back exactly.
        assert_int_equal(edit_undo(w, &err), 1);
        got = read_kind(w, TILE_LAYER_MATERIAL, area);
        assert_memory_equal(got, base_m, n * TILE_MATERIALS);
        free(got);
    }
    assert_true(painted_masks > 0);
    free(base_h);
    free(base_m);
    world_close(w);
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

static void close_session(session *s) {
    fclose(s->out);
    world_close(s->ctx.world);
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

static const grid_rect ALL = {0, 0, 600, 600};
#define ALL_N (600 * 600)

static uint8_t *materials(session *s) {
    return read_kind(s->ctx.world, TILE_LAYER_MATERIAL, ALL);
}

// The largest difference of one weight between two material areas.
static int max_weight_difference(const uint8_t *a, const uint8_t *b) {
    int worst = 0;
    for (size_t k = 0; k < (size_t)ALL_N * TILE_MATERIALS; k++) {
        int d = abs((int)a[k] - (int)b[k]);
        if (d > worst) worst = d;
    }
    return worst;
}

static int is_automatic(const uint8_t *m) {
    for (size_t k = 0; k < ALL_N; k++)
        if (m[k * TILE_MATERIALS] != 255) return 0;
    return 1;
}

static const char *const PAINT = "tool paint material=3 radius=60 strength=0.7; "
                                 "stroke 100 100 450 300; "
                                 "tool paint material=5 radius=40 strength=0.5; "
                                 "stroke 300 80 200 500";

// Painting a paint layer on top shows exactly what painting a world without paint layers
// shows; the paint lives in the layer (hidden: the ground as it was), undo and redo are
// exact, and a paint layer under another shows its paint where the upper one is clear.
static void test_paint_tool_on_layer(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(600);
    session single, layered;
    open_session(&single, test_world_open(&p));
    open_session(&layered, test_world_open(&p));
    run(&single, PAINT);
    run(&layered, "layer new Paint kind=paint");
    run(&layered, PAINT);
    uint8_t *a = materials(&single), *b = materials(&layered);
    assert_memory_equal(a, b, (size_t)ALL_N * TILE_MATERIALS);
    assert_false(is_automatic(b));
    run(&layered, "layer set Paint visible=0");
    uint8_t *hidden = materials(&layered);
    assert_true(is_automatic(hidden));
    run(&layered, "layer set Paint visible=1");
    uint8_t *shown = materials(&layered);
    // Recomposed from the layer's coverage: within rounding of the tool's own result.
    assert_true(max_weight_difference(a, shown) <= 2);
    run(&layered, "undo; undo");
    uint8_t *again = materials(&layered);
    assert_memory_equal(again, b, (size_t)ALL_N * TILE_MATERIALS);
    free(again);
    run(&layered, "redo; redo");
    again = materials(&layered);
    assert_memory_equal(again, shown, (size_t)ALL_N * TILE_MATERIALS);
    free(again);
    // Half-transparent: what shows is half way between the ground and the paint.
    run(&layered, "layer set Paint opacity=0.5");
    uint8_t *half = materials(&layered);
    for (size_t k = 0; k < ALL_N; k++)
        assert_true(abs((int)half[k * 8] - (255 + shown[k * 8]) / 2) <= 2);
    free(half);
    // Paint under a layer: where the upper one paints nothing, the lower one's paint shows
    // as on a single world (up to rounding).
    run(&layered, "layer set Paint opacity=1; layer new Upper kind=paint; "
                  "tool paint material=7 radius=30 strength=1; stroke 550 550 560 580; "
                  "layer select Paint; tool paint material=2 radius=50 strength=0.6; "
                  "stroke 100 400 400 420");
    run(&single, "tool paint material=2 radius=50 strength=0.6; stroke 100 400 400 420");
    free(a);
    free(b);
    a = materials(&single);
    b = materials(&layered);
    int worst = 0;
    for (size_t k = 0; k < ALL_N; k++) {
        int64_t x = (int64_t)(k % 600), z = (int64_t)(k / 600);
        if ((x - 555) * (x - 555) + (z - 565) * (z - 565) < 80 * 80) continue; // Upper's
        for (int c = 0; c < TILE_MATERIALS; c++) {
            int d = abs((int)a[k * 8 + c] - (int)b[k * 8 + c]);
            if (d > worst) worst = d;
        }
    }
    if (worst > 2) fail_msg("paint under a layer differs by %d", worst);
    // Heights go into height layers only; a locked or hidden paint layer refuses paint.
    run(&layered, "tool raise radius=20 strength=0.5");
    run_fails(&layered, "stroke 10 10 40 40", "is a paint layer");
    run_fails(&layered, "layer merge Paint", "only layers of one kind");
    run(&layered, "layer set Paint locked=1; tool paint material=1");
    run_fails(&layered, "stroke 10 10 40 40", "locked");
    run_fails(&layered, "layer set Paint locked=0 blend=max", "blend is for height layers");
    free(a);
    free(b);
    free(hidden);
    free(shown);
    close_session(&single);
    close_session(&layered);
}

// Merging paint layers keeps what shows (opacity and masks baked in); merging masked
// height layers keeps the heights; both are one undo step.
static void test_merge_masked(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(600);
    session s;
    open_session(&s, test_world_open(&p));
    run(&s, "layer new Lo kind=paint opacity=0.6; tool paint material=3 radius=80 strength=0.8; "
            "stroke 100 100 500 200; layer new Hi kind=paint opacity=0.7; "
            "tool paint material=6 radius=70 strength=0.9; stroke 200 50 300 550; "
            "layer mask Hi height=-inf,60 falloff=20 slope=0,25,5");
    uint8_t *before = materials(&s);
    run(&s, "layer merge Hi");
    uint8_t *after = materials(&s);
    int d = max_weight_difference(before, after);
    if (d > 2) fail_msg("merged paint differs by %d", d);
    run(&s, "undo");
    uint8_t *undone = materials(&s);
    assert_memory_equal(undone, before, (size_t)ALL_N * TILE_MATERIALS);
    free(before);
    free(after);
    free(undone);
    // Heights: a masked add layer over a max layer, merged.
    run(&s, "layer select Sculpt; tool raise radius=100 strength=0.8; stroke 100 300 500 300; "
            "layer new Cap blend=max opacity=0.8; tool set height=80 radius=90 strength=1; "
            "stroke 150 250 450 350; layer new Bumps; tool raise radius=60 strength=0.5; "
            "stroke 100 100 500 500; layer mask Bumps slope=5,40,5 height=20,inf falloff=10");
    float *h0 = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    run(&s, "layer merge Bumps");
    float *h1 = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    double worst = 0;
    size_t at = 0;
    for (size_t k = 0; k < ALL_N; k++)
        if (fabs((double)h0[k] - h1[k]) > worst) worst = fabs((double)h0[k] - h1[k]), at = k;
    if (worst > 1e-3)
        fail_msg("merged masked heights differ by %g m at (%zu, %zu)", worst, at % 600, at / 600);
    // The merged layer holds the difference: hiding it shows Sculpt alone.
    run(&s, "layer set Cap visible=0");
    run(&s, "undo; undo");
    float *h2 = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    assert_memory_equal(h2, h0, sizeof(float) * ALL_N);
    free(h0);
    free(h1);
    free(h2);
    close_session(&s);
}

// A saved paint stack loads the same; paint from before paint layers (only in the
// composite's tiles) becomes the ground's own paint, under a new paint layer.
static void test_saved_paint(void **state) {
    (void)state;
    char dir[] = "/tmp/orogen_paint_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[256], legacy[256];
    snprintf(path, sizeof path, "%s/a.world", dir);
    snprintf(legacy, sizeof legacy, "%s/b.world", dir);
    world_params p = test_flat_fbm_params(600);
    session s;
    open_session(&s, test_world_open(&p));
    run(&s, "layer new Paint kind=paint opacity=0.8");
    run(&s, PAINT);
    run(&s, "layer mask Paint height=-inf,70 falloff=15");
    uint8_t *saved = materials(&s);
    og_error err;
    if (world_save(s.ctx.world, path, 0, &err) != 0) fail_msg("%s", err.msg);
    close_session(&s);
    world_settings set = {
        .cache_budget_bytes = (size_t)256 << 20, .workers = 2, .warn = test_silent};
    world *w = world_load(path, &set, NULL, &err);
    if (!w) fail_msg("%s", err.msg);
    open_session(&s, w);
    uint8_t *loaded = materials(&s);
    assert_memory_equal(saved, loaded, (size_t)ALL_N * TILE_MATERIALS);
    run(&s, "layer set Paint visible=0");
    uint8_t *hidden = materials(&s);
    assert_true(is_automatic(hidden));
    run(&s, "layer set Paint visible=1");
    free(loaded);
    loaded = materials(&s);
    assert_memory_equal(saved, loaded, (size_t)ALL_N * TILE_MATERIALS);
    close_session(&s);
    // Paint written straight into the composite (as before paint layers).
    w = test_world_open(&p);
    open_session(&s, w);
    edit *e = edit_begin(w, "old paint", &err);
    edit_set_layer_mode(e, EDIT_LAYER_COMPOSED);
    tile_view v;
    tile_key key = {.layer = TILE_LAYER_MATERIAL, .tx = 1, .ty = 0};
    if (edit_tile_acquire(e, key, &v, &err) != 0) fail_msg("%s", err.msg);
    uint8_t *m = v.data;
    for (size_t k = 0; k < TILE_SAMPLES; k += 3) {
        memset(m + k * 8, 0, 8);
        m[k * 8 + 2] = 200;
        m[k * 8 + 4] = 55;
    }
    edit_tile_release(e, &v);
    if (edit_commit(e, &err) != 0) fail_msg("%s", err.msg);
    uint8_t *old = materials(&s);
    if (world_save(w, legacy, 0, &err) != 0) fail_msg("%s", err.msg);
    close_session(&s);
    w = world_load(legacy, &set, NULL, &err);
    if (!w) fail_msg("%s", err.msg);
    open_session(&s, w);
    run(&s, "layer new Over kind=paint; tool paint material=6 radius=60 strength=1; "
            "stroke 300 100 400 100; layer set Over visible=0");
    uint8_t *now = materials(&s);
    assert_memory_equal(old, now, (size_t)ALL_N * TILE_MATERIALS);
    close_session(&s);
    free(saved);
    free(loaded);
    free(hidden);
    free(old);
    free(now);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    assert_int_equal(system(cmd), 0);
}

// A painted mask: coverage painted with the brush (target=mask) across tile edges limits
// a height layer exactly as the formula on plain arrays says (base + coverage x value);
// erasing, inverting, clearing, duplicating, undo/redo and save/load keep it.
static void test_painted_mask(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(600);
    session s;
    open_session(&s, test_world_open(&p));
    run(&s, "layer new Hills opacity=0.8; tool raise radius=150 strength=0.8; "
            "stroke 100 300 500 300; stroke 300 100 300 500");
    float *full = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    run(&s, "layer mask Hills painted=1");
    float *none = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    run_fails(&s, "layer select Sculpt; tool raise target=mask; stroke 1 1", "no painted mask");
    run(&s, "layer select Hills; tool set target=mask height=0.5 radius=60 strength=1; "
            "stroke 200 256 400 256; tool raise target=mask amount=4 radius=40 strength=1; "
            "stroke 256 150 256 200; tool lower target=mask amount=1 radius=30 strength=0.3; "
            "stroke 300 240 330 270; tool smooth target=mask radius=20 strength=1; "
            "stroke 180 250 420 260");
    const layer_table *t = &world_get_params(s.ctx.world)->layers;
    int32_t id = t->layers[layer_table_find(t, "Hills")].id;
    float *got = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    float *base = test_read_slot(s.ctx.world, TILE_SLOT_BASE, ALL);
    float *v = test_read_slot(s.ctx.world, id, ALL);
    float *cov = test_read_slot(s.ctx.world, layer_coverage_slot(id), ALL);
    size_t wrong = 0, partial = 0, covered = 0;
    for (size_t k = 0; k < ALL_N; k++) {
        assert_true(cov[k] >= 0.0f && cov[k] <= 1.0f); // kept within 0..1
        float w = 0.8f * cov[k];
        float want = v[k] != v[k] || !(w > 0) ? base[k] : base[k] + w * v[k];
        partial += cov[k] > 0 && cov[k] < 1;
        covered += cov[k] > 0;
        if (memcmp(&want, &got[k], sizeof want) && wrong++ < 3)
            print_error("sample %zu: formula %.9g, composite %.9g\n", k, want, got[k]);
        if (cov[k] == 0) assert_true(got[k] == none[k]);
    }
    assert_int_equal(wrong, 0);
    assert_true(partial > 1000 && covered > 10000);
    // Inverted: the layer shows where the coverage is not.
    run(&s, "layer mask Hills invert=1");
    float *inv = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    for (size_t k = 0; k < ALL_N; k++)
        if (cov[k] == 0) assert_true(fabsf(inv[k] - full[k]) <= 1e-3f * (1 + fabsf(full[k])));
    // Duplicated: the copy brings its coverage (the duplicate adds the layer again).
    run(&s, "layer mask Hills invert=0; layer duplicate Hills; layer set Hills visible=0");
    float *dup = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    for (size_t k = 0; k < ALL_N; k++)
        assert_true(fabsf(dup[k] - got[k]) <= 1e-3f * (1 + fabsf(got[k])));
    run(&s, "undo; undo");
    // Cleared: nothing painted, one undo step.
    run(&s, "layer mask Hills painted=clear");
    float *cleared = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    assert_memory_equal(cleared, none, sizeof(float) * ALL_N);
    run(&s, "undo");
    float *back = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    assert_memory_equal(back, got, sizeof(float) * ALL_N);
    // Saved and loaded: the same composite, and the coverage still paints.
    char dir[] = "/tmp/orogen_mask_XXXXXX", path[256];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/m.world", dir);
    og_error err;
    if (world_save(s.ctx.world, path, 0, &err) != 0) fail_msg("%s", err.msg);
    close_session(&s);
    world_settings set = {
        .cache_budget_bytes = (size_t)256 << 20, .workers = 2, .warn = test_silent};
    world *w = world_load(path, &set, NULL, &err);
    if (!w) fail_msg("%s", err.msg);
    open_session(&s, w);
    float *loaded = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    assert_memory_equal(loaded, got, sizeof(float) * ALL_N);
    run(&s, "layer set Hills visible=0; layer set Hills visible=1");
    free(loaded);
    loaded = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    assert_memory_equal(loaded, got, sizeof(float) * ALL_N);
    close_session(&s);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    assert_int_equal(system(cmd), 0);
    float *all[] = {full, none, got, base, v, cov, inv, dup, cleared, back, loaded};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        free(all[i]);
}

// A layer command changes the layer table only: subscribers hear WORLD_EVENT_LAYERS and
// the areas it recomposed, never WORLD_EVENT_PARAMS (on which the viewport and the planet
// renderer rebuild everything).
static void test_layer_commands_publish_layers(void **state) {
    (void)state;
    world_params p = test_flat_fbm_params(600);
    session s;
    open_session(&s, test_world_open(&p));
    run(&s, "layer new Hills; tool raise radius=40 strength=0.5; stroke 100 100 150 120; "
            "layer new Paint kind=paint; tool paint material=3 radius=30; stroke 400 400");
    world_subscription *sub = world_events_subscribe(world_event_hub(s.ctx.world), NULL, NULL);
    const char *steps[] = {"layer set Hills opacity=0.5", "layer set Paint visible=0",
                           "layer mask Hills slope=0,20", "undo",
                           "layer move Hills top",        "layer set Hills visible=0"};
    for (size_t k = 0; k < sizeof steps / sizeof steps[0]; k++) {
        run(&s, steps[k]);
        world_event e[64];
        size_t n = world_subscription_take(sub, e, 64);
        int layers = 0, params = 0, areas = 0;
        for (size_t i = 0; i < n; i++) {
            layers += e[i].kind == WORLD_EVENT_LAYERS;
            params += e[i].kind == WORLD_EVENT_PARAMS;
            if (e[i].kind == WORLD_EVENT_AREA && e[i].level == 0) {
                areas++;
                assert_true(e[i].rect.x0 >= 0 && e[i].rect.x1 <= 600);
                // Only around what the layers hold (Hills near 100..150, Paint near 400).
                assert_true(e[i].rect.x1 - e[i].rect.x0 <= 300);
            }
        }
        // (Moving Hills over the paint layer changes nothing seen: no area.)
        if (params || !layers || (!areas && strncmp(steps[k], "layer move", 10)))
            fail_msg("%s: %d params, %d layers, %d areas", steps[k], params, layers, areas);
    }
    world_events_unsubscribe(sub);
    close_session(&s);
}

static int64_t stored(world *w, tile_layer kind, int32_t slot) {
    return tile_store_count(world_store(w), tile_layer_in_slot(kind, slot));
}

// Deleting and merging empty the layer's tiles in the same step: saving drops them from
// the store, and undo (after the save) brings the layer back whole.
static void test_removed_layers_leave_store(void **state) {
    (void)state;
    char dir[] = "/tmp/orogen_drop_XXXXXX", path[256];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/d.world", dir);
    world_params p = test_flat_fbm_params(600);
    session s;
    open_session(&s, test_world_open(&p));
    run(&s, "layer new Gone; tool raise radius=60 strength=0.5; stroke 100 100 500 500; "
            "layer mask Gone painted=1; tool raise target=mask radius=80 strength=1; "
            "stroke 100 100 300 300; layer new P kind=paint; tool paint material=2 radius=50; "
            "stroke 100 500 500 100; layer new P2 kind=paint; tool paint material=4 radius=40; "
            "stroke 300 100 300 500");
    float *h0 = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    uint8_t *m0 = materials(&s);
    const layer_table *t = &world_get_params(s.ctx.world)->layers;
    int32_t gone = t->layers[layer_table_find(t, "Gone")].id,
            p2 = t->layers[layer_table_find(t, "P2")].id;
    og_error err;
    if (world_save(s.ctx.world, path, 0, &err) != 0) fail_msg("%s", err.msg);
    assert_true(stored(s.ctx.world, TILE_LAYER_COARSE, gone) > 0);
    assert_true(stored(s.ctx.world, TILE_LAYER_COARSE, layer_coverage_slot(gone)) > 0);
    assert_true(stored(s.ctx.world, TILE_LAYER_MATERIAL, p2) > 0);
    run(&s, "layer delete Gone; layer merge P2");
    if (world_save(s.ctx.world, path, 0, &err) != 0) fail_msg("%s", err.msg);
    assert_int_equal(stored(s.ctx.world, TILE_LAYER_COARSE, gone), 0);
    assert_int_equal(stored(s.ctx.world, TILE_LAYER_COARSE, layer_coverage_slot(gone)), 0);
    assert_int_equal(stored(s.ctx.world, TILE_LAYER_MATERIAL, p2), 0);
    run(&s, "undo; undo");
    float *h1 = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    uint8_t *m1 = materials(&s);
    assert_memory_equal(h0, h1, sizeof(float) * ALL_N);
    assert_memory_equal(m0, m1, (size_t)ALL_N * TILE_MATERIALS);
    run(&s, "layer set Gone visible=0; layer set Gone visible=1; layer set P2 visible=0; "
            "layer set P2 visible=1");
    free(h1);
    free(m1);
    h1 = read_kind(s.ctx.world, TILE_LAYER_COARSE, ALL);
    m1 = materials(&s);
    for (size_t k = 0; k < ALL_N; k++)
        assert_true(fabsf(h0[k] - h1[k]) <= 1e-4f * (1 + fabsf(h0[k])));
    assert_true(max_weight_difference(m0, m1) <= 2);
    if (world_save(s.ctx.world, path, 0, &err) != 0) fail_msg("%s", err.msg);
    assert_true(stored(s.ctx.world, TILE_LAYER_COARSE, gone) > 0);
    close_session(&s);
    free(h0);
    free(h1);
    free(m0);
    free(m1);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    assert_int_equal(system(cmd), 0);
}

// ---- kill -9 ----------------------------------------------------------------------

// A session of paint layers (two, a mask reading the heights, strokes on both, a hidden
// and shown layer, an undo), as one killed process runs it and an uninterrupted one.
static const char *const KILLED_SESSION =
    "layer new Paint kind=paint opacity=0.8; tool paint material=3 radius=60 strength=0.7; "
    "stroke 100 100 450 300; layer new Moss kind=paint; tool paint material=6 radius=40 "
    "strength=0.5; stroke 300 80 200 500; layer mask Paint height=-inf,70 falloff=15; "
    "layer select Paint; tool paint material=5 radius=30 strength=0.6; stroke 500 100 500 550; "
    "layer set Moss visible=0; layer set Moss visible=1; tool paint material=2 radius=50 "
    "strength=0.9; stroke 50 550 550 50; undo; stroke 150 450 450 150";

// The killed process (this program run again with --killed-session DIR): saves the base
// world as DIR/a.world and DIR/b.world, runs the session on b, says so on stdout and
// waits to be killed, its journal (b.world.recover) left as the kill leaves it.
static int killed_session(const char *dir) {
    char a[4200], b[4200];
    snprintf(a, sizeof a, "%s/a.world", dir);
    snprintf(b, sizeof b, "%s/b.world", dir);
    world_params p = test_flat_fbm_params(600);
    session s;
    open_session(&s, test_world_open(&p));
    og_error err;
    run(&s, "tool raise radius=80 strength=0.6; stroke 100 100 500 400");
    if (world_save(s.ctx.world, a, 0, &err) != 0 || world_save(s.ctx.world, b, 0, &err) != 0) {
        fprintf(stderr, "killed session: %s\n", err.msg);
        return 1;
    }
    if (cmd_run(&s.ctx, KILLED_SESSION, strlen(KILLED_SESSION), "-c", &err) != 0) {
        fprintf(stderr, "killed session: %s\n", err.msg);
        return 1;
    }
    world_journal_wait(s.ctx.world); // the last step's write (on the journal's thread) done
    printf("ready\n");
    fflush(stdout);
    for (;;)
        pause();
}

static world *load_saved(const char *path) {
    world_settings set = {
        .cache_budget_bytes = (size_t)256 << 20, .workers = 2, .warn = test_silent};
    og_error err;
    world *w = world_load(path, &set, NULL, &err);
    if (!w) fail_msg("%s: %s", path, err.msg);
    return w;
}

// What the test compares: the material composite, each paint layer's own weights and
// its painted coverage, the heights and the layer listing.
typedef struct paint_state {
    uint8_t *composite, *layer[2];
    float *heights;
    char listing[2048];
} paint_state;

static void paint_state_read(session *s, paint_state *out) {
    out->composite = materials(s);
    const layer_table *t = &world_get_params(s->ctx.world)->layers;
    for (int i = 0; i < 2; i++) {
        int at = layer_table_find(t, i ? "Moss" : "Paint");
        assert_true(at >= 0);
        layer_grid g;
        og_error err;
        if (layer_grid_init(&g, world_get_params(s->ctx.world), TILE_LAYER_MATERIAL, 0, &err))
            fail_msg("%s", err.msg);
        g.layer = (tile_layer)tile_layer_in_slot(TILE_LAYER_MATERIAL, t->layers[at].id);
        out->layer[i] = malloc((size_t)ALL_N * TILE_MATERIALS);
        if (layer_grid_read_samples(s->ctx.world, &g, ALL, out->layer[i], &err) != 0)
            fail_msg("%s", err.msg);
    }
    out->heights = test_read_slot(s->ctx.world, 0, ALL);
    rewind(s->out);
    run(s, "layers");
    size_t n = fread(out->listing, 1, sizeof out->listing - 1, s->out);
    out->listing[n] = 0;
    rewind(s->out);
    assert_int_equal(ftruncate(fileno(s->out), 0), 0);
}

static void paint_state_expect_equal(const paint_state *a, const paint_state *b) {
    assert_memory_equal(a->composite, b->composite, (size_t)ALL_N * TILE_MATERIALS);
    for (int i = 0; i < 2; i++)
        assert_memory_equal(a->layer[i], b->layer[i], (size_t)ALL_N * TILE_MATERIALS);
    assert_memory_equal(a->heights, b->heights, sizeof(float) * ALL_N);
    assert_string_equal(a->listing, b->listing);
}

static void paint_state_free(paint_state *a) {
    free(a->composite);
    free(a->layer[0]);
    free(a->layer[1]);
    free(a->heights);
}

// A process painting paint layers is killed with SIGKILL after its last step: `recover`
// on its world replays the journal to exactly what the same session shows uninterrupted
// (composite, each layer's weights, heights, the listing), and its steps undo alike.
static void test_killed_paint_session_recovers(void **state) {
    (void)state;
    char dir[] = "/tmp/orogen_paint_kill_XXXXXX";
    assert_non_null(mkdtemp(dir));
    int out[2];
    assert_int_equal(pipe(out), 0);
    pid_t child = fork();
    if (child == 0) { // a fresh program: no thread of this one's pools is missing in it
        dup2(out[1], 1);
        close(out[0]);
        execl("/proc/self/exe", "test_paint_layers", "--killed-session", dir, (char *)NULL);
        _exit(127);
    }
    close(out[1]);
    char line[16] = "";
    ssize_t got = read(out[0], line, sizeof line - 1);
    assert_true(got > 0 && !strncmp(line, "ready", 5));
    kill(child, SIGKILL);
    int status;
    assert_int_equal(waitpid(child, &status, 0), child);
    assert_true(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    close(out[0]);

    char a[4200], b[4200];
    snprintf(a, sizeof a, "%s/a.world", dir);
    snprintf(b, sizeof b, "%s/b.world", dir);
    session whole, recovered;
    open_session(&whole, load_saved(a));
    run(&whole, KILLED_SESSION);
    open_session(&recovered, load_saved(b));
    run(&recovered, "recover");
    paint_state x, y;
    paint_state_read(&whole, &x);
    paint_state_read(&recovered, &y);
    assert_false(is_automatic(x.composite));
    paint_state_expect_equal(&x, &y);
    paint_state_free(&x);
    paint_state_free(&y);
    run(&whole, "undo; undo");
    run(&recovered, "undo; undo");
    paint_state_read(&whole, &x);
    paint_state_read(&recovered, &y);
    paint_state_expect_equal(&x, &y);
    paint_state_free(&x);
    paint_state_free(&y);
    close_session(&whole);
    close_session(&recovered);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    assert_int_equal(system(cmd), 0);
}

int main(int argc, char **argv) {
    if (argc == 3 && !strcmp(argv[1], "--killed-session")) return killed_session(argv[2]);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paint_composite_matches_arrays),
        cmocka_unit_test(test_paint_tool_on_layer),
        cmocka_unit_test(test_merge_masked),
        cmocka_unit_test(test_saved_paint),
        cmocka_unit_test(test_painted_mask),
        cmocka_unit_test(test_layer_commands_publish_layers),
        cmocka_unit_test(test_removed_layers_leave_store),
        cmocka_unit_test(test_killed_paint_session_recovers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
