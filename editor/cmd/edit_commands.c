#include "editor/cmd/edit_commands.h"

#include "editor/cmd/record.h"

#include "io/param_file.h"

#include "editor/edit/edit.h"
#include "editor/world/history.h"
#include "editor/tools/stamp.h"
#include "editor/tools/stamp_user.h"
#include "editor/tools/stroke.h"
#include "editor/tools/volume_brush.h"
#include "io/parse.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

// The settings tool t had when it was last used (its defaults the first time), on the
// face the current brush is on.
static brush recalled_tool(const cmd_context *ctx, brush_tool t) {
    brush b;
    if (ctx->tool_remembered & (1u << t))
        b = ctx->tool_memory[t];
    else
        brush_defaults(&b, t);
    b.face = ctx->brush.face;
    return b;
}

static void remember_tool(cmd_context *ctx, const brush *b) {
    ctx->tool_memory[b->tool] = *b;
    ctx->tool_remembered |= 1u << b->tool;
}

int cmd_tool(cmd_context *ctx, int argc, char **argv, og_error *err) {
    if (argc == 1) {
        brush_print(&ctx->brush, ctx->out);
        fprintf(ctx->out, "memory=%s\nradius_chosen=%d\n",
                ctx->tool_size_per_tool ? "per_tool" : "shared", ctx->radius_chosen);
        return 0;
    }
    int t = brush_tool_parse(argv[1]);
    if (t < 0) {
        og_error_set(err, "unknown tool '%s' (tools:", argv[1]);
        for (int i = 0; i < BRUSH_TOOL_COUNT; i++) {
            size_t n = strlen(err->msg);
            snprintf(err->msg + n, sizeof err->msg - n, " %s", brush_tool_name((brush_tool)i));
        }
        size_t n = strlen(err->msg);
        snprintf(err->msg + n, sizeof err->msg - n, " lower)");
        return -1;
    }
    // Each tool keeps its own settings (Terrain3D, Unreal): the one left is remembered,
    // the one picked comes back as it was. Raise and lower are one tool, inverted.
    // Size and strength are the artist's, shared by every tool (as Unreal's and Terrain3D's
    // brush size), unless memory=per_tool asks each tool to keep its own. Strength is
    // shared within the surface tools and within the volume tools: a carve at a raise's
    // half strength would leave half-solid rock in a tunnel.
    brush b = ctx->brush;
    int per_tool = ctx->tool_size_per_tool;
    for (int i = 2; i < argc; i++)
        if (strncmp(argv[i], "memory=", 7) == 0) {
            const char *m = argv[i] + 7;
            if (strcmp(m, "shared") != 0 && strcmp(m, "per_tool") != 0)
                return og_error_set(err, "tool: memory=%s: expected shared or per_tool", m);
            per_tool = strcmp(m, "per_tool") == 0;
        }
    if (b.tool != (brush_tool)t) {
        remember_tool(ctx, &ctx->brush);
        b = recalled_tool(ctx, (brush_tool)t);
        if (!per_tool) b.radius = ctx->brush.radius;
        if (!per_tool && brush_tool_is_volume(b.tool) == brush_tool_is_volume(ctx->brush.tool))
            b.strength = ctx->brush.strength;
    }
    if (t == BRUSH_RAISE) b.invert = strcmp(argv[1], "lower") == 0;
    // auto_radius= is the radius the editor's view picks from the distance to the ground
    // (a brush that shows at any distance) until the user gives a radius=.
    int chosen = ctx->radius_chosen;
    for (int i = 2; i < argc; i++) {
        char buf[512], *key = NULL, *value = NULL;
        if (strncmp(argv[i], "memory=", 7) == 0) continue;
        if (parse_setting(argv[i], buf, sizeof buf, &key, &value, err) != 0) return -1;
        if (strcmp(key, "auto_radius") == 0) {
            brush checked = b; // checked even when the user's radius makes it moot
            if (brush_set(&checked, "radius", value, err) != 0) return -1;
            if (!chosen) b.radius = checked.radius;
            continue;
        }
        if (strcmp(key, "radius") == 0) chosen = 1;
        if (brush_set(&b, key, value, err) != 0) return -1;
    }
    ctx->radius_chosen = chosen;
    ctx->tool_size_per_tool = per_tool;
    if (argc == 2 || b.tool != ctx->brush.tool) ctx->tool_serial++; // a tool picked
    ctx->brush = b;
    remember_tool(ctx, &b);
    return 0;
}

static int parse_point(char **argv, int i, double *x, double *z, og_error *err) {
    return parse_number(argv[i], "X", x, err) || parse_number(argv[i + 1], "Z", z, err) ? -1 : 0;
}

// The volume tools' dab and stroke: X Y Z points (metres, Y up).
static int volume_points(const char *cmd, const char *tool, int argc, char **argv,
                         int with_pressure, double (**points)[3], double **pressure, size_t *count,
                         og_error *err) {
    int numbers = argc - 1;
    int ok = with_pressure ? numbers == 3 || numbers == 4 : numbers >= 3 && numbers % 3 == 0;
    if (!ok)
        return og_error_set(err, "%s: %s is a volume tool: expected %s (got %d numbers)", cmd, tool,
                            with_pressure ? "X Y Z [PRESSURE]" : "X Y Z triples", numbers);
    *count = with_pressure ? 1 : (size_t)numbers / 3;
    *points = calloc(*count, sizeof **points);
    *pressure = calloc(*count, sizeof **pressure);
    if (!*points || !*pressure) return og_error_set(err, "out of memory");
    static const char *const axis[] = {"X", "Y", "Z"};
    for (size_t i = 0; i < *count; i++) {
        (*pressure)[i] = 1.0;
        for (int a = 0; a < 3; a++)
            if (parse_number(argv[1 + 3 * i + a], axis[a], &(*points)[i][a], err) != 0) return -1;
    }
    if (numbers == 4 && parse_number(argv[4], "pressure", &(*pressure)[0], err) != 0) return -1;
    return 0;
}

static int volume_command(cmd_context *ctx, int argc, char **argv, int dab, og_error *err) {
    double(*points)[3] = NULL, *pressure = NULL;
    size_t count = 0;
    int rc = volume_points(argv[0], brush_tool_name(ctx->brush.tool), argc, argv, dab, &points,
                           &pressure, &count, err);
    if (rc == 0) rc = volume_brush_apply(ctx->world, &ctx->brush, points, pressure, count, err);
    free(points);
    free(pressure);
    return rc;
}

int cmd_dab(cmd_context *ctx, int argc, char **argv, og_error *err) {
    if (brush_tool_is_volume(ctx->brush.tool)) return volume_command(ctx, argc, argv, 1, err);
    if (argc > 4)
        return og_error_set(err, "dab: %s takes X Z [PRESSURE] (got %d numbers)",
                            brush_tool_name(ctx->brush.tool), argc - 1);
    double x = 0, z = 0, pressure = 1.0;
    if (parse_point(argv, 1, &x, &z, err) != 0) return -1;
    if (argc > 3 && parse_number(argv[3], "pressure", &pressure, err) != 0) return -1;
    stroke *s = stroke_begin(ctx->world, &ctx->brush, err);
    if (!s) return -1;
    if (stroke_to(s, x, z, pressure, err) != 0) {
        stroke_cancel(s);
        return -1;
    }
    return stroke_end(s, err);
}

int cmd_stroke(cmd_context *ctx, int argc, char **argv, og_error *err) {
    if (brush_tool_is_volume(ctx->brush.tool)) return volume_command(ctx, argc, argv, 0, err);
    if ((argc - 1) % 2 != 0)
        return og_error_set(err, "stroke: expected X Z pairs (got %d numbers)", argc - 1);
    // Check every point before touching the world.
    for (int i = 1; i < argc; i += 2) {
        double x = 0, z = 0;
        if (parse_point(argv, i, &x, &z, err) != 0) return -1;
    }
    stroke *s = stroke_begin(ctx->world, &ctx->brush, err);
    if (!s) return -1;
    for (int i = 1; i < argc; i += 2) {
        double x = 0, z = 0;
        parse_point(argv, i, &x, &z, err);
        if (stroke_to(s, x, z, 1.0, err) != 0) {
            stroke_cancel(s);
            return -1;
        }
    }
    return stroke_end(s, err);
}

int cmd_stroke_begin(cmd_context *ctx, int argc, char **argv, og_error *err) {
    // Overrides for this stroke only (the viewport's Ctrl and Shift): the tool stays.
    brush b = ctx->brush;
    int face = -1;
    for (int i = 1; i < argc; i++) {
        char buf[256], *key = NULL, *value = NULL;
        if (parse_setting(argv[i], buf, sizeof buf, &key, &value, err) != 0) return -1;
        if (strcmp(key, "face") == 0) { // a planet's stroke from the viewport: where it starts
            brush probe = b;
            if (brush_set(&probe, "face", value, err) != 0) return -1;
            face = probe.face;
        } else if (strcmp(key, "invert") == 0) {
            int inv;
            if (parse_switch(value, key, &inv, err) != 0) return -1;
            b.invert = inv;
        } else if (strcmp(key, "tool") == 0) {
            int t = brush_tool_parse(value);
            if (t < 0) return og_error_set(err, "tool: unknown tool '%s'", value);
            // That tool's own settings at the size the cursor shows.
            double radius = b.radius;
            b = recalled_tool(ctx, (brush_tool)t);
            b.radius = radius;
            if (t == BRUSH_RAISE) b.invert = strcmp(value, "lower") == 0;
        } else {
            return og_error_set(err, "stroke_begin: unknown setting '%s' (invert, tool, face)",
                                key);
        }
    }
    if (face >= 0) b.face = face;
    stroke *s = stroke_begin(ctx->world, &b, err);
    if (!s) return -1;
    ctx->stroke = s;
    return 0;
}

static int no_stroke(const char *name, og_error *err) {
    return og_error_set(err, "%s: no stroke in progress (stroke_begin starts one)", name);
}

// Undoes the open stroke's dabs and closes it.
static void stroke_abandon(cmd_context *ctx) {
    stroke_cancel(ctx->stroke);
    ctx->stroke = NULL;
}

// Lays the open stroke's next dab (the stroke is open). A failed dab leaves the stroke
// half-applied: it is abandoned whole.
static int stroke_point(cmd_context *ctx, const double p[3], double pressure, og_error *err) {
    int rc = stroke_is_volume(ctx->stroke) ? stroke_to_3d(ctx->stroke, p, pressure, err)
                                           : stroke_to(ctx->stroke, p[0], p[2], pressure, err);
    if (rc != 0) stroke_abandon(ctx);
    return rc;
}

int cmd_stroke_to(cmd_context *ctx, int argc, char **argv, og_error *err) {
    if (!ctx->stroke) return no_stroke(argv[0], err);
    double p[3] = {0}, pressure = 1.0;
    if (stroke_is_volume(ctx->stroke)) {
        double(*points)[3] = NULL, *pressures = NULL;
        size_t count = 0;
        int rc = volume_points(argv[0], brush_tool_name(ctx->brush.tool), argc, argv, 1, &points,
                               &pressures, &count, err);
        if (rc == 0) memcpy(p, points[0], sizeof p), pressure = pressures[0];
        free(points);
        free(pressures);
        if (rc != 0) {
            stroke_abandon(ctx);
            return -1;
        }
    } else {
        if (argc > 4)
            return og_error_set(err,
                                "stroke_to: the stroke's tool takes X Z [PRESSURE] (got %d "
                                "numbers)",
                                argc - 1);
        if (parse_point(argv, 1, &p[0], &p[2], err) != 0) return -1;
        if (argc > 3 && parse_number(argv[3], "pressure", &pressure, err) != 0) return -1;
    }
    return stroke_point(ctx, p, pressure, err);
}

int cmd_stroke_to_point(cmd_context *ctx, const cmd_stroke_point *pt, og_error *err) {
    if (!ctx->stroke) return no_stroke("stroke_to", err);
    int volume = stroke_is_volume(ctx->stroke);
    if (pt->volume != volume)
        return og_error_set(err, "stroke_to: the stroke's tool takes %s", volume ? "X Y Z" : "X Z");
    double p[3] = {pt->x, pt->y, pt->z};
    if (stroke_point(ctx, p, 1.0, err) != 0) return -1;
    // The command it stands for, for --record and `history script`: 17 significant
    // digits read back as the same doubles, so a replay lays the same dabs.
    char numbers[3][32];
    char *argv[5] = {"stroke_to", numbers[0], numbers[1], numbers[2], NULL};
    snprintf(numbers[0], sizeof numbers[0], "%.17g", pt->x);
    snprintf(numbers[1], sizeof numbers[1], "%.17g", volume ? pt->y : pt->z);
    snprintf(numbers[2], sizeof numbers[2], "%.17g", pt->z);
    if (!volume) argv[3] = NULL;
    cmd_record(ctx, volume ? 4 : 3, argv);
    return 0;
}

int cmd_stroke_hold(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc;
    if (!ctx->stroke) return no_stroke(argv[0], err);
    double seconds;
    if (parse_number(argv[1], "seconds", &seconds, err) != 0) return -1;
    if (stroke_hold(ctx->stroke, seconds, err) != 0) {
        stroke_abandon(ctx); // as stroke_to: a failed dab abandons the stroke whole
        return -1;
    }
    return 0;
}

int cmd_stroke_is_open(const cmd_context *ctx) {
    return ctx->stroke != NULL;
}

void cmd_cancel_stroke(cmd_context *ctx) {
    if (!ctx->stroke) return;
    stroke_abandon(ctx);
    char *argv[] = {"stroke_cancel", NULL};
    cmd_record(ctx, 1, argv);
}

int cmd_end_stroke(cmd_context *ctx, og_error *err) {
    stroke *s = ctx->stroke;
    if (!s) return 0;
    ctx->stroke = NULL;
    if (stroke_dab_count(s) == 0) { // a click that laid no dab leaves no step
        stroke_cancel(s);
        return 0;
    }
    return stroke_end(s, err);
}

int cmd_stroke_end(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc;
    if (!ctx->stroke) return no_stroke(argv[0], err);
    return cmd_end_stroke(ctx, err);
}

int cmd_stroke_cancel(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc;
    if (!ctx->stroke) return no_stroke(argv[0], err);
    stroke_abandon(ctx);
    return 0;
}

int cmd_undo(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv;
    int rc = edit_undo(ctx->world, err);
    if (rc < 0) return -1;
    if (rc == 0) return og_error_set(err, "undo: nothing to undo");
    return 0;
}

int cmd_redo(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv;
    int rc = edit_redo(ctx->world, err);
    if (rc < 0) return -1;
    if (rc == 0) return og_error_set(err, "redo: nothing to redo");
    return 0;
}

// history script FILE: the session so far, as a script (written atomically).
static int write_session_script(cmd_context *ctx, const char *path, og_error *err) {
    ctx->skip_record = 1; // a replay must not write the file again
    if (!ctx->session)
        return og_error_set(err, "history script: no session is kept here (the editor window "
                                 "keeps one; batch runs can use --record FILE)");
    fflush(ctx->session);
    static const char head[] = "# An Orogen session: replay it on the world it started from,\n"
                               "# e.g. orogen START.world --batch THIS_FILE\n";
    size_t n = *ctx->session_len;
    char *text = malloc(sizeof head + n);
    if (!text) return og_error_set(err, "out of memory");
    memcpy(text, head, sizeof head - 1);
    memcpy(text + sizeof head - 1, *ctx->session_text, n);
    int rc = param_file_write_atomic(path, text, sizeof head - 1 + n, err);
    free(text);
    if (rc == 0) fprintf(ctx->out, "wrote %s\n", path);
    return rc;
}

int cmd_history(cmd_context *ctx, int argc, char **argv, og_error *err) {
    if (argc > 1 && strcmp(argv[1], "script") == 0) {
        if (argc != 3) return og_error_set(err, "history script: expected a FILE");
        return write_session_script(ctx, argv[2], err);
    }
    if (argc > 2) return og_error_set(err, "history: expected budget=MIB or script FILE");
    history *h = world_history(ctx->world);
    for (int i = 1; i < argc; i++) {
        char buf[128], *key = NULL, *value = NULL;
        double mb = 0;
        if (parse_setting(argv[i], buf, sizeof buf, &key, &value, err) != 0) return -1;
        if (strcmp(key, "budget") != 0)
            return og_error_set(err, "history: unknown setting '%s' (budget=MiB)", key);
        if (parse_number(value, "budget", &mb, err) != 0) return -1;
        if (!(mb >= 1 && mb <= 1048576))
            return og_error_set(err, "budget: expected MiB in [1, 1048576], got '%g'", mb);
        size_t dropped = history_set_budget(h, (size_t)(mb * 1048576.0));
        ctx->settings.history_budget_bytes = (size_t)(mb * 1048576.0);
        if (dropped)
            fprintf(ctx->out, "dropped the %zu oldest step%s to fit the budget\n", dropped,
                    dropped == 1 ? "" : "s");
    }
    size_t n = history_count(h), pos = history_position(h);
    for (size_t i = 0; i < n; i++) {
        const history_step *s = history_at(h, i);
        fprintf(ctx->out, "%c %zu %s tiles=%zu bytes=%zu raw_bytes=%zu\n", i < pos ? '*' : ' ',
                i + 1, s->label, s->tile_count, s->bytes, s->raw_bytes);
    }
    fprintf(ctx->out,
            "steps=%zu undoable=%zu redoable=%zu bytes=%zu budget=%zu dropped=%llu modified=%d\n",
            n, pos, n - pos, history_bytes(h), history_budget(h),
            (unsigned long long)history_dropped_total(h), world_is_modified(ctx->world));
    return 0;
}

int cmd_stamp(cmd_context *ctx, int argc, char **argv, og_error *err) {
    stamp_placement p;
    stamp_placement_defaults(&p);
    if (parse_number(argv[2], "X", &p.x, err) != 0 || parse_number(argv[3], "Z", &p.z, err) != 0)
        return -1;
    int intensity_given = 0;
    for (int i = 4; i < argc; i++) {
        char buf[512], *key = NULL, *value = NULL;
        if (parse_setting(argv[i], buf, sizeof buf, &key, &value, err) != 0 ||
            stamp_placement_set(&p, key, value, err) != 0)
            return -1;
        intensity_given |= strcmp(key, "intensity") == 0;
    }
    if (!intensity_given && p.layer == TILE_LAYER_DETAIL)
        p.intensity = 0.5; // detail is fine relief
    stamp_source s;
    if (stamp_find(argv[1], ctx->resource_dir, ctx->stamp_dir, &s, err) != 0) return -1;
    int rc = stamp_apply(ctx->world, &s, &p, err);
    stamp_source_free(&s);
    return rc;
}

int cmd_stamp_add(cmd_context *ctx, int argc, char **argv, og_error *err) {
    char name[256];
    if (stamp_user_add(argv[1], argc > 2 ? argv[2] : NULL, ctx->resource_dir, ctx->stamp_dir, name,
                       sizeof name, err) != 0)
        return -1;
    fprintf(ctx->out, "stamp %s added to %s\n", name, ctx->stamp_dir);
    return 0;
}

int cmd_stamps(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv, (void)err;
    stamp_list(ctx->resource_dir, ctx->stamp_dir, ctx->out);
    return 0;
}
