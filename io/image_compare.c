// Image comparison in plain C over bytes; only image_rmse_files touches files (through
// io/image_read.h).
#include "io/image_compare.h"

#include "io/image_read.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

double image_rmse_rgb8(const unsigned char *a, const unsigned char *b, size_t pixels) {
    if (pixels == 0) return 0.0;
    // Exact integer sum: at most 3 * 255^2 * 16384^2 for the largest image, far below 2^64.
    uint64_t sum = 0;
    for (size_t i = 0; i < 3 * pixels; i++) {
        const int d = (int)a[i] - (int)b[i];
        sum += (uint64_t)(d * d);
    }
    return sqrt((double)sum / (3.0 * (double)pixels));
}

int image_rmse_files(const char *path_a, const char *path_b, double *rmse, og_error *err) {
    unsigned char *a = NULL, *b = NULL;
    int wa, ha, wb, hb;
    int rc = -1;
    if (image_read_rgb8(path_a, &a, &wa, &ha, err) != 0) goto done;
    if (image_read_rgb8(path_b, &b, &wb, &hb, err) != 0) goto done;
    if (wa != wb || ha != hb) {
        og_error_set(err, "%s is %dx%d but %s is %dx%d", path_a, wa, ha, path_b, wb, hb);
        goto done;
    }
    *rmse = image_rmse_rgb8(a, b, (size_t)wa * (size_t)ha);
    rc = 0;
done:
    free(a);
    free(b);
    return rc;
}

void image_diff_rgb8(const unsigned char *a, const unsigned char *b, size_t pixels, int gain,
                     unsigned char *out) {
    for (size_t i = 0; i < 3 * pixels; i++) {
        const int d = abs((int)a[i] - (int)b[i]) * gain;
        out[i] = (unsigned char)(d > 255 ? 255 : d);
    }
}

void image_box_down_rgb8(const unsigned char *big, int width, int height, int k,
                         unsigned char *out) {
    const size_t row = (size_t)width * k * 3;
    const int n = k * k;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            for (int c = 0; c < 3; c++) {
                int sum = 0;
                for (int j = 0; j < k; j++) {
                    const unsigned char *p =
                        big + ((size_t)y * k + j) * row + (size_t)x * k * 3 + c;
                    for (int i = 0; i < k; i++)
                        sum += p[i * 3];
                }
                out[((size_t)y * width + x) * 3 + c] = (unsigned char)((sum + n / 2) / n);
            }
}
