// `material_rules` and `material_rule add|set|move|delete|reset`: the automatic material
// rule stack (editor/layers/material_rules.h), each change one undo step.
#include "editor/cmd/material_commands.h"

#include "editor/edit/edit.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// Prints rule i (0-based) as `rule N: TEXT`, with relative heights in metres.
static void print_rule(cmd_context *ctx, const world_params *p, int i) {
    const material_rule *r = &p->material_rules.rule[i];
    char text[512];
    material_rule_format(r, text, sizeof text);
    fprintf(ctx->out, "rule %d: %s", i + 1, text);
    if (r->height_on && (r->height_lo.relative || r->height_hi.relative)) {
        double sea = world_params_ocean_height(p);
        fprintf(ctx->out, " (height %.6g..%.6g m here)",
                material_height_metres(&r->height_lo, sea, p->max_height),
                material_height_metres(&r->height_hi, sea, p->max_height));
    }
    fputc('\n', ctx->out);
}

int cmd_material_rules(cmd_context *ctx, int argc, char **argv, og_error *err) {
    (void)argc, (void)argv, (void)err;
    const world_params *p = world_get_params(ctx->world);
    const material_rules *rules = &p->material_rules;
    fprintf(ctx->out, "material_rules: %d rule%s, bottom first (each covers the ones below)%s\n",
            rules->count, rules->count == 1 ? "" : "s",
            p->kind == WORLD_PLANET ? ", over the planet's own look (climate, latitude, height "
                                      "and slope)"
                                    : "");
    for (int i = 0; i < rules->count; i++)
        print_rule(ctx, p, i);
    return 0;
}

// A rule number 1..count (or count + 1 when past_end) from text.
static int rule_index(const char *text, int count, int past_end, const char *what, int *out,
                      og_error *err) {
    char *end;
    long n = strtol(text, &end, 10);
    int last = count + (past_end ? 1 : 0);
    if (*end || end == text || n < 1 || n > last) {
        if (!last) return og_error_set(err, "%s: there are no rules ('%s')", what, text);
        return og_error_set(err, "%s: expected a rule number 1..%d, got '%s'", what, last, text);
    }
    *out = (int)n - 1;
    return 0;
}

// key=value words onto a rule (at=I is the caller's); -1 with err naming the word.
static int apply_words(material_rule *r, int argc, char **argv, const char *what, og_error *err) {
    for (int i = 0; i < argc; i++) {
        char key[64];
        const char *eq = strchr(argv[i], '=');
        if (!eq || (size_t)(eq - argv[i]) >= sizeof key)
            return og_error_set(err, "%s: '%s' is not key=value", what, argv[i]);
        memcpy(key, argv[i], (size_t)(eq - argv[i]));
        key[eq - argv[i]] = 0;
        if (!strcmp(key, "at")) continue;
        og_error why;
        if (material_rule_set_option(r, key, eq + 1, &why))
            return og_error_set(err, "%s: %s", what, why.msg);
    }
    return 0;
}

// The command's own words as the undo step's label ("material_rule set 5 height=...").
static void label_of(char *label, size_t len, int argc, char **argv) {
    size_t n = 0;
    label[0] = 0;
    for (int i = 0; i < argc && n + 1 < len; i++)
        n += (size_t)snprintf(label + n, len - n, "%s%s", i ? " " : "", argv[i]);
}

static int commit(cmd_context *ctx, const material_rules *next, int argc, char **argv,
                  og_error *err) {
    char label[128];
    label_of(label, sizeof label, argc, argv);
    return edit_material_rules(ctx->world, next, label, err);
}

static int rule_add(cmd_context *ctx, material_rules *next, int argc, char **argv, og_error *err) {
    if (argc < 3)
        return og_error_set(err, "material_rule add: expected a material (sand, grass, rock, "
                                 "snow, dirt, gravel, moss, cliff)");
    material_rule rule = {0};
    og_error why;
    if (material_rule_set_option(&rule, "material", argv[2], &why))
        return og_error_set(err, "material_rule add: %s", why.msg);
    if (apply_words(&rule, argc - 3, argv + 3, "material_rule add", err)) return -1;
    int at = next->count;
    for (int i = 3; i < argc; i++)
        if (!strncmp(argv[i], "at=", 3) &&
            rule_index(argv[i] + 3, next->count, 1, "material_rule add at", &at, err))
            return -1;
    if (material_rules_insert(next, at, &rule, &why))
        return og_error_set(err, "material_rule add: %s", why.msg);
    if (commit(ctx, next, argc, argv, err)) return -1;
    fprintf(ctx->out, "added ");
    print_rule(ctx, world_get_params(ctx->world), at);
    return 0;
}

static int rule_move(cmd_context *ctx, material_rules *next, int from, const char *where, int argc,
                     char **argv, og_error *err) {
    int to = 0;
    if (!strcmp(where, "up"))
        to = from + 1;
    else if (!strcmp(where, "down"))
        to = from - 1;
    else if (!strcmp(where, "top"))
        to = next->count - 1;
    else if (!strcmp(where, "bottom"))
        to = 0;
    else if (!strncmp(where, "to=", 3)) {
        if (rule_index(where + 3, next->count, 0, "material_rule move to", &to, err)) return -1;
    } else
        return og_error_set(err,
                            "material_rule move: expected up, down, top, bottom or to=N, "
                            "got '%s'",
                            where);
    if (to < 0 || to >= next->count)
        return og_error_set(err, "material_rule move: rule %d is already at the %s", from + 1,
                            to < 0 ? "bottom" : "top");
    material_rules_move(next, from, to);
    if (commit(ctx, next, argc, argv, err)) return -1;
    fprintf(ctx->out, "moved to ");
    print_rule(ctx, world_get_params(ctx->world), to);
    return 0;
}

int cmd_material_rule(cmd_context *ctx, int argc, char **argv, og_error *err) {
    material_rules next = world_get_params(ctx->world)->material_rules;
    const char *verb = argv[1];
    if (!strcmp(verb, "add")) return rule_add(ctx, &next, argc, argv, err);
    if (!strcmp(verb, "reset")) {
        if (argc > 2) return og_error_set(err, "material_rule reset: takes no arguments");
        if (world_get_params(ctx->world)->kind == WORLD_PLANET)
            material_rules_planet_default(&next);
        else
            material_rules_default(&next);
        if (commit(ctx, &next, argc, argv, err)) return -1;
        fprintf(ctx->out, "material_rules: the default stack (%d rules)\n", next.count);
        return 0;
    }
    int is_set = !strcmp(verb, "set"), is_move = !strcmp(verb, "move"),
        is_delete = !strcmp(verb, "delete");
    if (!is_set && !is_move && !is_delete)
        return og_error_set(err,
                            "material_rule: expected add, set, move, delete or reset, got "
                            "'%s'",
                            verb);
    char what[32];
    snprintf(what, sizeof what, "material_rule %s", verb);
    if (argc < 3) return og_error_set(err, "%s: expected a rule number", what);
    int i = 0;
    if (rule_index(argv[2], next.count, 0, what, &i, err)) return -1;
    if (is_delete) {
        if (argc > 3) return og_error_set(err, "material_rule delete: takes only a rule number");
        material_rules_remove(&next, i);
        if (commit(ctx, &next, argc, argv, err)) return -1;
        fprintf(ctx->out, "deleted rule %d (%d left)\n", i + 1, next.count);
        return 0;
    }
    if (is_move) {
        if (argc != 4)
            return og_error_set(err, "material_rule move: expected N up|down|top|bottom|to=M");
        return rule_move(ctx, &next, i, argv[3], argc, argv, err);
    }
    if (argc < 4) return og_error_set(err, "material_rule set: expected key=value after the rule");
    for (int k = 3; k < argc; k++)
        if (!strncmp(argv[k], "at=", 3))
            return og_error_set(err, "material_rule set: at= is add's (move places a rule)");
    if (apply_words(&next.rule[i], argc - 3, argv + 3, what, err)) return -1;
    if (commit(ctx, &next, argc, argv, err)) return -1;
    fprintf(ctx->out, "set ");
    print_rule(ctx, world_get_params(ctx->world), i);
    return 0;
}
