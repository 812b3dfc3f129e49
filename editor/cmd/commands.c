#include "editor/cmd/commands.h"

#include "editor/edit/edit.h"
#include "editor/edit/layer_generate.h"
#include "editor/edit/coarse_mips_fill.h"
#include "editor/edit/material_mips_fill.h"
#include "editor/edit/recover.h"
#include "editor/cmd/base_pending.h"
#include "editor/cmd/edit_commands.h"
#include "editor/cmd/interchange_commands.h"
#include "editor/cmd/layer_commands.h"
#include "editor/cmd/record.h"
#include "editor/cmd/material_commands.h"
#include "editor/cmd/volume_commands.h"
#include "editor/cmd/tokenize.h"
#include "editor/gen/gen.h"
#include "editor/params/planet_presets.h"
#include "editor/world/volume_grid.h"
#include "io/parse.h"

#include <errno.h>
#include <limits.h>
#include <sys/stat.h>
#include <time.h>
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

// ---- argument parsing ----------------------------------------------------------

static int parse_face(int argc, char **argv, int index, int *face, og_error *err) {
    *face = 0;
    if (argc <= index) return 0;
    int64_t f = 0;
    if (parse_integer(argv[index], "face", &f, err) != 0) return -1;
    *face = (int)(f < -1 ? -1 : (f > 6 ? 6 : f));
    return 0;
}

// ---- parameter printing ----------------------------------------------------------

static void print_params(FILE *out, const world_params *p) {
    char value[WORLD_VALUE_MAX];
    for (size_t i = 0; i < world_params_key_count(); i++) {
        const char *key = world_params_key(i);
        if (world_params_get(p, key, value, sizeof value) == 0)
            fprintf(out, "%s = %s;\n", key, value);
    }
}

// ---- commands --------------------------------------------------------------------

static int replace_world(cmd_context *ctx, world *w) {
    cmd_base_drop(ctx);
    world_close(ctx->world);
    ctx->world = w;
    ctx->world_serial++;
    ctx->next = *world_get_params(w);
    world_publish(w, &(world_event){.kind = WORLD_EVENT_REPLACED});
    return 0;
}

// `new planet [preset=NAME] [KEY=VALUE ...]`: the preset first, then any world
// parameter (the New planet dialog sends every field it shows).
static int new_planet(cmd_context *ctx, int argc, char **argv, og_error *err) {
    world_params p;
    world_params_default(&p, WORLD_PLANET);
    for (int i = 2; i < argc; i++) {
        const char *eq = strchr(argv[i], '=');
        if (!eq || eq == argv[i])
            return og_error_set(err, "new planet: expected KEY=VALUE, got '%s'", argv[i]);
        char key[64];
        snprintf(key, sizeof key, "%.*s", (int)(eq - argv[i]), argv[i]);
        if (strcmp(key, "preset") == 0) {
            if (i != 2) return og_error_set(err, "new planet: preset= must come first");
            if (planet_preset_apply(&p, eq + 1, err) != 0) return -1;
        } else if (strcmp(key, "kind") == 0) {
            return og_error_set(err, "new planet: kind is planet here");
        } else if (world_params_set(&p, key, eq + 1, err) != 0) {
            return -1;
        }
    }
    if (world_params_validate(&p, err) != 0) return -1;
    world *w = world_create(&p, &ctx->settings, err);
    return w ? replace_world(ctx, w) : -1;
}

static int c_new(cmd_context *ctx, int argc, char **argv, og_error *err) {
    if (argc >= 3 && strcmp(argv[1], "planet") == 0) return new_planet(ctx, argc, argv, err);
    if (argc > 2) {
        if (strcmp(argv[1], "flat") != 0 || strncmp(argv[2], "from=", 5) != 0 || !argv[2][5])
            return og_error_set(err,
                                "new: expected 'new flat|planet' or 'new flat from=FILE "
                                "[import options]', got '%s'",
                                argv[2]);
        base_pending *pending;
        world *w = cmd_world_from_raster(ctx, argv[2] + 5, argc, argv, 3, &pending, err);
        if (!w) return -1;
        replace_world(ctx, w);
        ctx->base_pending = pending; // its parts not imported yet (NULL: all are)
        return 0;
    }
    world_kind kind;
    if (strcmp(argv[1], "flat") == 0)
        kind = WORLD_FLAT;
    else if (strcmp(argv[1], "planet") == 0)
        kind = WORLD_PLANET;
    else
        return og_error_set(err, "new: expected 'flat' or 'planet', got '%s'", argv[1]);
    world_params p;
    world_params_default(&p, kind);
    world *w = world_create(&p, &ctx->settings, err);
    if (!w) return -1;
    return replace_world(ctx, w);
}

static int c_load(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc;
    int errors = 0;
    world *w = world_load(argv[1], &ctx->settings, &errors, err);
    if (!w) return -1;
    material_mips_fill_missing(w); // paint saved before it had far levels
    coarse_mips_fill_missing(w);   // heights too
    replace_world(ctx, w);
    ctx->reported_errors += errors;
    fprintf(ctx->out, "loaded %s%s\n", argv[1],
            world_file_errors(w) ? " (with errors: those keys keep their defaults; save will not "
                                   "write over the file without force=1)"
            : world_read_only(w)[0] ? " (read-only: see above)"
                                    : "");
    return 0;
}

// save [FILE] [force=1]
static int c_save(cmd_context *ctx, int argc, char **argv, og_error *err) {
    const char *file = NULL;
    int force = 0;
    for (int i = 1; i < argc; i++) {
        if (strncmp(argv[i], "force=", 6) == 0) {
            if (parse_switch(argv[i] + 6, "force", &force, err) != 0) return -1;
        } else if (!file) {
            file = argv[i];
        } else {
            return og_error_set(err, "save: expected 'save [FILE] [force=1]', got '%s'", argv[i]);
        }
    }
    if (world_save(ctx->world, file, force, err) != 0) return -1;
    // Both files it wrote, by name.
    tile_store *store = world_store(ctx->world);
    fprintf(ctx->out, "saved %s\n", world_path(ctx->world));
    if (store)
        fprintf(ctx->out, "  and its tile store %s (%" PRId64 " tiles)\n", tile_store_path(store),
                tile_store_count(store, -1));
    return 0;
}

static void print_recovered(cmd_context *ctx, const recover_report *r) {
    fprintf(ctx->out,
            "recovered %zu journal record%s of the last session (its steps are in the "
            "history); the world is unsaved: save keeps them\n",
            r->records, r->records == 1 ? "" : "s");
    if (r->dropped_bytes)
        fprintf(ctx->out, "a torn last step (%zu bytes) was left out\n", r->dropped_bytes);
}

static void print_journal(void *user, const recover_entry *e) {
    cmd_context *ctx = user;
    char when[64] = "?";
    time_t t = (time_t)e->scan.last;
    struct tm tm;
    if (e->scan.valid_bytes && localtime_r(&t, &tm))
        strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S", &tm);
    fprintf(ctx->out, "%s: %zu step%s, last %s%s; %s\n", e->path, e->scan.records,
            e->scan.records == 1 ? "" : "s", when,
            e->scan.dropped_bytes ? " (a torn tail is left out)" : "", e->status);
}

// The world file a saved world's journal (WORLD.recover, WORLD.recover.oldN) is beside.
static int journal_world(const char *journal, char *out, size_t len) {
    const char *mark = strstr(journal, ".recover");
    const char *last = mark;
    while (last && (mark = strstr(last + 1, ".recover")))
        last = mark;
    if (!last || last == journal || (size_t)(last - journal) >= len) return -1;
    snprintf(out, len, "%.*s", (int)(last - journal), journal);
    return 0;
}

// recover [list | discard [JOURNAL] | JOURNAL]: replay (or drop, or list) the journals
// sessions that did not save left: the world's own, one set aside, or a never-saved
// world's (by its file).
static int c_recover(cmd_context *ctx, int argc, char **argv, og_error *err) {
    if (argc > 1 && !strcmp(argv[1], "list")) {
        if (argc > 2) return og_error_set(err, "recover: expected 'recover list'");
        if (!edit_recover_list(ctx->world, print_journal, ctx))
            fprintf(ctx->out, "no recovery journals\n");
        return 0;
    }
    int discard = argc > 1 && strcmp(argv[1], "discard") == 0;
    const char *journal = argc > 1 + discard ? argv[1 + discard] : NULL;
    if (argc > 2 + discard || (argc == 3 && !discard))
        return og_error_set(err,
                            "recover: expected 'recover [list | discard [JOURNAL] | JOURNAL]'");
    if (discard) {
        char path[4400];
        snprintf(path, sizeof path, "%s", journal ? journal : world_recovery_path(ctx->world));
        if ((journal ? edit_discard_journal(ctx->world, journal, err)
                     : world_recover_discard(ctx->world, err)) != 0)
            return -1;
        fprintf(ctx->out, "discarded the unsaved edits in %s\n", path);
        return 0;
    }
    recover_report r;
    recovery_scan scan;
    world_journal_wait(ctx->world); // the journal named may be this session's own
    if (journal && recovery_journal_read(journal, &scan, NULL, NULL, err) != 0) return -1;
    if (journal && scan.has_base) {
        world *w =
            edit_recover_unsaved(journal, &ctx->settings, cmd_world_from_raster_again, &r, err);
        if (!w) return -1;
        replace_world(ctx, w);
        print_recovered(ctx, &r);
        return 0;
    }
    if (journal && strcmp(journal, world_recovery_path(ctx->world)) != 0) {
        // Another world's journal: that world is opened to take its steps (the current
        // one stays if anything fails).
        char file[4400];
        struct stat st;
        if (journal_world(journal, file, sizeof file) == 0 && stat(file, &st) == 0) {
            char real_a[PATH_MAX], real_b[PATH_MAX];
            int same = world_path(ctx->world)[0] && realpath(file, real_a) &&
                       realpath(world_path(ctx->world), real_b) && !strcmp(real_a, real_b);
            if (!same) {
                int errors = 0;
                world *w = world_load(file, &ctx->settings, &errors, err);
                if (!w) return -1;
                material_mips_fill_missing(w);
                coarse_mips_fill_missing(w);
                if (edit_recover(w, journal, &r, err) != 0) {
                    world_close(w);
                    return -1;
                }
                replace_world(ctx, w);
                fprintf(ctx->out, "loaded %s\n", file);
                print_recovered(ctx, &r);
                return 0;
            }
        }
    }
    if (!journal && !world_recoverable(ctx->world, NULL)) {
        // Point at a never-saved world's edits, if a crash left some.
        char path[4400];
        if (edit_find_unsaved_journal(path, sizeof path, &scan))
            return og_error_set(err,
                                "recover: this world has no unsaved edits to recover; a world "
                                "that was never saved left %zu steps in %s: 'recover %s'",
                                scan.records, path, path);
    }
    if (edit_recover(ctx->world, journal, &r, err) != 0) return -1;
    print_recovered(ctx, &r);
    return 0;
}

static int c_generate(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv;
    return layer_generate(ctx->world, &ctx->next, err);
}

static int c_generator(cmd_context *ctx, int argc, char **argv, og_error *err) {
    if (argc == 1) {
        for (int g = 0; g < GEN_COUNT; g++)
            fprintf(ctx->out, "%d %s%s\n", g, gen_kind_name((gen_kind)g),
                    ctx->next.generator == (gen_kind)g ? " *" : "");
        return 0;
    }
    return world_params_set(&ctx->next, "generator", argv[1], err) == 0 ? 0 : -1;
}

// seed, octaves, w_factor, ...: set the next world's parameter, or print it.
static int c_param(cmd_context *ctx, int argc, char **argv, og_error *err) {
    if (argc == 1) {
        char value[WORLD_VALUE_MAX];
        world_params_get(&ctx->next, argv[0], value, sizeof value);
        fprintf(ctx->out, "%s\n", value);
        return 0;
    }
    return world_params_set(&ctx->next, argv[0], argv[1], err) == 0 ? 0 : -1;
}

static int c_set(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc;
    int rc = world_params_set(&ctx->next, argv[1], argv[2], err);
    if (rc == 1) return og_error_set(err, "set: unknown key '%s' (see 'nparams')", argv[1]);
    return rc;
}

static int c_params(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv, (void)err;
    print_params(ctx->out, world_get_params(ctx->world));
    return 0;
}

static int c_nparams(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv, (void)err;
    print_params(ctx->out, &ctx->next);
    return 0;
}

static int c_info(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv, (void)err;
    const world_params *p = world_get_params(ctx->world);
    tile_cache_stats s;
    tile_cache_stats_get(world_cache(ctx->world), &s);
    FILE *o = ctx->out;
    fprintf(o, "path=%s\n", world_path(ctx->world));
    fprintf(o, "kind=%s\n", p->kind == WORLD_PLANET ? "planet" : "flat");
    fprintf(o, "generator=%s\n", gen_kind_name(p->generator));
    fprintf(o, "size=%" PRId64 "\n", p->size);
    if (p->kind == WORLD_FLAT) fprintf(o, "size_z=%" PRId64 "\n", world_params_size_z(p));
    fprintf(o, "spacing=%.17g\n", p->spacing);
    fprintf(o, "tile_size=%d\n", TILE_SIZE);
    if (p->kind == WORLD_PLANET) {
        // The cube-face grid sample, hash, dab, stroke and stamp address with FACE and
        // face-local metres 0 .. face_extent_m.
        int64_t n = world_grid_face_samples(p);
        // True metres on the sphere: sample_metres is the datum's arc per cell.
        fprintf(o, "face_samples=%" PRId64 "\nface_extent_m=%.17g\nsample_metres=%.17g\n", n,
                (double)(n - 1) * world_grid_sample_metres(p), world_grid_sample_metres(p));
    }
    if (p->kind == WORLD_FLAT) {
        tile_key *bricks = NULL;
        size_t n = 0;
        og_error ignored;
        if (volume_list_bricks(ctx->world, &bricks, &n, &ignored) == 0)
            fprintf(o, "volume_voxel=%.17g\nvolume_bricks=%zu\n",
                    p->spacing / (p->volume_ratio > 0 ? p->volume_ratio : 1), n);
        free(bricks);
    }
    tile_store *store = world_store(ctx->world);
    fprintf(o, "tile_store=%s\n", store ? tile_store_path(store) : "");
    fprintf(o, "tiles_stored=%" PRId64 "\n", store ? tile_store_count(store, -1) : 0);
    fprintf(o, "tiles_unsaved=%" PRId64 "\n", tile_store_count(world_journal(ctx->world), -1));
    fprintf(o, "unsaved_changes=%d\n", world_is_modified(ctx->world));
    fprintf(o, "read_only=%s\n", world_read_only(ctx->world));
    fprintf(o, "recoverable_steps=%zu\n", world_recoverable(ctx->world, NULL));
    fprintf(o, "cache_budget_bytes=%zu\n", s.budget_bytes);
    fprintf(o, "cache_resident_bytes=%zu\n", s.resident_bytes);
    fprintf(o, "cache_resident_tiles=%zu\n", s.resident_tiles);
    fprintf(o, "cache_overhead_bytes=%zu\n", s.overhead_bytes);
    fprintf(o, "cache_hits=%" PRIu64 "\n", s.hits);
    fprintf(o, "cache_misses=%" PRIu64 "\n", s.misses);
    fprintf(o, "cache_queue_depth=%zu\n", s.queue_depth);
    fprintf(o, "cache_generated=%" PRIu64 "\n", s.generated);
    fprintf(o, "cache_loaded=%" PRIu64 "\n", s.loaded);
    fprintf(o, "cache_written=%" PRIu64 "\n", s.written);
    fprintf(o, "cache_evicted=%" PRIu64 "\n", s.evicted);
    fprintf(o, "cache_corrupt=%" PRIu64 "\n", s.corrupt);
    fprintf(o, "cache_workers=%d\n", s.workers);
    return 0;
}

static int c_sample(cmd_context *ctx, int argc, char **argv, og_error *err) {
    double x = 0, z = 0, h = 0;
    int face;
    if (parse_number(argv[1], "X", &x, err) || parse_number(argv[2], "Z", &z, err) ||
        parse_face(argc, argv, 3, &face, err))
        return -1;
    if (world_sample(ctx->world, face, x, z, &h, err) != 0) return -1;
    fprintf(ctx->out, "%.6f\n", h);
    return 0;
}

static int c_vsample(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc;
    double p[3], d = 0;
    static const char *const axis[] = {"X", "Y", "Z"};
    for (int a = 0; a < 3; a++)
        if (parse_number(argv[1 + a], axis[a], &p[a], err) != 0) return -1;
    if (volume_sample(ctx->world, p, &d, err) != 0) return -1;
    fprintf(ctx->out, "%.6f %s\n", d, d < 0 ? "inside" : "outside");
    return 0;
}

static int c_hash(cmd_context *ctx, int argc, char **argv, og_error *err) {
    double r[4];
    const char *names[4] = {"X0", "Z0", "X1", "Z1"};
    for (int i = 0; i < 4; i++)
        if (parse_number(argv[1 + i], names[i], &r[i], err) != 0) return -1;
    int face;
    if (parse_face(argc, argv, 5, &face, err) != 0) return -1;
    uint64_t digest, count;
    if (world_hash(ctx->world, face, r[0], r[1], r[2], r[3], &digest, &count, err) != 0) return -1;
    fprintf(ctx->out, "%016" PRIx64 "\n", digest);
    return 0;
}

static int c_exit(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv, (void)err;
    ctx->exit_requested = 1;
    return 0;
}

static int c_help(cmd_context *ctx, int argc, char **argv, og_error *err);
static int c_cmdlist(cmd_context *ctx, int argc, char **argv, og_error *err);

#define PARAM_CMD(key, arg, text)                                                                  \
    { key, key " [" arg "]", text " Without a value, prints it.", 0, 1, c_param, 0 }

static const cmd_def commands[] = {
    {"new",
     "new flat|planet | new planet [preset=earth|mars|moon|asteroid] [KEY=VALUE ...] | new "
     "flat from=FILE [import options]",
     "Replaces the current world with a new one of that kind, with default parameters (a "
     "planet preset sets radius, max_height, ocean_level, omega, atmosphere and spacing for an "
     "Earth-, Mars- or Moon-like body or a small asteroid; KEY=VALUE then sets any world "
     "parameter, as set does, e.g. radius=2000000 seed=7); 'from=' "
     "makes a bounded flat world sized and spaced by a heightmap or elevation raster and imports "
     "it (see import for the options).",
     1, 24, c_new, CMD_ENDS_STROKE},
    {"load", "load FILE",
     "Loads a world (.world) or planet (.planet) parameter file and its tile store.", 1, 1, c_load,
     CMD_ENDS_STROKE},
    {"save", "save [FILE] [force=1]",
     "Saves the world's parameter file and tile store (to FILE, or where it was loaded from) and "
     "names both. It will not write over a file that loaded with errors (their lines would "
     "become defaults) or a file that is not a parameter file, unless force=1.",
     0, 2, c_save, CMD_ENDS_STROKE},
    {"recover", "recover [list | discard [JOURNAL] | JOURNAL]",
     "Restores the edits a session that ended without saving (a crash, a kill) left in the "
     "world's recovery journal: every committed step, undoable, the world unsaved; the journal "
     "stays until a save keeps its edits. 'recover list' lists every journal (the world's, "
     "those set aside as WORLD.recover.old..., never-saved worlds') with its steps and time; "
     "'recover JOURNAL' restores one of them (a never-saved world's as a new world, another "
     "world's by opening it); 'recover discard [JOURNAL]' drops one.",
     0, 2, c_recover, CMD_ENDS_STROKE},
    {"generate", "generate",
     "Regenerates the world from the next parameters (see nparams). Edited tiles stay.", 0, 0,
     c_generate, CMD_ENDS_STROKE},
    {"generator", "generator [G]",
     "Lists the generators, or picks one (name or number) for the next generate.", 0, 1,
     c_generator, 0},
    PARAM_CMD("seed", "N", "Sets the random seed (an integer) for the next generate."),
    PARAM_CMD("octaves", "F",
              "Sets the fBm octave count (fractional allowed) for the next generate."),
    PARAM_CMD("w_factor", "F",
              "Sets the fBm weight factor (gain per octave) for the next generate."),
    PARAM_CMD("exponent", "F", "Sets the fBm exponent (lacunarity) for the next generate."),
    PARAM_CMD("radius", "F", "Sets the planet radius in metres for the next generate."),
    PARAM_CMD("max_height", "F",
              "Sets the maximal terrain height in metres for the next generate."),
    PARAM_CMD("ocean_level", "F",
              "Sets the ocean level for the next generate: metres above the datum on flat "
              "worlds, the sea's radius on planets (seed 004: radius + 10 is 10 m up)."),
    PARAM_CMD("omega", "F", "Sets the planet's angular velocity for the next generate."),
    PARAM_CMD("spacing", "F", "Sets the metres between coarse samples for the next generate."),
    PARAM_CMD("size", "N",
              "Sets the samples per side of a flat world (0 = unbounded) for the next generate."),
    {"set", "set KEY VALUE",
     "Sets any world parameter (see nparams for the keys) for the next generate.", 2, 2, c_set, 0},
    {"params", "params", "Prints the current world's parameters.", 0, 0, c_params, 0},
    {"nparams", "nparams", "Prints the parameters the next generate will use.", 0, 0, c_nparams, 0},
    {"info", "info", "Prints key=value facts about the world, its tile store and the tile cache.",
     0, 0, c_info, 0},
    {"sample", "sample X Z [FACE]", "Prints the height in metres at world position X, Z (metres).",
     2, 3, c_sample, 0},
    {"vsample", "vsample X Y Z",
     "Prints the signed distance in metres from X, Y, Z (metres, Y up) to the solid's surface "
     "(terrain with its caves, overhangs and arches) and whether the point is inside or outside.",
     3, 3, c_vsample, 0},
    {"hash", "hash X0 Z0 X1 Z1 [FACE]",
     "Prints a hex digest of the coarse heights in that rectangle (metres).", 4, 5, c_hash, 0},
    {"tool", "tool [NAME] [KEY=VALUE ...]",
     "Picks and sets up the brush: raise lower smooth flatten set ramp noise terrace thermal "
     "hydraulic paint, and the volume tools fill carve vsmooth vflatten (3D points). Keys: radius "
     "(m) strength (0-1) falloff (smooth linear spherical constant "
     "curve) curve=t:v,... spacing (x radius) hold (1: a brush held still keeps dabbing) invert "
     "target (coarse detail) face amount height "
     "mode (both raise lower) scale octaves seed step sharpness talus iterations droplets erosion "
     "deposition evaporation capacity inertia material depth (m along the view ray, volume tools) "
     "lock (surface plane), memory (shared: radius is one for all tools and strength one for "
     "the surface tools and one for the volume tools, the default; per_tool: each tool keeps "
     "its own), auto_radius (m: a radius the editor picks from the distance to the ground; "
     "ignored once a radius= was given, which radius_chosen=1 shows). Without arguments, "
     "prints the brush.",
     0, 24, cmd_tool, 0},
    {"dab", "dab X Z [PRESSURE] | dab X Y Z [PRESSURE]",
     "One dab of the brush at X, Z (metres); the volume tools (fill carve vsmooth vflatten) take "
     "a 3D point X Y Z (Y up). One undo step.",
     2, 4, cmd_dab, CMD_ENDS_STROKE},
    {"stroke", "stroke X0 Z0 X1 Z1 [X2 Z2 ...] | stroke X0 Y0 Z0 [X1 Y1 Z1 ...]",
     "Drags the brush along the points (metres), dabbing every spacing x radius; the volume tools "
     "take X Y Z triples (fill and carve sweep a capsule between them). One undo step.",
     2, CMD_MAX_ARGS, cmd_stroke, CMD_ENDS_STROKE},
    {"arch", "arch X0 Y0 Z0 X1 Y1 Z1 [rise=M] [thickness=M]",
     "Adds a rock arch from foot X0 Y0 Z0 to foot X1 Y1 Z1 (metres, Y up), its middle rise "
     "metres above the line between them (half the span) and thickness metres thick (6). One "
     "undo step.",
     6, 8, cmd_arch, CMD_ENDS_STROKE},
    {"tunnel", "tunnel X0 Y0 Z0 X1 Y1 Z1 [...] [radius=R|R0,R1,...]",
     "Carves a tunnel along the points (metres, Y up), radius metres wide (5), or one radius per "
     "point. One undo step.",
     6, CMD_MAX_ARGS, cmd_tunnel, CMD_ENDS_STROKE},
    {"spire", "spire X Y Z [height=M] [radius=M] [taper=F] [cap=M]",
     "Adds a rock spire standing on X Y Z: height metres tall (30), radius metres at the foot "
     "(6), taper x radius at the top (0.3), and with cap= a capstone of that radius (a "
     "hoodoo). One undo step.",
     3, 7, cmd_spire, CMD_ENDS_STROKE},
    {"overhang", "overhang X0 Z0 X1 Z1 [distance=M] [thickness=M]",
     "Pushes a shelf of rock out from the cliff edge X0 Z0 - X1 Z1 (metres) over its lower side: "
     "distance metres out (8), thickness metres thick (4), its top level with the ground at the "
     "edge. One undo step.",
     4, 6, cmd_overhang, CMD_ENDS_STROKE},
    {"stroke_begin", "stroke_begin [invert=0|1] [tool=NAME] [face=F]",
     "Starts a stroke with the current tool (as a drag in the viewport does); stroke_to extends "
     "it, stroke_end makes it one undo step. invert=, tool= and face= (a planet's face the "
     "points are given on) change this stroke only (the viewport's Ctrl and Shift). Commands "
     "that change the world (dab, stamp, undo, save, load, ...) end it first.",
     0, 3, cmd_stroke_begin, CMD_ENDS_STROKE},
    {"stroke_to", "stroke_to X Z [PRESSURE] | stroke_to X Y Z [PRESSURE]",
     "Drags the open stroke to X, Z (metres), dabbing every spacing x radius; PRESSURE 0-1 (1). "
     "A volume tool's stroke takes X Y Z (Y up).",
     2, 4, cmd_stroke_to, 0},
    {"stroke_hold", "stroke_hold SECONDS",
     "The open stroke's brush rests where it is for SECONDS (0-60), as a brush held still in the "
     "viewport: it keeps dabbing there, 2 / spacing dabs a second (the tool's hold=0 turns that "
     "off; not ramp or the volume tools).",
     1, 1, cmd_stroke_hold, 0},
    {"stroke_end", "stroke_end",
     "Ends the open stroke as one undo step (a stroke that laid no dab leaves none).", 0, 0,
     cmd_stroke_end, 0},
    {"stroke_cancel", "stroke_cancel",
     "Abandons the open stroke: the terrain returns to how it was before it.", 0, 0,
     cmd_stroke_cancel, 0},
    {"stamp", "stamp NAME X Z [scale= rot= mirror= intensity= mode= layer= face=]",
     "Places a stamp centred at X, Z (metres): a functional shape, a library or user stamp (see "
     "stamps) or an image file. scale multiplies its natural size (128 samples, or one sample per "
     "pixel), rot is degrees, mirror none|x|z|xz, intensity metres at value 1 (50; 0.5 on detail), "
     "mode add|subtract|max|min|blend, layer coarse|detail. One undo step.",
     3, 10, cmd_stamp, CMD_ENDS_STROKE},
    {"stamp_add", "stamp_add IMAGE [NAME]",
     "Makes an image a user stamp: copies it into the user stamp folder as NAME (default: the "
     "file's name; NAME_2... when taken). Dropping an image on the editor window does this.",
     1, 2, cmd_stamp_add, CMD_NOT_RECORDED},
    {"stamps", "stamps",
     "Lists the stamps: functional shapes, the built-in library and the user's stamp folder.", 0, 0,
     cmd_stamps, 0},
    {"import",
     "import FILE [min= max= | scale= offset=] [spacing=] [x= z= | anchor=centre] "
     "[layer=] [resample=] [blend=] [falloff=] [channel=] [endian=] [format=] [width= height=]",
     "Imports a heightmap or elevation raster as one undo step: images (PNG, TIFF, EXR, PGM, PFM) "
     "through OpenImageIO, GeoTIFF, SRTM .hgt, ESRI ASCII grid and other rasters through GDAL, "
     "RAW/R16 (uint16 little-endian; endian=big, format=f32; square sizes inferred). Heights are "
     "metres as stored; 8/16-bit images map 0..top to min..max (default 0..max_height) unless "
     "scale=/offset= (height = stored x scale + offset) or the file's FILE.json sidecar say "
     "otherwise. Row 0, column 0 lands at x, z (default 0, 0 or the sidecar's origin), columns "
     "toward +X, rows toward +Z; anchor=centre centres it there. spacing= metres per sample "
     "(default: the file's georeferencing, else one world sample per pixel); layer coarse|detail, "
     "or new|NAME: into a new or the named height layer (made active); "
     "resample nearest|bilinear|bicubic; blend replace|add|max|min with falloff= metres at the "
     "edge; channel= names an image channel. Voids (nodata, NaN) are filled and counted.",
     1, 18, cmd_import, CMD_ENDS_STROKE},
    {"export",
     "export FILE [region=X0,Z0,X1,Z1] [preset=] [layer=] [layers=] [bits=] [min= max= | scale= "
     "offset=] | export N FILE.obj [size=]",
     "Writes a heightmap of the region (metres, corners; default the whole bounded world; "
     "layers=NAME: one height layer's signed change, layers=upto=NAME: the layers up to it) by "
     "the extension: .png 16-bit, .tif float GeoTIFF (bits=16: 16-bit TIFF), .exr float "
     "(channel Y), .r16/.raw 16-bit little-endian; plus FILE.json with spacing, origin and the "
     "height mapping (16-bit: the region's range, or min/max or scale/offset). Prints the "
     "settings for Unreal and Unity. preset unreal|unity|godot|houdini|blender checks the format "
     "and crops to the sizes the engine imports. tiles=CxR writes a grid of files sharing their "
     "edge samples, named NAME_x0_y0 (Unity: NAME_0_0; pattern= with {name} {x} {y}), each "
     "with its sidecar, plus FILE.json for the set; shard=I/N writes only the I-th of N "
     "contiguous runs of tiles (for GNU parallel or a Slurm array). layer=normals writes a "
     "tangent-space normal map "
     "(.png), layer=materials the material weights as FILE_m0-3.png and FILE_m4-7.png (RGBA). "
     ".obj, .ply and .glb write a mesh (metres, +Y up; simplify=METRES, solid=1, centred=1). "
     "Written to a temp file and renamed. On planets, export N FILE.obj [size=PIXELS] (seed "
     "004) writes the N-th subdivision of the cube (0 .. 20: 12 x 2^N triangles, watertight) "
     "with normals and per-face UVs, and FILE_height_F.png (16-bit, with .json) and "
     "FILE_normal_F.png for the six faces F, size= pixels per side at most (1024).",
     1, 16, cmd_export, 0},
    {"layers", "layers",
     "Lists the edit layers, top first: * the active one, index (0 = bottom), name, kind, "
     "blend, opacity, visible, locked, how many tiles hold its edits and its mask.",
     0, 0, cmd_layers, 0},
    {"layer",
     "layer new NAME [kind=height] [blend=add|replace|max|min] [opacity=0..1] | layer select "
     "NAME | layer set NAME [name=] [blend=] [opacity=] [visible=0|1] [locked=0|1] | layer mask "
     "NAME [height=LO,HI] [slope=] [curvature=] [flow=] [falloff=M] [invert=0|1] [clear] | layer "
     "move "
     "NAME up|down|top|bottom|to=I | layer duplicate NAME [NEW] | layer merge NAME | layer "
     "clear NAME | layer delete NAME",
     "Changes the stack of edit layers over the generated terrain (one undo step each). Tools "
     "write into the active layer (new and duplicate make theirs active); a hidden or locked "
     "active layer refuses them. merge folds a layer into the one below, keeping what is seen.",
     1, 12, cmd_layer, CMD_ENDS_STROKE},
    {"material_rules", "material_rules",
     "Lists the automatic material rules, bottom first: which material covers unpainted "
     "ground by height, slope and curvature.",
     0, 0, cmd_material_rules, 0},
    {"material_rule",
     "material_rule add MATERIAL [height=LO,HI[,EDGE]] [slope=LO,HI[,EDGE]] "
     "[curvature=LO,HI[,EDGE]] [breakup=B] [at=N] | set N KEY=VALUE ... | move N "
     "up|down|top|bottom|to=M | delete N | reset",
     "Changes the material rule stack (one undo step): heights in metres or percent of the "
     "relief above the sea (62%, 62%+40), slopes in degrees, curvature -100 x Laplacian "
     "(positive convex), EDGE a soft edge outside the range, off removes a term, breakup "
     "0..1 noise on the edge; reset brings back the default stack.",
     1, 12, cmd_material_rule, CMD_ENDS_STROKE},
    {"undo", "undo", "Undoes the last change (stroke, stamp, generate).", 0, 0, cmd_undo,
     CMD_ENDS_STROKE},
    {"redo", "redo", "Redoes the last undone change.", 0, 0, cmd_redo, CMD_ENDS_STROKE},
    {"history", "history [budget=MIB] | history script FILE",
     "Lists the undo steps (* = applied) and their memory; sets the history memory budget. "
     "'history script FILE' writes this session's commands (mouse strokes as stroke_begin, "
     "stroke_to with every point, stroke_end) as a script that replays it on the world it "
     "started from (the editor window keeps the session).",
     0, 2, cmd_history, CMD_ENDS_STROKE},
    {"help", "help [COMMAND]", "Prints help on all commands or one.", 0, 1, c_help, 0},
    {"cmdlist", "cmdlist", "Lists the command names.", 0, 0, c_cmdlist, 0},
    {"exit", "exit", "Stops (the rest of the script is not run).", 0, 0, c_exit, CMD_ENDS_STROKE},
};
#define BUILTIN_COUNT (sizeof commands / sizeof commands[0])

// Commands registered from outside (cmd_register), after the built-in ones.
#define REGISTERED_MAX 64
static const cmd_def *registered[REGISTERED_MAX];
static size_t registered_count;

size_t cmd_count(void) {
    return BUILTIN_COUNT + registered_count;
}

static const cmd_def *command_at(size_t i) {
    if (i < BUILTIN_COUNT) return &commands[i];
    return i - BUILTIN_COUNT < registered_count ? registered[i - BUILTIN_COUNT] : NULL;
}

const char *cmd_name(size_t i) {
    const cmd_def *c = command_at(i);
    return c ? c->name : NULL;
}

static const cmd_def *find_command(const char *name) {
    for (size_t i = 0; i < cmd_count(); i++)
        if (strcmp(command_at(i)->name, name) == 0) return command_at(i);
    return NULL;
}

int cmd_register(const cmd_def *defs, size_t count, og_error *err) {
    if (registered_count + count > REGISTERED_MAX)
        return og_error_set(err, "cmd_register: more than %d registered commands", REGISTERED_MAX);
    for (size_t i = 0; i < count; i++) {
        int taken = find_command(defs[i].name) != NULL;
        for (size_t k = 0; k < i && !taken; k++)
            taken = strcmp(defs[k].name, defs[i].name) == 0;
        if (taken)
            return og_error_set(err, "cmd_register: '%s' is already a command", defs[i].name);
    }
    for (size_t i = 0; i < count; i++)
        registered[registered_count++] = &defs[i];
    return 0;
}

static int c_help(cmd_context *ctx, int argc, char **argv, og_error *err) {
    if (argc > 1) {
        const cmd_def *c = find_command(argv[1]);
        if (!c) return og_error_set(err, "help: unknown command '%s' (try 'cmdlist')", argv[1]);
        fprintf(ctx->out, "%s\n  %s\n", c->usage, c->help);
        return 0;
    }
    fprintf(ctx->out, "Commands are separated by ';' or new lines; '#' starts a comment.\n");
    for (size_t i = 0; i < cmd_count(); i++)
        fprintf(ctx->out, "  %-26s %s\n", command_at(i)->usage, command_at(i)->help);
    return 0;
}

static int c_cmdlist(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv, (void)err;
    for (size_t i = 0; i < cmd_count(); i++)
        fprintf(ctx->out, "%s\n", command_at(i)->name);
    return 0;
}

// ---- driver ----------------------------------------------------------------------

static int execute(cmd_context *ctx, int argc, char **argv, og_error *err) {
    const cmd_def *c = find_command(argv[0]);
    if (!c) return og_error_set(err, "unknown command '%s' (try 'cmdlist' or 'help')", argv[0]);
    int n = argc - 1;
    if (n < c->min_args || n > c->max_args)
        return og_error_set(err, "%s: wrong number of arguments; usage: %s", c->name, c->usage);
    // A stroke is one undo step: nothing else changes the world in its middle.
    if (ctx->stroke && (c->flags & CMD_ENDS_STROKE) && cmd_end_stroke(ctx, err) != 0) return -1;
    ctx->skip_record = 0;
    // A world made from a raster and imported in parts so far: only a heightmap export
    // takes its parts (cmd_export); everything else that may read the world sees the whole.
    const int reads_no_world = c->run == c_new || c->run == c_exit || c->run == c_help ||
                               c->run == c_cmdlist || (c->flags & CMD_WHILE_BUSY);
    if (ctx->base_pending && c->run != cmd_export && !reads_no_world &&
        cmd_base_settle(ctx, err) != 0)
        return -1;
    // The crash journal's writer thread writes a step's record after its commit: what a
    // command prints (a hash, the history) follows the records of every step before it,
    // so a kill after a printed line loses no step it showed (e2e_faults).
    if (!reads_no_world && ctx->world) world_journal_wait(ctx->world);
    if (c->run(ctx, argc, argv, err) != 0) return -1;
    // `exit` is left out: a replay goes on to whatever follows it.
    if ((ctx->record || ctx->session) && c->run != c_exit && !(c->flags & CMD_NOT_RECORDED) &&
        !ctx->skip_record)
        cmd_record(ctx, argc, argv);
    return 0;
}

// 1 when every command of the script passes the test (and the text parsed).
static int every_command(const cmd_script *s, int (*test)(const cmd_def *c, int flags), int flags) {
    if (s->malformed) return 0;
    for (size_t i = 0; i < s->count; i++) {
        const cmd_def *c = find_command(s->calls[i].argv[0]);
        if (!c || !test(c, flags)) return 0;
    }
    return 1;
}

static int is_builtin(const cmd_def *c, int flags) {
    (void)flags;
    return c >= commands && c < commands + BUILTIN_COUNT;
}

static int has_flags(const cmd_def *c, int flags) {
    return (c->flags & flags) == flags;
}

int cmd_script_is_builtin(const cmd_script *s) {
    return every_command(s, is_builtin, 0);
}

int cmd_script_all_flagged(const cmd_script *s, int flags) {
    return every_command(s, has_flags, flags);
}

// Text checks tokenise the text for the question only (an empty script on no memory).
static int text_test(const char *text, size_t len, int (*test)(const cmd_def *c, int flags),
                     int flags) {
    cmd_script s;
    og_error ignored = {{0}};
    if (cmd_script_parse(&s, text, len, "", &ignored) != 0) return 0;
    int all = every_command(&s, test, flags);
    cmd_script_free(&s);
    return all;
}

int cmd_text_is_builtin(const char *text, size_t len) {
    return text_test(text, len, is_builtin, 0);
}

int cmd_text_all_flagged(const char *text, size_t len, int flags) {
    return text_test(text, len, has_flags, flags);
}

int cmd_script_run(cmd_context *ctx, const cmd_script *s, og_error *err) {
    og_error inner = {{0}};
    for (size_t i = 0; i < s->count; i++) {
        const cmd_call *c = &s->calls[i];
        if (execute(ctx, c->argc, c->argv, &inner) != 0)
            return og_error_set(err, "%s:%d: error: %s", s->label, c->line, inner.msg);
        if (ctx->exit_requested) return 0;
    }
    if (s->malformed) {
        *err = s->parse_error;
        return -1;
    }
    return 0;
}

int cmd_run(cmd_context *ctx, const char *text, size_t len, const char *label, og_error *err) {
    cmd_script s;
    if (cmd_script_parse(&s, text, len, label, err) != 0) return -1;
    int rc = cmd_script_run(ctx, &s, err);
    cmd_script_free(&s);
    return rc;
}
