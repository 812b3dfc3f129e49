// Writes a contact sheet of the material textures to look at: each tiled 2 x 2 (so a
// seam would show), four to a row, albedo above its height channel:
//   material_sheet OUT.png
// and prints how long generating all of them took (one thread).
#include "io/image_read.h"
#include "renderer/material_textures.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define S MATERIAL_TEXTURE_SIZE
#define REP 2     // repeats per side
#define PER_ROW 4 // textures per row

static double now_ms(clockid_t clock) {
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: material_sheet OUT.png\n");
        return 2;
    }
    enum { COUNT = MATERIAL_TEXTURE_COUNT, ROWS = (COUNT + PER_ROW - 1) / PER_ROW };
    static unsigned char tex[COUNT][S * S * 4];
    // CPU time as well as wall time: on a busy machine the wall time mostly measures
    // the other processes.
    const double w0 = now_ms(CLOCK_MONOTONIC), c0 = now_ms(CLOCK_THREAD_CPUTIME_ID);
    for (int i = 0; i < COUNT; i++)
        material_texture_generate(i, tex[i]);
    const double w1 = now_ms(CLOCK_MONOTONIC), c1 = now_ms(CLOCK_THREAD_CPUTIME_ID);
    printf("generated %d textures in %.1f ms (%.1f ms of CPU)\n", COUNT, w1 - w0, c1 - c0);

    const int cw = S * REP, ch = S * REP;          // one cell: a tiled texture
    const int w = PER_ROW * cw, h = ROWS * 2 * ch; // albedo row, then height row
    unsigned char *img = calloc((size_t)w * h, 3);
    if (!img) return 1;
    for (int i = 0; i < COUNT; i++) {
        const int ox = (i % PER_ROW) * cw, oy = (i / PER_ROW) * 2 * ch;
        for (int y = 0; y < ch; y++)
            for (int x = 0; x < cw; x++) {
                const unsigned char *p = tex[i] + 4 * ((size_t)(y % S) * S + (size_t)(x % S));
                unsigned char *a = img + 3 * ((size_t)(oy + y) * w + (size_t)(ox + x));
                unsigned char *b = img + 3 * ((size_t)(oy + ch + y) * w + (size_t)(ox + x));
                a[0] = p[0], a[1] = p[1], a[2] = p[2];
                b[0] = b[1] = b[2] = p[3];
            }
    }
    og_error err;
    int rc = image_write_rgb8(argv[1], img, w, h, &err);
    free(img);
    if (rc != 0) {
        fprintf(stderr, "material_sheet: %s\n", err.msg);
        return 1;
    }
    for (int i = 0; i < COUNT; i++)
        printf("%d %s\n", i, material_texture_name(i));
    return 0;
}
