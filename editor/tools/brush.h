// Brush settings: the current tool and everything the user can set on it with
// `tool NAME key=value ...`. Values are validated when set, so a brush in use is
// always valid.
#ifndef OROGEN_EDITOR_BRUSH_H
#define OROGEN_EDITOR_BRUSH_H

#include "editor/tools/erosion.h"
#include "io/err.h"
#include "io/tile.h"

#include <stdint.h>
#include <stdio.h>

typedef enum brush_tool {
    BRUSH_RAISE,     // add height (invert: lower)
    BRUSH_SMOOTH,    // blend toward the blurred surface (invert: sharpen)
    BRUSH_FLATTEN,   // blend toward a height: height=, or the height under the stroke start
    BRUSH_SET,       // blend toward height= (required)
    BRUSH_RAMP,      // a ramp between a stroke's first and last points
    BRUSH_NOISE,     // add fBm (invert: subtract)
    BRUSH_TERRACE,   // blend toward terraces of step metres
    BRUSH_THERMAL,   // thermal erosion down to the talus angle
    BRUSH_HYDRAULIC, // droplet erosion
    BRUSH_PAINT,     // material weights (invert: remove the material)
    // Volume tools (editor/tools/volume_brush.h): 3D points, the volume layer.
    BRUSH_FILL,     // add a ball per dab, a capsule along a stroke
    BRUSH_CARVE,    // subtract a ball per dab, a capsule along a stroke
    BRUSH_VSMOOTH,  // blend the combined surface toward its blur
    BRUSH_VFLATTEN, // blend the combined surface toward a level plane (height=, else the first
                    // dab's)
    BRUSH_TOOL_COUNT
} brush_tool;

typedef enum brush_falloff {
    FALLOFF_SMOOTH,    // 1 - smoothstep(t)
    FALLOFF_LINEAR,    // 1 - t
    FALLOFF_SPHERICAL, // sqrt(1 - t^2)
    FALLOFF_CONSTANT,  // 1
    FALLOFF_CURVE,     // the user's curve= points, piecewise linear
    FALLOFF_TIP,       // 1 - sqrt(1 - (1 - t)^2): a sharp peak (Unreal's "tip")
    FALLOFF_COUNT
} brush_falloff;

typedef enum flatten_mode { FLATTEN_BOTH, FLATTEN_RAISE, FLATTEN_LOWER } flatten_mode;

#define BRUSH_CURVE_MAX 16
// Largest brush radius in samples of the layer it edits (a dab then covers ~53M samples).
#define BRUSH_MAX_RADIUS_SAMPLES 4096.0
// No edit writes a height beyond this many metres (keeps every layer finite).
#define BRUSH_HEIGHT_LIMIT 1.0e6

typedef struct brush {
    brush_tool tool;
    double radius;   // metres
    double strength; // 0-1, times pressure
    brush_falloff falloff;
    int curve_count; // curve: t ascending 0..1, value 0..1
    float curve_t[BRUSH_CURVE_MAX], curve_v[BRUSH_CURVE_MAX];
    double spacing; // dab spacing along a stroke, as a fraction of the radius
    int hold;       // held still, a stroke keeps dabbing (stroke_hold); 0: it does not
    int invert;
    tile_layer target; // coarse or detail (height tools); paint always edits materials
    // target=mask: raise, lower, smooth, set and flatten paint the active layer's painted
    // mask coverage (0..1, editor/layers/layer_table.h) instead of heights.
    int mask;
    int face;      // planet face edited (0 on flat worlds)
    double amount; // raise, noise: metres per dab at full strength
    int has_height;
    double height; // flatten (optional), set (required): target height in metres
    flatten_mode flatten;
    double noise_scale; // metres per noise cell
    double noise_octaves;
    uint32_t seed;            // noise and hydraulic
    double terrace_step;      // metres
    double terrace_sharpness; // 0 (ramps) .. 1 (flat treads, vertical risers)
    thermal_params thermal;
    hydraulic_params hydraulic; // droplets = per dab
    int material;               // paint: 0 .. TILE_MATERIALS-1
    // Volume tools in the viewport: the brush centre is the picked surface point pushed
    // depth metres along the view ray (negative: toward the camera), or with lock_plane
    // the view ray's crossing of the level plane through the stroke's first centre.
    double depth;
    int lock_plane;
} brush;

const char *brush_tool_name(brush_tool t);
// Whether the tool edits the volume layer (takes X Y Z points).
static inline int brush_tool_is_volume(brush_tool t) {
    return t >= BRUSH_FILL && t <= BRUSH_VFLATTEN;
}
int brush_tool_parse(const char *name); // -1 if unknown
const char *brush_falloff_name(brush_falloff f);

// Defaults for a tool (radius 20 m, strength 0.5, smooth falloff, spacing 0.25, ...;
// fill and carve: strength 1, a whole ball per dab).
void brush_defaults(brush *b, brush_tool tool);
// Sets one key=value; the brush is unchanged on error (which names the key).
int brush_set(brush *b, const char *key, const char *value, og_error *err);
// Prints every setting as key=value lines.
void brush_print(const brush *b, FILE *out);
// Names of the settable keys, for help.
const char *brush_keys(void);

// Falloff weight at t = distance / radius in [0, 1] (0 beyond).
float brush_falloff_weight(const brush *b, float t);

#endif
