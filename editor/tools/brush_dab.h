// One brush dab: the brush resolved at a position, in the sample units of the layer
// it edits, and its application either to a world's tiles (through an edit) or to
// one plain array (the reference the tiled path must match bit for bit).
#ifndef OROGEN_EDITOR_BRUSH_DAB_H
#define OROGEN_EDITOR_BRUSH_DAB_H

#include "editor/tools/brush.h"
#include "editor/edit/edit.h"
#include "editor/world/layer_grid.h"
#include "editor/params/world_grid.h"

typedef struct brush_dab {
    const brush *brush;
    double cx, cz;  // centre, in samples
    double radius;  // in samples
    float strength; // brush strength x pressure
    double spacing; // metres per sample of the edited layer
    float target;   // flatten / set: height to blend toward
    // ramp: from (ax, az) at height ha to (bx, bz) at hb, in samples
    double ax, az, bx, bz;
    float ha, hb;
    uint64_t seed; // hydraulic: this dab's droplets
    // Planets (editor/tools/planet_dab.h): the dab measured on the sphere. A sample's
    // weight comes from its great-circle distance to centre_dir, so a dab goes on over
    // face edges and corners as over a continuous surface; noise is 3D; rect (the
    // samples of this face the dab's cap covers) replaces the disc's rectangle.
    int sphere;
    int face;
    int64_t face_samples; // coarse samples per face side
    double index_scale;   // coarse samples per sample of the edited layer (1 / detail ratio)
    double planet_radius; // metres to the datum
    double centre_dir[3];
    double ramp_a[3], ramp_b[3]; // ramp: its ends' directions (a great-circle segment)
    grid_rect rect;
} brush_dab;

// Planets: the unit direction of sample (x, z) of the dab's face (any index, past the
// face's edges too: the face's coordinates extend beyond it).
void brush_dab_sample_direction(const brush_dab *d, double x, double z, double dir[3]);

// Planets: the height at sample (x, z) of d's face in its extended samples (past the
// face's edges, on the neighbouring face where that direction lands), bilinear.
int brush_dab_read_sphere(world *w, const layer_grid *g, const brush_dab *d, double x, double z,
                          float *out, og_error *err);

// The samples a dab can change (before clipping to the world).
grid_rect brush_dab_rect(const brush_dab *d);

// Applies the dab to the world (edits the tiles of g's layer through e).
int brush_dab_apply(edit *e, const layer_grid *g, const brush_dab *d, og_error *err);

// The same in two steps, for a dab over several planet faces: begin reads what the
// dab needs (and runs a neighbourhood tool on it), finish writes it and frees the job,
// so no face reads samples another face's part has already changed. *job is NULL
// when the dab misses g; discard drops a job unapplied.
typedef struct brush_dab_job brush_dab_job;
int brush_dab_begin(edit *e, const layer_grid *g, const brush_dab *d, brush_dab_job **job,
                    og_error *err);
int brush_dab_finish(brush_dab_job *job, og_error *err);
void brush_dab_discard(brush_dab_job *job);

// Planets' erosion tools, run once over the whole cap: the neighbourhood tool over
// area r (plus its halo) of g's face in that face's extended samples (past its edges
// the neighbouring faces are read), leaving the heights before and after it and the
// weights, row-major over `area`, for the caller to write onto every face.
typedef struct brush_dab_area {
    grid_rect area;
    float *before, *after, *weight;
} brush_dab_area;
int brush_dab_compute_area(edit *e, const layer_grid *g, const brush_dab *d, grid_rect r,
                           brush_dab_area *out, og_error *err);
void brush_dab_area_free(brush_dab_area *a);

// Applies the dab to a plain row-major array holding the samples of `area` (floats
// for coarse/detail, TILE_MATERIALS bytes per sample for the material layer).
// Samples outside `area` read as its nearest edge sample, as outside a bounded world.
// With area = the whole bounded world this is the same operation as brush_dab_apply.
int brush_dab_apply_array(const brush_dab *d, tile_layer layer, void *data, grid_rect area,
                          og_error *err);
// The same as one dab of a stroke that began with the samples stroke_start (the same
// layout as data; NULL: data as it is, the dab its own stroke). Paint needs it: a
// stroke's coverage is measured from where it began (brush_dab.c paint_row).
int brush_dab_apply_array_since(const brush_dab *d, tile_layer layer, void *data,
                                const void *stroke_start, grid_rect area, og_error *err);

#endif
