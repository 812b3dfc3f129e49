#include "renderer/clip_refine_mesh.h"

#include <stdlib.h>
#include <string.h>

int clip_refine_piece_refinable(const clip_piece *p) {
    return p->kind == CLIP_PIECE_BLOCK || p->kind == CLIP_PIECE_FIXUP;
}

typedef struct refine_builder {
    clip_refine_mesh *mesh;
    size_t cap;
    int failed;
} refine_builder;

// Fine vertex (x, z) in half units; on_line: its copy placed on the coarse edge.
static void push(refine_builder *b, int x, int z, int on_line) {
    clip_refine_mesh *m = b->mesh;
    if (b->failed) return;
    if (m->index_count == b->cap) {
        size_t cap = b->cap ? b->cap * 2 : 65536;
        uint32_t *grown = realloc(m->indices, cap * sizeof *grown);
        if (!grown) {
            b->failed = 1;
            return;
        }
        m->indices = grown;
        b->cap = cap;
    }
    size_t grid = (size_t)m->side * m->side;
    m->indices[m->index_count++] = (uint32_t)((size_t)z * m->side + x + (on_line ? grid : 0));
}

// The quads of vertices [x0, x1] x [z0, z1] (base units) at half spacing (the base
// mesh's diagonal), then a zero-area triangle through each side's odd vertices' on-line
// copies.
static void add_fine(refine_builder *b, int bx0, int bz0, int bx1, int bz1) {
    const int x0 = 2 * bx0, z0 = 2 * bz0, x1 = 2 * bx1, z1 = 2 * bz1;
    for (int z = z0; z < z1; z++)
        for (int x = x0; x < x1; x++) {
            push(b, x, z, 0), push(b, x, z + 1, 0), push(b, x + 1, z, 0);
            push(b, x + 1, z, 0), push(b, x, z + 1, 0), push(b, x + 1, z + 1, 0);
        }
    for (int x = x0; x + 2 <= x1; x += 2) {
        push(b, x, z0, 0), push(b, x + 1, z0, 1), push(b, x + 2, z0, 0);
        push(b, x + 2, z1, 0), push(b, x + 1, z1, 1), push(b, x, z1, 0);
    }
    for (int z = z0; z + 2 <= z1; z += 2) {
        push(b, x0, z + 2, 0), push(b, x0, z + 1, 1), push(b, x0, z, 0);
        push(b, x1, z, 0), push(b, x1, z + 1, 1), push(b, x1, z + 2, 0);
    }
}

// The same quads at the level's density, through the grid's even vertices.
static void add_coarse(refine_builder *b, int bx0, int bz0, int bx1, int bz1) {
    for (int z = 2 * bz0; z < 2 * bz1; z += 2)
        for (int x = 2 * bx0; x < 2 * bx1; x += 2) {
            push(b, x, z, 0), push(b, x, z + 2, 0), push(b, x + 2, z, 0);
            push(b, x + 2, z, 0), push(b, x, z + 2, 0), push(b, x + 2, z + 2, 0);
        }
}

// A piece's parts of at most CLIP_REFINE_PART quads a side, both forms.
static void add_parts(refine_builder *b, const clip_piece *p, size_t piece) {
    clip_refine_mesh *r = b->mesh;
    r->part_first[piece] = (uint32_t)(piece * CLIP_REFINE_PARTS_MAX);
    uint32_t n = 0;
    for (int z = p->z0; z < p->z1; z += CLIP_REFINE_PART)
        for (int x = p->x0; x < p->x1; x += CLIP_REFINE_PART) {
            if (n == CLIP_REFINE_PARTS_MAX) {
                b->failed = 1; // a piece larger than the base mesh makes
                return;
            }
            clip_refine_part *q = &r->parts[piece * CLIP_REFINE_PARTS_MAX + n++];
            q->x0 = (uint16_t)x, q->z0 = (uint16_t)z;
            q->x1 = (uint16_t)(x + CLIP_REFINE_PART < p->x1 ? x + CLIP_REFINE_PART : p->x1);
            q->z1 = (uint16_t)(z + CLIP_REFINE_PART < p->z1 ? z + CLIP_REFINE_PART : p->z1);
            q->fine_first = (uint32_t)r->index_count;
            add_fine(b, q->x0, q->z0, q->x1, q->z1);
            q->fine_count = (uint32_t)(r->index_count - q->fine_first);
            q->coarse_first = (uint32_t)r->index_count;
            add_coarse(b, q->x0, q->z0, q->x1, q->z1);
            q->coarse_count = (uint32_t)(r->index_count - q->coarse_first);
        }
    r->part_count[piece] = n;
}

int clip_refine_mesh_build(clip_refine_mesh *r, const clipmap_mesh *base) {
    memset(r, 0, sizeof *r);
    r->side = 2 * base->n - 1;
    const size_t grid = (size_t)r->side * r->side;
    r->vertex_count = 2 * grid;
    r->piece_count = base->piece_count;
    r->vertices = malloc(r->vertex_count * 2 * sizeof *r->vertices);
    r->first = calloc(base->piece_count ? base->piece_count : 1, sizeof *r->first);
    r->count = calloc(base->piece_count ? base->piece_count : 1, sizeof *r->count);
    r->part_first = calloc(base->piece_count ? base->piece_count : 1, sizeof *r->part_first);
    r->part_count = calloc(base->piece_count ? base->piece_count : 1, sizeof *r->part_count);
    r->parts = calloc((base->piece_count ? base->piece_count : 1) * CLIP_REFINE_PARTS_MAX,
                      sizeof *r->parts);
    refine_builder b = {r, 0,
                        !r->vertices || !r->first || !r->count || !r->part_first ||
                            !r->part_count || !r->parts};
    for (size_t v = 0; !b.failed && v < grid; v++) {
        uint16_t x = (uint16_t)(v % (size_t)r->side), z = (uint16_t)(v / (size_t)r->side);
        r->vertices[2 * v] = x, r->vertices[2 * v + 1] = z;
        r->vertices[2 * (grid + v)] = (uint16_t)(x | CLIP_REFINE_ON_LINE);
        r->vertices[2 * (grid + v) + 1] = z;
    }
    for (size_t i = 0; !b.failed && i < base->piece_count; i++) {
        if (!clip_refine_piece_refinable(&base->pieces[i])) continue;
        r->first[i] = (uint32_t)r->index_count;
        const clip_piece *p = &base->pieces[i];
        add_fine(&b, p->x0, p->z0, p->x1, p->z1);
        r->count[i] = (uint32_t)(r->index_count - r->first[i]);
        add_parts(&b, p, i);
    }
    if (b.failed) {
        clip_refine_mesh_free(r);
        return -1;
    }
    return 0;
}

void clip_refine_mesh_free(clip_refine_mesh *r) {
    free(r->vertices);
    free(r->indices);
    free(r->first);
    free(r->count);
    free(r->parts);
    free(r->part_first);
    free(r->part_count);
    memset(r, 0, sizeof *r);
}
