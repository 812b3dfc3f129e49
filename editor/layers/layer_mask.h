// A layer's mask: where the layer applies, as a weight 0..1 per sample, read from the
// composite of the layers below it (procedural terms) and from a painted coverage.
//
// Terms (each optional; the weights of the set ones multiply):
//   height=LO,HI      metres, the composite height below the layer.
//   slope=LO,HI       degrees 0..90, atan of the gradient by central differences.
//   curvature=LO,HI   -100 x the Laplacian (1/m): positive on convex ground (ridges, hill
//                     tops), negative in concave (valleys, hollows); the units and sign of
//                     Esri's curvature (1/100 of a metre per metre squared). A dome
//                     h = c - a r^2 reads 400 a everywhere.
//   flow=LO,HI        m^2 of upstream contributing area (D-infinity, Tarboton 1997) over
//                     the evaluation window only: the sample's own cell counts, so a
//                     ridge reads spacing^2. A catchment reaching further upstream than
//                     the border (64 samples past the evaluated area) is cut there, so
//                     large values are lower bounds (tests/test_layer_mask.c measures how
//                     rarely that moves a weight); pits and flats pass nothing on.
// Each term is 1 inside [LO, HI] and 0 beyond, with a smoothstep edge outside the range:
// over [LO - E, LO] and [HI, HI + E]. E is the term's edge width in its own units: for
// height it is `falloff=M` (metres); slope, curvature and flow take it as an optional
// third value (`slope=20,40,5`: 5 degrees); 0 (the default) is a hard edge. LO and HI may
// be -inf/inf for an open range; `off` removes a term.
//   painted=1         the painted coverage (0..1) multiplies the terms.
//   invert=1          the weight becomes 1 - (terms x painted).
// After layer_mask_init nothing is set: weight 1 everywhere.
#ifndef OROGEN_EDITOR_LAYERS_LAYER_MASK_H
#define OROGEN_EDITOR_LAYERS_LAYER_MASK_H

#include "io/err.h"

#include <stddef.h>

// Samples of context the flow term needs each side of the evaluated area.
#define LAYER_MASK_FLOW_BORDER 64

typedef struct layer_mask_range {
    int on;
    double lo, hi;
    double edge; // smoothstep width outside [lo, hi], in the term's units; 0 = hard
} layer_mask_range;

typedef struct layer_mask {
    layer_mask_range height; // its edge is the `falloff` key
    layer_mask_range slope;
    layer_mask_range curvature;
    layer_mask_range flow;
    int invert;
    int painted;
} layer_mask;

void layer_mask_init(layer_mask *m);
// 1 when the mask can be anything but 1 everywhere (a term, painted or invert set).
int layer_mask_active(const layer_mask *m);
// Samples of composite context layer_mask_evaluate needs each side: 0 with height only,
// 1 with slope or curvature, LAYER_MASK_FLOW_BORDER with flow.
int layer_mask_border(const layer_mask *m, double spacing);
// Sets one key (see above) from its text value; 0, or -1 with an error naming the key
// and the value (unknown key, not a number, NaN, LO > HI, negative edge, slope beyond
// 0..90). A failed call leaves the mask unchanged.
int layer_mask_set_option(layer_mask *m, const char *key, const char *value, og_error *err);
// Applies space-separated key=value pairs (layer_mask_format's output) to m; on error
// m is unchanged. Empty text sets nothing.
int layer_mask_parse(layer_mask *m, const char *text, og_error *err);
// The set keys as space-separated key=value pairs (numbers exact, shortest), "" when nothing
// is set; layer_mask_parse on a fresh mask gives m back bit for bit. Returns the full
// text's length as snprintf does (>= len means it was cut).
int layer_mask_format(const layer_mask *m, char *buf, size_t len);
// Weights for a w x h area. below: the composite heights below the layer over the area
// and b samples around it ((w + 2b) x (h + 2b), row-major; b >= layer_mask_border for
// exact terms, smaller b clamps at the window's edge). spacing: metres between samples.
// painted: w x h coverage 0..1, or NULL where nothing is painted (coverage 0) - used only
// when m->painted. out: w x h weights 0..1.
void layer_mask_evaluate(const layer_mask *m, const float *below, int w, int h, int b,
                         double spacing, const float *painted, float *out);

// The terms one at a time on plain arrays, for tests and the mask editor's overlay.
// Each writes w x h values from a (w + 2b) x (h + 2b) window.
void layer_mask_slope_degrees(const float *below, int w, int h, int b, double spacing, float *out);
void layer_mask_curvature(const float *below, int w, int h, int b, double spacing, float *out);
// Returns 0, or -1 when out of memory (out untouched).
int layer_mask_flow_area(const float *below, int w, int h, int b, double spacing, float *out);
// One range's text, "LO,HI[,EDGE]" or "off", for rules that share the masks' ranges:
// min/max bound LO and HI, unit names them in errors ("degrees"). Format writes what
// parse reads back exactly, as snprintf counts.
int layer_mask_range_parse(const char *key, const char *value, double min, double max,
                           const char *unit, layer_mask_range *out, og_error *err);
int layer_mask_range_format(const layer_mask_range *r, char *buf, size_t len);
// A term's weight for value v: 1 inside [lo, hi], smoothstep to 0 over the edge.
double layer_mask_range_weight(const layer_mask_range *r, double v);

#endif
