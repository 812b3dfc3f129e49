#include "editor/tools/brush.h"

#include "io/parse.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *tool_names[BRUSH_TOOL_COUNT] = {
    "raise",   "smooth",    "flatten", "set",  "ramp",  "noise",   "terrace",
    "thermal", "hydraulic", "paint",   "fill", "carve", "vsmooth", "vflatten"};
static const char *falloff_names[FALLOFF_COUNT] = {"smooth",   "linear", "spherical",
                                                   "constant", "curve",  "tip"};
static const char *flatten_names[] = {"both", "raise", "lower"};

const char *brush_tool_name(brush_tool t) {
    return (unsigned)t < BRUSH_TOOL_COUNT ? tool_names[t] : "unknown";
}

int brush_tool_parse(const char *name) {
    for (int i = 0; i < BRUSH_TOOL_COUNT; i++)
        if (strcmp(name, tool_names[i]) == 0) return i;
    if (strcmp(name, "lower") == 0) return BRUSH_RAISE; // brush_set_tool inverts it
    return -1;
}

const char *brush_falloff_name(brush_falloff f) {
    return (unsigned)f < FALLOFF_COUNT ? falloff_names[f] : "unknown";
}

void brush_defaults(brush *b, brush_tool tool) {
    memset(b, 0, sizeof *b);
    b->tool = tool;
    b->radius = 20.0;
    b->strength = 0.5;
    b->falloff = FALLOFF_SMOOTH;
    b->spacing = 0.25;
    b->hold = 1;
    b->target = tool == BRUSH_PAINT ? TILE_LAYER_MATERIAL : TILE_LAYER_COARSE;
    // Raise: 4 m a dab at full strength, so a one-second stroke at the default
    // strength shows from the first view (~16 m held still); noise keeps 1 m.
    b->amount = tool == BRUSH_RAISE ? 4.0 : 1.0;
    b->height = 0.0;
    b->noise_scale = 50.0;
    b->noise_octaves = 4.0;
    b->seed = 1;
    b->terrace_step = 10.0;
    b->terrace_sharpness = 0.8;
    // 25 degrees and 50 passes: a stroke across the default world's hills visibly slumps
    // them (35 and 20 left ~1 m there, as most of its slopes are below 35 degrees).
    b->thermal = (thermal_params){.talus_deg = 12.0f, .iterations = 100, .rate = 0.5f};
    hydraulic_params_default(&b->hydraulic);
    b->hydraulic.droplets = 2000;
    b->material = 1;
    if (tool == BRUSH_FILL || tool == BRUSH_CARVE) b->strength = 1.0;
}

float brush_falloff_weight(const brush *b, float t) {
    if (!(t < 1.0f)) return 0.0f;
    if (t < 0.0f) t = 0.0f;
    switch (b->falloff) {
    case FALLOFF_LINEAR:
        return 1.0f - t;
    case FALLOFF_SPHERICAL:
        return sqrtf(1.0f - t * t);
    case FALLOFF_CONSTANT:
        return 1.0f;
    case FALLOFF_TIP:
        return 1.0f - sqrtf(1.0f - (1.0f - t) * (1.0f - t));
    case FALLOFF_CURVE: {
        int n = b->curve_count;
        if (t <= b->curve_t[0]) return b->curve_v[0];
        for (int i = 1; i < n; i++)
            if (t <= b->curve_t[i]) {
                float span = b->curve_t[i] - b->curve_t[i - 1];
                float a = span > 0 ? (t - b->curve_t[i - 1]) / span : 1.0f;
                return b->curve_v[i - 1] + a * (b->curve_v[i] - b->curve_v[i - 1]);
            }
        return b->curve_v[n - 1];
    }
    default:
        return 1.0f - t * t * (3.0f - 2.0f * t);
    }
}

static int parse_curve(brush *b, const char *value, og_error *err) {
    // "t:v,t:v,..." with t rising from 0 to 1.
    int n = 0;
    float ts[BRUSH_CURVE_MAX], vs[BRUSH_CURVE_MAX];
    const char *p = value;
    while (*p) {
        if (n == BRUSH_CURVE_MAX)
            return og_error_set(err, "curve: at most %d points", BRUSH_CURVE_MAX);
        double t, v;
        const char *end;
        if (parse_scan_f64(p, &t, &end) != 0 || *end != ':')
            return og_error_set(err, "curve: expected t:value pairs like 0:1,0.5:0.7,1:0, got '%s'",
                                value);
        p = end + 1;
        if (parse_scan_f64(p, &v, &end) != 0 || (*end && *end != ','))
            return og_error_set(err, "curve: expected t:value pairs like 0:1,0.5:0.7,1:0, got '%s'",
                                value);
        if (!(t >= 0 && t <= 1) || !(v >= 0 && v <= 1))
            return og_error_set(err, "curve: point %d (%g:%g) must have t and value in [0, 1]",
                                n + 1, t, v);
        if (n && !(t > ts[n - 1]))
            return og_error_set(err, "curve: point %d: t must rise (%g after %g)", n + 1, t,
                                ts[n - 1]);
        ts[n] = (float)t;
        vs[n] = (float)v;
        n++;
        p = *end ? end + 1 : end;
    }
    if (n < 2) return og_error_set(err, "curve: needs at least 2 points, e.g. 0:1,1:0");
    b->curve_count = n;
    memcpy(b->curve_t, ts, sizeof ts);
    memcpy(b->curve_v, vs, sizeof vs);
    return 0;
}

int brush_set(brush *b, const char *key, const char *value, og_error *err) {
    brush n = *b;
    double v = 0;
    int rc = 0;
    if (strcmp(key, "radius") == 0) {
        rc = parse_number_in(value, key, 1e-3, 1e6, &n.radius, err);
    } else if (strcmp(key, "strength") == 0) {
        rc = parse_number_in(value, key, 0, 1, &n.strength, err);
    } else if (strcmp(key, "spacing") == 0) {
        rc = parse_number_in(value, key, 0.01, 10, &n.spacing, err);
    } else if (strcmp(key, "falloff") == 0) {
        int f = -1;
        for (int i = 0; i < FALLOFF_COUNT; i++)
            if (strcmp(value, falloff_names[i]) == 0) f = i;
        if (f < 0)
            return og_error_set(
                err, "falloff: '%s' is not smooth, linear, spherical, tip, constant or curve",
                value);
        if (f == FALLOFF_CURVE && n.curve_count < 2)
            return og_error_set(err, "falloff: give the points first with curve=t:v,t:v,...");
        n.falloff = (brush_falloff)f;
    } else if (strcmp(key, "curve") == 0) {
        rc = parse_curve(&n, value, err);
        if (rc == 0) n.falloff = FALLOFF_CURVE;
    } else if (strcmp(key, "hold") == 0) {
        if (strcmp(value, "1") && strcmp(value, "0"))
            return og_error_set(err, "hold: '%s' is not 0 or 1", value);
        n.hold = strcmp(value, "1") == 0;
    } else if (strcmp(key, "invert") == 0) {
        if (strcmp(value, "1") && strcmp(value, "0") && strcmp(value, "true") &&
            strcmp(value, "false"))
            return og_error_set(err, "invert: '%s' is not 0, 1, true or false", value);
        n.invert = strcmp(value, "1") == 0 || strcmp(value, "true") == 0;
    } else if (strcmp(key, "target") == 0 || strcmp(key, "layer") == 0) {
        n.mask = strcmp(value, "mask") == 0;
        if (strcmp(value, "coarse") == 0 || n.mask)
            n.target = TILE_LAYER_COARSE;
        else if (strcmp(value, "detail") == 0)
            n.target = TILE_LAYER_DETAIL;
        else
            return og_error_set(err, "%s: '%s' is not coarse, detail or mask", key, value);
        if (n.tool == BRUSH_PAINT)
            return og_error_set(err, "%s: paint always edits the material layer", key);
        if (n.mask && n.tool != BRUSH_RAISE && n.tool != BRUSH_SMOOTH && n.tool != BRUSH_SET &&
            n.tool != BRUSH_FLATTEN)
            return og_error_set(err,
                                "%s: mask: only raise, lower, smooth, set and flatten paint a "
                                "layer's mask coverage, not %s",
                                key, brush_tool_name(n.tool));
    } else if (strcmp(key, "face") == 0) {
        rc = parse_integer_in(value, key, 0, 5, &v, err);
        n.face = (int)v;
    } else if (strcmp(key, "amount") == 0) {
        rc = parse_number_in(value, key, 0, 1e4, &n.amount, err);
    } else if (strcmp(key, "height") == 0) {
        rc = parse_number_in(value, key, -BRUSH_HEIGHT_LIMIT, BRUSH_HEIGHT_LIMIT, &n.height, err);
        n.has_height = 1;
    } else if (strcmp(key, "mode") == 0) {
        int m = -1;
        for (int i = 0; i < 3; i++)
            if (strcmp(value, flatten_names[i]) == 0) m = i;
        if (m < 0) return og_error_set(err, "mode: '%s' is not both, raise or lower", value);
        n.flatten = (flatten_mode)m;
    } else if (strcmp(key, "scale") == 0) {
        rc = parse_number_in(value, key, 1e-3, 1e7, &n.noise_scale, err);
    } else if (strcmp(key, "octaves") == 0) {
        rc = parse_number_in(value, key, 0.1, 16, &n.noise_octaves, err);
    } else if (strcmp(key, "seed") == 0) {
        rc = parse_integer_in(value, key, 0, 4294967295.0, &v, err);
        n.seed = (uint32_t)v;
        n.hydraulic.seed = n.seed;
    } else if (strcmp(key, "step") == 0) {
        rc = parse_number_in(value, key, 1e-3, 1e5, &n.terrace_step, err);
    } else if (strcmp(key, "sharpness") == 0) {
        rc = parse_number_in(value, key, 0, 1, &n.terrace_sharpness, err);
    } else if (strcmp(key, "talus") == 0) {
        rc = parse_number_in(value, key, 0.1, 89, &v, err);
        n.thermal.talus_deg = (float)v;
    } else if (strcmp(key, "iterations") == 0) {
        rc = parse_integer_in(value, key, 1, 1000, &v, err);
        n.thermal.iterations = (int)v;
    } else if (strcmp(key, "droplets") == 0) {
        rc = parse_integer_in(value, key, 1, 1e6, &v, err);
        n.hydraulic.droplets = (int)v;
    } else if (strcmp(key, "erosion") == 0) {
        rc = parse_number_in(value, key, 0, 1, &v, err);
        n.hydraulic.erosion = (float)v;
    } else if (strcmp(key, "deposition") == 0) {
        rc = parse_number_in(value, key, 0, 1, &v, err);
        n.hydraulic.deposition = (float)v;
    } else if (strcmp(key, "evaporation") == 0) {
        rc = parse_number_in(value, key, 0, 1, &v, err);
        n.hydraulic.evaporation = (float)v;
    } else if (strcmp(key, "capacity") == 0) {
        rc = parse_number_in(value, key, 0, 1000, &v, err);
        n.hydraulic.capacity = (float)v;
    } else if (strcmp(key, "inertia") == 0) {
        rc = parse_number_in(value, key, 0, 1, &v, err);
        n.hydraulic.inertia = (float)v;
    } else if (strcmp(key, "depth") == 0) {
        rc = parse_number_in(value, key, -1e4, 1e4, &n.depth, err);
    } else if (strcmp(key, "lock") == 0) {
        if (strcmp(value, "surface") && strcmp(value, "plane"))
            return og_error_set(err, "lock: '%s' is not surface or plane", value);
        n.lock_plane = strcmp(value, "plane") == 0;
    } else if (strcmp(key, "material") == 0) {
        rc = parse_integer_in(value, key, 0, TILE_MATERIALS - 1, &v, err);
        n.material = (int)v;
    } else {
        return og_error_set(err, "unknown brush setting '%s' (settings: %s)", key, brush_keys());
    }
    if (rc != 0) return -1;
    *b = n;
    return 0;
}

const char *brush_keys(void) {
    return "radius strength falloff curve spacing invert target face amount height mode scale "
           "octaves seed step sharpness talus iterations droplets erosion deposition "
           "evaporation capacity inertia material depth lock hold";
}

void brush_print(const brush *b, FILE *o) {
    fprintf(o, "tool=%s\nradius=%.17g\nstrength=%.17g\nfalloff=%s\n", brush_tool_name(b->tool),
            b->radius, b->strength, brush_falloff_name(b->falloff));
    if (b->curve_count) {
        fprintf(o, "curve=");
        for (int i = 0; i < b->curve_count; i++)
            fprintf(o, "%s%g:%g", i ? "," : "", b->curve_t[i], b->curve_v[i]);
        fprintf(o, "\n");
    }
    fprintf(o, "spacing=%.17g\nhold=%d\ninvert=%d\ntarget=%s\nface=%d\n", b->spacing, b->hold,
            b->invert, b->mask ? "mask" : tile_layer_name(b->target), b->face);
    switch (b->tool) {
    case BRUSH_RAISE:
        fprintf(o, "amount=%.17g\n", b->amount);
        break;
    case BRUSH_FLATTEN:
        fprintf(o, "mode=%s\n", flatten_names[b->flatten]);
        if (b->has_height)
            fprintf(o, "height=%.17g\n", b->height);
        else
            fprintf(o, "height=(under the stroke start)\n");
        break;
    case BRUSH_SET:
        if (b->has_height)
            fprintf(o, "height=%.17g\n", b->height);
        else
            fprintf(o, "height=(not set)\n");
        break;
    case BRUSH_NOISE:
        fprintf(o, "amount=%.17g\nscale=%.17g\noctaves=%.17g\nseed=%u\n", b->amount, b->noise_scale,
                b->noise_octaves, b->seed);
        break;
    case BRUSH_TERRACE:
        fprintf(o, "step=%.17g\nsharpness=%.17g\n", b->terrace_step, b->terrace_sharpness);
        break;
    case BRUSH_THERMAL:
        fprintf(o, "talus=%g\niterations=%d\n", b->thermal.talus_deg, b->thermal.iterations);
        break;
    case BRUSH_HYDRAULIC:
        fprintf(o,
                "droplets=%d\nerosion=%g\ndeposition=%g\nevaporation=%g\ncapacity=%g\ninertia=%"
                "g\nseed=%u\n",
                b->hydraulic.droplets, b->hydraulic.erosion, b->hydraulic.deposition,
                b->hydraulic.evaporation, b->hydraulic.capacity, b->hydraulic.inertia, b->seed);
        break;
    case BRUSH_PAINT:
        fprintf(o, "material=%d\n", b->material);
        break;
    case BRUSH_FILL:
    case BRUSH_CARVE:
    case BRUSH_VSMOOTH:
    case BRUSH_VFLATTEN:
        fprintf(o, "depth=%.17g\nlock=%s\n", b->depth, b->lock_plane ? "plane" : "surface");
        if (b->tool == BRUSH_VFLATTEN) {
            if (b->has_height)
                fprintf(o, "height=%.17g\n", b->height);
            else
                fprintf(o, "height=(the stroke's first centre)\n");
        }
        break;
    default:
        break;
    }
}
