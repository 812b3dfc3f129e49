// Stamps: a height shape placed once on the coarse or detail layer (one undo step).
// Sources: the functional shapes (editor/stamp_shapes.h), the built-in library
// (resources/stamps/NAME.png), the user's stamp folder, or any image file
// OpenImageIO reads (colour becomes luminance).
#ifndef OROGEN_EDITOR_STAMP_H
#define OROGEN_EDITOR_STAMP_H

#include "editor/world/world.h"
#include "io/err.h"
#include "io/tile.h"

#include <stdio.h>

typedef enum stamp_mode {
    STAMP_ADD,      // h + v
    STAMP_SUBTRACT, // h - v
    STAMP_MAX,      // max(h, lowest height under the stamp + v): raises the shape from the ground
    STAMP_MIN,      // min(h, highest height under the stamp - v): carves the shape in
    STAMP_BLEND,    // toward (height at the centre + v), fading out over the outer 30%
    STAMP_MODE_COUNT
} stamp_mode;

// Functional stamps span 128 samples of the layer at scale 1; image stamps one
// sample per pixel.
#define STAMP_FUNCTIONAL_SAMPLES 128

typedef struct stamp_source {
    char name[256];
    int shape;     // a stamp_shape, or -1 for an image
    float *pixels; // image: width x height values (8/16-bit images in [0, 1])
    int width, height;
    double support; // stamp_image_support of an image read by stamp_find; 0: not known
} stamp_source;

typedef struct stamp_placement {
    double x, z;     // centre, metres (face-local on planets)
    double scale;    // times the natural size; > 0
    double rotation; // degrees, counter-clockwise seen from above
    int mirror_x, mirror_z;
    double intensity; // metres of height at stamp value 1
    stamp_mode mode;
    tile_layer layer; // coarse or detail
    int face;
} stamp_placement;

// Defaults: scale 1, no rotation or mirroring, intensity 50 m (coarse), add.
void stamp_placement_defaults(stamp_placement *p);
// Sets one key=value of a placement (scale rot mirror intensity mode layer face).
int stamp_placement_set(stamp_placement *p, const char *key, const char *value, og_error *err);

// Finds a stamp by name: a functional shape, a library stamp in resource_dir/stamps,
// a stamp in user_dir (NAME.png/.tif/.exr/...), or a path to an image file.
int stamp_find(const char *name, const char *resource_dir, const char *user_dir, stamp_source *out,
               og_error *err);
void stamp_source_free(stamp_source *s);
// 1 when file's extension is one of the image formats stamps are read from.
int stamp_is_image_file(const char *file);
// Prints every available stamp, one per line: "NAME KIND [about]".
void stamp_list(const char *resource_dir, const char *user_dir, FILE *out);

// Places the stamp as one undo step.
int stamp_apply(world *w, const stamp_source *s, const stamp_placement *p, og_error *err);
// The same operation on a plain array holding `area` of the layer (the reference).
int stamp_apply_array(const world_params *params, const stamp_source *s, const stamp_placement *p,
                      float *data, int64_t area_x0, int64_t area_z0, int64_t width, int64_t height,
                      og_error *err);

#endif
