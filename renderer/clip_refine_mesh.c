#include "renderer/clip_refine_mesh.h"

#include <stdlib.h>
#include <string.h>

int clip_refine_piece_refinable(const clip_piece *p) {
    return p->kind == CLIP_PIECE_BLOCK || p->kind == CLIP_PIECE_FIXUP;
}

typedef struct refine_builder {
    clip_refine_mesh *mesh;
    size_t cap, coarse_cap;
    size_t base_indices; // the base mesh's own, before the parts' coarse triangles
    int failed;
} refine_builder;

// Grows an index array by one; 0 when out of memory.
static int grow(refine_builder *b, void **items, size_t *count, size_t *cap, size_t size) {
    if (b->failed) return 0;
    if (*count == *cap) {
        size_t bigger = *cap ? *cap * 2 : 65536;
        void *grown = realloc(*items, bigger * size);
        if (!grown) {
            b->failed = 1;
            return 0;
        }
        *items = grown;
        *cap = bigger;
    }
    return 1;
}

// Fine vertex (x, z) in half units; on_line: its copy placed on the coarse edge.
static void push(refine_builder *b, int x, int z, int on_line) {
    clip_refine_mesh *m = b->mesh;
    if (!grow(b, (void **)&m->indices, &m->index_count, &b->cap, sizeof *m->indices)) return;
    size_t grid = (size_t)m->side * m->side;
    m->indices[m->index_count++] = (uint32_t)((size_t)z * m->side + x + (on_line ? grid : 0));
}

// Base mesh vertex (x, z).
static void push_coarse(refine_builder *b, int x, int z) {
    clip_refine_mesh *m = b->mesh;
    if (!grow(b, (void **)&m->coarse, &m->coarse_count, &b->coarse_cap, sizeof *m->coarse)) return;
    m->coarse[m->coarse_count++] = (uint16_t)(z * ((m->side + 1) / 2) + x);
}

// The quads of vertices [x0, x1] x [z0, z1] (base units) at half spacing (the base
// mesh's diagonal).
static void add_fine(refine_builder *b, int bx0, int bz0, int bx1, int bz1) {
    const int x0 = 2 * bx0, z0 = 2 * bz0, x1 = 2 * bx1, z1 = 2 * bz1;
    for (int z = z0; z < z1; z++)
        for (int x = x0; x < x1; x++) {
            push(b, x, z, 0), push(b, x, z + 1, 0), push(b, x + 1, z, 0);
            push(b, x + 1, z, 0), push(b, x, z + 1, 0), push(b, x + 1, z + 1, 0);
        }
}

// A zero-area triangle through each side's odd vertices' on-line copies.
static void add_seams(refine_builder *b, int bx0, int bz0, int bx1, int bz1) {
    const int x0 = 2 * bx0, z0 = 2 * bz0, x1 = 2 * bx1, z1 = 2 * bz1;
    for (int x = x0; x + 2 <= x1; x += 2) {
        push(b, x, z0, 0), push(b, x + 1, z0, 1), push(b, x + 2, z0, 0);
        push(b, x + 2, z1, 0), push(b, x + 1, z1, 1), push(b, x, z1, 0);
    }
    for (int z = z0; z + 2 <= z1; z += 2) {
        push(b, x0, z + 2, 0), push(b, x0, z + 1, 1), push(b, x0, z, 0);
        push(b, x1, z, 0), push(b, x1, z + 1, 1), push(b, x1, z + 2, 0);
    }
}

// The same quads at the level's density, through the base mesh's vertices.
static void add_coarse(refine_builder *b, int x0, int z0, int x1, int z1) {
    for (int z = z0; z < z1; z++)
        for (int x = x0; x < x1; x++) {
            push_coarse(b, x, z), push_coarse(b, x, z + 1), push_coarse(b, x + 1, z);
            push_coarse(b, x + 1, z), push_coarse(b, x, z + 1), push_coarse(b, x + 1, z + 1);
        }
}

// A piece's parts of at most CLIP_REFINE_PART quads a side, both forms; each form's
// ranges of a piece's parts follow one another (their fine quads, then their seams),
// so that neighbouring parts drawn alike join into one draw.
static void add_parts(refine_builder *b, const clip_piece *p, size_t piece) {
    clip_refine_mesh *r = b->mesh;
    r->part_first[piece] = (uint32_t)(piece * CLIP_REFINE_PARTS_MAX);
    clip_refine_part *parts = &r->parts[piece * CLIP_REFINE_PARTS_MAX];
    uint32_t n = 0;
    for (int z = p->z0; z < p->z1; z += CLIP_REFINE_PART)
        for (int x = p->x0; x < p->x1; x += CLIP_REFINE_PART) {
            if (n == CLIP_REFINE_PARTS_MAX) {
                b->failed = 1; // a piece larger than the base mesh makes
                return;
            }
            clip_refine_part *q = &parts[n++];
            q->x0 = (uint16_t)x, q->z0 = (uint16_t)z;
            q->x1 = (uint16_t)(x + CLIP_REFINE_PART < p->x1 ? x + CLIP_REFINE_PART : p->x1);
            q->z1 = (uint16_t)(z + CLIP_REFINE_PART < p->z1 ? z + CLIP_REFINE_PART : p->z1);
        }
    r->part_count[piece] = n;
    for (uint32_t k = 0; k < n; k++) {
        clip_refine_part *q = &parts[k];
        q->fine_first = (uint32_t)r->index_count;
        add_fine(b, q->x0, q->z0, q->x1, q->z1);
        q->fine_count = (uint32_t)(r->index_count - q->fine_first);
    }
    for (uint32_t k = 0; k < n; k++) {
        clip_refine_part *q = &parts[k];
        q->seam_first = (uint32_t)r->index_count;
        add_seams(b, q->x0, q->z0, q->x1, q->z1);
        q->seam_count = (uint32_t)(r->index_count - q->seam_first);
    }
    for (uint32_t k = 0; k < n; k++) {
        clip_refine_part *q = &parts[k];
        q->coarse_first = (uint32_t)(b->base_indices + r->coarse_count);
        add_coarse(b, q->x0, q->z0, q->x1, q->z1);
        q->coarse_count = (uint32_t)(b->base_indices + r->coarse_count - q->coarse_first);
    }
}

int clip_refine_mesh_build(clip_refine_mesh *r, const clipmap_mesh *base) {
    memset(r, 0, sizeof *r);
    r->side = 2 * base->n - 1;
    const size_t grid = (size_t)r->side * r->side;
    r->vertex_count = 2 * grid;
    r->piece_count = base->piece_count;
    r->vertices = malloc(r->vertex_count * 2 * sizeof *r->vertices);
    r->part_first = calloc(base->piece_count ? base->piece_count : 1, sizeof *r->part_first);
    r->part_count = calloc(base->piece_count ? base->piece_count : 1, sizeof *r->part_count);
    r->parts = calloc((base->piece_count ? base->piece_count : 1) * CLIP_REFINE_PARTS_MAX,
                      sizeof *r->parts);
    refine_builder b = {r, 0, 0, base->index_count,
                        !r->vertices || !r->part_first || !r->part_count || !r->parts};
    for (size_t v = 0; !b.failed && v < grid; v++) {
        uint16_t x = (uint16_t)(v % (size_t)r->side), z = (uint16_t)(v / (size_t)r->side);
        r->vertices[2 * v] = x, r->vertices[2 * v + 1] = z;
        r->vertices[2 * (grid + v)] = (uint16_t)(x | CLIP_REFINE_ON_LINE);
        r->vertices[2 * (grid + v) + 1] = z;
    }
    for (size_t i = 0; !b.failed && i < base->piece_count; i++) {
        if (clip_refine_piece_refinable(&base->pieces[i])) add_parts(&b, &base->pieces[i], i);
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
    free(r->coarse);
    free(r->parts);
    free(r->part_first);
    free(r->part_count);
    memset(r, 0, sizeof *r);
}
