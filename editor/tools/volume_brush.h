// The volume tools: fill, carve, vsmooth and vflatten edit the volume layer
// (editor/world/volume_grid.h) at 3D points, metres, y up.
//
// - fill / carve: a ball of radius x strength x pressure around each point, and the
//   capsule (round cone when pressures differ) swept between consecutive points, is
//   added to (fill) or cut out of (carve) the solid. fill also removes the ball from
//   earlier carvings and carve from earlier fills, so the last edit wins. The falloff
//   rounds the seam where the new shape meets earlier volume edits, over
//   radius x (1 - falloff(0.5)) / 2 (constant falloff: hard CSG).
// - vsmooth: dabs every spacing x radius along the path; each blends the combined
//   surface toward its 3x3x3 blur by strength x pressure x falloff(distance / radius).
// - vflatten: the same toward the level plane at height= (else the first point's
//   height): solid below it, air above.
// vsmooth and vflatten write the combined surface they produce into the volume layer,
// so the part of the ground they touched becomes a volume edit (it stays put if the
// heightfield is edited later).
#ifndef OROGEN_EDITOR_VOLUME_BRUSH_H
#define OROGEN_EDITOR_VOLUME_BRUSH_H

#include "editor/tools/brush.h"
#include "editor/world/world.h"
#include "io/err.h"

#include <stddef.h>

// A stroke laid point by point (the viewport's drag): one undo step at the end. The
// points are checked as they come (a bad one is refused and the stroke stays open).
typedef struct volume_stroke volume_stroke;
volume_stroke *volume_stroke_begin(world *w, const brush *b, og_error *err);
// The same with its own undo label (the shape generators: "arch", "tunnel", ...).
volume_stroke *volume_stroke_begin_labelled(world *w, const brush *b, const char *label,
                                            og_error *err);
int volume_stroke_to(volume_stroke *s, const double p[3], double pressure, og_error *err);
// Lifts the pen: the next point starts a new piece at p (nothing is laid between). The
// first point of a stroke is laid as a dab.
int volume_stroke_move(volume_stroke *s, const double p[3], double pressure, og_error *err);
// Commits the stroke as one step (none when no point was laid) and frees it.
int volume_stroke_end(volume_stroke *s, og_error *err);
// Undoes what the stroke did and frees it.
void volume_stroke_cancel(volume_stroke *s);
long volume_stroke_dabs(const volume_stroke *s);

// Applies the brush's volume tool along count points (count >= 1; one point is one
// dab) with a pressure 0-1 each (NULL: all 1), as one undo step ("TOOL stroke"). Bad
// input (not a volume tool, a planet, a point that is not finite or
// lies outside the world, more bricks than the tile cache can hold) is refused with
// err naming it, and nothing changes.
int volume_brush_apply(world *w, const brush *b, const double (*points)[3], const double *pressure,
                       size_t count, og_error *err);

// Voxels the last point laid in this process visited (for benchmarks).
long long volume_brush_last_voxels(void);

#endif
