// Seed 004's planet export (`export N FILE`) on an Earth-sized planet at subdivisions
// N = 8 and N = 10 with 782-pixel face images (the default size=1024 picks face-grid
// level 7), against the physical floor of writing the same bytes: memcpy of every
// file's contents into a buffer and write + fsync of it to a new file, as the export
// does (each file durable before the set is renamed into place).
// The first export also generates the images' tiles (reported apart); the figures are
// medians of the warm runs, where the tiles are in the cache.
#include "bench/bench_journals.h"
#include "bench/bench_timing.h"
#include "editor/interchange/export_planet.h"
#include "editor/world/world.h"

#include <dirent.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define RUNS 3

static void quiet(void *u, const char *m) {
    (void)u, (void)m;
}

static void check(int rc, const og_error *err, const char *what) {
    if (rc == 0) return;
    fprintf(stderr, "bench_planet_export: %s: %s\n", what, err->msg);
    exit(1);
}

// memcpy + write + fsync of every file in dir into dir/copy: seconds, and bytes.
static double copy_floor(const char *dir, long long *bytes) {
    char copies[4300];
    snprintf(copies, sizeof copies, "%s/copy", dir);
    mkdir(copies, 0755);
    DIR *d = opendir(dir);
    struct dirent *e;
    char *files[64];
    size_t sizes[64];
    char names[64][256];
    int count = 0;
    *bytes = 0;
    while ((e = readdir(d)) && count < 64) {
        char path[4500];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) continue;
        FILE *f = fopen(path, "rb");
        files[count] = malloc((size_t)st.st_size + 1);
        sizes[count] = fread(files[count], 1, (size_t)st.st_size, f);
        fclose(f);
        snprintf(names[count], sizeof names[0], "%s", e->d_name);
        *bytes += (long long)sizes[count];
        count++;
    }
    closedir(d);
    double t0 = bench_now();
    for (int i = 0; i < count; i++) {
        char *buf = malloc(sizes[i] + 1);
        memcpy(buf, files[i], sizes[i]);
        char path[4500];
        snprintf(path, sizeof path, "%s/%s", copies, names[i]);
        int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        size_t done = 0;
        while (done < sizes[i]) {
            ssize_t n = write(fd, buf + done, sizes[i] - done);
            if (n <= 0) break;
            done += (size_t)n;
        }
        fsync(fd);
        close(fd);
        free(buf);
    }
    double t = bench_now() - t0;
    for (int i = 0; i < count; i++)
        free(files[i]);
    return t;
}

int main(void) {
    bench_journals_private(); // no crash journals left in the user's folder
    world_params p;
    world_params_default(&p, WORLD_PLANET);
    world_settings s = {.cache_budget_bytes = (size_t)2 << 30, .workers = 2, .warn = quiet};
    og_error err;
    world *w = world_create(&p, &s, &err);
    if (!w) check(-1, &err, "world_create");
    char dir[] = "/tmp/orogen-bench-planet-XXXXXX";
    if (!mkdtemp(dir)) return 1;
    printf("Earth-sized planet (radius %.0f m, %.0f m spacing), default size=1024\n", p.radius,
           p.spacing);
    const int levels[2] = {8, 10};
    for (int k = 0; k < 2; k++) {
        char sub[256], path[512];
        snprintf(sub, sizeof sub, "%s/n%d", dir, levels[k]);
        mkdir(sub, 0755);
        snprintf(path, sizeof path, "%s/planet.obj", sub);
        export_planet_report r;
        double cold = 0, t[RUNS], floor_t[RUNS];
        long long bytes = 0;
        for (int run = 0; run <= RUNS; run++) {
            double t0 = bench_now();
            check(export_planet(w, levels[k], path, 0, &r, &err), &err, "export");
            double dt = bench_now() - t0;
            if (run == 0)
                cold = dt;
            else
                t[run - 1] = dt, floor_t[run - 1] = copy_floor(sub, &bytes);
        }
        double ours = bench_median(t, RUNS), peer = bench_median(floor_t, RUNS);
        printf("export %d: %zu vertices, %zu triangles, 12 images of %d px, %d files, %lld "
               "bytes\n",
               levels[k], r.vertices, r.triangles, r.image_size, r.files, bytes);
        printf("  orogen export %.3f s (first run, generating the tiles: %.3f s); memcpy + write "
               "+ fsync of the same bytes %.3f s: %.1fx the floor (%.1f MB/s vs %.1f MB/s)\n",
               ours, cold, peer, ours / peer, bytes / ours / 1e6, bytes / peer / 1e6);
    }
    char cmd[4300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
    world_close(w);
    return 0;
}
