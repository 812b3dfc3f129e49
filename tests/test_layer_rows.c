// A rectangle read row by row straight from the tiles (editor/world/layer_rows.c), whole
// rows and parts of them (each run up to a tile's edge or the rectangle's), gives the samples
// layer_grid_read copies, for rectangles at random places and sizes that straddle tile edges and
// corners (coarse and detail layers, an unbounded and a bounded world, after an edit changed some
// tiles); those past a bounded world's edge or over more than 4 x 4 tiles are refused (1) with
// nothing pinned.
#include "editor/edit/edit.h"
#include "editor/edit/edit_commit.h"
#include "editor/tools/brush_dab.h"
#include "editor/world/layer_rows.h"
#include "support/test_world.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

// A raise dab over a tile corner, committed: some tiles edited, some generated.
static void raise_corner(world *w, const layer_grid *g) {
    og_error err;
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    brush_dab d = {.brush = &b,
                   .cx = 250.5,
                   .cz = 260.25,
                   .radius = 40.0,
                   .strength = 1.0f,
                   .spacing = g->spacing,
                   .seed = 1};
    edit *e = edit_begin(w, "raise", &err);
    assert_non_null(e);
    assert_int_equal(brush_dab_apply(e, g, &d, &err), 0);
    assert_int_equal(edit_commit(e, &err), 0);
}

static void compare(world *w, tile_layer layer, int64_t size, uint64_t *rng, long counts[2]) {
    og_error err;
    layer_grid g;
    assert_int_equal(layer_grid_init(&g, world_get_params(w), layer, 0, &err), 0);
    if (layer == TILE_LAYER_COARSE) raise_corner(w, &g);
    for (int c = 0; c < 60; c++) {
        int64_t span = size ? size : 1200;
        int64_t x0 = (int64_t)(test_rng_unit(rng) * (double)span) - (size ? 40 : 600);
        int64_t z0 = (int64_t)(test_rng_unit(rng) * (double)span) - (size ? 40 : 600);
        int64_t wd = 1 + (int64_t)(test_rng_unit(rng) * (c % 10 == 0 ? 1100.0 : 300.0));
        int64_t ht = 1 + (int64_t)(test_rng_unit(rng) * (c % 10 == 0 ? 1100.0 : 300.0));
        grid_rect r = {x0, z0, x0 + wd, z0 + ht};
        layer_rows rows;
        int rc = layer_rows_open(w, &g, r, &rows, &err);
        assert_true(rc == 0 || rc == 1);
        grid_rect in = layer_grid_clip(&g, r);
        int inside = in.x0 == r.x0 && in.x1 == r.x1 && in.z0 == r.z0 && in.z1 == r.z1;
        int64_t tiles =
            (world_grid_floor_div(r.x1 - 1, TILE_SIZE) - world_grid_floor_div(r.x0, TILE_SIZE) +
             1) *
            (world_grid_floor_div(r.z1 - 1, TILE_SIZE) - world_grid_floor_div(r.z0, TILE_SIZE) + 1);
        assert_int_equal(rc, inside && tiles <= LAYER_ROWS_TILES ? 0 : 1);
        counts[rc]++;
        if (rc != 0) continue;
        float *want = malloc((size_t)(wd * ht) * sizeof *want);
        float *got = malloc((size_t)wd * sizeof *got);
        assert_non_null(want);
        assert_non_null(got);
        assert_int_equal(layer_grid_read(w, &g, r, want, &err), 0);
        for (int64_t z = r.z0; z < r.z1; z++) { // a part of the row, or all of it
            int64_t a = r.x0 + (int64_t)(test_rng_unit(rng) * (double)wd), b = r.x1;
            if (z % 2)
                a = r.x0;
            else
                b = a + (int64_t)(test_rng_unit(rng) * (double)(r.x1 - a + 1));
            for (int64_t x = a; x < b;) { // one tile's run at a time
                int64_t end;
                const float *p = layer_rows_at(&rows, z, x, &end);
                assert_true(end > x && end <= r.x1 && (end == r.x1 || end % TILE_SIZE == 0));
                int64_t to = end < b ? end : b;
                memcpy(got + (x - a), p, (size_t)(to - x) * sizeof *got);
                x = to;
            }
            if (memcmp(got, want + (z - r.z0) * wd + (a - r.x0), (size_t)(b - a) * sizeof *got))
                fail_msg("rect %lld,%lld .. %lld,%lld: row %lld, %lld..%lld differs",
                         (long long)r.x0, (long long)r.z0, (long long)r.x1, (long long)r.z1,
                         (long long)z, (long long)a, (long long)b);
        }
        layer_rows_close(&rows);
        free(want);
        free(got);
    }
}

static void test_rows_match_layer_grid_read(void **state) {
    (void)state;
    uint64_t rng = 0x243f6a8885a308d3ull;
    long counts[2] = {0, 0};
    for (int bounded = 0; bounded < 2; bounded++) {
        world_params p = test_flat_fbm_params(bounded ? 700 : 0);
        world *w = test_world_open(&p);
        compare(w, TILE_LAYER_COARSE, bounded ? 700 : 0, &rng, counts);
        compare(w, TILE_LAYER_DETAIL, bounded ? 700 : 0, &rng, counts);
        og_error err;
        assert_int_equal(layer_rows_open(w, &(layer_grid){.layer = TILE_LAYER_MATERIAL},
                                         (grid_rect){0, 0, 8, 8}, &(layer_rows){0}, &err),
                         1);
        world_close(w);
    }
    print_message("%ld rectangles read row by row, %ld refused\n", counts[0], counts[1]);
    assert_true(counts[0] >= 100 && counts[1] >= 10);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rows_match_layer_grid_read),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
