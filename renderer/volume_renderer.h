// The viewport's volume edits (caves, overhangs, arches): a surface-nets mesh per edited
// brick (renderer/volume_mesh.h) within VOLUME_VIEW_BRICKS brick columns of the camera,
// re-meshed only where edits land, drawn with the terrain's materials; and the mask
// that tells the terrain shader where those meshes replace the heightfield. Also picks
// against the meshes, so a brush can reach into an overhang. Owned by the terrain
// renderer, which forwards the world's change notifications.
#ifndef OROGEN_RENDERER_VOLUME_RENDERER_H
#define OROGEN_RENDERER_VOLUME_RENDERER_H

#include "editor/layers/material_rules.h"
#include "editor/world/world.h"
#include "io/err.h"
#include "renderer/camera.h"
#include "renderer/render_settings.h"

#include <epoxy/gl.h>
#include <stdint.h>

// Brick columns per side of the window around the camera that is meshed and masked.
#define VOLUME_VIEW_BRICKS 128

typedef struct volume_renderer volume_renderer;

volume_renderer *volume_renderer_create(const char *shader_dir, og_error *err);
void volume_renderer_destroy(volume_renderer *vr);

// Everything may have changed (another world, new parameters): list the bricks again.
void volume_renderer_reset(volume_renderer *vr);
// Voxel columns [rect) changed: re-mesh the bricks over them; new_bricks when the volume
// layer changed (an edit may have made bricks: list them again).
void volume_renderer_touched(volume_renderer *vr, grid_rect voxel_columns, int new_bricks);

// Re-meshes what changed near the camera, at most budget_ms of meshing per call (0: no
// limit). 1 when every mesh is current, 0 while some wait, -1 on error.
int volume_renderer_update(volume_renderer *vr, world *w, const camera *cam, double budget_ms,
                           og_error *err);

// The terrain program's mask uniforms (volume_mask.glsl), its sampler on texture unit.
void volume_renderer_mask_uniforms(volume_renderer *vr, GLuint prog, const camera *cam, int unit);

// Draws the meshes: albedo is the material texture array, rules the automatic material
// rules; returns triangles drawn.
uint64_t volume_renderer_draw(volume_renderer *vr, const camera *cam, const float view_proj[16],
                              const render_settings *s, GLuint albedo, double fog_density,
                              double ocean_level, double max_height, const float tex_period[2],
                              const material_rules_resolved *rules);

// The nearest mesh hit along origin + t dir (dir unit), t in (0, max): 0 and *t, or -1.
int volume_renderer_pick(const volume_renderer *vr, const double origin[3], const double dir[3],
                         double max, double *t);
// Whether the heightfield at (x, y, z) metres is hidden (a mesh draws the ground there).
int volume_renderer_replaces(const volume_renderer *vr, double x, double y, double z);
// Whether any volume ground is drawn (it replaces the heightfield's ground there).
int volume_renderer_active(const volume_renderer *vr);

#endif
