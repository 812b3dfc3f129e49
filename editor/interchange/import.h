// Import: a height raster (io/raster.h) placed on the coarse or detail layer as one
// undo step, at true scale: heights as stored unless mapped (min=/max=, scale=/
// offset=, or the file's sidecar), sample spacing from the file's georeferencing,
// resampled to the world's spacing and blended into what is there.
//
// Placement: the raster's first stored sample (row 0, column 0: the top-left of an
// image, the north-west corner of a north-up DEM) sits at x, z; columns run toward
// +X, rows toward +Z. anchor=centre centres the raster on x, z instead. Export
// follows the same convention, so import -> export -> import is the identity.
#ifndef OROGEN_EDITOR_INTERCHANGE_IMPORT_H
#define OROGEN_EDITOR_INTERCHANGE_IMPORT_H

#include "editor/interchange/sidecar.h"
#include "editor/world/world.h"
#include "editor/layers/layer_table.h"
#include "io/err.h"
#include "io/raster.h"
#include "io/tile.h"

#include <stdint.h>

// The most world samples one import writes (an SRTM tile at 1 m would be 10^10).
#define IMPORT_MAX_SAMPLES ((int64_t)1 << 27)

typedef enum import_blend { IMPORT_REPLACE, IMPORT_ADD, IMPORT_MAX, IMPORT_MIN } import_blend;
typedef enum import_resample { IMPORT_NEAREST, IMPORT_BILINEAR, IMPORT_BICUBIC } import_resample;

typedef struct import_options {
    raster_read_options read; // channel=, endian=, format=, width=, height=
    int has_min_max, has_scale;
    double min, max;      // metres at the lowest / highest stored value (normalised formats)
    double scale, offset; // height = stored value x scale + offset
    double spacing;       // metres between the raster's samples; 0: the file's, else the layer's
    int has_position, anchor_centre;
    double x, z; // metres
    tile_layer layer;
    // layer=new or layer=NAME: the import goes into a new height layer (named after the
    // file) or the named one, made active, in the same undo step; "" for the active layer.
    char edit_layer[LAYER_NAME_MAX];
    import_resample resample;
    import_blend blend;
    double falloff;     // metres over which the patch's edge fades into the terrain
    int starting_state; // the world's base (new flat from=): no undo step (not a key)
    // Writes only the layer samples inside limit (not a key; a world made from a raster
    // imports its parts as they are needed: editor/cmd/base_pending.h). The report still
    // describes the whole placement.
    int has_limit;
    grid_rect limit;
} import_options;

typedef struct import_report {
    int width, height;           // source samples
    double spacing_x, spacing_z; // source metres per sample
    double min, max;             // metres, after mapping
    int64_t voids;               // filled samples
    double x0, z0, x1, z1;       // placed rectangle, metres
    int64_t samples;             // layer samples written
    char mapping[160];           // how stored values became metres
    char source[300];            // what was read
    int adopted_georef;          // the world had no place: it took the raster's
} import_report;

void import_options_defaults(import_options *o);
// One key=value: min max scale offset spacing x z anchor layer resample blend falloff
// channel endian format width height.
int import_options_set(import_options *o, const char *key, const char *value, og_error *err);

// Reads path and applies it as one undo step. report (may be NULL) says what happened.
int import_apply(world *w, const char *path, const import_options *o, import_report *report,
                 og_error *err);

// A raster read once and mapped to metres, ready to place (and to size a world by).
typedef struct import_source {
    raster raster; // samples in metres
    double spacing_x,
        spacing_z;  // metres per sample: spacing=, the file's or the sidecar's; 0: none
    int has_origin; // the sidecar gave where row 0, column 0 goes
    double origin_x, origin_z;
    double min, max;   // metres
    char mapping[160]; // how stored values became metres
} import_source;

// Reads path with o's reader options and maps it: o's min/max or scale/offset, else the
// file's sidecar, else 0..top to 0..default_max metres for 8/16-bit images and RAW.
int import_source_read(const char *path, const import_options *o, double default_max,
                       import_source *s, og_error *err);
void import_source_free(import_source *s);
// import_apply with the source already read.
int import_apply_source(world *w, const char *path, const import_source *s, const import_options *o,
                        import_report *report, og_error *err);

// What the import dialog shows before importing: the raster as stored (its samples
// are not kept), a histogram of its values and, for the options being edited, the
// heights they map to (import_preview_mapping).
#define IMPORT_PREVIEW_BINS 48
typedef struct import_preview {
    raster header;                      // size, kind, bits, spacing, voids, description; no samples
    double stored_min, stored_max;      // the values as stored
    int histogram[IMPORT_PREVIEW_BINS]; // counts over stored_min .. stored_max
    int has_sidecar;
    sidecar sc;
} import_preview;

int import_preview_read(const char *path, const import_options *o, import_preview *p,
                        og_error *err);
// height = stored x *scale + *offset for options o, as import_source_read maps;
// how says which rule applies.
int import_preview_mapping(const char *path, const import_preview *p, const import_options *o,
                           double default_max, double *scale, double *offset, char *how,
                           size_t how_len, og_error *err);

#endif
