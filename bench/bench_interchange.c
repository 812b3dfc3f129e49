// Import and export against the tools everyone uses for the same conversions, in
// the same run: an 8192^2 16-bit PNG imported into a world and exported as a float
// EXR against `oiiotool in.png -d float -o out.exr`; SRTM .hgt tiles (1201^2, and a
// 3601^2 one made from it by GDAL) imported against
// `gdal_translate -ot Float32` to a raw float file. Medians of 3. Goal: <= 1.5x.
// Also the same PNG -> EXR as whole processes (orogen start to exit against oiiotool;
// goal <= 1.2x) and a tiled export split over 2 processes against 1 (goal >= 1.8x; at
// once, and each alone under the load the 1-process run had), of a generated world and
// of one made from a 16-bit PNG (`new flat from=`).
// Usage: bench_interchange [--only exr|shards] [DEM.hgt] (default tests/data/dem/N44W072.hgt)
#include "bench/bench_journals.h"
#include "bench/bench_timing.h"
#include "editor/interchange/export.h"
#include "editor/interchange/import.h"
#include "editor/world/world.h"
#include "io/image_read.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

enum { REPS = 3, SIDE = 8192 };

// User + system seconds of the waited-for children so far (all their threads).
static double children_cpu(void) {
    struct rusage u;
    getrusage(RUSAGE_CHILDREN, &u);
    return (double)u.ru_utime.tv_sec + u.ru_utime.tv_usec * 1e-6 + (double)u.ru_stime.tv_sec +
           u.ru_stime.tv_usec * 1e-6;
}

// Wall seconds of cmd; *cpu (may be NULL) gets its CPU seconds.
static double run_tool_cpu(const char *cmd, double *cpu) {
    double t0 = bench_now(), c0 = children_cpu();
    if (system(cmd) != 0) {
        fprintf(stderr, "bench_interchange: '%s' failed\n", cmd);
        exit(1);
    }
    if (cpu) *cpu = children_cpu() - c0;
    return bench_now() - t0;
}

static double run_tool(const char *cmd) {
    return run_tool_cpu(cmd, NULL);
}

static long long file_bytes(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 ? (long long)st.st_size : -1;
}

static world *bounded_world(int64_t size, double spacing) {
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.generator = GEN_FLAT;
    p.size = size;
    p.spacing = spacing;
    world_settings s = {.cache_budget_bytes = (size_t)3 << 30, .workers = 2};
    og_error err;
    world *w = world_create(&p, &s, &err);
    if (!w) {
        fprintf(stderr, "bench_interchange: %s\n", err.msg);
        exit(1);
    }
    return w;
}

// One orogen process making `world` and writing shard i of count of a 4x4 tiled float EXR
// export of it (without export: only the world, to time a shard's fixed part), pinned to
// core `core`, with one cache worker: a shard stands for one machine's core, so runs
// compare the same work split, not thread counts. Processes, not fork() alone: this one
// has thread pools a forked child would lack.
static pid_t start_shard(const char *world, const char *dir, int i, int count, int core,
                         int export) {
    pid_t pid = fork();
    if (pid != 0) return pid;
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "%s", world);
    if (export)
        snprintf(cmd + strlen(cmd), sizeof cmd - strlen(cmd),
                 "; export %s/tiles.exr tiles=4x4 shard=%d/%d", dir, i, count);
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(core, &one);
    sched_setaffinity(0, sizeof one, &one);
    int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    execl(OROGEN_BINARY, OROGEN_BINARY, "--workers", "1", "-c", cmd, (char *)NULL);
    _exit(127);
}

// Waits for every child; *critical gets the CPU seconds of the busiest one, and each[i]
// (each may be NULL) those of child pids[i].
static void wait_shards(double *critical, const pid_t *pids, double *each, int count) {
    int ok = 1, status;
    struct rusage u;
    pid_t pid;
    *critical = 0;
    while ((pid = wait4(-1, &status, 0, &u)) > 0) {
        ok &= WIFEXITED(status) && WEXITSTATUS(status) == 0;
        double cpu = (double)u.ru_utime.tv_sec + u.ru_utime.tv_usec * 1e-6 +
                     (double)u.ru_stime.tv_sec + u.ru_stime.tv_usec * 1e-6;
        if (cpu > *critical) *critical = cpu;
        for (int i = 0; each && i < count; i++)
            if (pids[i] == pid) each[i] = cpu;
    }
    if (!ok) {
        fprintf(stderr, "bench_interchange: a shard failed\n");
        exit(1);
    }
}

// Wall time of `count` (<= 2) shard processes at once, each on a core of its own (as GNU
// parallel would run them); *critical gets the CPU seconds of the busiest shard, each[i]
// those of shard i.
static double sharded(const char *world, const char *dir, int count, double *critical,
                      double *each) {
    double t0 = bench_now();
    pid_t pids[2];
    for (int i = 0; i < count; i++)
        pids[i] = start_shard(world, dir, i, count, i % (int)sysconf(_SC_NPROCESSORS_ONLN), 1);
    wait_shards(critical, pids, each, count);
    return bench_now() - t0;
}

// The longest wall time of `count` shards run one after another on core 0: the build's
// wall time with a machine per shard (what sharding is for), measured under the same
// load as the one-process run beside it, so it needs no idle second core.
static double longest_shard_alone(const char *world, const char *dir, int count) {
    double longest = 0, cpu;
    for (int i = 0; i < count; i++) {
        double t0 = bench_now();
        start_shard(world, dir, i, count, 0, 1);
        wait_shards(&cpu, NULL, NULL, 0);
        longest = fmax(longest, bench_now() - t0);
    }
    return longest;
}

// The tiled export of `world` as 1 process against 2 shards (at once, and each alone),
// interleaved, medians of 5: the machine is shared, and its load drifts over a run.
static int bench_shards(const char *label, const char *world, const char *dir) {
    enum { SHARD_REPS = 5 };
    double t1[SHARD_REPS], t2[SHARD_REPS], ta[SHARD_REPS], c1[SHARD_REPS], c2[SHARD_REPS],
        ts[SHARD_REPS], cs[SHARD_REPS], each[2][SHARD_REPS], load0[3], load1[3];
    if (getloadavg(load0, 3) != 3) load0[0] = -1;
    for (int i = 0; i < SHARD_REPS; i++) {
        double two_cpu[2];
        t1[i] = sharded(world, dir, 1, &c1[i], NULL);
        t2[i] = sharded(world, dir, 2, &c2[i], two_cpu);
        each[0][i] = two_cpu[0], each[1][i] = two_cpu[1];
        ta[i] = longest_shard_alone(world, dir, 2);
        // The fixed part of every shard: start-up, world making and exit.
        double t0 = bench_now();
        start_shard(world, dir, 0, 1, 0, 0);
        wait_shards(&cs[i], NULL, NULL, 0);
        ts[i] = bench_now() - t0;
    }
    if (getloadavg(load1, 3) != 3) load1[0] = -1;
    double one = bench_median(t1, SHARD_REPS), two = bench_median(t2, SHARD_REPS),
           alone = bench_median(ta, SHARD_REPS), fixed = bench_median(ts, SHARD_REPS);
    const long cores = sysconf(_SC_NPROCESSORS_ONLN);
    printf("tiled export (orogen processes, 1 worker and 1 core each; %s, 4x4 float EXR tiles; "
           "machine load %.1f at the start, %.1f at the end, %ld cores):\n",
           label, load0[0], load1[0], cores);
    printf("  2 shards in parallel on this machine: 1 shard %.2f s, 2 shards %.2f s; speed-up "
           "%.2fx (goal >= 1.8x) %s%s\n",
           one, two, one / two, one / two >= 1.8 ? "PASS" : "MISS",
           load0[0] > cores - 2 || load1[0] > cores - 2
               ? " (the other load leaves no second core free: see the next lines)"
               : "");
    printf("  a machine per shard (each shard alone, under the same load as the 1-shard run): "
           "longest shard %.2f s; speed-up %.2fx (goal >= 1.8x) %s\n",
           alone, one / alone, one / alone >= 1.8 ? "PASS" : "MISS");
    printf("  fixed cost of a shard (start-up, world, exit; no export): %.3f s, %.1f%% of one "
           "shard of 2; CPU %.3f s\n",
           fixed, 100.0 * fixed / alone, bench_median(cs, SHARD_REPS));
    // Each process's own CPU seconds: the speed-up with a core per shard, which the wall
    // times above only show on a machine nothing else is using.
    one = bench_median(c1, SHARD_REPS), two = bench_median(c2, SHARD_REPS);
    printf("  CPU seconds of the busiest process: 1 shard %.2f s, 2 shards %.2f s (shard 0 %.2f s, "
           "shard 1 %.2f s); speed-up %.2fx with a core per shard (goal >= 1.8x) %s\n",
           one, two, bench_median(each[0], SHARD_REPS), bench_median(each[1], SHARD_REPS),
           one / two, one / two >= 1.8 ? "PASS" : "MISS");
    return 0;
}

// Imports an SRTM tile into a 3601^2 world at 30 m against gdal_translate writing it
// as raw floats; prints both medians.
static int bench_dem(const char *dem, const char *raw) {
    double t_dem[REPS], t_gdal[REPS];
    char cmd[1024];
    og_error err;
    for (int i = 0; i < REPS; i++) {
        world *w = bounded_world(3601, 30.0);
        import_options o;
        import_options_defaults(&o);
        o.spacing = 30.0;
        double t0 = bench_now();
        if (import_apply(w, dem, &o, NULL, &err) != 0) {
            fprintf(stderr, "bench_interchange: %s\n", err.msg);
            return 1;
        }
        t_dem[i] = bench_now() - t0;
        world_close(w);
        snprintf(cmd, sizeof cmd, "gdal_translate -q -of ENVI -ot Float32 '%s' '%s'", dem, raw);
        t_gdal[i] = run_tool(cmd);
    }
    double d = bench_median(t_dem, REPS), g = bench_median(t_gdal, REPS);
    printf("%s import: orogen %.3f s; gdal_translate to raw float %.3f s; ratio %.2fx "
           "(goal <= 1.5x) %s\n",
           strrchr(dem, '/') ? strrchr(dem, '/') + 1 : dem, d, g, d / g,
           d / g <= 1.5 ? "MET" : "MISS");
    return 0;
}

int main(int argc, char **argv) {
    bench_journals_private(); // no crash journals left in the user's folder
    // --only exr | shards: just that part (the machine is shared; benches run sparingly).
    const char *only = argc > 2 && !strcmp(argv[1], "--only") ? argv[2] : NULL;
    if (only) argc -= 2, argv += 2;
    const char *dem = argc > 1 ? argv[1] : OROGEN_SOURCE_DIR "/tests/data/dem/N44W072.hgt";
    char dir[] = "/tmp/orogen-bench-ix-XXXXXX";
    if (!mkdtemp(dir)) return 1;
    char png[256], exr[256], peer_exr[256], raw[256], cmd[1024];
    snprintf(png, sizeof png, "%s/in.png", dir);
    snprintf(exr, sizeof exr, "%s/out.exr", dir);
    snprintf(peer_exr, sizeof peer_exr, "%s/peer.exr", dir);
    snprintf(raw, sizeof raw, "%s/peer.bil", dir);

    if (only && !strcmp(only, "shards")) goto shards;
    // A terrain-like 16-bit image: smooth relief plus fine detail (compresses like one).
    float *h = malloc(sizeof(float) * SIDE * SIDE);
    for (int z = 0; z < SIDE; z++)
        for (int x = 0; x < SIDE; x++) {
            double v = 0.5 + 0.3 * sin(x * 0.003) * cos(z * 0.004) +
                       0.1 * sin(x * 0.05 + z * 0.03) + 0.02 * sin(x * 0.9) * sin(z * 1.1);
            h[(size_t)z * SIDE + x] = (float)(v * 65535.0);
        }
    og_error err;
    if (image_write_samples(png, h, SIDE, SIDE, IMAGE_WRITE_UINT16, NULL, &err) != 0) {
        fprintf(stderr, "bench_interchange: %s\n", err.msg);
        return 1;
    }
    free(h);

    double t_import[REPS], t_export[REPS], t_peer[REPS];
    for (int i = 0; i < REPS; i++) {
        world *w = bounded_world(SIDE, 1.0);
        import_options o;
        import_options_defaults(&o);
        o.has_min_max = 3, o.min = 0, o.max = 1000;
        double t0 = bench_now();
        if (import_apply(w, png, &o, NULL, &err) != 0) {
            fprintf(stderr, "bench_interchange: %s\n", err.msg);
            return 1;
        }
        t_import[i] = bench_now() - t0;
        export_options e;
        export_options_defaults(&e);
        t0 = bench_now();
        if (export_heightmap(w, exr, &e, NULL, NULL, &err) != 0) {
            fprintf(stderr, "bench_interchange: %s\n", err.msg);
            return 1;
        }
        t_export[i] = bench_now() - t0;
        world_close(w);
        snprintf(cmd, sizeof cmd, "oiiotool '%s' -d float -o '%s'", png, peer_exr);
        t_peer[i] = run_tool(cmd);
    }
    double imp = bench_median(t_import, REPS), ex = bench_median(t_export, REPS),
           peer = bench_median(t_peer, REPS);
    printf("8192^2 PNG16 -> EXR float: orogen import %.2f s + export %.2f s = %.2f s; "
           "oiiotool %.2f s; ratio %.2fx (goal <= 1.5x) %s\n",
           imp, ex, imp + ex, peer, (imp + ex) / peer, (imp + ex) / peer <= 1.5 ? "PASS" : "MISS");
    printf("  import alone %.2fx, export alone %.2fx of oiiotool's conversion\n", imp / peer,
           ex / peer);

    // As a user runs it: one orogen process from start to exit (loading, world making,
    // import, export) against one oiiotool process, alternated, medians of 3.
    double t_whole[REPS], t_tool[REPS], c_whole[REPS], c_tool[REPS];
    for (int i = 0; i < REPS; i++) {
        snprintf(cmd, sizeof cmd, "'%s' -c 'new flat from=%s min=0 max=1000; export %s' >/dev/null",
                 OROGEN_BINARY, png, exr);
        t_whole[i] = run_tool_cpu(cmd, &c_whole[i]);
        snprintf(cmd, sizeof cmd, "oiiotool '%s' -d float -o '%s'", png, peer_exr);
        t_tool[i] = run_tool_cpu(cmd, &c_tool[i]);
    }
    double whole = bench_median(t_whole, REPS), tool = bench_median(t_tool, REPS);
    printf("8192^2 PNG16 -> EXR float, whole processes: orogen %.2f s, oiiotool %.2f s; ratio "
           "%.2fx (goal <= 1.2x) %s\n",
           whole, tool, whole / tool, whole / tool <= 1.2 ? "PASS" : "MISS");
    // The work, all threads counted (what a machine shared with other jobs sees; both
    // compress on every core, so wall time alone swings with the load).
    whole = bench_median(c_whole, REPS), tool = bench_median(c_tool, REPS);
    printf("  the same in CPU seconds (user + system, all threads): orogen %.2f s, oiiotool %.2f "
           "s; ratio %.2fx (goal <= 1.2x) %s\n",
           whole, tool, whole / tool, whole / tool <= 1.2 ? "PASS" : "MISS");
    printf("  files: orogen %lld bytes, oiiotool %lld bytes (both ZIP, deflate level 4; the "
           "heights in metres carry more mantissa bits than oiiotool's 0..1 values)\n",
           file_bytes(exr), file_bytes(peer_exr));
    if (only && !strcmp(only, "exr")) goto done; // its 500 MB of files go too

    if (bench_dem(dem, raw) != 0) return 1;
    // SRTM1's 3601^2 (1 arc-second) tiles: made from the 3 arc-second one by GDAL.
    char dem1[300];
    snprintf(dem1, sizeof dem1, "%s/N44W072.hgt", dir);
    snprintf(cmd, sizeof cmd,
             "gdal_translate -q -of SRTMHGT -outsize 3601 3601 -r bilinear '%s' '%s'", dem, dem1);
    if (system(cmd) != 0) {
        fprintf(stderr, "bench_interchange: could not make a 3601^2 .hgt: %s\n", cmd);
        return 1;
    }
    if (bench_dem(dem1, raw) != 0) return 1;
    {
        // A 4096^2 region (4097^2 samples) of generated terrain as a simplified .glb.
        world_params p;
        world_params_default(&p, WORLD_FLAT);
        p.size = 4097;
        world_settings ws = {.cache_budget_bytes = (size_t)2 << 30, .workers = 2};
        world *w = world_create(&p, &ws, &err);
        export_options e;
        export_options_defaults(&e);
        e.simplify = 0.5;
        char glb[300];
        snprintf(glb, sizeof glb, "%s/terrain.glb", dir);
        export_mesh_report m;
        if (!w || export_mesh_file(w, glb, &e, &m, &err) != 0) { // warms the cache
            fprintf(stderr, "bench_interchange: %s\n", err.msg);
            return 1;
        }
        double t0 = bench_now();
        export_mesh_file(w, glb, &e, &m, &err);
        double t = bench_now() - t0;
        printf(".glb of a 4096^2 region, simplify=%.2f m: %.2f s, %.2f M input triangles/s; %zu "
               "-> %zu triangles; height error %.3f m against the %.2f m target %s\n",
               e.simplify, t, (double)m.input_triangles / t / 1e6, m.input_triangles, m.triangles,
               m.achieved_error, e.simplify, m.achieved_error <= e.simplify ? "MET" : "MISS");
        world_close(w);
    }
shards:;
    // Two worlds: generated (its tiles made as they are read) and made from a 16-bit PNG of
    // the same terrain (`new flat from=`: the raster is decoded whole, then a shard imports
    // only the tiles its part reads, editor/cmd/base_pending.h).
    char world_png[256], from_png[600];
    snprintf(world_png, sizeof world_png, "%s/world.png", dir);
    snprintf(cmd, sizeof cmd, "'%s' -c 'new flat; set size 4097; generate; export %s' >/dev/null",
             OROGEN_BINARY, world_png);
    run_tool(cmd);
    snprintf(from_png, sizeof from_png, "new flat from=%s", world_png);
    const struct {
        const char *label, *world;
    } worlds[2] = {{"4097^2 generated world", "new flat; set size 4097; generate"},
                   {"4097^2 world from a 16-bit PNG (new flat from=)", from_png}};
    for (int k = 0; k < 2; k++)
        if (bench_shards(worlds[k].label, worlds[k].world, dir) != 0) return 1;
done:
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : 1;
}
