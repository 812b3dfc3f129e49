// The automatic material rules: an editable stack that says which material covers
// unpainted ground by its height, slope and curvature (README.md, "Material rules").
//
// Bottom first, each rule lays its material over what the rules below it made, with a
// weight: the product of its terms (each 1 inside its range, a smoothstep edge outside,
// as layer masks' terms, editor/layers/layer_mask.h), moved by `breakup` (0..1) times
// the material's own large-scale variation so the edges are not contour lines. A rule
// without terms covers everything (the usual first rule). Heights are metres above the
// datum, or relative to the world's relief: "62%" is 62% of the way from the sea to
// max_height, "62%+40" 40 m above that, so the default snow line follows max_height as
// it always did. Pure data; saved in the parameter file (`material_rule = ...;` lines).
#ifndef OROGEN_EDITOR_LAYERS_MATERIAL_RULES_H
#define OROGEN_EDITOR_LAYERS_MATERIAL_RULES_H

#include "editor/layers/layer_mask.h"
#include "io/err.h"

#include <stddef.h>

#define MATERIAL_RULES_MAX 16 // what the shaders' uniform arrays hold
#define MATERIAL_COUNT 8      // the material textures: sand .. cliff

// A height bound: metres, or percent of the relief above the sea plus metres.
typedef struct material_height {
    int relative;
    double percent; // relative only
    double metres;
} material_height;

typedef struct material_rule {
    int material; // 0 sand, 1 grass, 2 rock, 3 snow, 4 dirt, 5 gravel, 6 moss, 7 cliff
    int height_on;
    material_height height_lo, height_hi;
    double height_edge;         // metres
    layer_mask_range slope;     // degrees
    layer_mask_range curvature; // -100 x Laplacian, positive convex (as layer masks)
    double breakup;             // 0..1
} material_rule;

typedef struct material_rules {
    int count;
    material_rule rule[MATERIAL_RULES_MAX]; // bottom first
    // The default stack that no file gave: the first rule line read replaces it (so a
    // file without the keys keeps the default). Not part of the stack's value, nor is
    // reading (the rule numbers read so far, until material_rules_finish).
    int implicit;
    unsigned reading;
} material_rules;

// "sand" .. "cliff"; NULL out of range. Parse takes a name or an index 0-7, -1 if neither.
const char *material_name(int material);
int material_parse(const char *text);

// Today's look: sand, grass above the beach, rock on steep ground, cliff steeper, snow
// above 62% of the relief on gentle slopes (what materials.glsl hard-coded before);
// implicit (see above).
void material_rules_default(material_rules *r);
// A planet's default: no rules, so the planet's own look (by climate, latitude, height and
// slope) shows; its rules lay over that look as a flat world's lay over the first rule.
// Implicit as above.
void material_rules_planet_default(material_rules *r);
// For a planet's file once read: planet files saved before planets took rules hold the
// flat default stack (save wrote it; it drew nothing), which reads as the planet default.
void material_rules_planet_adopt(material_rules *r);
int material_rules_equal(const material_rules *a, const material_rules *b);

// A rule from its text, "MATERIAL [height=LO,HI[,EDGE]] [slope=...] [curvature=...]
// [breakup=B]". -1 with err naming the word and what was expected.
int material_rule_parse(material_rule *out, const char *text, og_error *err);
// One key of a rule (material, height, slope, curvature, breakup); `off` removes a
// term. The rule is unchanged on error.
int material_rule_set_option(material_rule *r, const char *key, const char *value, og_error *err);
// The rule's text (parse reads it back exactly); returns the length as snprintf does.
int material_rule_format(const material_rule *r, char *buf, size_t len);

// Inserts rule at index at (0 = bottom); -1 with err when the stack is full.
int material_rules_insert(material_rules *r, int at, const material_rule *rule, og_error *err);
void material_rules_remove(material_rules *r, int i);
void material_rules_move(material_rules *r, int from, int to);

// The parameter file's lines, bottom first: `material_rule_1 = RULE;` ..
// `material_rule_16`, or `material_rules = none;` for an empty stack (a file without
// them keeps the implicit default stack). read_entry returns 1 for another key, -1
// with err for a bad value; finish (after the last line) closes gaps a person left by
// deleting a line. A repeated number is the parameter file's duplicate key (the last
// wins, with a warning).
int material_rules_read_entry(material_rules *r, const char *key, const char *value, og_error *err);
void material_rules_finish(material_rules *r);
// Appends the lines (with a comment) to a growing text; -1 when out of memory.
int material_rules_format_lines(const material_rules *r, char **text, size_t *len, size_t *cap);

// The rules with heights in metres for a world's sea level and max_height, as the
// shaders take them: per term the four corners of its weight (starts rising, reaches 1,
// starts falling, reaches 0; LO - EDGE, LO, HI, HI + EDGE), open ends and terms not set
// as +-1e30; slopes as rise over run (their edges ease in rise over run, as the
// shaders' rules always did, so the default stack draws what it drew before).
typedef struct material_rules_resolved {
    int count;
    int material[MATERIAL_RULES_MAX];
    float height[MATERIAL_RULES_MAX][4], slope[MATERIAL_RULES_MAX][4];
    float curvature[MATERIAL_RULES_MAX][4];
    float breakup[MATERIAL_RULES_MAX];
    int uses_curvature; // some rule reads curvature
} material_rules_resolved;

double material_height_metres(const material_height *b, double sea, double max_height);
void material_rules_resolve(const material_rules *r, double sea, double max_height,
                            material_rules_resolved *out);
// Bit i set when rule i can have weight somewhere with heights in [hmin, hmax] and
// slopes up to slope_max (rise over run): a renderer skips the others (curvature is
// assumed to reach any value).
unsigned material_rules_live(const material_rules_resolved *r, double hmin, double hmax,
                             double slope_max);

#endif
