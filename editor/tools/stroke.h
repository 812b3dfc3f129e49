// A stroke: press, drag, release. Dabs are laid along the path every
// spacing x radius; the whole stroke is one edit (one undo step). Flatten picks its
// height under the first point when none is set; ramp applies once at release,
// from the first point to the last.
#ifndef OROGEN_EDITOR_STROKE_H
#define OROGEN_EDITOR_STROKE_H

#include "editor/tools/brush.h"
#include "editor/world/world.h"

typedef struct stroke stroke;

// Checks the brush against the world (radius in samples, face, set's height).
stroke *stroke_begin(world *w, const brush *b, og_error *err);
// Moves the brush to (x, z) metres (face-local on planets) with pressure 0-1: the first
// call lays one dab there, later calls lay dabs along the segment from the last point.
int stroke_to(stroke *s, double x, double z, double pressure, og_error *err);
// The volume tools' strokes (editor/tools/volume_brush.h) take 3D points (metres, y up);
// each form refuses the other's tools.
int stroke_to_3d(stroke *s, const double p[3], double pressure, og_error *err);
int stroke_is_volume(const stroke *s);
// The brush rests at the stroke's last point for seconds (0-60): a brush held still
// keeps applying, as in Unreal and Terrain3D, 2 / spacing dabs a second (the dabs a
// pointer moving two radii a second lays), fractions carried to the next call. Nothing
// when the brush's hold is 0, before the first point, for ramp and the volume tools.
int stroke_hold(stroke *s, double seconds, og_error *err);
// Commits the stroke as one undo step and frees it.
int stroke_end(stroke *s, og_error *err);
// Undoes what the stroke did so far and frees it.
void stroke_cancel(stroke *s);

// Dabs laid so far (for benchmarks and tests).
long stroke_dab_count(const stroke *s);

#endif
