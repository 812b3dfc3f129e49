// The benchmark's reference renderer: the whole bounded world at full resolution as
// one static mesh (one vertex per level-0 coarse sample), drawn with one
// glDrawElements. What the clipmap is measured against for speed (Tabakovic 2024's "no LOD")
// and for visual accuracy (it shades like the clipmap's height view). Bench-only code.
#ifndef OROGEN_BENCH_NAIVE_MESH_H
#define OROGEN_BENCH_NAIVE_MESH_H

#include "editor/world/world.h"
#include "io/err.h"
#include "renderer/camera.h"
#include "renderer/terrain_renderer.h"

#include <epoxy/gl.h>
#include <stdint.h>

typedef struct naive_mesh {
    GLuint prog, prog_sky, vao, empty_vao, vbo, ibo;
    int64_t size;       // samples per side
    double anchor[3];   // world metres the vertex positions are relative to
    double max_height;  // the world's, for the height colour ramp
    uint64_t triangles; // per frame
    size_t gpu_bytes;   // vertex + index buffers
} naive_mesh;

// Reads every level-0 coarse tile of the bounded flat world w (blocking on the tile
// cache) and uploads the mesh. Shaders: naive.vert and naive.frag from shader_dir
// (which also holds the lighting.glsl and colour_ramp.glsl they include), the sky
// from resource_dir/shaders. 0, or -1 with err.
int naive_mesh_create(naive_mesh *m, world *w, const char *shader_dir, const char *resource_dir,
                      og_error *err);
void naive_mesh_destroy(naive_mesh *m);

// Draws sky and terrain into the current framebuffer as terrain_renderer_draw does in
// view VIEW_HEIGHT (reversed-Z, the same projection, sun and sky).
int naive_mesh_draw(naive_mesh *m, const camera *cam, const render_settings *s, int width,
                    int height, og_error *err);

#endif
