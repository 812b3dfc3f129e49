#include "renderer/clipmap_mesh.h"

#include <stdlib.h>
#include <string.h>

typedef struct mesh_builder {
    clipmap_mesh *mesh;
    size_t index_cap, piece_cap;
    int failed;
} mesh_builder;

static void push_index(mesh_builder *b, int x, int z) {
    clipmap_mesh *m = b->mesh;
    if (b->failed) return;
    if (m->index_count == b->index_cap) {
        size_t cap = b->index_cap ? b->index_cap * 2 : 4096;
        uint16_t *grown = realloc(m->indices, cap * sizeof *grown);
        if (!grown) {
            b->failed = 1;
            return;
        }
        m->indices = grown;
        b->index_cap = cap;
    }
    m->indices[m->index_count++] = (uint16_t)(z * m->n + x);
}

static clip_piece *begin_piece(mesh_builder *b, clip_piece_kind kind, int trim, int x0, int z0,
                               int x1, int z1) {
    clipmap_mesh *m = b->mesh;
    if (b->failed) return NULL;
    if (m->piece_count == b->piece_cap) {
        size_t cap = b->piece_cap ? b->piece_cap * 2 : 32;
        clip_piece *grown = realloc(m->pieces, cap * sizeof *grown);
        if (!grown) {
            b->failed = 1;
            return NULL;
        }
        m->pieces = grown;
        b->piece_cap = cap;
    }
    clip_piece *p = &m->pieces[m->piece_count++];
    *p = (clip_piece){
        kind,         trim,        (uint32_t)m->index_count, 0, (uint16_t)x0, (uint16_t)z0,
        (uint16_t)x1, (uint16_t)z1};
    return p;
}

static void end_piece(mesh_builder *b, clip_piece *p) {
    if (p) p->count = (uint32_t)(b->mesh->index_count - p->first);
}

// A grid of quads between vertex corners (x0, z0) and (x1, z1), inclusive.
static void add_grid(mesh_builder *b, clip_piece_kind kind, int trim, int x0, int z0, int x1,
                     int z1) {
    clip_piece *p = begin_piece(b, kind, trim, x0, z0, x1, z1);
    for (int z = z0; z < z1; z++)
        for (int x = x0; x < x1; x++) {
            push_index(b, x, z), push_index(b, x, z + 1), push_index(b, x + 1, z);
            push_index(b, x + 1, z), push_index(b, x, z + 1), push_index(b, x + 1, z + 1);
        }
    end_piece(b, p);
}

// The same as culling units of at most CLIPMAP_CULL_QUADS quads a side: a 63-quad block
// seen edge-on is mostly outside the view; its parts are not.
static void add_grid_parts(mesh_builder *b, clip_piece_kind kind, int x0, int z0, int x1, int z1) {
    for (int z = z0; z < z1; z += CLIPMAP_CULL_QUADS)
        for (int x = x0; x < x1; x += CLIPMAP_CULL_QUADS) {
            int xe = x + CLIPMAP_CULL_QUADS < x1 ? x + CLIPMAP_CULL_QUADS : x1;
            int ze = z + CLIPMAP_CULL_QUADS < z1 ? z + CLIPMAP_CULL_QUADS : z1;
            add_grid(b, kind, -1, x, z, xe, ze);
        }
}

// Along the outer edge every other vertex has no partner on the coarser level; a
// zero-area triangle through it closes the T-junction against rasterisation gaps.
static void add_degenerate_ring(mesh_builder *b) {
    int last = b->mesh->n - 1;
    clip_piece *p = begin_piece(b, CLIP_PIECE_DEGENERATE, -1, 0, 0, last, last);
    for (int i = 0; i + 2 <= last; i += 2) {
        push_index(b, i, 0), push_index(b, i + 1, 0), push_index(b, i + 2, 0);
        push_index(b, i + 2, last), push_index(b, i + 1, last), push_index(b, i, last);
        push_index(b, 0, i + 2), push_index(b, 0, i + 1), push_index(b, 0, i);
        push_index(b, last, i), push_index(b, last, i + 1), push_index(b, last, i + 2);
    }
    end_piece(b, p);
}

int clipmap_mesh_build(clipmap_mesh *mesh, int n) {
    memset(mesh, 0, sizeof *mesh);
    if (n < CLIPMAP_MIN_N || n > CLIPMAP_MAX_N || ((n + 1) & n) != 0) return -1;
    int m = (n + 1) / 4;
    mesh->n = n;
    mesh->m = m;
    mesh->vertex_count = (size_t)n * n;
    mesh->vertices = malloc(mesh->vertex_count * 2 * sizeof *mesh->vertices);
    if (!mesh->vertices) return -1;
    for (int z = 0; z < n; z++)
        for (int x = 0; x < n; x++) {
            mesh->vertices[2 * ((size_t)z * n + x)] = (uint16_t)x;
            mesh->vertices[2 * ((size_t)z * n + x) + 1] = (uint16_t)z;
        }

    mesh_builder b = {mesh, 0, 0, 0};
    // Per axis: block, block, fix-up (2 quads), block, block.
    const int start[4] = {0, m - 1, 2 * m, 3 * m - 1};
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            if ((i == 1 || i == 2) && (j == 1 || j == 2)) continue; // the finer level's hole
            add_grid_parts(&b, CLIP_PIECE_BLOCK, start[i], start[j], start[i] + m - 1,
                           start[j] + m - 1);
        }
    int f0 = 2 * m - 2, f1 = 2 * m, last = n - 1;
    add_grid(&b, CLIP_PIECE_FIXUP, -1, f0, 0, f1, m - 1);
    add_grid(&b, CLIP_PIECE_FIXUP, -1, f0, 3 * m - 1, f1, last);
    add_grid(&b, CLIP_PIECE_FIXUP, -1, 0, f0, m - 1, f1);
    add_grid(&b, CLIP_PIECE_FIXUP, -1, 3 * m - 1, f0, last, f1);

    int h0 = m - 1, h1 = 3 * m - 1; // the hole, vertex bounds
    add_grid(&b, CLIP_PIECE_TRIM, CLIP_TRIM_X_HIGH, h1 - 1, h0, h1, h1);
    add_grid(&b, CLIP_PIECE_TRIM, CLIP_TRIM_X_LOW, h0, h0, h0 + 1, h1);
    add_grid(&b, CLIP_PIECE_TRIM, CLIP_TRIM_Z_HIGH_XA, h0, h1 - 1, h1 - 1, h1);
    add_grid(&b, CLIP_PIECE_TRIM, CLIP_TRIM_Z_HIGH_XB, h0 + 1, h1 - 1, h1, h1);
    add_grid(&b, CLIP_PIECE_TRIM, CLIP_TRIM_Z_LOW_XA, h0, h0, h1 - 1, h0 + 1);
    add_grid(&b, CLIP_PIECE_TRIM, CLIP_TRIM_Z_LOW_XB, h0 + 1, h0, h1, h0 + 1);

    add_degenerate_ring(&b);
    add_grid_parts(&b, CLIP_PIECE_INTERIOR, h0, h0, h1, h1);
    if (b.failed) {
        clipmap_mesh_free(mesh);
        return -1;
    }
    return 0;
}

void clipmap_mesh_free(clipmap_mesh *mesh) {
    free(mesh->vertices);
    free(mesh->indices);
    free(mesh->pieces);
    memset(mesh, 0, sizeof *mesh);
}

void clipmap_trims_for_offset(int m, int off_x, int off_z, clip_trim out[2]) {
    int xa = off_x == m - 1;
    out[0] = xa ? CLIP_TRIM_X_HIGH : CLIP_TRIM_X_LOW;
    if (off_z == m - 1)
        out[1] = xa ? CLIP_TRIM_Z_HIGH_XA : CLIP_TRIM_Z_HIGH_XB;
    else
        out[1] = xa ? CLIP_TRIM_Z_LOW_XA : CLIP_TRIM_Z_LOW_XB;
}
