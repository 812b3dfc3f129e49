// Edit layer benchmarks (issue 30's speed goals), each figure beside its reference
// from the same run:
//  1. one raise dab (radius 64 samples, the whole edit: begin, dab, the active layer
//     taking it, the composite, mips, undo capture) on the top of 8 layers (2 of them
//     masked) against the same dab on a world of one layer (goal: within 1.5x);
//  2. the same dab on layer 2 of 8, everything above recomposed (goal: within 2.5x);
//  3. switching a layer off over a 4096^2 edited area, the full-resolution composite
//     back (goal: under 1 s), and its throughput per visible layer against a memcpy of
//     the same tiles (goal: within 4x).
// Figures are medians of several runs, ratios medians of the per-run ratios; goals are
// reported (PASS/MISS), not asserted.
#include "editor/cmd/commands.h"
#include "editor/edit/edit.h"
#include "editor/world/world.h"
#include "bench/bench_timing.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RUNS 7

static void quiet(void *user, const char *message) {
    (void)user, (void)message;
}

typedef struct session {
    cmd_context ctx;
    FILE *out;
} session;

static void run(session *s, const char *script) {
    og_error err;
    if (cmd_run(&s->ctx, script, strlen(script), "bench", &err) != 0) {
        fprintf(stderr, "bench_layers: %s: %s\n", script, err.msg);
        exit(1);
    }
}

static void open_session(session *s, int64_t size) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.size = size;
    p.spacing = 1.0;
    p.octaves = 6;
    world_settings set = {.cache_budget_bytes = (size_t)3 << 30, .workers = 2, .warn = quiet};
    og_error err;
    world *w = world_create(&p, &set, &err);
    if (!w) {
        fprintf(stderr, "bench_layers: %s\n", err.msg);
        exit(1);
    }
    s->out = fopen("/dev/null", "w");
    cmd_context_init(&s->ctx, w, &set, s->out, OROGEN_RESOURCE_DIR);
}

static void close_session(session *s) {
    world_close(s->ctx.world);
    fclose(s->out);
}

// Seconds for one dab as its own edit (undone after, so every run starts alike).
static double dab_seconds(session *s) {
    double t0 = bench_now();
    run(s, "dab 1000 1000");
    double t = bench_now() - t0;
    run(s, "undo");
    return t;
}

static const char *verdict(int ok) {
    return ok ? "PASS" : "MISS";
}

int main(void) {
    // 1 and 2: a one-layer world and one of 8 layers, each layer edited under the dab.
    session one, eight;
    open_session(&one, 2048);
    open_session(&eight, 2048);
    const char *content = "tool raise radius=300 strength=0.3; stroke 700 700 1300 1300";
    run(&one, content);
    run(&eight, content);
    for (int i = 1; i < 8; i++) {
        char cmd[256];
        snprintf(cmd, sizeof cmd, "layer new L%d%s; %s", i,
                 i == 3   ? " blend=max"
                 : i == 5 ? " opacity=0.5"
                          : "",
                 content);
        run(&eight, cmd);
    }
    run(&eight, "layer mask L2 height=-inf,400 falloff=50; layer mask L6 slope=0,35,5");
    run(&one, "tool raise radius=64 strength=0.5");
    run(&eight, "tool raise radius=64 strength=0.5; layer select L7");
    double t1[RUNS], t8[RUNS], t2[RUNS], r8[RUNS], r2[RUNS];
    dab_seconds(&one), dab_seconds(&eight); // warm the tiles
    for (int r = 0; r < RUNS; r++) {
        t1[r] = dab_seconds(&one);
        run(&eight, "layer select L7");
        t8[r] = dab_seconds(&eight);
        run(&eight, "layer select L1");
        t2[r] = dab_seconds(&eight);
        r8[r] = t8[r] / t1[r];
        r2[r] = t2[r] / t1[r];
    }
    double m1 = bench_median(t1, RUNS), m8 = bench_median(t8, RUNS), m2 = bench_median(t2, RUNS);
    double q8 = bench_median(r8, RUNS), q2 = bench_median(r2, RUNS);
    printf("raise dab r=64, whole edit: one layer %.2f ms; top of 8 layers (2 masked) %.2f ms: "
           "%.2fx %s (goal 1.5x)\n",
           m1 * 1e3, m8 * 1e3, q8, verdict(q8 <= 1.5));
    printf("raise dab r=64 on layer 2 of 8 (6 above recomposed): %.2f ms: %.2fx %s (goal 2.5x)\n",
           m2 * 1e3, q2, verdict(q2 <= 2.5));
    close_session(&one);
    close_session(&eight);

    // 3. Switching a layer over a 4096^2 edited area (two layers edited everywhere).
    session big;
    open_session(&big, 4096);
    run(&big, "tool raise radius=1500 strength=0.2; stroke 1024 1024 3072 1024 3072 3072 1024 "
              "3072 1024 1024 2048 2048; layer new Top; stroke 1024 3072 3072 1024");
    int tiles = (4096 / 256) * (4096 / 256), layers = 3; // base, Sculpt, Top
    size_t tile_bytes = sizeof(float) * 256 * 256;
    float *src = malloc(tile_bytes * (size_t)tiles), *dst = malloc(tile_bytes * (size_t)tiles);
    memset(src, 1, tile_bytes * (size_t)tiles);
    double tt[RUNS], tm[RUNS], rr[RUNS];
    for (int r = 0; r < RUNS; r++) {
        double t0 = bench_now();
        run(&big, "layer set Top visible=0");
        tt[r] = bench_now() - t0;
        run(&big, "undo");
        // The reference: a memcpy of every tile the composite reads and writes.
        t0 = bench_now();
        for (int k = 0; k < layers + 1; k++)
            memcpy(dst, src, tile_bytes * (size_t)tiles);
        tm[r] = bench_now() - t0;
        rr[r] = tt[r] / tm[r];
    }
    double mt = bench_median(tt, RUNS), mm = bench_median(tm, RUNS), qr = bench_median(rr, RUNS);
    printf("switch a layer off over 4096^2 (%d tiles, %d layers read + the composite written, "
           "one undo step): %.3f s %s (goal 1 s); memcpy of the same bytes %.1f ms: %.1fx %s "
           "(goal 4x)\n",
           tiles, layers, mt, verdict(mt < 1.0), mm * 1e3, qr, verdict(qr <= 4.0));
    free(src);
    free(dst);
    close_session(&big);
    return 0;
}
