// Editing engine benchmarks, each figure beside its reference from the same run:
//  1. one dab of radius 64 samples on resident tiles, per touched sample, against a
//     memcpy of the same bytes (4 per touched sample) from cache: raise and smooth,
//     both the steady state inside a stroke and the full cost of a one-dab edit
//     (begin, first-touch snapshot, commit with undo capture and mips; its crash journal
//     record is written after, on the journal's writer thread: timed apart);
//  2. one raise dab of radius 512 samples inside a stroke: on every core, on one
//     core, and on a plain array (one thread, no tiles: the reference);
//  3. a 1000-dab stroke over 4 tiles with undo capture, then its undo and redo; the
//     same stroke drawn in 200 moves (live mip levels per move) against one move;
//  4. that stroke's history memory against the raw bytes of the tiles it covers and
//     the bytes it actually changed, and the cost of appending its step to the crash
//     recovery journal against the stroke's own time (goal: under 5%);
//  5. hydraulic (100k droplets) and thermal (20 iterations) erosion of a 1024^2
//     grid against a memcpy of the grid.
// Figures are medians of several runs, ratios medians of the per-run ratios; goals
// are reported (PASS/MISS), not asserted.
#include "editor/tools/brush_dab.h"
#include "editor/edit/edit.h"
#include "editor/edit/edit_commit.h"
#include "editor/edit/detail_pd.h"
#include "editor/edit/edit_mips.h"
#include "editor/edit/layer_composite.h"
#include "editor/tools/erosion.h"
#include "editor/gen/gen.h"
#include "editor/world/history.h"
#include "editor/edit/parallel.h"
#include "editor/tools/stamp.h"
#include "editor/tools/stamp_image_cache.h"
#include "editor/tools/stroke.h"
#include "editor/world/recovery_journal.h"
#include "editor/world/world.h"

#include <dirent.h>
#include <math.h>
#include <sched.h>
#include "bench/bench_journals.h"
#include "bench/bench_timing.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define RUNS 7

static void quiet(void *u, const char *m) {
    (void)u, (void)m;
}

static void check(int rc, const og_error *err, const char *what) {
    if (rc == 0) return;
    fprintf(stderr, "bench_edit: %s: %s\n", what, err->msg);
    exit(1);
}

static void *xmalloc(size_t n) {
    void *p = malloc(n);
    if (!p) {
        fprintf(stderr, "bench_edit: out of memory (%zu bytes)\n", n);
        exit(1);
    }
    return p;
}

// Called through a volatile pointer so the compiler keeps every copy.
static void *(*volatile copy_bytes)(void *, const void *, size_t) = memcpy;

// Seconds per copy of `bytes` from src to dst, both already in cache.
static double memcpy_seconds(void *dst, const void *src, size_t bytes, int reps) {
    copy_bytes(dst, src, bytes);
    double t0 = bench_now();
    for (int i = 0; i < reps; i++)
        copy_bytes(dst, src, bytes);
    return (bench_now() - t0) / reps;
}

// ---- the summary ----------------------------------------------------------------------

static struct {
    char text[200];
    int pass;
} goals[16];
static int goal_count;

// Records `value` against `limit` (at most, or strictly below when strict).
static void goal(const char *what, double value, double limit, int strict, const char *unit) {
    if (goal_count == (int)(sizeof goals / sizeof *goals)) return;
    int pass = strict ? value < limit : value <= limit;
    snprintf(goals[goal_count].text, sizeof goals[0].text, "%-46s %9.3f%s  (goal %s %g%s)", what,
             value, unit, strict ? "<" : "<=", limit, unit);
    goals[goal_count++].pass = pass;
}

// ---- shared setup ---------------------------------------------------------------------

// An unbounded flat fBm world with 1 m between coarse samples.
static world *bench_world(layer_grid *g) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.spacing = 1.0;
    world_settings s = {.warn = quiet};
    og_error err;
    world *w = world_create(&p, &s, &err);
    if (!w) check(-1, &err, "world_create");
    check(layer_grid_init(g, world_get_params(w), TILE_LAYER_COARSE, 0, &err), &err,
          "layer_grid_init");
    return w;
}

static brush_dab dab_of(const brush *b, double cx, double cz) {
    return (brush_dab){.brush = b,
                       .cx = cx,
                       .cz = cz,
                       .radius = b->radius,
                       .strength = (float)b->strength,
                       .spacing = 1.0,
                       .seed = 1};
}

// Samples whose falloff weight is > 0 (inside the disc), as brush_dab.c finds them.
static long disc_samples(const brush_dab *d) {
    grid_rect r = brush_dab_rect(d);
    long n = 0;
    for (int64_t z = r.z0; z < r.z1; z++)
        for (int64_t x = r.x0; x < r.x1; x++) {
            float dx = (float)((double)x - d->cx), dz = (float)((double)z - d->cz);
            n += sqrtf(dx * dx + dz * dz) / (float)d->radius < 1.0f;
        }
    return n;
}

static long rect_samples(grid_rect r) {
    return (long)((r.x1 - r.x0) * (r.z1 - r.z0));
}

// One edit with one dab, committed: generates the tiles and mips and makes them
// edited (so that later steps never undo to pristine tiles, which would drop them).
static void warm(world *w, const layer_grid *g, const brush_dab *d) {
    og_error err;
    edit *e = edit_begin(w, "warm", &err);
    if (!e) check(-1, &err, "edit_begin");
    check(brush_dab_apply(e, g, d, &err), &err, "brush_dab_apply");
    check(edit_commit(e, &err), &err, "edit_commit");
}

// Seconds per dab, n dabs inside an open edit.
static double dab_seconds(edit *e, const layer_grid *g, const brush_dab *d, int n) {
    og_error err;
    double t0 = bench_now();
    for (int i = 0; i < n; i++)
        check(brush_dab_apply(e, g, d, &err), &err, "brush_dab_apply");
    return (bench_now() - t0) / n;
}

// Seconds per one-dab edit (begin, dab, commit); *commit_s gets the commit's share.
// Each edit starts as a user's would, with the previous step's background work done:
// its crash journal record written (the journal's writer thread), *journal_s the time
// from the commit's return until it was, then the history's zstd of its deltas
// (history.c), *squeeze_s its time (on this thread, waiting for or helping the
// background). Neither is in the step's time; *cpu_s (every thread's CPU) has the write.
static double dab_edit_seconds(world *w, const layer_grid *g, const brush_dab *d, int n,
                               double *commit_s, double *journal_s, double *squeeze_s,
                               double *cpu_s) {
    og_error err;
    double total = 0, commit = 0, journal = 0, squeeze = 0, cpu = 0;
    for (int i = 0; i < n; i++) {
        double s0 = bench_now();
        history_undo_peek(world_history(w)); // the squeeze of the step before, finished
        squeeze += bench_now() - s0;
        double c0 = bench_process_cpu(), t0 = bench_now();
        edit *e = edit_begin(w, "dab", &err);
        if (!e) check(-1, &err, "edit_begin");
        check(brush_dab_apply(e, g, d, &err), &err, "brush_dab_apply");
        double t1 = bench_now();
        check(edit_commit(e, &err), &err, "edit_commit");
        double t2 = bench_now();
        world_journal_wait(w); // its record in the journal's file
        journal += bench_now() - t2;
        cpu += bench_process_cpu() - c0;
        total += t2 - t0;
        commit += t2 - t1;
    }
    *commit_s = commit / n;
    *journal_s = journal / n;
    *squeeze_s = squeeze / n;
    *cpu_s = cpu / n;
    return total / n;
}

// Seconds per one-dab edit, n of them back to back with nothing waited for between
// them: each also finishes what the one before left to the background (its journal
// write, the history's zstd of its deltas, at its history_push), as a script's would.
static double dab_edits_back_to_back(world *w, const layer_grid *g, const brush_dab *d, int n) {
    og_error err;
    history_undo_peek(world_history(w));
    world_journal_wait(w);
    double t0 = bench_now();
    for (int i = 0; i < n; i++) {
        edit *e = edit_begin(w, "dab", &err);
        if (!e) check(-1, &err, "edit_begin");
        check(brush_dab_apply(e, g, d, &err), &err, "brush_dab_apply");
        check(edit_commit(e, &err), &err, "edit_commit");
    }
    history_undo_peek(world_history(w));
    world_journal_wait(w);
    return (bench_now() - t0) / n;
}

// Where a one-dab step's time goes: edit_commit's parts timed one by one (medians).
static void dab_step_parts(world *w, const layer_grid *g, const brush_dab *d) {
    enum { N = 50 };
    double dab[N], take[N], mips[N], record[N];
    og_error err;
    for (int i = 0; i < N; i++) {
        history_undo_peek(world_history(w)); // the squeeze of the step before, finished
        double t0 = bench_now();
        edit *e = edit_begin(w, "dab", &err);
        if (!e) check(-1, &err, "edit_begin");
        check(brush_dab_apply(e, g, d, &err), &err, "brush_dab_apply");
        double t1 = bench_now();
        check(layer_take_edit(e, &err), &err, "layer_take_edit");
        double t2 = bench_now();
        edit_record_start(e); // as edit_commit: level-0 deltas in the pool beside the mips
        check(edit_mips_update(e, &err), &err, "edit_mips_update");
        const dirty_rect *rects;
        size_t count = edit_dirty_rects(e, &rects);
        check(detail_pd_update(w, rects, count, &err), &err, "detail_pd_update");
        double t3 = bench_now();
        check(edit_record(e, &err), &err, "edit_record");
        double t4 = bench_now();
        world_journal_wait(w); // its record written (the journal's thread), as a user's next
        dab[i] = t1 - t0, take[i] = t2 - t1, mips[i] = t3 - t2, record[i] = t4 - t3;
    }
    printf("  where its time goes (medians of %d): begin + snapshot + dab %.0f us, layer take "
           "%.0f us, mip levels %.0f us, undo record (14 tiles' deltas encoded, the 2 level-0 ones "
           "begun in the pool beside the mips; history; the crash journal record handed to its "
           "writer thread) %.0f us\n",
           N, bench_median(dab, N) * 1e6, bench_median(take, N) * 1e6, bench_median(mips, N) * 1e6,
           bench_median(record, N) * 1e6);
}

// ---- 1. a dab of radius 64 samples --------------------------------------------------------

static void bench_dab64(brush_tool tool, double goal_ratio) {
    layer_grid g;
    world *w = bench_world(&g);
    brush b;
    brush_defaults(&b, tool);
    b.radius = 64.0;
    brush_dab d = dab_of(&b, 128.0, 128.0); // in the middle of tile (0, 0)
    long disc = disc_samples(&d), rect = rect_samples(brush_dab_rect(&d));
    size_t bytes = (size_t)disc * 4;
    void *src = xmalloc(bytes), *dst = xmalloc(bytes);
    memset(src, 1, bytes);
    warm(w, &g, &d);

    og_error err;
    edit *e = edit_begin(w, "steady", &err);
    if (!e) check(-1, &err, "edit_begin");
    check(brush_dab_apply(e, &g, &d, &err), &err, "brush_dab_apply"); // first touch: snapshot
    // Dabs and copies alternate in short chunks so that both see the same machine load;
    // the ratio is the median of the per-run ratios.
    // The ratio is of CPU time (the wall clock of a shared machine counts other
    // programs' time slices): the dabs' of every thread of the process, the copies'
    // of the copying thread alone (any other thread's work counts against the dab).
    const int chunks = 10, steady_n = tool == BRUSH_RAISE ? 100 : 20, edit_n = 50;
    double steady[RUNS], full[RUNS], commit[RUNS], copy[RUNS], ratio[RUNS], journal[RUNS];
    double steady_cpu[RUNS], copy_cpu[RUNS], squeeze[RUNS], full_cpu[RUNS], back[RUNS];
    for (int r = 0; r < RUNS; r++) {
        steady[r] = copy[r] = steady_cpu[r] = copy_cpu[r] = 0;
        for (int k = 0; k < chunks; k++) {
            double c0 = bench_process_cpu();
            steady[r] += dab_seconds(e, &g, &d, steady_n) / chunks;
            double c1 = bench_process_cpu();
            copy_bytes(dst, src, bytes); // so memcpy_seconds' own first copy is hot too
            double c2 = bench_thread_cpu();
            copy[r] += memcpy_seconds(dst, src, bytes, 2000) / chunks;
            steady_cpu[r] += (c1 - c0) / steady_n / chunks;
            copy_cpu[r] += (bench_thread_cpu() - c2) / 2001 / chunks;
        }
        ratio[r] = steady_cpu[r] / copy_cpu[r];
    }
    edit_abort(e);
    for (int r = 0; r < RUNS; r++) {
        full[r] =
            dab_edit_seconds(w, &g, &d, edit_n, &commit[r], &journal[r], &squeeze[r], &full_cpu[r]);
        back[r] = dab_edits_back_to_back(w, &g, &d, edit_n);
    }

    double s = bench_median(steady, RUNS), c = bench_median(copy, RUNS),
           f = bench_median(full, RUNS);
    double k = bench_median(commit, RUNS), q = bench_median(ratio, RUNS);
    const char *name = brush_tool_name(tool);
    printf("%s dab, radius 64 samples, resident tiles: %ld samples in the disc (%ld in the rect)\n",
           name, disc, rect);
    printf(
        "  inside a stroke: %.1f us per dab = %.2f ns per disc sample (%.2f ns per rect sample)\n",
        s * 1e6, s * 1e9 / disc, s * 1e9 / rect);
    printf("  memcpy of the same %zu bytes (in cache): %.2f us = %.3f ns per sample; "
           "dab / memcpy = %.1fx (goal <= %g) in CPU time (%.2f us / %.3f us)\n",
           bytes, c * 1e6, c * 1e9 / disc, q, goal_ratio, bench_median(steady_cpu, RUNS) * 1e6,
           bench_median(copy_cpu, RUNS) * 1e6);
    printf("  as its own edit (begin + snapshot + dab + commit with undo capture and mips): "
           "%.0f us (commit %.0f us; CPU of all threads %.0f us) = %.1f ns per disc sample, "
           "%.0fx the memcpy; then, in the background, its crash journal record written "
           "%.0f us after the commit returned, the history's zstd of its deltas %.0f us\n",
           f * 1e6, k * 1e6, bench_median(full_cpu, RUNS) * 1e6, f * 1e9 / disc, f / c,
           bench_median(journal, RUNS) * 1e6, bench_median(squeeze, RUNS) * 1e6);
    printf("  back to back (each step also finishing the last one's journal write and zstd): "
           "%.0f us per step\n",
           bench_median(back, RUNS) * 1e6);
    if (tool == BRUSH_SMOOTH && q > goal_ratio)
        printf("  why smooth misses: each dab blurs its disc's area and a 2k halo (161^2 samples "
               "at r=64) with two box sums down columns (float running sums restarted every "
               "2k + 1 rows, read straight from the tiles, 64 columns a sweep) and two along rows "
               "(power-of-two runs over each row's packed span), then blends the disc; only what "
               "the disc takes is computed. On an AVX-512 Zen 5 (perf, 100k steady dabs): ~36%% "
               "column boxes, ~22%% row boxes, ~18%% blend, the rest spans, row reads and "
               "set-up. None is bound by one latency or unit: the running sums already add each "
               "row's change off their chains; 64 columns a sweep (not 32) and the sums kept in "
               "registers made the column boxes ~20%% faster alone, the dab ~6%%; the blend "
               "without its square root is ~16%% faster alone, the dab within noise; the row boxes "
               "take ~4.6 cycles per 16 samples a pass in L1 (valignd for vpermt2ps: no faster). "
               "Also tried and dropped: packed rows aligned to cache lines (dab slower), the "
               "non-chain adds on the FMA units, the blend's whole vectors stored unmasked, "
               "prefetching the blend's next row (no change). 20x (~7.4 us) needs ~40%% off all "
               "three passes; with their data in L1 the column and row boxes still take ~75%% and "
               "~85%% of their time in the dab: fewer operations per sample, more than hotter "
               "data\n");
    char what[80];
    snprintf(what, sizeof what, "%s dab r=64, per sample vs memcpy", name);
    goal(what, q, goal_ratio, 0, "x");
    if (tool == BRUSH_RAISE) {
        dab_step_parts(w, &g, &d);
        if (f > 100e-6)
            printf("  why the step misses: left are the layer take, the mip levels and the undo "
                   "deltas (the level-0 ones on the pool's other thread beside the mips); the "
                   "crash journal's write (36-39 us of ~90 KB) is off the step, on the journal's "
                   "writer thread (timed above); on a loaded machine the step waits for the "
                   "pool thread's core\n");
        goal("raise dab r=64 as its own undo step (journal record written after), us", f * 1e6,
             100.0, 0, " us");
    }
    free(src);
    free(dst);
    world_close(w);
}

// ---- 2. a raise dab of radius 512 samples ---------------------------------------------------

// Sets the CPU affinity of every thread of the process (the editor's pool included).
static int pin_all_threads(const cpu_set_t *set) {
    DIR *dir = opendir("/proc/self/task");
    if (!dir) return -1;
    int rc = 0;
    struct dirent *ent;
    while ((ent = readdir(dir)) != NULL) {
        if (ent->d_name[0] < '0' || ent->d_name[0] > '9') continue;
        if (sched_setaffinity((pid_t)atoi(ent->d_name), sizeof *set, set) != 0) rc = -1;
    }
    closedir(dir);
    return rc;
}

static void bench_dab512(void) {
    layer_grid g;
    world *w = bench_world(&g);
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    b.radius = 512.0;
    brush_dab d = dab_of(&b, 1024.0, 1024.0); // 25 tiles
    grid_rect area = brush_dab_rect(&d);
    long disc = disc_samples(&d), rect = rect_samples(area);

    og_error err;
    edit *e = edit_begin(w, "steady", &err);
    if (!e) check(-1, &err, "edit_begin");
    check(brush_dab_apply(e, &g, &d, &err), &err, "brush_dab_apply"); // generate + snapshot
    float *plain = xmalloc((size_t)rect * sizeof *plain);
    check(layer_grid_read(w, &g, area, plain, &err), &err, "layer_grid_read");

    cpu_set_t all, one;
    int pinned = sched_getaffinity(0, sizeof all, &all) == 0 && CPU_COUNT(&all) > 1;
    if (pinned) {
        CPU_ZERO(&one);
        for (int c = 0; c < CPU_SETSIZE; c++)
            if (CPU_ISSET(c, &all)) {
                CPU_SET(c, &one);
                break;
            }
    }
    const int n = 5;
    double multi[RUNS], single[RUNS], array[RUNS];
    for (int r = 0; r < RUNS; r++) {
        multi[r] = dab_seconds(e, &g, &d, n);
        if (pinned && pin_all_threads(&one) == 0) {
            single[r] = dab_seconds(e, &g, &d, n);
        } else {
            pinned = 0;
        }
        if (pinned) pin_all_threads(&all);
        double t0 = bench_now();
        for (int i = 0; i < n; i++)
            check(brush_dab_apply_array(&d, TILE_LAYER_COARSE, plain, area, &err), &err,
                  "brush_dab_apply_array");
        array[r] = (bench_now() - t0) / n;
    }
    edit_abort(e);
    double m = bench_median(multi, RUNS), a = bench_median(array, RUNS);
    printf("raise dab, radius 512 samples: %ld samples in the disc, %ld in the rect, 25 tiles\n",
           disc, rect);
    printf("  inside a stroke, %d threads: %.2f ms (%.2f ns per disc sample)\n", parallel_threads(),
           m * 1e3, m * 1e9 / disc);
    if (pinned) {
        double s = bench_median(single, RUNS);
        printf("  inside a stroke, the same threads pinned to one core: %.2f ms; scaling %.2fx\n",
               s * 1e3, s / m);
    } else {
        printf("  inside a stroke on one core: not measured (one CPU, or affinity refused)\n");
    }
    printf("  reference, brush_dab_apply_array on a plain %lldx%lld array (1 thread): %.2f ms; "
           "tiled %d threads / array = %.2f\n",
           (long long)(area.x1 - area.x0), (long long)(area.z1 - area.z0), a * 1e3,
           parallel_threads(), m / a);
    goal("raise dab r=512, ms inside a stroke", m * 1e3, 10.0, 0, " ms");
    free(plain);
    world_close(w);
}

// ---- 3 and 4. a 1000-dab stroke, its undo and redo, its history memory ------------------

// Samples whose bytes differ between a and b (elements of `el` bytes).
static long changed_samples(const unsigned char *a, const unsigned char *b, size_t bytes,
                            size_t el) {
    long n = 0;
    for (size_t i = 0; i < bytes; i += el)
        n += memcmp(a + i, b + i, el) != 0;
    return n;
}

static void copy_tile(world *w, tile_key key, void *out) {
    tile_view v;
    og_error err;
    check(tile_cache_acquire(world_cache(w), key, &v, &err), &err, "tile_cache_acquire");
    memcpy(out, v.data, tile_layer_bytes((tile_layer)key.layer));
    tile_cache_release(world_cache(w), &v);
}

static double stroke_seconds(world *w, const brush *b, double x0, double z0, double x1, double z1,
                             long *dabs) {
    og_error err;
    double t0 = bench_now();
    stroke *s = stroke_begin(w, b, &err);
    if (!s) check(-1, &err, "stroke_begin");
    check(stroke_to(s, x0, z0, 1.0, &err), &err, "stroke_to");
    check(stroke_to(s, x1, z1, 1.0, &err), &err, "stroke_to");
    *dabs = stroke_dab_count(s);
    check(stroke_end(s, &err), &err, "stroke_end");
    return bench_now() - t0;
}

// The same stroke drawn as the window draws it, one stroke_to per mouse move (each
// brings the mip levels up to date and publishes, so the viewport shows it live);
// *end_s gets stroke_end's share (the commit).
static double stroke_moves_seconds(world *w, const brush *b, double x0, double z0, double x1,
                                   double z1, int moves, double *end_s) {
    og_error err;
    double t0 = bench_now();
    stroke *s = stroke_begin(w, b, &err);
    if (!s) check(-1, &err, "stroke_begin");
    for (int i = 0; i <= moves; i++) {
        double f = (double)i / moves;
        check(stroke_to(s, x0 + f * (x1 - x0), z0 + f * (z1 - z0), 1.0, &err), &err, "stroke_to");
    }
    double t1 = bench_now();
    check(stroke_end(s, &err), &err, "stroke_end");
    double t2 = bench_now();
    *end_s = t2 - t1;
    return t2 - t0;
}

static void bench_stroke(void) {
    layer_grid g;
    world *w = bench_world(&g);
    brush b;
    brush_defaults(&b, BRUSH_RAISE);
    b.radius = 32.0;
    // A diagonal through the corner shared by tiles (0,0), (1,0), (0,1) and (1,1); the
    // discs stay inside those four. Dabs at 0, step, ..., 999 step: exactly 1000.
    const double x0 = 128, z0 = 128, x1 = 384, z1 = 384;
    b.spacing = hypot(x1 - x0, z1 - z0) / 999.5 / b.radius;
    long dabs;
    stroke_seconds(w, &b, x0, z0, x1, z1, &dabs); // warm: tiles resident and edited

    history *h = world_history(w);
    og_error err;
    double st[RUNS], un[RUNS], re[RUNS], ratio[RUNS];
    for (int r = 0; r < RUNS; r++) {
        st[r] = stroke_seconds(w, &b, x0, z0, x1, z1, &dabs);
        double t0 = bench_now();
        if (edit_undo(w, &err) != 1) check(-1, &err, "edit_undo");
        double t1 = bench_now();
        if (edit_redo(w, &err) != 1) check(-1, &err, "edit_redo");
        re[r] = bench_now() - t1;
        un[r] = t1 - t0;
        ratio[r] = (un[r] + re[r]) / st[r];
    }
    double s = bench_median(st, RUNS), u = bench_median(un, RUNS), d = bench_median(re, RUNS);
    double q = bench_median(ratio, RUNS);
    printf("stroke: %ld raise dabs of radius 32 samples, (128,128) to (384,384) m, over 4 tiles\n",
           dabs);
    printf("  stroke with undo capture %.2f ms (%.1f us per dab); undo %.2f ms; redo %.2f ms; "
           "(undo + redo) / stroke = %.3f\n",
           s * 1e3, s * 1e6 / (double)dabs, u * 1e3, d * 1e3, q);
    goal("(undo + redo) / stroke, 1000-dab stroke", q, 1.0, 1, "");

    // Drawn in 200 moves, against the same dabs in one move (whose mip levels are
    // brought up to date once): the live updates should cost little more than that.
    const int moves = 200;
    double mv[RUNS], mv_end[RUNS], one[RUNS], mv_ratio[RUNS];
    for (int r = 0; r < RUNS; r++) {
        one[r] = stroke_seconds(w, &b, x0, z0, x1, z1, &dabs);
        mv[r] = stroke_moves_seconds(w, &b, x0, z0, x1, z1, moves, &mv_end[r]);
        mv_ratio[r] = mv[r] / one[r];
    }
    printf("  drawn in %d moves (live mip levels and publishing per move): %.2f ms, stroke_end "
           "%.2f ms; in one move %.2f ms; ratio %.2f\n",
           moves, bench_median(mv, RUNS) * 1e3, bench_median(mv_end, RUNS) * 1e3,
           bench_median(one, RUNS) * 1e3, bench_median(mv_ratio, RUNS));
    goal("stroke in 200 moves / in one move", bench_median(mv_ratio, RUNS), 1.5, 0, "x");

    // The last stroke's step: compare every tile it holds before (undone) and after.
    const history_step *step = history_at(h, history_position(h) - 1);
    size_t tiles = step->tile_count;
    unsigned char **after = xmalloc((tiles ? tiles : 1) * sizeof *after);
    for (size_t i = 0; i < tiles; i++) {
        after[i] = xmalloc(tile_layer_bytes((tile_layer)step->tiles[i].key.layer));
        copy_tile(w, step->tiles[i].key, after[i]);
    }
    if (edit_undo(w, &err) != 1) check(-1, &err, "edit_undo");
    long changed = 0, changed0 = 0;
    size_t level0_tiles = 0, delta_bytes = 0;
    for (size_t i = 0; i < tiles; i++) {
        tile_key key = step->tiles[i].key;
        size_t bytes = tile_layer_bytes((tile_layer)key.layer);
        unsigned char *before = xmalloc(bytes);
        copy_tile(w, key, before);
        long c = changed_samples(before, after[i], bytes, bytes / TILE_SAMPLES);
        changed += c;
        if (key.level == 0) {
            changed0 += c;
            level0_tiles++;
        }
        delta_bytes += step->tiles[i].bytes;
        free(before);
        free(after[i]);
    }
    free(after);
    if (edit_redo(w, &err) != 1) check(-1, &err, "edit_redo");
    double held = (double)step->bytes;
    printf("  history: the step holds %zu bytes (%zu in %zu compressed tile deltas: %zu at level "
           "0, %zu mip tiles)\n",
           step->bytes, delta_bytes, tiles, level0_tiles, tiles - level0_tiles);
    printf("  vs raw bytes of its tiles (%zu): %.4f; vs 4 B x %ld samples changed (%ld at level 0, "
           "%ld in mips) = %ld B: %.3f (level 0 only: %.3f)\n",
           step->raw_bytes, held / (double)step->raw_bytes, changed, changed0, changed - changed0,
           4 * changed, held / (4.0 * (double)changed), held / (4.0 * (double)changed0));
    goal("stroke history bytes / (4 B x changed samples)", held / (4.0 * (double)changed), 1.0, 0,
         "x");

    // Crash recovery: the stroke's step appended to a recovery journal, as every
    // committed step is (the fdatasync runs on the journal's flusher thread).
    char dir[] = "/tmp/orogen-bench-journal-XXXXXX", path[64];
    if (!mkdtemp(dir)) check(-1, &err, "mkdtemp");
    snprintf(path, sizeof path, "%s/w.recover", dir);
    recovery_journal *j = recovery_journal_open(path, "", NULL, NULL, 0, &err);
    if (!j) check(-1, &err, "recovery_journal_open");
    double ap[RUNS], share[RUNS];
    for (int r = 0; r < RUNS; r++) {
        double t0 = bench_now();
        check(recovery_journal_append(j, RECOVERY_STEP, step, &err), &err, "journal append");
        // Until the writer thread has written it: the work, wherever it runs.
        check(recovery_journal_wait(j, &err), &err, "journal write");
        ap[r] = bench_now() - t0;
        share[r] = ap[r] / st[r];
    }
    recovery_journal_close(j);
    remove(path);
    remove(dir);
    double a = bench_median(ap, RUNS), sh = bench_median(share, RUNS);
    printf("  recovery journal: appending the step (%zu bytes) until written %.3f ms = %.2f%% of "
           "the stroke\n",
           step->bytes, a * 1e3, sh * 100);
    goal("recovery journal append / stroke, %", sh * 100, 5.0, 0, "%");
    world_close(w);
}

// ---- 5. erosion -------------------------------------------------------------------------

static void bench_erosion(void) {
    enum { N = 1024 };
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.spacing = 1.0;
    float *terrain = xmalloc((size_t)N * N * sizeof *terrain);
    float *h = xmalloc((size_t)N * N * sizeof *h), *wt = xmalloc((size_t)N * N * sizeof *wt);
    float *tile = xmalloc(tile_layer_bytes(TILE_LAYER_COARSE));
    for (int ty = 0; ty < N / TILE_SIZE; ty++)
        for (int tx = 0; tx < N / TILE_SIZE; tx++) {
            gen_tile(&p, (tile_key){TILE_LAYER_COARSE, 0, 0, tx, ty}, tile);
            for (int z = 0; z < TILE_SIZE; z++)
                memcpy(terrain + (size_t)(ty * TILE_SIZE + z) * N + tx * TILE_SIZE,
                       tile + z * TILE_SIZE, TILE_SIZE * sizeof *tile);
        }
    free(tile);
    for (int z = 0; z < N; z++)
        for (int x = 0; x < N; x++)
            wt[z * N + x] = x > 0 && z > 0 && x < N - 1 && z < N - 1 ? 1.0f : 0.0f;

    hydraulic_params hp;
    hydraulic_params_default(&hp);
    hp.droplets = 100000;
    thermal_params tp = {.talus_deg = 35.0f, .iterations = 20, .rate = 0.5f}; // brush defaults
    erosion_grid g = {h, wt, N, N, 1.0f, NULL};
    const int runs = 5;
    double hyd[5], th[5], copy[5];
    hydraulic_report rep = {0};
    for (int r = 0; r < runs; r++) {
        copy[r] = memcpy_seconds(h, terrain, (size_t)N * N * sizeof *h, 20);
        double t0 = bench_now();
        erosion_hydraulic(&g, &hp, &rep);
        hyd[r] = bench_now() - t0;
        memcpy(h, terrain, (size_t)N * N * sizeof *h);
        t0 = bench_now();
        erosion_thermal(&g, &tp);
        th[r] = bench_now() - t0;
    }
    double y = bench_median(hyd, runs), t = bench_median(th, runs), c = bench_median(copy, runs);
    printf("erosion on %dx%d samples (weight 1 inside a 1-sample zero border):\n", N, N);
    printf(
        "  hydraulic, %d droplets (default parameters): %.1f ms = %.2f M droplets/s "
        "(%d started, eroded %.0f m x cells); memcpy of the grid (4 MiB): %.3f ms; ratio %.0fx\n",
        hp.droplets, y * 1e3, hp.droplets / y / 1e6, rep.droplets, rep.eroded, c * 1e3, y / c);
    printf("  thermal, %d iterations (talus %g deg, rate %g): %.1f ms = %.2f ns per sample per "
           "iteration; %.0fx the memcpy\n",
           tp.iterations, tp.talus_deg, tp.rate, t * 1e3, t * 1e9 / ((double)N * N * tp.iterations),
           t / c);
    goal("hydraulic erosion, 100k droplets on 1024^2, ms", y * 1e3, 150.0, 0, " ms");
    free(terrain);
    free(h);
    free(wt);
}

// A 512x512 library stamp at 37 degrees, scale 1 (one sample per pixel), placed as
// its own undo step; reference: memcpy of the footprint's bytes.
static void bench_stamp(void) {
    layer_grid g;
    world *w = bench_world(&g);
    og_error err;
    stamp_source src;
    check(stamp_find("mountain", OROGEN_RESOURCE_DIR, NULL, &src, &err), &err, "stamp_find");
    stamp_placement p;
    stamp_placement_defaults(&p);
    p.x = p.z = 1024.0;
    p.rotation = 37.0;
    check(stamp_apply(w, &src, &p, &err), &err, "stamp warm-up"); // loads the tiles
    double t[RUNS], a[RUNS], c[RUNS];
    double half = 256.0 * (cos(37.0 * M_PI / 180.0) + sin(37.0 * M_PI / 180.0));
    size_t bytes = (size_t)(2 * half + 1) * (size_t)(2 * half + 1) * sizeof(float);
    float *buf = xmalloc(bytes), *dst = xmalloc(bytes);
    memset(buf, 0, bytes);
    int64_t side = (int64_t)(2 * half) + 8;
    float *plain = xmalloc((size_t)(side * side) * sizeof *plain);
    memset(plain, 0, (size_t)(side * side) * sizeof *plain);
    double cpu[RUNS];   // the process's CPU time (every thread's), steadier under load
    double a_cpu[RUNS]; // the plain array's (one thread)
    double squeeze[RUNS], squeeze_cpu[RUNS];
    // As a user's would, each step starts with the history's background zstd of the step
    // before finished (as dab_edit_seconds does): else it ends inside the step (history_push
    // on this thread, or the core the step's rows share), as much of it as the other core
    // left undone (the lead's two quiet runs before this: 3.73 and 4.95 ms). It is timed
    // right after the step instead, on this thread and the background's.
    history_undo_peek(world_history(w));
    for (int r = 0; r < RUNS; r++) {
        double t0 = bench_now(), c0 = bench_process_cpu();
        check(stamp_apply(w, &src, &p, &err), &err, "stamp_apply");
        t[r] = bench_now() - t0;
        cpu[r] = bench_process_cpu() - c0;
        t0 = bench_now(), c0 = bench_process_cpu();
        history_undo_peek(world_history(w));
        squeeze[r] = bench_now() - t0;
        squeeze_cpu[r] = bench_process_cpu() - c0;
        t0 = bench_now(), c0 = bench_thread_cpu();
        check(stamp_apply_array(world_get_params(w), &src, &p, plain, 1024 - side / 2,
                                1024 - side / 2, side, side, &err),
              &err, "stamp_apply_array");
        a[r] = bench_now() - t0;
        a_cpu[r] = bench_thread_cpu() - c0;
        c[r] = memcpy_seconds(dst, buf, bytes, 20);
    }
    printf("stamp: 512x512 library stamp at 37 degrees, scale 1 (%zu footprint samples)\n",
           bytes / sizeof(float));
    printf("  as its own undo step (rows on 2 threads + commit): %.2f ms (CPU time %.2f ms); "
           "plain array, 1 thread: %.2f ms; memcpy of the footprint: %.3f ms (%.0fx)\n",
           bench_median(t, RUNS) * 1e3, bench_median(cpu, RUNS) * 1e3, bench_median(a, RUNS) * 1e3,
           bench_median(c, RUNS) * 1e3, bench_median(t, RUNS) / bench_median(c, RUNS));
    printf("  then the history's zstd of its deltas (in the background; here waited for at "
           "once): %.2f ms (CPU time %.2f ms)\n",
           bench_median(squeeze, RUNS) * 1e3, bench_median(squeeze_cpu, RUNS) * 1e3);
    goal("512^2 stamp as its own undo step, ms", bench_median(t, RUNS) * 1e3, 3.2, 0, " ms");
    // Where the step's time goes beyond the stamp's own rows (the plain array's CPU).
    printf("  the step's CPU beyond the rows alone: %.2f ms (snapshots, the active layer's take, "
           "mip levels, undo encoding, history)\n",
           (bench_median(cpu, RUNS) - bench_median(a_cpu, RUNS)) * 1e3);
    free(buf);
    free(dst);
    free(plain);
    stamp_source_free(&src);
    world_close(w);
}

// The stamp command finds its image each time: the first read decodes the PNG, a read of
// the unchanged file again is the kept decode (a copy).
static void bench_stamp_find(void) {
    double first[RUNS], again[RUNS];
    og_error err;
    for (int r = 0; r < RUNS; r++) {
        stamp_source src;
        stamp_image_cache_clear();
        double t0 = bench_now();
        check(stamp_find("mountain", OROGEN_RESOURCE_DIR, NULL, &src, &err), &err, "stamp_find");
        first[r] = bench_now() - t0;
        stamp_source_free(&src);
        t0 = bench_now();
        check(stamp_find("mountain", OROGEN_RESOURCE_DIR, NULL, &src, &err), &err, "stamp_find");
        again[r] = bench_now() - t0;
        stamp_source_free(&src);
    }
    double ratio = bench_median(again, RUNS) / bench_median(first, RUNS);
    printf("  finding the 512x512 PNG stamp: first read (decode) %.2f ms, the same file again "
           "%.3f ms (%.3fx)\n",
           bench_median(first, RUNS) * 1e3, bench_median(again, RUNS) * 1e3, ratio);
    goal("stamp image found again vs its first read (decode)", ratio, 0.1, 0, "x");
}

// Runs the sections named on the command line (dab, dab512, stroke, erosion, stamp),
// or all of them.
static int wanted(int argc, char **argv, const char *section) {
    if (argc < 2) return 1;
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], section) == 0) return 1;
    return 0;
}

int main(int argc, char **argv) {
    bench_journals_private(); // no crash journals left in the user's folder
    double t0 = bench_now();
    printf("bench_edit: medians of %d runs (erosion: 5), %d threads in the editing pool\n", RUNS,
           parallel_threads());
    if (wanted(argc, argv, "dab")) {
        bench_dab64(BRUSH_RAISE, 8.0);
        bench_dab64(BRUSH_SMOOTH, 20.0);
    }
    if (wanted(argc, argv, "dab512")) bench_dab512();
    if (wanted(argc, argv, "stroke")) bench_stroke();
    if (wanted(argc, argv, "erosion")) bench_erosion();
    if (wanted(argc, argv, "stamp")) bench_stamp(), bench_stamp_find();
    int passed = 0;
    printf("summary (%.0f s):\n", bench_now() - t0);
    for (int i = 0; i < goal_count; i++) {
        printf("  %s  %s\n", goals[i].pass ? "PASS" : "MISS", goals[i].text);
        passed += goals[i].pass;
    }
    printf("  %d of %d goals met\n", passed, goal_count);
    return 0;
}
