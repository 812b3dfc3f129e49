// The clipmap's blocks and fix-ups at twice the density, for parts of a coarse level
// whose sampling error shows on the screen (renderer/clip_refine.h decides which): a
// level's samples are 4 to 8 pixels wide, so a rough far ridge drawn from them stands
// lower than the full-resolution ridge and the sky shows where the ground should.
// Each refinable piece of the base mesh (clipmap_mesh.h) comes in parts of at most 8 x 8
// quads, each with a range of indices into a grid of (2n - 1)^2 vertices at half the
// level's spacing; the vertex shader takes their heights from the finer shading windows
// (renderer/clip_slopes.h).
//
// Where a refined part meets an unrefined one (or the finer level, or the trim) its
// border vertices lie on the coarse edge (the shader gives them no refinement weight),
// so every second one is a T-junction: each refined part also draws zero-area
// triangles along its four sides (its seams, a range of their own drawn by a program of
// their own: terrain.vert's SEAM) through a copy of the grid whose vertices the shader
// always puts on the coarse edge between their two neighbours (CLIP_REFINE_ON_LINE), which
// close those T-junctions against rasterisation gaps and stay flat where both sides are
// refined.
#ifndef OROGEN_RENDERER_CLIP_REFINE_MESH_H
#define OROGEN_RENDERER_CLIP_REFINE_MESH_H

#include "renderer/clipmap_mesh.h"

#include <stddef.h>
#include <stdint.h>

#define CLIP_REFINE_ON_LINE 0x8000u // set in a vertex's x: the copy placed on the coarse edge

#define CLIP_REFINE_PART 8       // quads a side of a piece's parts: a cell (clip_cells.h)
#define CLIP_REFINE_PARTS_MAX 16 // parts of a piece at most (a fix-up is 2 x 63 quads)

// A part of a refinable piece in two forms: at twice the density through the refined
// grid (its quads, and apart its seams: the zero-area triangles along its four sides),
// and at the level's density through the base mesh's vertices (its triangles, drawn by
// the base program: a refined vertex costs about twice a base one on llvmpipe).
typedef struct clip_refine_part {
    uint16_t x0, z0, x1, z1; // vertex bounds (inclusive), the base mesh's units
    uint32_t fine_first, fine_count, seam_first, seam_count; // in indices
    // In the base mesh's index buffer, where its own indices are followed by `coarse`.
    uint32_t coarse_first, coarse_count;
} clip_refine_part;

typedef struct clip_refine_mesh {
    int side;           // vertices per side of the refined grid: 2n - 1
    uint16_t *vertices; // 2 * side^2 (x, z) pairs in half level units; the second half
                        // are the on-line copies (x | CLIP_REFINE_ON_LINE)
    size_t vertex_count;
    uint32_t *indices;
    size_t index_count;
    // The parts' triangles at the level's density (base mesh vertex indices), to follow
    // the base mesh's own indices in its index buffer.
    uint16_t *coarse;
    size_t coarse_count;
    size_t piece_count;
    // Per base piece (the base mesh's order) its parts (part_first[i] .. + part_count[i]
    // in parts), so that a piece can be refined in some parts only (render skyline=P);
    // none for the kinds that are never refined (trims, the degenerate ring).
    clip_refine_part *parts;
    uint32_t *part_first, *part_count;
} clip_refine_mesh;

// Whether a base piece's kind has a refined form (blocks and fix-ups).
int clip_refine_piece_refinable(const clip_piece *p);

// Builds the refined forms of base's pieces; -1 when out of memory.
int clip_refine_mesh_build(clip_refine_mesh *r, const clipmap_mesh *base);
void clip_refine_mesh_free(clip_refine_mesh *r);

#endif
