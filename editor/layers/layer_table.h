// A world's stack of edit layers over its base (README.md, "Layers"): order, names,
// kinds, blends, opacity, flags and masks. Pure data, saved in the parameter file (one
// `layer.I = ...;` line per layer, bottom first) and kept in the undo history with the
// world's other parameters. The layers' tiles live in the tile store under their id
// (io/tile.h, tile_key_slot), so renaming or reordering a layer moves no tile.
#ifndef OROGEN_EDITOR_LAYER_TABLE_H
#define OROGEN_EDITOR_LAYER_TABLE_H

#include "editor/layers/layer_mask.h"
#include "io/err.h"

#include <stddef.h>
#include <stdint.h>

#define LAYER_MAX 32
#define LAYER_NAME_MAX 48
// Ids start above the tile slots of the composite (0) and the base (1).
#define LAYER_FIRST_ID 2
// The largest id; the slots above it hold layers' painted mask coverage (io/tile.h).
#define LAYER_ID_MAX 0x3fffff
// The tile slot of layer id's painted mask coverage: float 0..1 per sample in coarse
// tiles (never painted: 0).
static inline int32_t layer_coverage_slot(int32_t id) {
    return id + LAYER_ID_MAX + 1;
}

typedef enum layer_blend {
    LAYER_BLEND_ADD = 0, // a signed delta added to the layers below
    LAYER_BLEND_REPLACE, // the layer's own height where it has one
    LAYER_BLEND_MAX,     // the higher of the layer's height and the layers below
    LAYER_BLEND_MIN,     // the lower of them
    LAYER_BLEND_COUNT
} layer_blend;

// What a layer's tiles hold. Its kind is fixed when it is made.
typedef enum layer_kind {
    LAYER_KIND_HEIGHT = 0, // coarse heights combined by its blend (layer_blend.h)
    LAYER_KIND_PAINT,      // material weights laid over the layers below by their coverage
                           // (editor/layers/paint_blend.h); blend does not apply
    LAYER_KIND_COUNT
} layer_kind;

typedef struct layer_info {
    int32_t id; // stable: its tiles' slot
    char name[LAYER_NAME_MAX];
    layer_kind kind;
    layer_blend blend;
    double opacity; // 0-1
    int visible, locked;
    layer_mask mask; // where the layer applies (editor/layers/layer_mask.h); zero: everywhere
} layer_info;

typedef struct layer_table {
    int count;
    int active;      // index of the layer tools write to
    int32_t next_id; // never reused, so a deleted layer's tiles never reappear in another
    layer_info layers[LAYER_MAX]; // bottom first
} layer_table;

// The stack a world without layers gets: one add layer named "Sculpt".
void layer_table_default(layer_table *t);
// Index of the layer named name, or -1.
int layer_table_find(const layer_table *t, const char *name);
// Index of the layer with that id, or -1.
int layer_table_find_id(const layer_table *t, int32_t id);
// Whether two tables are the same stack (every field).
int layer_table_equal(const layer_table *a, const layer_table *b);

const char *layer_blend_name(layer_blend b);
const char *layer_kind_name(layer_kind k);
int layer_kind_parse(const char *text);  // -1 if not a kind
int layer_blend_parse(const char *text); // -1 if not a blend

// A layer name: 1-47 letters, digits, '_', '-' or '.' (so commands and files need no
// quoting). Returns 0, or -1 with err saying what is wrong with it.
int layer_name_check(const char *name, og_error *err);

// Inserts a new empty layer at index at (0 = bottom) with a fresh id. Returns its index,
// or -1 with err (full, bad or taken name).
int layer_table_insert(layer_table *t, int at, const char *name, layer_blend blend, double opacity,
                       og_error *err);
// Removes the layer at index i (the active index follows its layer, or the one below).
void layer_table_remove(layer_table *t, int i);
// Moves the layer at index from to index to (the active index follows its layer).
void layer_table_move(layer_table *t, int from, int to);

// The tile kind a layer's tiles hold (io/tile.h): coarse heights or material weights.
int layer_tile_kind(const layer_info *l);
// Index of the highest visible layer of that kind, or -1.
int layer_table_top_visible(const layer_table *t, layer_kind kind);

// Sets one of the layer's fields from text: name, blend (height layers), opacity, visible,
// locked.
// Returns 0, 1 for an unknown key, or -1 with err naming the field and the bad value.
int layer_info_set(layer_table *t, int i, const char *key, const char *value, og_error *err);

// The parameter file's lines. A `layer.I` value (I = 0 for the bottom layer, 1, ...): "NAME id=N
// blend=B opacity=O visible=V locked=L [MASK KEY=VALUE ...]" (layer_mask_format's keys); a paint
// layer's "NAME id=N kind=paint opacity=O ..." (no blend), appended
// on top; `layer_active` names the active layer; `layer_next_id`. Returns 0, 1 when key is not a
// layer key, -1 with err for a bad value.
int layer_table_read_entry(layer_table *t, const char *key, const char *value, og_error *err);
// After the last entry: checks ids are unique and fixes next_id. -1 with err if not.
int layer_table_finish(layer_table *t, og_error *err);
// Appends the table's lines (with a comment) to a growing text; -1 when out of memory.
int layer_table_format(const layer_table *t, char **text, size_t *len, size_t *cap);
// Whether key is one of a mask's (height, slope, curvature, flow, falloff, invert, painted).
int layer_mask_key(const char *key);
// One layer's value as the file and `layers` write it (mask keys last, when it has one).
void layer_info_format(const layer_info *l, char *buf, size_t len);

#endif
