// An image stamp's values along rows of a flat world's samples: the rotated, scaled
// image read bilinearly, a row span at a time (vectorised), with the same arithmetic
// as the sample-by-sample reading in stamp.c (bit for bit the same values).
#ifndef OROGEN_STAMP_IMAGE_H
#define OROGEN_STAMP_IMAGE_H

#include <stdint.h>

typedef struct stamp_image_map {
    const float *pixels; // width x height values
    int width, height;   // width * height < 2^31
    double spacing;      // metres per sample of the layer
    double x, z;         // the stamp's centre, metres
    double cos_r, sin_r; // its rotation
    double half_w, half_h;
    int mirror_x, mirror_z;
    // Metres from the centre past which every sample reads exactly 0 (the image's
    // support, stamp_image_support, scaled); 0: not known, the whole footprint counts.
    // Only add and subtract may narrow to it: there a 0 changes nothing.
    double support;
} stamp_image_map;

// Samples [x0, x1) of row z narrowed to a span [*a, *b) that holds every sample of the
// footprint (|u|, |v| < 1) on that row within the support (when known), and a sample
// or two more (*a >= *b: none).
void stamp_image_span(const stamp_image_map *m, int64_t z, int64_t x0, int64_t x1, int64_t *a,
                      int64_t *b);

// For samples x0 .. x0 + n - 1 of row z: edge[i] = max(|u|, |v|) (inside the footprint
// when < 1) and value[i], the image's value there (only meaningful inside).
void stamp_image_values(const stamp_image_map *m, int64_t z, int64_t x0, int n, float *value,
                        double *edge);

// The same through one path: 0 plain C, 1 AVX2, 2 AVX-512 (the same values; tests
// compare them); stamp_image_paths() of them run on this processor.
void stamp_image_values_path(int path, const stamp_image_map *m, int64_t z, int64_t x0, int n,
                             float *value, double *edge);
int stamp_image_paths(void);
// The radius, in pixels from the image's centre, past which its bilinear reading is
// exactly 0 everywhere (the farthest non-zero pixel, NaN included, plus the reading's
// reach): most library stamps fade to 0 at their inscribed circle.
double stamp_image_support(const float *pixels, int width, int height);

// Adds value[i] * k to row[i] where edge[i] < 1, as stamp.c's add mode does sample by
// sample (a NaN sum keeps the old height; the sum is clamped to [-limit, limit]).
void stamp_image_add(float *row, const float *value, const double *edge, float k, float limit,
                     int n);

#endif
