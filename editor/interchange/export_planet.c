#include "editor/interchange/export_planet.h"

#include "editor/edit/parallel.h"
#include "editor/interchange/sidecar.h"
#include "editor/params/world_grid.h"
#include "io/image_read.h"
#include "io/param_file.h"
#include "io/path_folder.h"
#include "io/tile_cache.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#define FACES 6
#define FILES_MAX (4 * FACES + 2) // heights, their sidecars, normals; the OBJ and .mtl

int export_planet_wanted(const char *first) {
    if (!first || !*first) return 0;
    for (const char *c = first; *c; c++)
        if (!isdigit((unsigned char)*c)) return 0;
    return 1;
}

// ---- the files: staged under hidden names, renamed together at the end -------------

typedef struct staged_files {
    char final[FILES_MAX][4200];
    char staged[FILES_MAX][4300];
    int count;
} staged_files;

static const char *add_file(staged_files *f, const char *final_path) {
    snprintf(f->final[f->count], sizeof f->final[0], "%s", final_path);
    char dir[4200], base[4200];
    path_folder(final_path, dir, sizeof dir);
    snprintf(base, sizeof base, "%s", final_path);
    // The extension stays last: the image writer picks the format by it.
    const char *name = basename(base), *dot = strrchr(name, '.');
    if (!dot) dot = name + strlen(name);
    snprintf(f->staged[f->count], sizeof f->staged[0], "%s/.%.*s.part-%d%s", dir, (int)(dot - name),
             name, (int)getpid(), dot);
    return f->staged[f->count++];
}

static void discard_files(staged_files *f) {
    for (int i = 0; i < f->count; i++)
        unlink(f->staged[i]);
}

static int publish_files(staged_files *f, long long *bytes, og_error *err) {
    *bytes = 0;
    for (int i = 0; i < f->count; i++) {
        FILE *probe = fopen(f->staged[i], "rb");
        if (probe) {
            fseek(probe, 0, SEEK_END);
            *bytes += ftell(probe);
            fclose(probe);
        }
    }
    for (int i = 0; i < f->count; i++)
        if (rename(f->staged[i], f->final[i]) != 0) {
            og_error_set(err,
                         "%s: cannot rename into place (%s); the files renamed before it "
                         "are new, the rest were not written",
                         f->final[i], strerror(errno));
            for (int k = i; k < f->count; k++)
                unlink(f->staged[k]);
            return -1;
        }
    path_sync_folder(f->final[0]); // best effort: each file was synced before its rename
    return 0;
}

// ---- the face images ----------------------------------------------------------------

typedef struct face_images {
    world *w;
    const world_params *p;
    int level, size;
    float *heights[FACES]; // size x size metres, row j = face coordinate t of sample j
    double min, max;       // over all faces
    staged_files *files;
    const char *stem; // FILE without .obj
} face_images;

// Copies level `level` of face `face` (size x size samples) out of the tile cache.
static int read_face(face_images *fi, int face, og_error *err) {
    tile_cache *cache = world_cache(fi->w);
    const int tiles = (fi->size + TILE_SIZE - 1) / TILE_SIZE;
    // Queue every tile first so both workers generate while this thread copies.
    for (int ty = 0; ty < tiles; ty++)
        for (int tx = 0; tx < tiles; tx++) {
            tile_view v;
            tile_key key = {TILE_LAYER_COARSE, face, fi->level, tx, ty};
            tile_cache_request(cache, key, &v);
            if (v.data) tile_cache_release(cache, &v);
        }
    for (int ty = 0; ty < tiles; ty++)
        for (int tx = 0; tx < tiles; tx++) {
            tile_view v;
            tile_key key = {TILE_LAYER_COARSE, face, fi->level, tx, ty};
            if (tile_cache_acquire(cache, key, &v, err) != 0) return -1;
            const float *src = v.data;
            for (int j = 0; j < TILE_SIZE && ty * TILE_SIZE + j < fi->size; j++) {
                int cols = fi->size - tx * TILE_SIZE;
                if (cols > TILE_SIZE) cols = TILE_SIZE;
                memcpy(fi->heights[face] + (size_t)(ty * TILE_SIZE + j) * fi->size + tx * TILE_SIZE,
                       src + (size_t)j * TILE_SIZE, sizeof(float) * (size_t)cols);
            }
            tile_cache_release(cache, &v);
        }
    return 0;
}

// Face coordinate in [-1, 1] of image sample i (its centre).
static double image_coord(int size, double i) {
    return (i + 0.5) / size * 2.0 - 1.0;
}

static int write_normal_map(const face_images *fi, int face, const char *path, og_error *err) {
    const int n = fi->size;
    unsigned char *rgb = malloc((size_t)n * n * 3);
    double *warped = malloc(sizeof(double) * (size_t)n);
    double(*pos)[3] = malloc(sizeof *pos * (size_t)n * n); // each sample's surface point
    if (!rgb || !warped || !pos) {
        free(rgb);
        free(warped);
        free(pos);
        return og_error_set(err, "%s: out of memory", path);
    }
    for (int i = 0; i < n; i++)
        warped[i] = tan(image_coord(n, i) * (M_PI / 4.0));
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const size_t k = (size_t)j * n + i;
            double d[3];
            world_grid_face_direction_warped(face, warped[i], warped[j], d);
            const double r = fi->p->radius + fi->heights[face][k];
            for (int c = 0; c < 3; c++)
                pos[k][c] = d[c] * r;
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            // Central differences on the sphere (one-sided at the face's border).
            const double *a = pos[(size_t)j * n + (i > 0 ? i - 1 : i)];
            const double *b = pos[(size_t)j * n + (i < n - 1 ? i + 1 : i)];
            const double *c = pos[(size_t)(j > 0 ? j - 1 : j) * n + i];
            const double *d = pos[(size_t)(j < n - 1 ? j + 1 : j) * n + i];
            const double *centre = pos[(size_t)j * n + i];
            double du[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            double dv[3] = {d[0] - c[0], d[1] - c[1], d[2] - c[2]};
            double m[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2],
                           du[0] * dv[1] - du[1] * dv[0]};
            double len = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
            double outward = m[0] * centre[0] + m[1] * centre[1] + m[2] * centre[2];
            double sign = outward < 0 ? -1.0 : 1.0;
            unsigned char *px = rgb + ((size_t)j * n + i) * 3;
            for (int k = 0; k < 3; k++) {
                double v = len > 0 ? sign * m[k] / len : centre[k] / fi->p->radius;
                px[k] = (unsigned char)lround((v * 0.5 + 0.5) * 255.0);
            }
        }
    free(pos);
    int rc = image_write_u8(path, rgb, n, n, 3, err);
    free(rgb);
    free(warped);
    return rc;
}

static int write_height_image(const face_images *fi, int face, const char *path, og_error *err) {
    const size_t count = (size_t)fi->size * fi->size;
    uint16_t *q = malloc(count * sizeof *q);
    if (!q) return og_error_set(err, "%s: out of memory", path);
    const double range = fi->max - fi->min > 0 ? fi->max - fi->min : 1.0;
    for (size_t k = 0; k < count; k++)
        q[k] = (uint16_t)lround((fi->heights[face][k] - fi->min) / range * 65535.0);
    int rc = image_write_u16(path, q, fi->size, fi->size, 1, err);
    free(q);
    return rc;
}

typedef struct image_job {
    face_images *fi;
    const char *height_path[FACES], *normal_path[FACES];
} image_job;

static int images_task(void *user, int task, og_error *err) {
    image_job *job = user;
    const int face = task / 2;
    return task % 2 == 0 ? write_height_image(job->fi, face, job->height_path[face], err)
                         : write_normal_map(job->fi, face, job->normal_path[face], err);
}

static int write_face_images(face_images *fi, og_error *err) {
    image_job job = {.fi = fi};
    char path[4300];
    const world_params *p = fi->p;
    const double sample = world_grid_sample_metres(p); // true metres on the sphere
    const double cell = ldexp(sample, fi->level);      // face-local metres per pixel
    for (int f = 0; f < FACES; f++) {
        snprintf(path, sizeof path, "%s_height_%d.png", fi->stem, f);
        const char *staged = add_file(fi->files, path);
        job.height_path[f] = staged;
        sidecar s = {.spacing = cell,
                     // Pixel centres in the face-local metres sample and dab take.
                     .origin_x = 0.5 * (cell - sample),
                     .origin_z = 0.5 * (cell - sample),
                     .width = fi->size,
                     .height = fi->size,
                     .scale = (fi->max - fi->min > 0 ? fi->max - fi->min : 1.0) / 65535.0,
                     .offset = fi->min,
                     .min = fi->min,
                     .max = fi->max,
                     .format = "png16",
                     .layer = "coarse"};
        char extra[800];
        snprintf(extra, sizeof extra,
                 "  \"face\": %d,\n  \"radius\": %.17g,\n  \"level\": %d,\n"
                 "  \"projection\": \"cube face %s; pixel (i, j) looks along normalize(face axes "
                 "with tan(s pi/4), tan(t pi/4)), s and t = (index + 0.5) / width x 2 - 1; "
                 "surface = direction x (radius + height)\"",
                 f, p->radius, fi->level,
                 (const char *const[]){"+X", "-X", "+Y", "-Y", "+Z", "-Z"}[f]);
        // sidecar_write names it after the staged image: staged + ".json".
        staged_files *sf = fi->files;
        snprintf(sf->final[sf->count], sizeof sf->final[0], "%s_height_%d.png.json", fi->stem, f);
        snprintf(sf->staged[sf->count++], sizeof sf->staged[0], "%s.json", staged);
        if (sidecar_write(staged, &s, extra, err) != 0) return -1;
        snprintf(path, sizeof path, "%s_normal_%d.png", fi->stem, f);
        job.normal_path[f] = add_file(fi->files, path);
    }
    return parallel_run(2 * FACES, images_task, &job, err);
}

// ---- the mesh -----------------------------------------------------------------------

// A point of the cube's surface lattice (integer coordinates in [-q, q]), the key that
// makes the faces share their edge vertices.
static uint64_t lattice_key(int face, int a, int b, int q) {
    int A = 2 * a - q, B = 2 * b - q, v[3];
    switch (face) { // world_grid_face_direction's axes
    case 0:
        v[0] = q, v[1] = B, v[2] = -A;
        break;
    case 1:
        v[0] = -q, v[1] = B, v[2] = A;
        break;
    case 2:
        v[0] = A, v[1] = q, v[2] = -B;
        break;
    case 3:
        v[0] = A, v[1] = -q, v[2] = B;
        break;
    case 4:
        v[0] = A, v[1] = B, v[2] = q;
        break;
    default:
        v[0] = -A, v[1] = B, v[2] = -q;
        break;
    }
    uint64_t side = 2 * (uint64_t)q + 1;
    return ((uint64_t)(v[0] + q) * side + (uint64_t)(v[1] + q)) * side + (uint64_t)(v[2] + q);
}

typedef struct planet_mesh {
    double *pos, *normal; // 3 per vertex
    size_t vertices, cap_vertices;
    uint64_t *keys; // open addressing: key + 1, 0 = empty
    uint32_t *slot_vertex;
    size_t slots;
    uint32_t *tri; // 3 vertex indices and 3 vt indices per triangle
    size_t triangles;
    float *vt; // 2 per texture vertex
    size_t vts;
    uint32_t *vt_of_point; // the current face's texture vertex per lattice point, or ~0
} planet_mesh;

static double bilinear(const face_images *fi, int face, double s, double t) {
    const int n = fi->size;
    double u = (s + 1) * 0.5 * n - 0.5, v = (t + 1) * 0.5 * n - 0.5;
    u = fmin(fmax(u, 0), n - 1), v = fmin(fmax(v, 0), n - 1);
    int i = (int)u, j = (int)v;
    int i1 = i + 1 < n ? i + 1 : i, j1 = j + 1 < n ? j + 1 : j;
    double fu = u - i, fv = v - j;
    const float *h = fi->heights[face];
    double top = h[(size_t)j * n + i] + (h[(size_t)j * n + i1] - h[(size_t)j * n + i]) * fu;
    double bottom = h[(size_t)j1 * n + i] + (h[(size_t)j1 * n + i1] - h[(size_t)j1 * n + i]) * fu;
    return top + (bottom - top) * fv;
}

static uint32_t mesh_vertex(planet_mesh *m, const face_images *fi, int face, int a, int b, int q) {
    uint64_t key = lattice_key(face, a, b, q) + 1;
    size_t slot = (size_t)((key * 0x9E3779B97F4A7C15ull) >> 20) & (m->slots - 1);
    while (m->keys[slot] && m->keys[slot] != key)
        slot = (slot + 1) & (m->slots - 1);
    if (m->keys[slot]) return m->slot_vertex[slot];
    const uint32_t index = (uint32_t)m->vertices++;
    m->keys[slot] = key;
    m->slot_vertex[slot] = index;
    double s = 2.0 * a / q - 1, t = 2.0 * b / q - 1, d[3];
    world_grid_face_direction(face, s, t, d);
    double r = fi->p->radius + bilinear(fi, face, s, t);
    for (int k = 0; k < 3; k++)
        m->pos[index * 3 + k] = d[k] * r, m->normal[index * 3 + k] = 0;
    return index;
}

static void mesh_triangle(planet_mesh *m, const face_images *fi, int face, int q, const int c[6]) {
    uint32_t v[3], t[3];
    for (int k = 0; k < 3; k++) {
        v[k] = mesh_vertex(m, fi, face, c[2 * k], c[2 * k + 1], q);
        // Texture vertices are per face: its own image's coordinates.
        uint32_t *tv = m->vt_of_point + (size_t)c[2 * k + 1] * (q + 1) + c[2 * k];
        if (*tv == UINT32_MAX) {
            *tv = (uint32_t)m->vts++;
            m->vt[*tv * 2] = (float)c[2 * k] / q;
            m->vt[*tv * 2 + 1] = 1.0f - (float)c[2 * k + 1] / q; // OBJ's v runs up
        }
        t[k] = *tv;
    }
    const double *a = m->pos + v[0] * 3, *b = m->pos + v[1] * 3, *e = m->pos + v[2] * 3;
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double ae[3] = {e[0] - a[0], e[1] - a[1], e[2] - a[2]};
    double n[3] = {ab[1] * ae[2] - ab[2] * ae[1], ab[2] * ae[0] - ab[0] * ae[2],
                   ab[0] * ae[1] - ab[1] * ae[0]};
    if (n[0] * (a[0] + b[0] + e[0]) + n[1] * (a[1] + b[1] + e[1]) + n[2] * (a[2] + b[2] + e[2]) <
        0) { // wind counter-clockwise seen from outside
        uint32_t swap = v[1];
        v[1] = v[2], v[2] = swap;
        swap = t[1], t[1] = t[2], t[2] = swap;
        for (int k = 0; k < 3; k++)
            n[k] = -n[k];
    }
    for (int k = 0; k < 3; k++) // area-weighted vertex normals
        for (int c3 = 0; c3 < 3; c3++)
            m->normal[v[k] * 3 + c3] += n[c3];
    uint32_t *out = m->tri + m->triangles++ * 6;
    memcpy(out, v, sizeof v);
    memcpy(out + 3, t, sizeof t);
}

// ROAM's bintree at depth N over one face: even N, a 2^(N/2) grid of cells split by
// alternating diagonals; odd N, each cell of the 2^((N-1)/2) grid split into four
// around its centre. Lattice coordinates are in half cells (q = 2 x cells).
static void mesh_face(planet_mesh *m, const face_images *fi, int face, int subdivision) {
    const int cells = 1 << (subdivision / 2), q = 2 * cells;
    memset(m->vt_of_point, 0xff, sizeof *m->vt_of_point * (size_t)(q + 1) * (q + 1));
    for (int j = 0; j < cells; j++)
        for (int i = 0; i < cells; i++) {
            int x0 = 2 * i, x1 = 2 * i + 2, z0 = 2 * j, z1 = 2 * j + 2;
            if (subdivision % 2) {
                int cx = 2 * i + 1, cz = 2 * j + 1;
                const int tris[4][6] = {{x0, z0, x1, z0, cx, cz},
                                        {x1, z0, x1, z1, cx, cz},
                                        {x1, z1, x0, z1, cx, cz},
                                        {x0, z1, x0, z0, cx, cz}};
                for (int k = 0; k < 4; k++)
                    mesh_triangle(m, fi, face, q, tris[k]);
            } else if ((i + j) % 2 == 0) {
                const int a[6] = {x0, z0, x1, z0, x1, z1}, b[6] = {x0, z0, x1, z1, x0, z1};
                mesh_triangle(m, fi, face, q, a);
                mesh_triangle(m, fi, face, q, b);
            } else {
                const int a[6] = {x1, z0, x1, z1, x0, z1}, b[6] = {x1, z0, x0, z1, x0, z0};
                mesh_triangle(m, fi, face, q, a);
                mesh_triangle(m, fi, face, q, b);
            }
        }
}

static void mesh_free(planet_mesh *m) {
    free(m->pos);
    free(m->normal);
    free(m->keys);
    free(m->slot_vertex);
    free(m->tri);
    free(m->vt);
    free(m->vt_of_point);
}

static int build_mesh(planet_mesh *m, const face_images *fi, int subdivision, og_error *err) {
    const size_t triangles = (size_t)12 << subdivision, vertices = ((size_t)6 << subdivision) + 2;
    memset(m, 0, sizeof *m);
    m->slots = 1;
    while (m->slots < 2 * vertices)
        m->slots <<= 1;
    m->pos = malloc(vertices * 3 * sizeof(double));
    m->normal = malloc(vertices * 3 * sizeof(double));
    m->keys = calloc(m->slots, sizeof *m->keys);
    m->slot_vertex = malloc(m->slots * sizeof *m->slot_vertex);
    m->tri = malloc(triangles * 6 * sizeof *m->tri);
    const size_t cells = (size_t)1 << (subdivision / 2), q = 2 * cells;
    const size_t face_points = (cells + 1) * (cells + 1) + (subdivision % 2 ? cells * cells : 0);
    m->vt = malloc(FACES * face_points * 2 * sizeof *m->vt);
    m->vt_of_point = malloc((q + 1) * (q + 1) * sizeof *m->vt_of_point);
    if (!m->pos || !m->normal || !m->keys || !m->slot_vertex || !m->tri || !m->vt ||
        !m->vt_of_point)
        return og_error_set(err, "export: out of memory for a subdivision-%d mesh", subdivision);
    for (int f = 0; f < FACES; f++)
        mesh_face(m, fi, f, subdivision);
    for (size_t v = 0; v < m->vertices; v++) {
        double *n = m->normal + v * 3, len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++)
            n[k] = len > 0 ? n[k] / len : m->pos[v * 3 + k] / fi->p->radius;
    }
    return 0;
}

// The OBJ's materials, one per face group, linking its images so importers (Blender,
// Houdini, assimp) load them: the heights as the colour and the displacement map.
static int write_mtl(const face_images *fi, const char *path, og_error *err) {
    char stem[4200];
    snprintf(stem, sizeof stem, "%s", fi->stem);
    const char *name = basename(stem);
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f) return og_error_set(err, "%s: out of memory", path);
    fprintf(f,
            "# Orogen planet: face F's images (%s_height_F.png heights, %s_normal_F.png "
            "object-space normals)\n",
            name, name);
    for (int face = 0; face < FACES; face++)
        fprintf(f, "newmtl face_%d\nKd 1 1 1\nmap_Kd %s_height_%d.png\ndisp %s_height_%d.png\n",
                face, name, face, name, face);
    if (fclose(f) != 0 || !text) {
        free(text);
        return og_error_set(err, "%s: out of memory", path);
    }
    int rc = param_file_write_atomic(path, text, len, err);
    free(text);
    return rc;
}

static int write_obj(const planet_mesh *m, const face_images *fi, int subdivision, const char *path,
                     og_error *err) {
    char stem[4200];
    snprintf(stem, sizeof stem, "%s", fi->stem);
    const char *name = basename(stem); // the images sit beside the OBJ
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f) return og_error_set(err, "%s: out of memory", path);
    fprintf(f,
            "# Orogen planet: subdivision %d of the cube, metres from the centre, +Y up (face 2)\n"
            "# radius %.17g; vt of group face_F address %s_height_F.png (heights, .json: "
            "metres) and %s_normal_F.png (object-space normals)\nmtllib %s.mtl\no planet\n",
            subdivision, fi->p->radius, name, name, name);
    // %.12g: millimetres at Earth's radius.
    for (size_t v = 0; v < m->vertices; v++)
        fprintf(f, "v %.12g %.12g %.12g\n", m->pos[v * 3], m->pos[v * 3 + 1], m->pos[v * 3 + 2]);
    for (size_t v = 0; v < m->vertices; v++)
        fprintf(f, "vn %.7g %.7g %.7g\n", m->normal[v * 3], m->normal[v * 3 + 1],
                m->normal[v * 3 + 2]);
    for (size_t t = 0; t < m->vts; t++)
        fprintf(f, "vt %.9g %.9g\n", m->vt[t * 2], m->vt[t * 2 + 1]);
    const size_t per_face = m->triangles / FACES;
    for (size_t k = 0; k < m->triangles; k++) {
        if (k % per_face == 0)
            fprintf(f, "g face_%zu\nusemtl face_%zu\n", k / per_face, k / per_face);
        const uint32_t *tr = m->tri + k * 6;
        fprintf(f, "f %u/%u/%u %u/%u/%u %u/%u/%u\n", tr[0] + 1, tr[3] + 1, tr[0] + 1, tr[1] + 1,
                tr[4] + 1, tr[1] + 1, tr[2] + 1, tr[5] + 1, tr[2] + 1);
    }
    if (fclose(f) != 0 || !text) {
        free(text);
        return og_error_set(err, "%s: out of memory", path);
    }
    int rc = param_file_write_atomic(path, text, len, err);
    free(text);
    return rc;
}

// ---- the export ---------------------------------------------------------------------

static int pick_level(const world_params *p, int image_size, int *level, int *size, og_error *err) {
    const int64_t n = world_grid_face_samples(p); // a whole number of tiles
    int l = 0;
    while ((n >> l) > image_size && l < 8)
        l++;
    if ((n >> l) > image_size)
        return og_error_set(err,
                            "size=%d: this planet's faces have %lld samples per side; the "
                            "coarsest image export is 1/256 of that: size=%lld or more",
                            image_size, (long long)n, (long long)(n >> 8));
    *level = l;
    *size = (int)(n >> l);
    return 0;
}

int export_planet(world *w, int subdivision, const char *path, int image_size,
                  export_planet_report *rep, og_error *err) {
    const world_params *p = world_get_params(w);
    memset(rep, 0, sizeof *rep);
    if (p->kind != WORLD_PLANET)
        return og_error_set(err, "export N FILE: planets only (seed 004); a flat world exports "
                                 "with export FILE [region=...]");
    if (subdivision < 0 || subdivision > EXPORT_PLANET_MAX_SUBDIVISION)
        return og_error_set(err, "export N FILE: N is the cube's subdivision, 0 .. %d, got %d",
                            EXPORT_PLANET_MAX_SUBDIVISION, subdivision);
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/') || strcasecmp(dot, ".obj") != 0)
        return og_error_set(
            err, "%s: export N FILE writes an .obj (with its face images beside it)", path);
    if (image_size == 0) image_size = EXPORT_PLANET_DEFAULT_IMAGE;
    if (image_size < 1 || image_size > EXPORT_PLANET_MAX_IMAGE)
        return og_error_set(err, "size=%d: face images are 1 .. %d pixels per side", image_size,
                            EXPORT_PLANET_MAX_IMAGE);
    char stem[4200];
    snprintf(stem, sizeof stem, "%.*s", (int)(dot - path), path);
    staged_files *files = calloc(1, sizeof *files);
    face_images fi = {.w = w, .p = p, .files = files, .stem = stem};
    planet_mesh m = {0};
    int rc = -1;
    if (!files) return og_error_set(err, "%s: out of memory", path);
    if (pick_level(p, image_size, &fi.level, &fi.size, err) != 0) goto done;
    fi.min = INFINITY, fi.max = -INFINITY;
    for (int f = 0; f < FACES; f++) {
        fi.heights[f] = malloc(sizeof(float) * (size_t)fi.size * fi.size);
        if (!fi.heights[f]) {
            og_error_set(err, "%s: out of memory for %d x %d face images", path, fi.size, fi.size);
            goto done;
        }
        if (read_face(&fi, f, err) != 0) goto done;
        for (size_t k = 0; k < (size_t)fi.size * fi.size; k++)
            fi.min = fmin(fi.min, fi.heights[f][k]), fi.max = fmax(fi.max, fi.heights[f][k]);
    }
    if (write_face_images(&fi, err) != 0) goto done;
    if (build_mesh(&m, &fi, subdivision, err) != 0) goto done;
    if (write_obj(&m, &fi, subdivision, add_file(files, path), err) != 0) goto done;
    char mtl[4300];
    snprintf(mtl, sizeof mtl, "%s.mtl", stem);
    if (write_mtl(&fi, add_file(files, mtl), err) != 0) goto done;
    if (publish_files(files, &rep->bytes, err) != 0) goto done;
    rep->vertices = m.vertices;
    rep->triangles = m.triangles;
    rep->image_size = fi.size;
    rep->level = fi.level;
    rep->min = fi.min;
    rep->max = fi.max;
    rep->files = files->count;
    rc = 0;
done:
    if (rc != 0) discard_files(files);
    for (int f = 0; f < FACES; f++)
        free(fi.heights[f]);
    mesh_free(&m);
    free(files);
    return rc;
}
