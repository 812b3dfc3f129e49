#include "renderer/material_rule_uniforms.h"

void material_rule_uniforms(GLuint prog, const material_rules_resolved *rules, unsigned live) {
    GLsizei n = rules->count;
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_rule_count"), n);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_rules_live"), (GLint)live);
    if (!n) return;
    glProgramUniform1iv(prog, glGetUniformLocation(prog, "u_rule_material"), n, rules->material);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_rule_height"), n, &rules->height[0][0]);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_rule_slope"), n, &rules->slope[0][0]);
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_rule_curvature"), n,
                        &rules->curvature[0][0]);
    glProgramUniform1fv(prog, glGetUniformLocation(prog, "u_rule_breakup"), n, rules->breakup);
}
