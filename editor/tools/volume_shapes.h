// Common 3D shapes made with the volume tools, each one undo step: an arch between two
// feet, a tunnel along a path with a radius at each point, a rock spire or hoodoo, and
// an overhang pushed out from a cliff's edge. All hard-edged (constant falloff).
#ifndef OROGEN_EDITOR_VOLUME_SHAPES_H
#define OROGEN_EDITOR_VOLUME_SHAPES_H

#include "editor/world/world.h"
#include "io/err.h"

#include <stddef.h>

// An arch of rock `thickness` metres thick from foot a to foot b (metres, y up), its
// middle `rise` metres above the straight line between them (a parabola).
int volume_arch(world *w, const double a[3], const double b[3], double rise, double thickness,
                og_error *err);
// Carves a tunnel along count points with radius[i] metres at point i.
int volume_tunnel(world *w, const double (*points)[3], const double *radius, size_t count,
                  og_error *err);
// A spire standing on base (metres), `height` tall, `radius` wide at the foot and
// radius x taper at the top; cap > 0 adds a capstone of that radius (a hoodoo).
int volume_spire(world *w, const double base[3], double height, double radius, double taper,
                 double cap, og_error *err);
// An overhang along the cliff edge from (x0, z0) to (x1, z1) (metres): a shelf of rock
// `thickness` thick whose top is the ground at the edge, pushed `distance` metres out
// over the lower side.
int volume_overhang(world *w, double x0, double z0, double x1, double z1, double distance,
                    double thickness, og_error *err);

#endif
