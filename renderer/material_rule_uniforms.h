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
// Where the far texture (the materials' far-scale variation, 4 a layer) holds material m:
// layer slot / 4, component slot % 4. The first layer holds sand, grass, rock and cliff,
// the default rules' materials below the snow line, so most of a default world's
// levels read one layer (materials.glsl far_of says the same).
int material_far_slot(int material);
// Whether a rule in live lays a material of the far texture's second layer.
int material_rules_read_far_b(const material_rules_resolved *rules, unsigned live);

#endif
