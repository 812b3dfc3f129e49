// The automatic material rules as the shaders take them (materials.glsl's u_rule_*).
#ifndef OROGEN_RENDERER_MATERIAL_RULE_UNIFORMS_H
#define OROGEN_RENDERER_MATERIAL_RULE_UNIFORMS_H

#include "editor/layers/material_rules.h"

#include <epoxy/gl.h>

// Sets the rule arrays and count on prog (live: u_rules_live, the rules to evaluate).
void material_rule_uniforms(GLuint prog, const material_rules_resolved *rules, unsigned live);

#endif
