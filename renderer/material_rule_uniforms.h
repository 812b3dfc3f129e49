// The automatic material rules as the shaders take them (materials.glsl's u_rule_*).
#ifndef OROGEN_RENDERER_MATERIAL_RULE_UNIFORMS_H
#define OROGEN_RENDERER_MATERIAL_RULE_UNIFORMS_H

#include "editor/layers/material_rules.h"

#include <epoxy/gl.h>

// Sets the rule arrays and count on prog.
void material_rule_uniforms(GLuint prog, const material_rules_resolved *rules);
// The RULE_CALLS text materials.glsl takes for the rules whose bit is set in live: each
// rule with the terms it has, so a program holds only what can show where it draws.
void material_rule_calls(const material_rules_resolved *rules, unsigned live, char *buf,
                         size_t len);

#endif
