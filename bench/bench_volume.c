// Volume layer benchmarks, each figure beside its reference from the same run:
//  1. a volume brush dab (carve, radius 16 voxels, one undo step each: begin, first-
//     touch snapshots, commit) in voxels visited per second, against the 2D raise dab
//     of the same radius (one undo step each) in samples per second;
//  2. re-meshing after a dab: the viewport's surface nets over every brick the dab
//     touched, in milliseconds, against the dab itself;
//  3. `.vdb` export of a 1024 x 1024-voxel region of the default world (with a carved
//     tunnel) in voxels computed per second, against OpenVDB's tools::meshToLevelSet
//     building the same narrow-band level set from the heightfield's triangle mesh
//     (goal: at least as fast).
// Medians of several runs; goals are reported (PASS/MISS), not asserted.
#include "bench/bench_journals.h"
#include "bench/bench_timing.h"
#include "editor/interchange/export_vdb.h"
#include "editor/tools/stroke.h"
#include "editor/tools/volume_brush.h"
#include "editor/world/layer_grid.h"
#include "editor/world/volume_mesh.h"
#include "editor/world/world.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define DAB_RUNS 15
#define EXPORT_RUNS 3
#define REGION 1024

double peer_vdb_mesh_to_level_set(const float *heights, int n, double spacing, double x0, double z0,
                                  double voxel, int half_width, long long *active);

static void quiet(void *u, const char *m) {
    (void)u, (void)m;
}

static void check(int rc, const og_error *err, const char *what) {
    if (rc == 0) return;
    fprintf(stderr, "bench_volume: %s: %s\n", what, err->msg);
    exit(1);
}

static double ground(world *w, double x, double z) {
    double h = 0;
    og_error err;
    check(world_sample(w, 0, x, z, &h, &err), &err, "sample");
    return h;
}

int main(void) {
    bench_journals_private(); // no crash journals left in the user's folder
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    p.spacing = 1;
    world_settings s = {.cache_budget_bytes = (size_t)2 << 30, .workers = 2, .warn = quiet};
    og_error err;
    world *w = world_create(&p, &s, &err);
    if (!w) check(-1, &err, "world_create");

    // 1. Dabs: carve (3D) and raise (2D), radius 16, one undo step each.
    const double radius = 16;
    double carve_t[DAB_RUNS], raise_t[DAB_RUNS];
    long long voxels = 0;
    brush carve;
    brush_defaults(&carve, BRUSH_CARVE);
    carve.radius = radius;
    brush raise;
    brush_defaults(&raise, BRUSH_RAISE);
    raise.radius = radius;
    for (int r = 0; r < DAB_RUNS; r++) {
        double x = 100 + 70 * r, z = 300;
        double at[1][3] = {{x, ground(w, x, z), z}};
        double t0 = bench_now();
        check(volume_brush_apply(w, &carve, (const double(*)[3])at, NULL, 1, &err), &err, "carve");
        carve_t[r] = bench_now() - t0;
        voxels = volume_brush_last_voxels();
        t0 = bench_now();
        stroke *st = stroke_begin(w, &raise, &err);
        if (!st) check(-1, &err, "stroke_begin");
        check(stroke_to(st, x, z + 200, 1.0, &err), &err, "stroke_to");
        check(stroke_end(st, &err), &err, "stroke_end");
        raise_t[r] = bench_now() - t0;
    }
    double samples = (2 * radius + 1) * (2 * radius + 1); // the dab's box of samples
    double ct = bench_median(carve_t, DAB_RUNS), rt = bench_median(raise_t, DAB_RUNS);
    printf("volume carve dab r=16 voxels: %.3f ms, %lld voxels visited: %.1f M voxels/s\n",
           ct * 1e3, voxels, voxels / ct * 1e-6);
    printf("2D raise dab r=16 samples:    %.3f ms, %.0f samples: %.1f M samples/s\n", rt * 1e3,
           samples, samples / rt * 1e-6);
    printf("  per voxel vs per sample: %.2fx the raise dab's rate\n",
           (voxels / ct) / (samples / rt));

    // 2. Re-meshing the bricks one dab touched (what the viewport does after it).
    double mesh_t[DAB_RUNS];
    long long bricks_meshed = 0, triangles = 0;
    volume_grid vg;
    check(volume_grid_init(&vg, world_get_params(w), &err), &err, "volume grid");
    for (int r = 0; r < DAB_RUNS; r++) {
        double x = 100 + 70 * r, z = 300, y = ground(w, x, z);
        double lo[3] = {x, y, z};
        volume_box box = volume_grid_box_around(&vg, lo, lo, radius + VOLUME_EXACT_VOXELS);
        double t0 = bench_now();
        bricks_meshed = triangles = 0;
        tile_key keys[64];
        if (volume_box_bricks(box) > 64) return 1; // a radius-16 dab touches a dozen at most
        size_t n = volume_box_brick_keys(box, keys);
        for (size_t b = 0; b < n; b++) {
            volume_mesh m;
            check(volume_mesh_brick(w, &vg, keys[b], &m, &err), &err, "mesh");
            triangles += (long long)(m.index_count / 3);
            bricks_meshed++;
            volume_mesh_free(&m);
        }
        mesh_t[r] = bench_now() - t0;
    }
    double mt = bench_median(mesh_t, DAB_RUNS);
    printf("re-meshing after a carve dab: %.2f ms for %lld bricks (%lld triangles), %.2fx the "
           "dab's %.2f ms\n",
           mt * 1e3, bricks_meshed, triangles, mt / ct, ct * 1e3);

    // 3. Export of a 1024^2 region with a tunnel through it.
    double x0 = 2048, z0 = 2048;
    double tunnel[3][3] = {
        {x0 + 100, 0, z0 + 500}, {x0 + 500, 0, z0 + 520}, {x0 + 900, 0, z0 + 400}};
    for (int i = 0; i < 3; i++)
        tunnel[i][1] = ground(w, tunnel[i][0], tunnel[i][2]) - 12;
    carve.radius = 8;
    check(volume_brush_apply(w, &carve, (const double(*)[3])tunnel, NULL, 3, &err), &err, "tunnel");
    export_options o;
    export_options_defaults(&o);
    o.has_region = 1;
    o.x0 = x0, o.z0 = z0, o.x1 = x0 + REGION - 1, o.z1 = z0 + REGION - 1;
    char path[] = "/tmp/orogen-bench-volume-XXXXXX";
    if (!mkdtemp(path)) return 1;
    char file[256];
    snprintf(file, sizeof file, "%s/region.vdb", path);
    double ours[EXPORT_RUNS], peer[EXPORT_RUNS];
    export_vdb_report rep;
    for (int r = 0; r < EXPORT_RUNS; r++) {
        double t0 = bench_now();
        check(export_vdb_file(w, file, &o, &rep, &err), &err, "export .vdb");
        ours[r] = bench_now() - t0;
    }
    layer_grid g;
    check(layer_grid_init(&g, world_get_params(w), TILE_LAYER_COARSE, 0, &err), &err, "grid");
    float *h = malloc((size_t)REGION * REGION * sizeof *h);
    grid_rect rect = {(int64_t)x0, (int64_t)z0, (int64_t)x0 + REGION, (int64_t)z0 + REGION};
    check(layer_grid_read(w, &g, rect, h, &err), &err, "read heights");
    long long peer_active = 0;
    for (int r = 0; r < EXPORT_RUNS; r++)
        peer[r] = peer_vdb_mesh_to_level_set(h, REGION, 1.0, x0, z0, 1.0, 3, &peer_active);
    double mo = bench_median(ours, EXPORT_RUNS), mp = bench_median(peer, EXPORT_RUNS);
    printf(".vdb export of %d x %d voxel columns, band 3: %.3f s (whole command: heights, "
           "bricks, level set, file of %lld bytes), %lld voxels computed: %.1f M voxels/s, "
           "%lld active\n",
           REGION, REGION, mo, rep.bytes, rep.voxels_written, rep.voxels_written / mo * 1e-6,
           rep.active_voxels);
    printf("OpenVDB meshToLevelSet of the same heightfield's %d triangles: %.3f s, %lld active "
           "(level set only, no file)\n",
           2 * (REGION - 1) * (REGION - 1), mp, peer_active);
    printf("  export / meshToLevelSet: %.2fx (goal <= 1: %s)\n", mo / mp,
           mo <= mp ? "PASS" : "MISS");
    unlink(file);
    rmdir(path);
    free(h);
    world_close(w);
    return 0;
}
