// The Materials panel: the automatic material rule stack, top rule first as it is laid
// over the others, each with its material's swatch and ranges. Every change runs a
// material_rule command (echoed, one undo step); Edit puts the rule's command in the
// console to change its ranges there.
#include "app/editor_ui_internal.h"

#include "app/value_field.h"
#include "renderer/material_textures.h"

#include <stdlib.h>

// The mean colour of each material texture (sand .. cliff), made once.
static const ui_color *material_means(void) {
    static ui_color means[MATERIAL_COUNT];
    static int made;
    if (made) return means;
    static unsigned char rgba[MATERIAL_TEXTURE_SIZE * MATERIAL_TEXTURE_SIZE * 4];
    for (int m = 0; m < MATERIAL_COUNT; m++) {
        material_texture_generate(m, rgba);
        double sum[3] = {0, 0, 0};
        for (size_t i = 0; i < (size_t)MATERIAL_TEXTURE_SIZE * MATERIAL_TEXTURE_SIZE; i++)
            for (int c = 0; c < 3; c++)
                sum[c] += rgba[i * 4 + c];
        double n = (double)MATERIAL_TEXTURE_SIZE * MATERIAL_TEXTURE_SIZE;
        means[m] = UI_RGBA((int)(sum[0] / n), (int)(sum[1] / n), (int)(sum[2] / n), 255);
    }
    made = 1;
    return means;
}

// The rule's terms as the panel shows them: what the command would write after the
// material ("everywhere" for none).
static const char *rule_terms(const material_rule *r, char *buf, size_t len) {
    char text[512];
    material_rule_format(r, text, sizeof text);
    const char *terms = strchr(text, ' ');
    snprintf(buf, len, "%s", terms ? terms + 1 : "everywhere");
    return buf;
}

// Opens the console with the rule's set command, its current terms to change.
static void edit_in_console(editor_ui *e, int number, const material_rule *r) {
    char terms[512];
    rule_terms(r, terms, sizeof terms);
    snprintf(e->console.input, sizeof e->console.input, "material_rule set %d %s", number,
             r->height_on || r->slope.on || r->curvature.on || r->breakup != 0 ? terms : "height=");
    e->console.open = 1;
    e->console.focus_input = 1;
}

// One term's value in a rule's text ("LO,HI[,EDGE]"), "" when the rule lacks it.
static void term_value(const char *rule_text, const char *key, char *out, size_t len) {
    char want[32];
    snprintf(want, sizeof want, " %s=", key);
    const char *at = strstr(rule_text, want);
    out[0] = 0;
    if (!at) return;
    at += strlen(want);
    snprintf(out, len, "%.*s", (int)strcspn(at, " "), at);
}

// The picked rule's own fields: material, each term on or off with its low, high and
// soft edge typed (heights in metres or "62%", "62%+40"), and breakup; each change
// one `material_rule set` (its errors name the field, shown where the user acted).
static void rule_editor(editor_ui *e, ui_context *ui, cmd_context *ctx, int n,
                        const material_rule *r) {
    static const char *const keys[3] = {"height", "slope", "curvature"};
    static const char *const labels[3] = {"Height (m, or % of the relief)", "Slope (degrees)",
                                          "Curvature (convex +)"};
    static const char *const first[3] = {"0,1000", "0,30,5", "0,inf"};
    char text[512], value[160];
    material_rule_format(r, text, sizeof text);
    ui_push_scope(ui, "Rule editor");
    ui_row(ui, 1, NULL, 0);
    ui_separator(ui);
    snprintf(value, sizeof value, "Rule %d, %s:", n, material_name(r->material));
    ui_label(ui, value);
    const char *names[MATERIAL_COUNT];
    for (int m = 0; m < MATERIAL_COUNT; m++)
        names[m] = material_name(m);
    int material = r->material;
    if (ui_combo(ui, "Material", &material, names, MATERIAL_COUNT))
        runf(e, ctx, "material_rule set %d material=%s", n, names[material]);
    ui_tooltip(ui, "The material the picked rule lays where its terms hold");
    for (int k = 0; k < 3; k++) {
        term_value(text, keys[k], value, sizeof value);
        ui_push_scope(ui, keys[k]);
        ui_row(ui, 1, NULL, 0);
        int on = value[0] != 0;
        if (ui_checkbox(ui, labels[k], &on))
            runf(e, ctx, "material_rule set %d %s=%s", n, keys[k], on ? first[k] : "off");
        ui_tooltip(ui, "The rule holds only within this range (off: at any)");
        if (on) {
            char part[3][64] = {"", "", ""};
            for (int p = 0, i = 0, c = 0; value[i] && p < 3; i++) { // LO,HI[,EDGE]
                if (value[i] == ',') {
                    p++, c = 0;
                } else if (c < 63) {
                    part[p][c++] = value[i];
                    part[p][c] = 0;
                }
            }
            if (!part[2][0]) snprintf(part[2], sizeof part[2], "0");
            ui_row(ui, 3, NULL, 0);
            static const char *const ends[3] = {"Low", "High", "Edge"};
            static const char *const tips[3] = {
                "Where the range starts (-inf: no lower bound); Enter sets it",
                "Where it ends (inf: no upper bound); Enter sets it",
                "The soft edge outside the range (0: hard); Enter sets it"};
            int set = -1;
            for (int p = 0; p < 3; p++)
                if (value_field(ui, ends[p], e->rule_fields[k][p], sizeof e->rule_fields[k][p],
                                part[p], tips[p]))
                    set = p;
            if (set >= 0) {
                snprintf(part[set], sizeof part[set], "%s", e->rule_fields[k][set]);
                runf(e, ctx, "material_rule set %d %s=%s,%s,%s", n, keys[k], part[0], part[1],
                     part[2]);
            }
        }
        ui_pop_scope(ui);
    }
    ui_row(ui, 2, NULL, 0);
    ui_label(ui, "Breakup (0-1)");
    char breakup[32];
    snprintf(breakup, sizeof breakup, "%.6g", r->breakup);
    if (value_field(ui, "Breakup", e->rule_fields[3][0], sizeof e->rule_fields[3][0], breakup,
                    "Noise that moves the rule's edges, so they are not contour lines (0-1); "
                    "Enter sets it"))
        runf(e, ctx, "material_rule set %d breakup=%s", n, e->rule_fields[3][0]);
    ui_pop_scope(ui);
}

void materials_panel(editor_ui *e, ui_context *ui, cmd_context *ctx) {
    const world_params *p = world_get_params(ctx->world);
    ui_row(ui, 1, NULL, 0);
    if (p->kind == WORLD_PLANET)
        ui_label_wrapped(ui,
                         "These rules lay over the planet's own look (by climate, latitude, "
                         "height and slope).",
                         ui_get_theme(ui)->text_dim);
    const material_rules *rules = &p->material_rules;
    const ui_color *means = material_means();
    const ui_color dim = ui_get_theme(ui)->text_dim;
    char line[600], terms[512];
    snprintf(line, sizeof line, "%d rule%s; each covers the ones below it where its terms hold",
             rules->count, rules->count == 1 ? "" : "s");
    ui_label_wrapped(ui, line, dim);
    int *sel = &e->selected_rule;
    if (*sel >= rules->count) *sel = rules->count - 1; // after a delete or an undo
    ui_push_scope(ui, "Rules");
    ui_rect rows[MATERIAL_RULES_MAX];
    for (int i = rules->count - 1; i >= 0; i--) { // top first, as it covers the others
        const material_rule *r = &rules->rule[i];
        ui_row(ui, 1, NULL, 0);
        snprintf(line, sizeof line, "%d %s", i + 1, material_name(r->material));
        if (ui_color_swatch(ui, line, means[r->material], *sel == i) &&
            !row_drag_active(&e->rule_drag))
            *sel = i;
        rows[i] = ui_last_rect(ui);
        row_drag_watch(&e->rule_drag, ui, i);
        ui_tooltip(ui, "A rule: its material covers the ground where its terms hold (click to "
                       "pick it and edit it below; drag it up or down the stack)");
        ui_label_wrapped(ui, rule_terms(r, terms, sizeof terms), dim);
        ui_tooltip(ui, "height: metres, or % of the relief above the sea; slope: degrees; "
                       "curvature: positive convex; a third number is the soft edge");
    }
    int from, to;
    if (row_drag_update(&e->rule_drag, ui, rows, rules->count, &from, &to)) {
        runf(e, ctx, "material_rule move %d to=%d", from + 1, to + 1);
        *sel = to;
    }
    ui_pop_scope(ui);
    if (*sel >= 0 && *sel < rules->count) {
        int n = *sel + 1;
        float by_label[4] = {-0.2f, -0.26f, -0.22f, 0}; // Delete whole at UI scale 1.5
        ui_row(ui, 4, by_label, 0);
        if (ui_button(ui, "Up") && n < rules->count) {
            runf(e, ctx, "material_rule move %d up", n);
            *sel = n;
        }
        ui_tooltip(ui, "Move the picked rule up the stack: it covers more of the others");
        if (ui_button(ui, "Down") && n > 1) {
            runf(e, ctx, "material_rule move %d down", n);
            *sel = n - 2;
        }
        ui_tooltip(ui, "Move the picked rule down the stack");
        if (ui_button(ui, "Edit")) edit_in_console(e, n, &rules->rule[*sel]);
        ui_tooltip(ui, "Put the picked rule's material_rule set command in the console, to "
                       "change its ranges there");
        if (ui_button(ui, "Delete")) runf(e, ctx, "material_rule delete %d", n);
        ui_tooltip(ui, "Delete the picked rule (undo brings it back)");
    }
    float add[2] = {0, ui_em(ui, 6.4f)};
    ui_row(ui, 2, add, 0);
    const char *names[MATERIAL_COUNT];
    for (int m = 0; m < MATERIAL_COUNT; m++)
        names[m] = material_name(m);
    ui_combo(ui, "Material##new rule", &e->new_rule_material, names, MATERIAL_COUNT);
    ui_tooltip(ui, "The material of a rule Add makes");
    if (ui_button(ui, "Add rule") && rules->count < MATERIAL_RULES_MAX) {
        runf(e, ctx, "material_rule add %s", names[e->new_rule_material]);
        e->selected_rule = rules->count; // the new top rule
    }
    ui_tooltip(ui, rules->count < MATERIAL_RULES_MAX
                       ? "Add a rule of that material on top, covering everything until you "
                         "give it ranges (Edit)"
                       : "The stack is full (16 rules)");
    ui_row(ui, 1, NULL, 0);
    if (ui_button(ui, "Default rules")) runf(e, ctx, "material_rule reset");
    ui_tooltip(ui, p->kind == WORLD_PLANET
                       ? "Back to no rules: the planet's own look (one undo step)"
                       : "Bring back the default stack: sand, grass, rock, cliff, snow (one "
                         "undo step)");
    if (*sel >= 0 && *sel < rules->count) rule_editor(e, ui, ctx, *sel + 1, &rules->rule[*sel]);
}
