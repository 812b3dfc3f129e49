// The Materials panel: the automatic material rule stack, top rule first as it is laid
// over the others, each with its material's swatch and ranges. Every change runs a
// material_rule command (echoed, one undo step); Edit puts the rule's command in the
// console to change its ranges there.
#include "app/editor_ui_internal.h"

#include "renderer/material_textures.h"

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

void materials_panel(editor_ui *e, ui_context *ui, cmd_context *ctx) {
    const world_params *p = world_get_params(ctx->world);
    ui_row(ui, 1, NULL, 0);
    if (p->kind == WORLD_PLANET) {
        ui_label_wrapped(ui,
                         "A planet draws its own material rules (by latitude, height and "
                         "slope).",
                         ui_get_theme(ui)->text_dim);
        return;
    }
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
    for (int i = rules->count - 1; i >= 0; i--) { // top first, as it covers the others
        const material_rule *r = &rules->rule[i];
        ui_row(ui, 1, NULL, 0);
        snprintf(line, sizeof line, "%d %s", i + 1, material_name(r->material));
        if (ui_color_swatch(ui, line, means[r->material], *sel == i)) *sel = i;
        ui_tooltip(ui, "A rule: its material covers the ground where its terms hold (click to "
                       "pick it for the buttons below)");
        ui_label_wrapped(ui, rule_terms(r, terms, sizeof terms), dim);
        ui_tooltip(ui, "height: metres, or % of the relief above the sea; slope: degrees; "
                       "curvature: positive convex; a third number is the soft edge");
    }
    ui_pop_scope(ui);
    if (*sel >= 0 && *sel < rules->count) {
        int n = *sel + 1;
        ui_row(ui, 4, NULL, 0);
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
    ui_tooltip(ui, "Bring back the default stack: sand, grass, rock, cliff, snow (one undo "
                   "step)");
}
