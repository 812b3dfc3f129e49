// Functional stamps (Crause 2010): heights as pure functions of stamp-local position,
// for the stamp engine to scale, rotate, mirror and add onto tiles.
//
// The footprint is the unit disc (the unit square [-1, 1]^2 for the ridge). Every
// shape is exactly 0 outside it and C1 everywhere, with value and slope reaching 0
// at its edge, so a placed stamp never leaves a step or a crease at its border.
// Values are in units of intensity, within [-1, 1]; all but the crater are >= 0.
//
// The cone is a mountain (Harris 2011's lake is a cone-shaped depression): the engine
// makes lakes by subtracting it (negative intensity).
#ifndef OROGEN_EDITOR_STAMP_SHAPES_H
#define OROGEN_EDITOR_STAMP_SHAPES_H

typedef enum stamp_shape {
    STAMP_SHAPE_GAUSSIAN, // exp(-4 r^2) renormalised: 1 at the centre, value and slope 0 at r = 1
    STAMP_SHAPE_CRATER,   // bowl down to -0.7, rim +0.3 at r = 0.65, ejecta blanket out to r = 1
    STAMP_SHAPE_CONE,     // straight flanks, rounded tip (1 at the centre), rounded foot
    STAMP_SHAPE_VOLCANO,  // concave cone, rim 1 at r = 0.16 around a caldera floored at 0.6
    STAMP_SHAPE_MESA,     // flat top 1 out to r = 0.5, smoothstep cliff, low talus apron
    STAMP_SHAPE_RIDGE,    // crest along v = 0, half-width 0.45 to 0.27; ends taper from |u| = 0.4
    STAMP_SHAPE_COUNT
} stamp_shape;

// "gaussian", "crater", "cone", "volcano", "mesa", "ridge"; NULL for an invalid shape.
const char *stamp_shape_name(stamp_shape s);
// The shape named name, or -1 if there is none (or name is NULL).
int stamp_shape_from_name(const char *name);

// Height at stamp-local (u, v). Finite for every input (0 for NaN and infinities);
// 0 for an invalid shape.
float stamp_shape_value(stamp_shape s, float u, float v);

#endif
