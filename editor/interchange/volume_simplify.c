#include "editor/interchange/volume_simplify.h"

#include "editor/interchange/mesh_distance.h"
#include "editor/interchange/mesh_manifold.h"

#include <math.h>
#include <meshoptimizer.h>
#include <stdlib.h>
#include <string.h>

enum { ROUNDS_PER_LEVEL = 6, MAX_SAMPLES_PER_EDGE = 64 };
#define LEVEL_STEP 0.7   // each level's target over the next's
#define FIRST_LEVEL 0.06 // the first level's target over the input's mean edge

// A face thinner than this (metres, its height over its longest edge) is a sliver.
#define SLIVER_M 1e-3

typedef struct simplifier {
    const volume_mesh *in;
    size_t triangles;            // the input's faces
    uint32_t *ring_start, *ring; // faces around input vertex v: ring[ring_start[v] ..]
    uint64_t *open;              // the input's open edges, a << 32 | b as its faces run them
    size_t open_count;
    uint32_t *faces;       // the last accepted result's faces by their sorted vertices, sorted
    size_t accepted;       // faces in it
    mesh_distance surface; // distance to the input
    double step;           // metres between samples on a result face: the input's mean edge
    double error;          // metres asked for
} simplifier;

static int u64_cmp(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

static int triple_cmp(const void *a, const void *b) {
    const uint32_t *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
    return 0;
}

// One face's use of an undirected edge.
typedef struct edge_use {
    uint64_t key; // lower << 32 | higher
    uint32_t face;
    uint32_t forward; // the face runs it from the lower vertex
} edge_use;

static int edge_cmp(const void *a, const void *b) {
    const edge_use *x = a, *y = b;
    return x->key != y->key ? (x->key < y->key ? -1 : 1)
                            : (x->face > y->face) - (x->face < y->face);
}

static edge_use *edges_of(const uint32_t *index, size_t triangles) {
    edge_use *e = malloc((triangles ? 3 * triangles : 1) * sizeof *e);
    if (!e) return NULL;
    for (size_t f = 0; f < triangles; f++)
        for (int c = 0; c < 3; c++) {
            uint32_t a = index[3 * f + c], b = index[3 * f + (c + 1) % 3];
            edge_use *u = e + 3 * f + c;
            u->key = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
            u->face = (uint32_t)f, u->forward = a < b;
        }
    qsort(e, 3 * triangles, sizeof *e, edge_cmp);
    return e;
}

static void simplifier_free(simplifier *s) {
    free(s->ring_start), free(s->ring), free(s->open), free(s->faces);
    mesh_distance_free(&s->surface);
}

// The faces around each vertex: ring[start[v] .. start[v + 1]).
static int rings_of(const uint32_t *index, size_t triangles, size_t vertices, uint32_t **start,
                    uint32_t **ring) {
    *start = calloc(vertices + 1, sizeof **start);
    *ring = malloc((triangles ? 3 * triangles : 1) * sizeof **ring);
    if (!*start || !*ring) {
        free(*start), free(*ring);
        *start = *ring = NULL;
        return -1;
    }
    for (size_t c = 0; c < 3 * triangles; c++)
        (*start)[index[c] + 1]++;
    for (size_t v = 0; v < vertices; v++)
        (*start)[v + 1] += (*start)[v];
    for (size_t c = 0; c < 3 * triangles; c++)
        (*ring)[(*start)[index[c]]++] = (uint32_t)(c / 3);
    memmove(*start + 1, *start, vertices * sizeof **start);
    (*start)[0] = 0;
    return 0;
}

static int simplifier_init(simplifier *s, const volume_mesh *m, double error_m) {
    memset(s, 0, sizeof *s);
    s->in = m, s->triangles = m->index_count / 3, s->error = error_m;
    const size_t T = s->triangles, V = m->vertex_count;
    s->open = malloc(3 * T * sizeof *s->open);
    s->faces = malloc(3 * T * sizeof *s->faces);
    edge_use *e = edges_of(m->index, T);
    if (rings_of(m->index, T, V, &s->ring_start, &s->ring) != 0 || !s->open || !s->faces || !e)
        goto fail;
    double length = 0;
    for (size_t i = 0; i < 3 * T; i++) {
        uint32_t a = (uint32_t)(e[i].key >> 32), b = (uint32_t)e[i].key;
        int alone =
            (i == 0 || e[i - 1].key != e[i].key) && (i + 1 == 3 * T || e[i + 1].key != e[i].key);
        if (alone) s->open[s->open_count++] = e[i].forward ? e[i].key : (uint64_t)b << 32 | a;
        const float *p = m->pos + 3 * (size_t)a, *q = m->pos + 3 * (size_t)b;
        length +=
            sqrt((double)(p[0] - q[0]) * (p[0] - q[0]) + (double)(p[1] - q[1]) * (p[1] - q[1]) +
                 (double)(p[2] - q[2]) * (p[2] - q[2]));
    }
    free(e);
    e = NULL;
    qsort(s->open, s->open_count, sizeof *s->open, u64_cmp);
    s->step = T ? length / (3.0 * (double)T) : 1;
    if (mesh_distance_build(&s->surface, m->pos, m->index, T) != 0) goto fail;
    return 0;
fail:
    free(e);
    simplifier_free(s);
    return -1;
}

static void corner(const volume_mesh *m, uint32_t v, double p[3]) {
    for (int k = 0; k < 3; k++)
        p[k] = m->pos[3 * (size_t)v + k];
}

// Points on face t, as dense as the input's vertices (its corners, the input's own,
// left out), against the input. Without raise: 1 when every point lies within *limit
// of it, else 0 and *nearest the input face nearest the first that does not (UINT32_MAX
// if none). With raise: *limit grows to the largest distance of any point; returns 1.
static int face_within(const simplifier *s, const uint32_t *t, double *limit, int raise,
                       uint32_t *nearest) {
    double a[3], b[3], c[3], longest = 0;
    corner(s->in, t[0], a), corner(s->in, t[1], b), corner(s->in, t[2], c);
    const double *p[3] = {a, b, c};
    for (int e = 0; e < 3; e++) {
        const double *u = p[e], *v = p[(e + 1) % 3];
        longest = fmax(longest, sqrt((u[0] - v[0]) * (u[0] - v[0]) + (u[1] - v[1]) * (u[1] - v[1]) +
                                     (u[2] - v[2]) * (u[2] - v[2])));
    }
    int n = (int)ceil(longest / s->step);
    n = n < 1 ? 1 : n > MAX_SAMPLES_PER_EDGE ? MAX_SAMPLES_PER_EDGE : n;
    for (int i = 0; i < n; i++)
        for (int j = i == 0; j <= (i == 0 ? n - 1 : n - i); j++) {
            double q[3], u = (double)i / n, v = (double)j / n;
            for (int k = 0; k < 3; k++)
                q[k] = a[k] + (b[k] - a[k]) * u + (c[k] - a[k]) * v;
            if (mesh_distance_within(&s->surface, q, *limit, nearest)) continue;
            if (!raise) return 0;
            *limit = mesh_distance_to(&s->surface, q, nearest); // only a farther point
        }
    return 1;
}

// Faces the last accepted result had passed the checks already.
static void accept(simplifier *s, const uint32_t *index, size_t faces) {
    for (size_t f = 0; f < faces; f++)
        mesh_face_sorted(index + 3 * f, s->faces + 3 * f);
    qsort(s->faces, faces, 3 * sizeof *s->faces, triple_cmp);
    s->accepted = faces;
}

static int known(const simplifier *s, const uint32_t *t) {
    uint32_t key[3];
    mesh_face_sorted(t, key);
    return bsearch(key, s->faces, s->accepted, 3 * sizeof *key, triple_cmp) != NULL;
}

// A sliver, or a face turned against the surface it replaces (the input's normals at its
// corners).
static int misshapen(const simplifier *s, const uint32_t *t) {
    double a[3], b[3], c[3], u[3], v[3], n[3], longest = 0;
    corner(s->in, t[0], a), corner(s->in, t[1], b), corner(s->in, t[2], c);
    for (int k = 0; k < 3; k++)
        u[k] = b[k] - a[k], v[k] = c[k] - a[k];
    n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2],
    n[2] = u[0] * v[1] - u[1] * v[0];
    const double *p[3] = {a, b, c};
    for (int e = 0; e < 3; e++) {
        const double *x = p[e], *y = p[(e + 1) % 3];
        longest = fmax(longest, sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                                     (x[2] - y[2]) * (x[2] - y[2])));
    }
    double twice_area = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (twice_area <= SLIVER_M * longest) return 1;
    double facing = 0;
    for (int k = 0; k < 3; k++)
        for (int q = 0; q < 3; q++)
            facing += n[k] * s->in->normal[3 * (size_t)t[q] + k];
    if (facing > 0) return 0;
    // Against the corners' normals; and against the input face nearest its middle (where
    // the region's sides flattened the surface, the corners' normals lie across it).
    double middle[3], x[3], y[3], z[3];
    for (int k = 0; k < 3; k++)
        middle[k] = (a[k] + b[k] + c[k]) / 3;
    uint32_t near;
    if (mesh_distance_to(&s->surface, middle, &near) == INFINITY) return 1;
    corner(s->in, s->in->index[3 * (size_t)near], x);
    corner(s->in, s->in->index[3 * (size_t)near + 1], y);
    corner(s->in, s->in->index[3 * (size_t)near + 2], z);
    for (int k = 0; k < 3; k++)
        u[k] = y[k] - x[k], v[k] = z[k] - x[k];
    facing = n[0] * (u[1] * v[2] - u[2] * v[1]) + n[1] * (u[2] * v[0] - u[0] * v[2]) +
             n[2] * (u[0] * v[1] - u[1] * v[0]);
    return facing <= 0;
}

// Checks a result (faces over the input's vertices); marks hot the input vertices around
// every failure and returns how many faces failed (-1: out of memory). *worst is the
// largest distance measured either way.
static long long check(const simplifier *s, const uint32_t *res, size_t faces, size_t made,
                       unsigned char *hot) {
    unsigned char *bad = calloc(faces ? faces : 1, 1);
    uint32_t *twins = malloc((faces ? faces : 1) * 4 * sizeof *twins);
    edge_use *e = edges_of(res, faces);
    mesh_distance result = {0};
    long long failed = -1;
    if (!bad || !twins || !e || mesh_distance_build(&result, s->in->pos, res, faces) != 0)
        goto done;
    for (size_t f = 0; f < faces; f++) // faces on the same three vertices
        mesh_face_sorted(res + 3 * f, twins + 4 * f), twins[4 * f + 3] = (uint32_t)f;
    qsort(twins, faces, 4 * sizeof *twins, triple_cmp);
    for (size_t i = 1; i < faces; i++)
        if (!triple_cmp(twins + 4 * i, twins + 4 * (i - 1)))
            bad[twins[4 * i + 3]] = bad[twins[4 * i - 1]] = 1;
    for (size_t i = 0, j; i < 3 * faces; i = j) { // each edge: two faces, opposite ways
        for (j = i + 1; j < 3 * faces && e[j].key == e[i].key; j++)
            ;
        int ok = j - i == 2 && e[i].forward != e[i + 1].forward;
        if (j - i == 1) { // open: only where the input was
            uint64_t a = e[i].key >> 32, b = e[i].key & 0xffffffffu;
            uint64_t run = e[i].forward ? e[i].key : b << 32 | a;
            ok = bsearch(&run, s->open, s->open_count, sizeof run, u64_cmp) != NULL;
        }
        for (size_t k = i; k < j && !ok; k++)
            bad[e[k].face] = 1;
    }
    for (size_t f = 0; f < made; f++) { // new faces: shape, distance to the input
        if (known(s, res + 3 * f)) continue;
        if (misshapen(s, res + 3 * f)) bad[f] = 1;
        uint32_t near;
        double limit = s->error;
        if (!face_within(s, res + 3 * f, &limit, 0, &near)) {
            bad[f] = 1;
            for (int c = 0; c < 3 && near != UINT32_MAX; c++)
                hot[s->in->index[3 * (size_t)near + c]] = 1;
        }
    }
    for (size_t v = 0; v < s->in->vertex_count; v++) { // every input vertex to the result
        if (s->ring_start[v] == s->ring_start[v + 1]) continue;
        double p[3];
        corner(s->in, (uint32_t)v, p);
        uint32_t near;
        if (!mesh_distance_within(&result, p, s->error, &near)) {
            hot[v] = 1;
            if (near != UINT32_MAX) bad[near] = 1;
        }
    }
    failed = 0;
    for (size_t f = 0; f < faces; f++)
        if (bad[f]) {
            failed++;
            for (int c = 0; c < 3; c++)
                hot[res[3 * f + c]] = 1;
        }
done:
    free(bad), free(twins), free(e);
    mesh_distance_free(&result);
    return failed;
}

// The largest distance either way between faces res and the input: from points on
// every face to the input, from every input vertex to them. -1 when out of memory.
static double measure(const simplifier *s, const uint32_t *res, size_t faces) {
    mesh_distance result;
    if (mesh_distance_build(&result, s->in->pos, res, faces) != 0) return -1;
    double worst = 0; // each point measured exactly only when it could raise it
    uint32_t near;
    for (size_t f = 0; f < faces; f++)
        face_within(s, res + 3 * f, &worst, 1, &near);
    for (size_t v = 0; v < s->in->vertex_count; v++) {
        if (s->ring_start[v] == s->ring_start[v + 1]) continue;
        double p[3];
        corner(s->in, (uint32_t)v, p);
        if (!mesh_distance_within(&result, p, worst, &near))
            worst = mesh_distance_to(&result, p, &near);
    }
    mesh_distance_free(&result);
    return worst;
}

// One simplification of `current` (faces over the input's vertices) with meshoptimizer
// to its own estimate `target`, its faces marked in `kept` left out; checked. Returns
// the faces of an accepted result in out (*made indices), 0 when it failed the checks
// (hot marks the vertices around the failures), -1 when out of memory.
static int attempt(const simplifier *s, const uint32_t *current, size_t faces,
                   const unsigned char *kept, double target, float scale, uint32_t *sub,
                   uint32_t *out, size_t *made, unsigned char *hot) {
    size_t n = 0;
    for (size_t f = 0; f < faces; f++)
        if (!kept[f]) memcpy(sub + n, current + 3 * f, 3 * sizeof *sub), n += 3;
    float estimate = 0;
    size_t m =
        n ? meshopt_simplify(out, sub, n, s->in->pos, s->in->vertex_count, 3 * sizeof(float), 0,
                             (float)(target / scale), meshopt_SimplifyLockBorder, &estimate)
          : 0;
    const size_t simplified = m / 3;
    for (size_t f = 0; f < faces; f++)
        if (kept[f]) memcpy(out + m, current + 3 * f, 3 * sizeof *out), m += 3;
    memset(hot, 0, s->in->vertex_count);
    long long failed = check(s, out, m / 3, simplified, hot);
    *made = m;
    return failed < 0 ? -1 : failed == 0;
}

// Targets from a small part of the error up to all of it, each simplifying the last
// accepted result further; a level whose failures do not clear in a few rounds ends it.
int volume_simplify(volume_mesh *m, double error_m, volume_simplify_report *rep, og_error *err) {
    memset(rep, 0, sizeof *rep);
    const size_t T = m->index_count / 3, V = m->vertex_count;
    if (T == 0) return 0;
    simplifier s;
    if (simplifier_init(&s, m, error_m) != 0) return og_error_set(err, "out of memory simplifying");
    unsigned char *kept = calloc(T, 1), *hot = malloc(V);
    uint32_t *sub = malloc(3 * T * sizeof *sub), *out = malloc(3 * T * sizeof *out);
    uint32_t *current = malloc(3 * T * sizeof *current), *start = NULL, *ring = NULL;
    int rc = -1, oom = 1;
    if (!kept || !hot || !sub || !out || !current) goto finish;
    memcpy(current, m->index, 3 * T * sizeof *current);
    size_t faces = T;
    accept(&s, current, faces); // the input's own faces need no checking
    const float scale = meshopt_simplifyScale(m->pos, V, 3 * sizeof(float));
    int levels = 0; // from a small part of an edge (few changes at a time) up to error_m
    while (error_m * pow(LEVEL_STEP, levels) > FIRST_LEVEL * s.step)
        levels++;
    for (int level = levels; level >= 0; level--) {
        double target = error_m * pow(LEVEL_STEP, level);
        memset(kept, 0, faces);
        free(start), free(ring);
        if (rings_of(current, faces, V, &start, &ring) != 0) goto finish;
        int accepted = 0;
        for (int round = 0; round < ROUNDS_PER_LEVEL && !accepted; round++) {
            size_t made;
            accepted = attempt(&s, current, faces, kept, target, scale, sub, out, &made, hot);
            if (accepted < 0) goto finish;
            rep->rounds++;
            if (accepted) {
                memcpy(current, out, made * sizeof *out);
                faces = made / 3;
                accept(&s, current, faces);
                break;
            }
            // Keep the faces around every failure as they are, a ring more each round (a
            // failure that moves on as its neighbours are kept is caught wider).
            for (int grow = 0; grow <= round; grow++)
                for (size_t v = 0; v < V; v++) {
                    if (hot[v] != 1 + grow) continue;
                    for (uint32_t i = start[v]; i < start[v + 1]; i++) {
                        kept[ring[i]] = 1;
                        for (int c = 0; c < 3; c++) // the next ring's vertices
                            if (!hot[current[3 * ring[i] + c]])
                                hot[current[3 * ring[i] + c]] = (unsigned char)(2 + grow);
                    }
                }
        }
        if (!accepted) break;
    }
    rep->max_error = faces < T ? measure(&s, current, faces) : 0;
    if (rep->max_error < 0) goto finish;
    memcpy(m->index, current, 3 * faces * sizeof *current);
    m->index_count = 3 * faces;
    oom = 0;
    mesh_manifold_report manifold; // drops the vertices no face uses any more
    rc = mesh_make_manifold(m, &manifold, err);
finish:
    if (oom) og_error_set(err, "out of memory simplifying");
    free(kept), free(hot), free(sub), free(out), free(current), free(start), free(ring);
    simplifier_free(&s);
    return rc;
}
