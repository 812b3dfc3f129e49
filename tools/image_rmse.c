// Compares two images for the golden-image tests in shell:
//   image_rmse A.png B.png [--max X] [--diff OUT.png]
// prints rmse=VALUE (io/image_compare.h: 0..255, a uniform difference d gives d), exits 1
// when the RMSE exceeds X, and with --diff writes |A-B|*4 (clamped) so a failing test
// leaves a visible difference behind. Exit 2 on bad usage or unreadable images.
#include "io/image_compare.h"
#include "io/image_read.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// The gain on |A-B| in the diff image: differences of a few levels become visible.
#define DIFF_GAIN 4

static int usage(void) {
    fprintf(stderr, "usage: image_rmse A.png B.png [--max X] [--diff OUT.png]\n");
    return 2;
}

int main(int argc, char **argv) {
    const char *paths[2] = {NULL, NULL};
    const char *diff_path = NULL;
    double max = INFINITY;
    int npaths = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--max") == 0 && i + 1 < argc) {
            char *end;
            errno = 0;
            max = strtod(argv[++i], &end);
            if (errno || end == argv[i] || *end || !(max >= 0)) {
                fprintf(stderr, "image_rmse: --max wants a number >= 0, not \"%s\"\n", argv[i]);
                return 2;
            }
        } else if (strcmp(argv[i], "--diff") == 0 && i + 1 < argc) {
            diff_path = argv[++i];
        } else if (argv[i][0] == '-' && argv[i][1] == '-') {
            return usage();
        } else if (npaths < 2) {
            paths[npaths++] = argv[i];
        } else {
            return usage();
        }
    }
    if (npaths != 2) return usage();

    og_error err;
    unsigned char *img[2] = {NULL, NULL};
    int w[2], h[2];
    int rc = 2;
    for (int k = 0; k < 2; k++)
        if (image_read_rgb8(paths[k], &img[k], &w[k], &h[k], &err) != 0) {
            fprintf(stderr, "image_rmse: %s\n", err.msg);
            goto done;
        }
    if (w[0] != w[1] || h[0] != h[1]) {
        fprintf(stderr, "image_rmse: %s is %dx%d but %s is %dx%d\n", paths[0], w[0], h[0], paths[1],
                w[1], h[1]);
        goto done;
    }
    const size_t n = (size_t)w[0] * (size_t)h[0];
    const double rmse = image_rmse_rgb8(img[0], img[1], n);
    printf("rmse=%.6f\n", rmse);
    if (diff_path) {
        unsigned char *diff = malloc(3 * n);
        if (!diff) {
            fprintf(stderr, "image_rmse: %s: out of memory\n", diff_path);
            goto done;
        }
        image_diff_rgb8(img[0], img[1], n, DIFF_GAIN, diff);
        int wrc = image_write_rgb8(diff_path, diff, w[0], h[0], &err);
        free(diff);
        if (wrc != 0) {
            fprintf(stderr, "image_rmse: %s\n", err.msg);
            goto done;
        }
    }
    rc = rmse > max ? 1 : 0;
    if (rc)
        fprintf(stderr, "image_rmse: %s vs %s: rmse %.6f > %g\n", paths[0], paths[1], rmse, max);
done:
    free(img[0]);
    free(img[1]);
    return rc;
}
