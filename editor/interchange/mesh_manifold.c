#include "editor/interchange/mesh_manifold.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

// Undirected edges by their two vertices: the first four faces, which way each runs
// (from the lower vertex or not) and how many faces use the edge.
typedef struct edge_slot {
    uint64_t key; // lower << 32 | higher; EMPTY when free
    uint32_t face[4];
    uint32_t count;
    uint8_t forward[4];
} edge_slot;

#define EMPTY UINT64_MAX

typedef struct edge_table {
    edge_slot *slots;
    size_t mask;
} edge_table;

static edge_slot *edge_find(edge_table *t, uint32_t a, uint32_t b) {
    uint64_t key = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
    uint64_t h = key * 0x9e3779b97f4a7c15ULL;
    size_t s = (size_t)(h ^ h >> 29) & t->mask;
    while (t->slots[s].key != EMPTY && t->slots[s].key != key)
        s = (s + 1) & t->mask;
    if (t->slots[s].key == EMPTY) {
        memset(&t->slots[s], 0, sizeof t->slots[s]);
        t->slots[s].key = key;
    }
    return &t->slots[s];
}

static int edge_table_init(edge_table *t, size_t triangles) {
    size_t size = 1024;
    while (size < triangles * 3 * 2)
        size *= 2;
    t->slots = malloc(size * sizeof *t->slots);
    if (!t->slots) return -1;
    for (size_t s = 0; s < size; s++)
        t->slots[s].key = EMPTY;
    t->mask = size - 1;
    return 0;
}

static void edge_table_fill(edge_table *t, const uint32_t *index, size_t triangles) {
    for (size_t f = 0; f < triangles; f++)
        for (int c = 0; c < 3; c++) {
            uint32_t a = index[3 * f + c], b = index[3 * f + (c + 1) % 3];
            edge_slot *e = edge_find(t, a, b);
            if (e->count < 4) e->face[e->count] = (uint32_t)f, e->forward[e->count] = a < b;
            e->count++;
        }
}

// Two faces on one edge, running it in opposite directions: the same sheet.
static int edge_is_manifold(const edge_slot *e) {
    return e->count == 2 && e->forward[0] != e->forward[1];
}

static uint32_t find_root(uint32_t *parent, uint32_t c) {
    while (parent[c] != c)
        c = parent[c] = parent[parent[c]];
    return c;
}

static void join(uint32_t *parent, uint32_t a, uint32_t b) {
    a = find_root(parent, a), b = find_root(parent, b);
    if (a != b) parent[a < b ? b : a] = a < b ? a : b;
}

static void join_pair(const volume_mesh *m, uint32_t *parent, uint32_t a, uint32_t b, uint32_t f0,
                      uint32_t f1);

// Four faces on one edge (two sheets through one surface-nets cell face, each running
// the edge both ways): the faces in turn around the edge, paired with a neighbour that
// runs it the other way. The pairing is decided once per edge, so both of its vertices
// split the same way.
static void pair_crowded(const volume_mesh *m, uint32_t *parent, const edge_slot *e) {
    uint32_t a = (uint32_t)(e->key >> 32), b = (uint32_t)e->key;
    const float *pa = m->pos + 3 * (size_t)a, *pb = m->pos + 3 * (size_t)b;
    double d[3], u[3], v[3], len = 0;
    for (int k = 0; k < 3; k++)
        d[k] = (double)pb[k] - pa[k], len += d[k] * d[k];
    if (len == 0) return;
    // A frame (u, v) across the edge.
    double any[3] = {fabs(d[0]) < fabs(d[1]) ? 1 : 0, fabs(d[0]) < fabs(d[1]) ? 0 : 1, 0};
    u[0] = d[1] * any[2] - d[2] * any[1], u[1] = d[2] * any[0] - d[0] * any[2],
    u[2] = d[0] * any[1] - d[1] * any[0];
    v[0] = d[1] * u[2] - d[2] * u[1], v[1] = d[2] * u[0] - d[0] * u[2],
    v[2] = d[0] * u[1] - d[1] * u[0];
    double angle[4];
    int order[4] = {0, 1, 2, 3};
    for (int q = 0; q < 4; q++) {
        const uint32_t *t = m->index + 3 * (size_t)e->face[q];
        uint32_t third = t[0] != a && t[0] != b ? t[0] : t[1] != a && t[1] != b ? t[1] : t[2];
        const float *p = m->pos + 3 * (size_t)third;
        double x = 0, y = 0;
        for (int k = 0; k < 3; k++)
            x += ((double)p[k] - pa[k]) * u[k], y += ((double)p[k] - pa[k]) * v[k];
        angle[q] = atan2(y, x);
    }
    for (int i = 1; i < 4; i++)
        for (int j = i; j > 0 && angle[order[j]] < angle[order[j - 1]]; j--) {
            int t = order[j];
            order[j] = order[j - 1], order[j - 1] = t;
        }
    for (int i = 0; i < 4; i++)
        if (e->forward[order[i]] == e->forward[order[(i + 1) % 4]]) return; // not two sheets
    join_pair(m, parent, a, b, e->face[order[0]], e->face[order[1]]);
    join_pair(m, parent, a, b, e->face[order[2]], e->face[order[3]]);
}

static uint32_t corner_of(const uint32_t *index, uint32_t face, uint32_t vertex) {
    for (uint32_t c = 3 * face; c < 3 * face + 3; c++)
        if (index[c] == vertex) return c;
    return 3 * face; // not reached: the edge's vertices are the face's
}

static int degenerate(const float *pos, const uint32_t *t) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return 1;
    const float *a = pos + 3 * t[0], *b = pos + 3 * t[1], *c = pos + 3 * t[2];
    double u[3], v[3];
    for (int k = 0; k < 3; k++)
        u[k] = (double)b[k] - a[k], v[k] = (double)c[k] - a[k];
    double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
           z = u[0] * v[1] - u[1] * v[0];
    return x == 0 && y == 0 && z == 0;
}

// Squared length of edge (a, b).
static double length2(const float *pos, uint32_t a, uint32_t b) {
    double l = 0;
    for (int k = 0; k < 3; k++) {
        double d = (double)pos[3 * (size_t)b + k] - pos[3 * (size_t)a + k];
        l += d * d;
    }
    return l;
}

// A sliver (three distinct vertices in a line, as a simplifier's collapse can leave) is
// removed by splitting the face across its long edge at its middle vertex: that face's
// two halves take the sliver's place, so the surface stays closed where dropping the
// sliver would open a hole of no area. Slivers whose neighbour is missing, or one too,
// are left for the degenerate filter. Returns -1 when out of memory.
static int split_slivers(volume_mesh *m) {
    size_t triangles = m->index_count / 3, count = 0;
    for (size_t f = 0; f < triangles; f++) {
        const uint32_t *t = m->index + 3 * f;
        count += t[0] != t[1] && t[1] != t[2] && t[2] != t[0] && degenerate(m->pos, t);
    }
    if (count == 0) return 0;
    // Per sliver: its middle corner c, and the face running its long edge back (b -> a).
    uint32_t *sliver = malloc(count * sizeof *sliver), *middle = malloc(count * sizeof *middle);
    int64_t *other = malloc(count * sizeof *other);
    uint32_t *index = realloc(m->index, (m->index_count + 3 * count) * sizeof *index);
    if (index) m->index = index;
    if (!sliver || !middle || !other || !index) {
        free(sliver), free(middle), free(other);
        return -1;
    }
    size_t n = 0;
    for (size_t f = 0; f < triangles; f++) {
        const uint32_t *t = m->index + 3 * f;
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0] || !degenerate(m->pos, t)) continue;
        int mid = 0;
        double longest = -1;
        for (int c = 0; c < 3; c++) { // the middle vertex faces the longest edge
            double l = length2(m->pos, t[(c + 1) % 3], t[(c + 2) % 3]);
            if (l > longest) longest = l, mid = c;
        }
        sliver[n] = (uint32_t)f, middle[n] = (uint32_t)mid, other[n++] = -1;
    }
    // One pass over the faces finds each sliver's neighbour (slivers are few).
    for (size_t g = 0; g < triangles; g++) {
        const uint32_t *t = m->index + 3 * g;
        for (size_t s = 0; s < n; s++) {
            const uint32_t *q = m->index + 3 * (size_t)sliver[s];
            uint32_t a = q[(middle[s] + 1) % 3], b = q[(middle[s] + 2) % 3];
            for (int c = 0; c < 3; c++)
                if (t[c] == b && t[(c + 1) % 3] == a) other[s] = other[s] < 0 ? (int64_t)g : -2;
        }
    }
    unsigned char *busy = calloc(triangles, 1); // a face split or removed once already
    if (!busy) {
        free(sliver), free(middle), free(other);
        return -1;
    }
    for (size_t s = 0; s < n; s++)
        busy[sliver[s]] = 1;
    size_t end = m->index_count;
    for (size_t s = 0; s < n; s++) {
        if (other[s] < 0 || busy[other[s]]) continue;
        uint32_t *q = m->index + 3 * (size_t)sliver[s], *g = m->index + 3 * (size_t)other[s];
        uint32_t c = q[middle[s]], a = q[(middle[s] + 1) % 3], b = q[(middle[s] + 2) % 3];
        int at = g[0] == b ? 0 : g[1] == b ? 1 : 2;
        uint32_t d = g[(at + 2) % 3];
        g[0] = b, g[1] = c, g[2] = d;                                    // (b, a, d) -> (b, c, d)
        m->index[end] = c, m->index[end + 1] = a, m->index[end + 2] = d; // and (c, a, d)
        end += 3;
        q[0] = q[1] = q[2] = c; // the sliver goes with the degenerate faces
        busy[other[s]] = 1;
    }
    m->index_count = end;
    free(busy), free(sliver), free(middle), free(other);
    return 0;
}

void mesh_face_sorted(const uint32_t *t, uint32_t out[3]) {
    uint32_t a = t[0], b = t[1], c = t[2], x;
    if (a > b) x = a, a = b, b = x;
    if (b > c) x = b, b = c, c = x;
    if (a > b) x = a, a = b, b = x;
    out[0] = a, out[1] = b, out[2] = c;
}

// Faces on the same three vertices: a pair wound against each other is a fin of no
// thickness (both go), a repeat wound the same way goes. Returns the faces left.
static int drop_twins(uint32_t *index, size_t triangles, size_t *left) {
    size_t size = 1024;
    while (size < triangles * 2)
        size *= 2;
    uint32_t *slot = malloc(size * sizeof *slot); // face + 1; 0 = empty
    unsigned char *gone = calloc(triangles ? triangles : 1, 1);
    if (!slot || !gone) {
        free(slot), free(gone);
        return -1;
    }
    memset(slot, 0, size * sizeof *slot);
    for (size_t f = 0; f < triangles; f++) {
        uint32_t key[3], other[3];
        mesh_face_sorted(index + 3 * f, key);
        uint64_t h = ((uint64_t)key[0] * 0x9e3779b97f4a7c15ULL) ^
                     ((uint64_t)key[1] * 0xc2b2ae3d27d4eb4fULL) ^
                     ((uint64_t)key[2] * 0x165667b19e3779f9ULL);
        size_t s = (size_t)(h ^ h >> 31) & (size - 1);
        for (; slot[s]; s = (s + 1) & (size - 1)) {
            uint32_t g = slot[s] - 1;
            mesh_face_sorted(index + 3 * (size_t)g, other);
            if (gone[g] || memcmp(key, other, sizeof key)) continue;
            // Same winding when f's first vertex is followed by the same vertex in g.
            const uint32_t *a = index + 3 * f, *b = index + 3 * (size_t)g;
            int at = b[0] == a[0] ? 0 : b[1] == a[0] ? 1 : 2;
            gone[f] = 1;
            if (b[(at + 1) % 3] != a[1]) gone[g] = 1;
            break;
        }
        if (!gone[f] && !slot[s]) slot[s] = (uint32_t)f + 1;
    }
    size_t kept = 0;
    for (size_t f = 0; f < triangles; f++)
        if (!gone[f]) memmove(index + 3 * kept++, index + 3 * f, 3 * sizeof *index);
    *left = kept;
    free(slot), free(gone);
    return 0;
}

// New vertices, one per class of corners (corners whose root is the same): positions
// and normals copied from the vertex each corner had. Vertices no corner names vanish.
static int rebuild_vertices(volume_mesh *m, uint32_t *parent, size_t corners, size_t *made) {
    uint32_t *id = malloc(corners * sizeof *id);
    float *pos = malloc(corners * 3 * sizeof *pos), *normal = malloc(corners * 3 * sizeof *normal);
    if (!id || !pos || !normal) {
        free(id), free(pos), free(normal);
        return -1;
    }
    memset(id, 0xff, corners * sizeof *id);
    for (size_t c = 0; c < corners; c++) // every corner straight to its root
        parent[c] = find_root(parent, (uint32_t)c);
    size_t n = 0;
    for (size_t c = 0; c < corners; c++) {
        uint32_t r = parent[c];
        if (id[r] == UINT32_MAX) {
            memcpy(pos + 3 * n, m->pos + 3 * (size_t)m->index[c], 3 * sizeof *pos);
            memcpy(normal + 3 * n, m->normal + 3 * (size_t)m->index[c], 3 * sizeof *normal);
            id[r] = (uint32_t)n++;
        }
        m->index[c] = id[r];
    }
    free(id);
    free(m->pos);
    free(m->normal);
    m->pos = pos, m->normal = normal;
    m->vertex_count = n;
    *made = n;
    return 0;
}

// Corners share a vertex when they name the same old vertex and faces of one sheet
// meet there (split); without split, every corner of a vertex shares it.
static void link_corners(const volume_mesh *m, uint32_t *parent, edge_table *t, int split) {
    size_t corners = m->index_count;
    for (size_t c = 0; c < corners; c++)
        parent[c] = (uint32_t)c;
    if (!split) { // plain compaction: the first corner of each vertex is its class
        uint32_t *first = malloc(m->vertex_count * sizeof *first);
        if (first) {
            memset(first, 0xff, m->vertex_count * sizeof *first);
            for (size_t c = 0; c < corners; c++) {
                uint32_t v = m->index[c];
                if (first[v] == UINT32_MAX) first[v] = (uint32_t)c;
                parent[c] = first[v];
            }
            free(first);
        }
        return;
    }
    for (size_t s = 0; s <= t->mask; s++) {
        const edge_slot *e = &t->slots[s];
        if (e->key == EMPTY) continue;
        if (edge_is_manifold(e))
            join_pair(m, parent, (uint32_t)(e->key >> 32), (uint32_t)e->key, e->face[0],
                      e->face[1]);
        else if (e->count == 4)
            pair_crowded(m, parent, e);
    }
}

// Faces f0 and f1 on edge (a, b) are one sheet: their corners at a and at b join.
static void join_pair(const volume_mesh *m, uint32_t *parent, uint32_t a, uint32_t b, uint32_t f0,
                      uint32_t f1) {
    join(parent, corner_of(m->index, f0, a), corner_of(m->index, f1, a));
    join(parent, corner_of(m->index, f0, b), corner_of(m->index, f1, b));
}

int mesh_make_manifold(volume_mesh *m, mesh_manifold_report *rep, og_error *err) {
    memset(rep, 0, sizeof *rep);
    size_t kept = 0, triangles = m->index_count / 3, before = m->vertex_count;
    if (split_slivers(m) != 0) return og_error_set(err, "out of memory making the mesh manifold");
    triangles = m->index_count / 3;
    for (size_t f = 0; f < triangles; f++)
        if (!degenerate(m->pos, m->index + 3 * f))
            memmove(m->index + 3 * kept++, m->index + 3 * f, 3 * sizeof *m->index);
    if (drop_twins(m->index, kept, &triangles) != 0)
        return og_error_set(err, "out of memory making the mesh manifold");
    rep->degenerate_dropped = (long long)(m->index_count / 3 - triangles);
    m->index_count = 3 * triangles;
    if (triangles == 0) {
        rep->unused_dropped = (long long)m->vertex_count;
        m->vertex_count = 0;
        return 0;
    }
    edge_table t;
    uint32_t *parent = malloc(m->index_count * sizeof *parent);
    if (!parent || edge_table_init(&t, triangles) != 0) {
        free(parent);
        return og_error_set(err, "out of memory making the mesh manifold");
    }
    // Used vertices before the split (for the report).
    link_corners(m, parent, NULL, 0);
    size_t used = 0;
    for (size_t c = 0; c < m->index_count; c++)
        used += parent[c] == c;
    rep->unused_dropped = (long long)(before - used);

    // Each vertex splits into the fans of faces joined across its manifold edges.
    edge_table_fill(&t, m->index, triangles);
    link_corners(m, parent, &t, 1);
    size_t made;
    if (rebuild_vertices(m, parent, m->index_count, &made) != 0) goto oom;
    rep->vertices_split = (long long)(made - used);

    // What still crowds an edge (sheets whose fans the split could not tell apart):
    // the first face and the first one running the edge the other way stay.
    for (size_t s = 0; s <= t.mask; s++)
        t.slots[s].key = EMPTY;
    kept = 0;
    for (size_t f = 0; f < triangles; f++) {
        const uint32_t *tri = m->index + 3 * f;
        int ok = 1;
        for (int c = 0; c < 3 && ok; c++) {
            uint32_t a = tri[c], b = tri[(c + 1) % 3];
            edge_slot *e = edge_find(&t, a, b);
            ok = e->count == 0 || (e->count == 1 && e->forward[0] != (a < b));
        }
        if (!ok) continue;
        for (int c = 0; c < 3; c++) {
            uint32_t a = tri[c], b = tri[(c + 1) % 3];
            edge_slot *e = edge_find(&t, a, b);
            e->forward[e->count < 4 ? e->count : 3] = a < b;
            e->count++;
        }
        memmove(m->index + 3 * kept++, tri, 3 * sizeof *tri);
    }
    rep->faces_dropped = (long long)(triangles - kept);
    m->index_count = 3 * kept;
    if (rep->faces_dropped) { // their vertices may be left unused
        link_corners(m, parent, NULL, 0);
        size_t left;
        if (rebuild_vertices(m, parent, m->index_count, &left) != 0) goto oom;
        rep->unused_dropped += (long long)(made - left);
    }
    free(parent);
    free(t.slots);
    return 0;
oom:
    free(parent);
    free(t.slots);
    return og_error_set(err, "out of memory making the mesh manifold");
}
