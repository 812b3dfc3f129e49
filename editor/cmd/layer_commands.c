#include "editor/cmd/layer_commands.h"

#include "editor/edit/edit_commit.h"
#include "editor/edit/layer_composite.h"
#include "editor/edit/paint_composite.h"
#include "io/parse.h"

#include <stdlib.h>
#include <string.h>

int cmd_layers(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv;
    const layer_table *t = &world_get_params(ctx->world)->layers;
    for (int i = t->count - 1; i >= 0; i--) { // top first, as a layer panel shows them
        const layer_info *l = &t->layers[i];
        size_t filled;
        if (layer_count_filled(ctx->world, l->id, &filled, err) != 0) return -1;
        char mask[512] = "none";
        if (layer_mask_active(&l->mask)) layer_mask_format(&l->mask, mask, sizeof mask);
        // A paint layer has no blend: it covers by its painted coverage.
        fprintf(ctx->out,
                "%c %d %s kind=%s blend=%s opacity=%g visible=%d locked=%d tiles=%zu mask=%s\n",
                i == t->active ? '*' : ' ', i, l->name, layer_kind_name(l->kind),
                l->kind == LAYER_KIND_PAINT ? "cover" : layer_blend_name(l->blend), l->opacity,
                l->visible, l->locked, filled, mask);
    }
    return 0;
}

static int find_layer(const layer_table *t, const char *name, og_error *err) {
    int i = layer_table_find(t, name);
    if (i < 0) {
        char names[LAYER_MAX * (LAYER_NAME_MAX + 1)] = "";
        for (int k = 0; k < t->count; k++) {
            strcat(names, k ? " " : "");
            strcat(names, t->layers[k].name);
        }
        return og_error_set(err, "layer: no layer named '%s' (the layers: %s)", name, names);
    }
    return i;
}

// The changes of one layer command: the new table, and the tiles to recompose with it.
typedef struct layer_change {
    const char *label;
    world_params next;
    int32_t recompose_ids[2];   // layers whose tiles change the composite (0: none)
    int32_t copy_from, copy_to; // duplicate: tiles from -> to
    int32_t clear_id;           // clear: that layer's tiles to nothing
    int merge_below;            // merge: layer index below the merged one (-1: none)
    int merge_paint;            // merge: of paint layers
    // A painted mask's coverage: copied (duplicate: from -> to, layer ids) or emptied
    // (clear: that layer's); recomposed as its layer's kind.
    int32_t coverage_from, coverage_to, coverage_clear;
    tile_layer coverage_kind;
} layer_change;

static int tiles_of(world *w, int32_t id, tile_key **keys, size_t *n, og_error *err) {
    *keys = NULL;
    *n = 0;
    return id ? layer_tiles(w, id, keys, n, err) : 0;
}

// Copies or empties a painted mask's coverage tiles.
static int change_coverage(edit *e, const layer_change *c, og_error *err) {
    int32_t from = c->coverage_clear ? -1 : layer_coverage_slot(c->coverage_from);
    int32_t to = layer_coverage_slot(c->coverage_clear ? c->coverage_clear : c->coverage_to);
    tile_key *keys;
    size_t n;
    if (layer_tiles(edit_world(e), c->coverage_clear ? to : from, &keys, &n, err) != 0) return -1;
    int rc = layer_copy_tiles(e, from, to, keys, n, err);
    free(keys);
    return rc;
}

// After emptying a coverage: the composite where it was painted (as the layer's kind).
static int recompose_coverage(edit *e, const layer_change *c, og_error *err) {
    tile_key *keys;
    size_t n;
    if (layer_tiles(edit_world(e), layer_coverage_slot(c->coverage_clear), &keys, &n, err) != 0)
        return -1;
    for (size_t i = 0; i < n; i++)
        keys[i].layer = tile_layer_in_slot(c->coverage_kind, c->coverage_clear);
    int rc = layer_recompose_tiles(e, keys, n, err);
    free(keys);
    return rc;
}

// Runs a change as one edit (one undo step).
static int apply_change(cmd_context *ctx, const layer_change *c, og_error *err) {
    world *w = ctx->world;
    tile_key *keys[2] = {NULL, NULL};
    size_t counts[2] = {0, 0};
    for (int i = 0; i < 2; i++)
        if (tiles_of(w, c->recompose_ids[i], &keys[i], &counts[i], err) != 0) {
            free(keys[0]);
            return -1;
        }
    edit *e = edit_begin(w, c->label, err);
    int rc = e ? 0 : -1;
    if (e) edit_set_layer_mode(e, EDIT_LAYER_COMPOSED);
    // Tile work that reads the table as it was comes first (merge), then the new table.
    if (rc == 0 && c->merge_below >= 0) { // over the tiles of both
        tile_key *both = malloc((counts[0] + counts[1] + 1) * sizeof *both);
        size_t n = 0;
        if (!both)
            rc = og_error_set(err, "out of memory merging layers");
        else {
            for (int i = 0; i < 2; i++)
                for (size_t k = 0; k < counts[i]; k++) {
                    tile_key key = keys[i][k];
                    key.layer = tile_layer_in_slot(tile_key_kind(key), 0); // the place
                    size_t m = 0;
                    while (m < n && !tile_key_equal(both[m], key))
                        m++;
                    if (m == n) both[n++] = key;
                }
            for (size_t k = 0; k < n; k++)
                both[k].layer = tile_layer_in_slot(tile_key_kind(both[k]), c->recompose_ids[0]);
            rc = c->merge_paint ? paint_merge_tiles(e, c->merge_below, both, n, err)
                                : layer_merge_tiles(e, c->merge_below, both, n, err);
            free(both);
        }
    }
    if (rc == 0 && c->copy_to)
        rc = layer_copy_tiles(e, c->copy_from, c->copy_to, keys[0], counts[0], err);
    if (rc == 0 && c->clear_id) rc = layer_copy_tiles(e, -1, c->clear_id, keys[0], counts[0], err);
    if (rc == 0 && (c->coverage_to || c->coverage_clear)) rc = change_coverage(e, c, err);
    if (rc == 0) rc = edit_set_params(e, &c->next, err);
    for (int i = 0; i < 2 && rc == 0; i++)
        rc = layer_recompose_tiles(e, keys[i], counts[i], err);
    if (rc == 0 && c->coverage_clear) rc = recompose_coverage(e, c, err);
    free(keys[0]);
    free(keys[1]);
    if (!e) return -1;
    if (rc != 0) {
        edit_abort(e);
        return -1;
    }
    return edit_commit(e, err);
}

// A layer leaving the table empties its tiles and painted coverage in the same step (the
// undo history keeps what they held), so saving drops them from the store.
static void forget_tiles(layer_change *c, const layer_info *l) {
    c->clear_id = l->id;
    c->coverage_clear = l->id;
    c->coverage_kind = (tile_layer)layer_tile_kind(l);
}

static int refuse_locked(const layer_info *l, const char *what, og_error *err) {
    if (!l->locked) return 0;
    return og_error_set(err,
                        "layer %s: layer '%s' is locked (unlock it with 'layer set %s locked=0')",
                        what, l->name, l->name);
}

static int layer_new(cmd_context *ctx, int argc, char **argv, layer_change *c, og_error *err) {
    layer_table *t = &c->next.layers;
    layer_blend blend = LAYER_BLEND_ADD;
    layer_kind kind = LAYER_KIND_HEIGHT;
    int has_blend = 0;
    double opacity = 1.0;
    for (int i = 3; i < argc; i++) {
        char buf[256], *key, *value;
        if (parse_setting(argv[i], buf, sizeof buf, &key, &value, err) != 0) return -1;
        if (!strcmp(key, "kind")) {
            int k = layer_kind_parse(value);
            if (k < 0)
                return og_error_set(err, "layer new: kind: expected height or paint, got '%s'",
                                    value);
            kind = (layer_kind)k;
        } else if (!strcmp(key, "blend")) {
            has_blend = 1;
            int b = layer_blend_parse(value);
            if (b < 0)
                return og_error_set(
                    err, "layer new: blend: expected add, replace, max or min, got '%s'", value);
            blend = (layer_blend)b;
        } else if (!strcmp(key, "opacity")) {
            char *end;
            opacity = strtod(value, &end);
            if (*end || end == value || !(opacity >= 0 && opacity <= 1))
                return og_error_set(
                    err, "layer new: opacity: expected a number from 0 to 1, got '%s'", value);
        } else {
            return og_error_set(err, "layer new: unknown setting '%s' (kind, blend, opacity)", key);
        }
    }
    (void)ctx;
    if (kind == LAYER_KIND_PAINT && has_blend)
        return og_error_set(err, "layer new: blend: a paint layer covers what is below by its "
                                 "painted coverage (blend is for height layers)");
    og_error why;
    int at = layer_table_insert(t, t->count ? t->active + 1 : 0, argv[2], blend, opacity, &why);
    if (at < 0) return og_error_set(err, "layer new: %s", why.msg);
    t->layers[at].kind = kind;
    t->active = at;
    return 0;
}

static int layer_set(layer_change *c, int i, int argc, char **argv, og_error *err) {
    layer_table *t = &c->next.layers;
    const layer_info before = t->layers[i];
    if (argc < 4)
        return og_error_set(
            err, "layer set: expected KEY=VALUE (name, blend, opacity, visible, locked)");
    for (int k = 3; k < argc; k++) {
        char buf[256], *key, *value;
        if (parse_setting(argv[k], buf, sizeof buf, &key, &value, err) != 0) return -1;
        og_error why;
        int rc = layer_info_set(t, i, key, value, &why);
        if (rc > 0)
            return og_error_set(err,
                                "layer set: unknown setting '%s' (name, blend, opacity, visible, "
                                "locked)",
                                key);
        if (rc < 0) return og_error_set(err, "layer set: %s", why.msg);
    }
    const layer_info *after = &t->layers[i];
    if (after->blend != before.blend || after->opacity != before.opacity ||
        after->visible != before.visible)
        c->recompose_ids[0] = after->id;
    return 0;
}

// `layer mask NAME [KEY=VALUE ...] [clear]`: without settings prints the mask.
// painted=clear empties the painted coverage (c->coverage_clear).
static int layer_mask_set(cmd_context *ctx, layer_change *c, layer_info *l, int argc, char **argv,
                          og_error *err) {
    if (argc == 3) {
        char text[512] = "none";
        if (layer_mask_active(&l->mask)) layer_mask_format(&l->mask, text, sizeof text);
        fprintf(ctx->out, "%s\n", text);
        return 0;
    }
    layer_mask m = l->mask;
    for (int k = 3; k < argc; k++) {
        if (!strcmp(argv[k], "clear")) {
            layer_mask_init(&m);
            continue;
        }
        char buf[256], *key, *value;
        if (parse_setting(argv[k], buf, sizeof buf, &key, &value, err) != 0) return -1;
        if (!layer_mask_key(key))
            return og_error_set(err,
                                "layer mask: unknown setting '%s' (height, slope, curvature, flow, "
                                "falloff, invert, painted, clear)",
                                key);
        if (!strcmp(key, "painted") && !strcmp(value, "clear")) {
            c->coverage_clear = l->id;
            c->coverage_kind = (tile_layer)layer_tile_kind(l);
            continue;
        }
        og_error why;
        if (layer_mask_set_option(&m, key, value, &why) != 0)
            return og_error_set(err, "layer mask: %s", why.msg);
    }
    l->mask = m;
    return 0;
}

static int layer_move(layer_change *c, int i, const char *where, og_error *err) {
    layer_table *t = &c->next.layers;
    int to;
    if (!strcmp(where, "up"))
        to = i + 1;
    else if (!strcmp(where, "down"))
        to = i - 1;
    else if (!strcmp(where, "top"))
        to = t->count - 1;
    else if (!strcmp(where, "bottom"))
        to = 0;
    else if (!strncmp(where, "to=", 3)) {
        int64_t v;
        if (parse_integer(where + 3, "to", &v, err) != 0) return -1;
        if (v < 0 || v >= t->count)
            return og_error_set(err,
                                "layer move: to: expected an index from 0 (bottom) to %d (top), "
                                "got %lld",
                                t->count - 1, (long long)v);
        to = (int)v;
    } else {
        return og_error_set(err, "layer move: expected up, down, top, bottom or to=I, got '%s'",
                            where);
    }
    if (to < 0 || to >= t->count)
        return og_error_set(err, "layer move: '%s' is already at the %s", t->layers[i].name,
                            to < 0 ? "bottom" : "top");
    layer_table_move(t, i, to);
    c->recompose_ids[0] = t->layers[to].id; // only where it has samples does order matter
    return 0;
}

int cmd_layer(cmd_context *ctx, int argc, char **argv, og_error *err) {
    const char *sub = argv[1];
    layer_change c = {.next = *world_get_params(ctx->world), .merge_below = -1};
    layer_table *t = &c.next.layers;
    char label[160];
    snprintf(label, sizeof label, "layer %s %s", sub, argc > 2 ? argv[2] : "");
    c.label = label;
    if (!strcmp(sub, "new")) {
        if (argc < 3) return og_error_set(err, "layer new: expected a NAME");
        if (layer_new(ctx, argc, argv, &c, err) != 0) return -1;
        return apply_change(ctx, &c, err);
    }
    static const char *const subs[] = {"select",    "set",   "mask",  "move",
                                       "duplicate", "merge", "clear", "delete"};
    size_t s = 0;
    while (s < sizeof subs / sizeof subs[0] && strcmp(subs[s], sub))
        s++;
    if (s == sizeof subs / sizeof subs[0])
        return og_error_set(err,
                            "layer: unknown action '%s' (new, select, set, mask, move, "
                            "duplicate, merge, clear, delete)",
                            sub);
    if (argc < 3) return og_error_set(err, "layer %s: expected a layer NAME", sub);
    int i = find_layer(t, argv[2], err);
    if (i < 0) return -1;
    layer_info *l = &t->layers[i];
    if (!strcmp(sub, "select")) {
        if (argc > 3) return og_error_set(err, "layer select: expected only a NAME");
        t->active = i;
    } else if (!strcmp(sub, "set")) {
        if (layer_set(&c, i, argc, argv, err) != 0) return -1;
    } else if (!strcmp(sub, "move")) {
        if (argc != 4)
            return og_error_set(err, "layer move: expected NAME up|down|top|bottom|to=I");
        if (layer_move(&c, i, argv[3], err) != 0) return -1;
    } else if (!strcmp(sub, "duplicate")) {
        if (argc > 4) return og_error_set(err, "layer duplicate: expected NAME [NEW_NAME]");
        char name[LAYER_NAME_MAX + 8];
        if (argc == 4)
            snprintf(name, sizeof name, "%s", argv[3]);
        else
            for (int n = 1; n < 1000; n++) {
                snprintf(name, sizeof name, n == 1 ? "%.*s_copy" : "%.*s_copy%d",
                         LAYER_NAME_MAX - 10, l->name, n);
                if (layer_table_find(t, name) < 0) break;
            }
        layer_info copy = *l;
        og_error why;
        int at = layer_table_insert(t, i + 1, name, copy.blend, copy.opacity, &why);
        if (at < 0) return og_error_set(err, "layer duplicate: %s", why.msg);
        t->layers[at].kind = copy.kind;
        t->layers[at].visible = copy.visible;
        t->layers[at].mask = copy.mask;
        t->active = at;
        c.copy_from = copy.id;
        c.copy_to = t->layers[at].id;
        c.coverage_from = copy.id; // its painted mask too
        c.coverage_to = t->layers[at].id;
        c.recompose_ids[0] = copy.id;
    } else if (!strcmp(sub, "merge")) {
        if (argc > 3) return og_error_set(err, "layer merge: expected only a NAME");
        if (i == 0)
            return og_error_set(
                err,
                "layer merge: '%s' is the bottom layer: there is none below to merge "
                "into",
                l->name);
        layer_info *below = &t->layers[i - 1];
        if (refuse_locked(l, "merge", err) || refuse_locked(below, "merge", err)) return -1;
        if (!l->visible || !below->visible)
            return og_error_set(
                err,
                "layer merge: layer '%s' is hidden: show it first (merging keeps what "
                "is seen)",
                l->visible ? below->name : l->name);
        if (l->kind != below->kind)
            return og_error_set(err,
                                "layer merge: '%s' is a %s layer and '%s' below it a %s layer: "
                                "only layers of one kind merge (move one first)",
                                l->name, layer_kind_name(l->kind), below->name,
                                layer_kind_name(below->kind));
        c.merge_below = i - 1;
        c.merge_paint = l->kind == LAYER_KIND_PAINT;
        c.recompose_ids[0] = l->id;
        forget_tiles(&c, l); // the merged layer's
        c.recompose_ids[1] = below->id;
        // Masks and (for paint) opacity are baked into the merged layer's samples.
        if (c.merge_paint || layer_mask_active(&l->mask) || layer_mask_active(&below->mask)) {
            if (!c.merge_paint) below->blend = LAYER_BLEND_ADD;
            below->opacity = 1.0;
            layer_mask_init(&below->mask);
        }
        layer_table_remove(t, i);
        t->active = i - 1;
    } else if (!strcmp(sub, "mask")) {
        if (layer_mask_set(ctx, &c, l, argc, argv, err) != 0) return -1;
        if (argc == 3) return 0; // printed it
        c.recompose_ids[0] = l->id;
    } else if (!strcmp(sub, "clear")) {
        if (argc > 3) return og_error_set(err, "layer clear: expected only a NAME");
        if (refuse_locked(l, "clear", err)) return -1;
        c.clear_id = l->id;
        c.recompose_ids[0] = l->id;
    } else { // delete
        if (argc > 3) return og_error_set(err, "layer delete: expected only a NAME");
        if (t->count == 1)
            return og_error_set(err,
                                "layer delete: '%s' is the only layer (a world keeps one for the "
                                "tools); clear it instead",
                                l->name);
        if (refuse_locked(l, "delete", err)) return -1;
        c.recompose_ids[0] = l->id;
        forget_tiles(&c, l);
        layer_table_remove(t, i);
    }
    if (layer_table_equal(t, &world_get_params(ctx->world)->layers) && !c.clear_id &&
        !c.coverage_clear)
        return 0;
    return apply_change(ctx, &c, err);
}
