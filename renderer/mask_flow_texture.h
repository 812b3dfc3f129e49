// The mask editor's flow field on the GPU: the upstream areas the app read around the view
// (render_settings.h mask_flow_*) as a float texture the terrain shader's overlay reads
// for the flow term, uploaded again only when the field changes.
#ifndef OROGEN_RENDERER_MASK_FLOW_TEXTURE_H
#define OROGEN_RENDERER_MASK_FLOW_TEXTURE_H

#include "renderer/camera.h"
#include "renderer/render_settings.h"

#include <epoxy/gl.h>

typedef struct mask_flow_texture {
    GLuint tex;
    int w, h;
    unsigned serial; // the field's serial last uploaded
} mask_flow_texture;

void mask_flow_texture_destroy(mask_flow_texture *t);
// Uploads s's field when it is new; binds it to unit and sets u_mask_flow_area (where
// the field lies, camera-relative) on prog. Without a field the flow term is not drawn.
void mask_flow_texture_bind(mask_flow_texture *t, GLuint prog, const render_settings *s,
                            const camera *cam, int unit);

#endif
