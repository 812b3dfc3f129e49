// The fixed geometry of a geometry clipmap level (Losasso & Hoppe 2004, in the GPU
// form of Asirvatham & Hoppe 2005; Crause 2010 section 3.6.2): one n x n grid of vertex
// positions shared by every level, and index ranges ("pieces") that select the parts a
// level draws. Built once on the CPU; the renderer uploads it and never changes it.
//
// Local coordinates run 0 .. n-1 per side (n = 2^k - 1, default 255); m = (n+1)/4.
// Per side a ring level is: block (m-1 quads), block, fix-up (2 quads), block, block.
// The finer level (half the spacing) fills the central 2m-quad hole except for a
// one-quad L-shaped trim whose sides depend on where the finer level sits.
#ifndef OROGEN_RENDERER_CLIPMAP_MESH_H
#define OROGEN_RENDERER_CLIPMAP_MESH_H

#include <stddef.h>
#include <stdint.h>

#define CLIPMAP_MIN_N 15
#define CLIPMAP_MAX_N 255     // indices are uint16 (n*n < 65536)
#define CLIPMAP_CULL_QUADS 16 // blocks and the interior come in parts this wide, for culling

typedef enum clip_piece_kind {
    CLIP_PIECE_BLOCK,      // a part of an m x m vertex block (12 blocks per ring)
    CLIP_PIECE_FIXUP,      // m x 3 or 3 x m vertices; 4 per ring
    CLIP_PIECE_TRIM,       // a side of the L-shaped interior trim
    CLIP_PIECE_DEGENERATE, // zero-area triangles along the outer edge (no T-junction cracks)
    CLIP_PIECE_INTERIOR    // the finest level's filled centre (2m x 2m quads)
} clip_piece_kind;

// Which trim pieces a level draws: the finer level's offset inside this level's hole
// is m-1 or m quads per axis (set by the camera's position); the trim takes the side
// the finer level leaves free.
typedef enum clip_trim {
    CLIP_TRIM_X_HIGH = 0, // finer level at x offset m-1: trim column at the high-x side
    CLIP_TRIM_X_LOW = 1,  // finer level at x offset m: trim column at the low-x side
    // The z-trims span the finer level's x extent, so they depend on both offsets:
    CLIP_TRIM_Z_HIGH_XA = 2, // z offset m-1, x offset m-1
    CLIP_TRIM_Z_HIGH_XB = 3, // z offset m-1, x offset m
    CLIP_TRIM_Z_LOW_XA = 4,  // z offset m,   x offset m-1
    CLIP_TRIM_Z_LOW_XB = 5,  // z offset m,   x offset m
    CLIP_TRIM_COUNT = 6
} clip_trim;

typedef struct clip_piece {
    clip_piece_kind kind;
    int trim;                // clip_trim for CLIP_PIECE_TRIM, else -1
    uint32_t first, count;   // range in the index array (GL_TRIANGLES)
    uint16_t x0, z0, x1, z1; // vertex bounds (inclusive), for culling
} clip_piece;

typedef struct clipmap_mesh {
    int n, m;
    uint16_t *vertices; // n*n (x, z) pairs: vertex v = z*n + x
    size_t vertex_count;
    uint16_t *indices;
    size_t index_count;
    clip_piece *pieces;
    size_t piece_count;
} clipmap_mesh;

// Builds the mesh for n vertices per side. n must be 2^k - 1 within
// [CLIPMAP_MIN_N, CLIPMAP_MAX_N]; returns -1 otherwise (or when out of memory).
int clipmap_mesh_build(clipmap_mesh *mesh, int n);
void clipmap_mesh_free(clipmap_mesh *mesh);

// The trim pieces a level draws for the finer level at (x, z) quad offsets, each
// m-1 or m. Writes 2 clip_trim values.
void clipmap_trims_for_offset(int m, int off_x, int off_z, clip_trim out[2]);

#endif
