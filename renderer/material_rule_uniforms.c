#include "renderer/material_rule_uniforms.h"

#include <stdio.h>

void material_rule_uniforms(GLuint prog, const material_rules_resolved *rules) {
    GLsizei n = rules->count;
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_rule_count"), n);
    if (!n) return;
    glProgramUniform1iv(prog, glGetUniformLocation(prog, "u_rule_material"), n, rules->material);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_rule_height"), n, &rules->height[0][0]);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_rule_slope"), n, &rules->slope[0][0]);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_rule_curvature"), n,
                        &rules->curvature[0][0]);
    glProgramUniform1fv(prog, glGetUniformLocation(prog, "u_rule_breakup"), n, rules->breakup);
}

// A term is set unless its corners are the whole line (material_rules_resolve).
static int term_set(const float c[4]) {
    return !(c[1] <= -1e30f && c[2] >= 1e30f);
}

void material_rule_calls(const material_rules_resolved *rules, unsigned live, char *buf,
                         size_t len) {
    size_t at = 0;
    if (len) buf[0] = 0;
    for (int i = 0; i < rules->count && at < len; i++) {
        if (!(live & (1u << i))) continue;
        int terms = (term_set(rules->height[i]) ? 1 : 0) | (term_set(rules->slope[i]) ? 2 : 0) |
                    (term_set(rules->curvature[i]) ? 4 : 0) | (rules->breakup[i] != 0 ? 8 : 0);
        int n = snprintf(buf + at, len - at, "%sR(%d,%d)", at ? " " : "", i, terms);
        if (n > 0) at += (size_t)n;
    }
}

int material_far_slot(int material) {
    static const int slot[8] = {0, 1, 2, 4, 5, 6, 7, 3}; // sand .. moss, cliff (material_name)
    return material >= 0 && material < 8 ? slot[material] : 0;
}

int material_rules_read_far_b(const material_rules_resolved *rules, unsigned live) {
    for (int i = 0; i < rules->count; i++)
        if ((live & (1u << i)) && material_far_slot(rules->material[i]) >= 4) return 1;
    return 0;
}
