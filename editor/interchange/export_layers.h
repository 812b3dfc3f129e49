// The layers that are not heights, as images: the normal map (8- or 16-bit PNG, tangent
// space with +Y up in the image, OpenGL's convention: R = +X, G = toward row 0,
// B = up) and the material weights (8-bit RGBA PNGs, four materials per file,
// exactly the stored weights: NAME_m0-3.png, NAME_m4-7.png).
#ifndef OROGEN_EDITOR_INTERCHANGE_EXPORT_LAYERS_H
#define OROGEN_EDITOR_INTERCHANGE_EXPORT_LAYERS_H

#include "editor/params/world_grid.h"
#include "editor/world/world.h"
#include "io/err.h"

// r: coarse (= material) samples; bits 8 or 16. files gets the paths written, one per line.
int export_normal_map(world *w, const char *path, grid_rect r, int bits, char *files,
                      size_t files_len, og_error *err);
int export_material_weights(world *w, const char *path, grid_rect r, char *files, size_t files_len,
                            og_error *err);

#endif
