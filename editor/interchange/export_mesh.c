#include "editor/interchange/export_mesh.h"

#include "editor/interchange/export_solid.h"
#include "editor/interchange/heightfield_error.h"
#include "editor/interchange/heightfield_simplify.h"
#include "editor/interchange/volume_simplify.h"
#include "editor/world/layer_grid.h"
#include "io/image_read.h"
#include "io/param_file.h"
#include "io/progress.h"

#include <math.h>
#include <meshoptimizer.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

enum { VERTEX_FLOATS = 8 }; // position, normal, uv

typedef struct mesh {
    float *v; // VERTEX_FLOATS per vertex
    uint32_t *idx;
    size_t vertices, indices;
    float lo[3], hi[3]; // bounds of the positions
} mesh;

static void mesh_free(mesh *m) {
    free(m->v);
    free(m->idx);
}

// The grid as triangles, counter-clockwise seen from above (+Y up, glTF's axes).
static int build_grid(const float *h, int64_t w, int64_t d, double spacing, double ox, double oz,
                      mesh *m) {
    m->vertices = (size_t)(w * d);
    m->indices = (size_t)((w - 1) * (d - 1) * 6);
    m->v = malloc(sizeof(float) * VERTEX_FLOATS * m->vertices);
    m->idx = malloc(sizeof(uint32_t) * m->indices);
    if (!m->v || !m->idx) return -1;
    for (int64_t j = 0; j < d; j++)
        for (int64_t i = 0; i < w; i++) {
            float *v = m->v + (size_t)(j * w + i) * VERTEX_FLOATS;
            const float *row = h + j * w;
            double dx = (row[i < w - 1 ? i + 1 : i] - row[i > 0 ? i - 1 : i]) /
                        ((double)((i < w - 1) + (i > 0)) * spacing);
            double dz = (h[(j < d - 1 ? j + 1 : j) * w + i] - h[(j > 0 ? j - 1 : j) * w + i]) /
                        ((double)((j < d - 1) + (j > 0)) * spacing);
            double len = sqrt(dx * dx + 1 + dz * dz);
            v[0] = (float)(ox + (double)i * spacing);
            v[1] = row[i];
            v[2] = (float)(oz + (double)j * spacing);
            v[3] = (float)(-dx / len);
            v[4] = (float)(1 / len);
            v[5] = (float)(-dz / len);
            v[6] = (float)((double)i / (double)(w - 1));
            v[7] = (float)((double)j / (double)(d - 1));
        }
    size_t k = 0;
    for (int64_t j = 0; j + 1 < d; j++)
        for (int64_t i = 0; i + 1 < w; i++) {
            uint32_t a = (uint32_t)(j * w + i), b = a + 1, c = a + (uint32_t)w, e = c + 1;
            m->idx[k++] = a, m->idx[k++] = c, m->idx[k++] = b;
            m->idx[k++] = b, m->idx[k++] = c, m->idx[k++] = e;
        }
    return 0;
}

// A closed solid: walls down from the boundary to a floor below the lowest point, and
// the floor fanned from its centre (watertight: every edge has two triangles).
static int add_base(mesh *m, int64_t w, int64_t d, float floor_y) {
    const size_t ring = (size_t)(2 * (w - 1) + 2 * (d - 1)); // boundary vertices, in order
    size_t nv = m->vertices + ring + 1, ni = m->indices + ring * 6 + ring * 3;
    float *v = realloc(m->v, sizeof(float) * VERTEX_FLOATS * nv);
    if (!v) return -1;
    m->v = v;
    uint32_t *idx = realloc(m->idx, sizeof(uint32_t) * ni);
    if (!idx) return -1;
    m->idx = idx;
    uint32_t *top = malloc(sizeof(uint32_t) * ring);
    if (!top) return -1;
    size_t r = 0; // the boundary: +X along z = 0, +Z along the last column, back -X, -Z
    for (int64_t i = 0; i < w - 1; i++)
        top[r++] = (uint32_t)i;
    for (int64_t j = 0; j < d - 1; j++)
        top[r++] = (uint32_t)(j * w + (w - 1));
    for (int64_t i = w - 1; i > 0; i--)
        top[r++] = (uint32_t)((d - 1) * w + i);
    for (int64_t j = d - 1; j > 0; j--)
        top[r++] = (uint32_t)(j * w);
    const uint32_t base0 = (uint32_t)m->vertices;
    double cx = 0, cz = 0;
    for (size_t q = 0; q < ring; q++) {
        float *dst = m->v + (size_t)(base0 + q) * VERTEX_FLOATS;
        memcpy(dst, m->v + (size_t)top[q] * VERTEX_FLOATS, sizeof(float) * VERTEX_FLOATS);
        dst[1] = floor_y;
        dst[3] = 0, dst[4] = -1, dst[5] = 0;
        cx += dst[0], cz += dst[2];
    }
    float *centre = m->v + (size_t)(base0 + ring) * VERTEX_FLOATS;
    centre[0] = (float)(cx / (double)ring), centre[1] = floor_y,
    centre[2] = (float)(cz / (double)ring);
    centre[3] = 0, centre[4] = -1, centre[5] = 0, centre[6] = 0.5f, centre[7] = 0.5f;
    size_t k = m->indices;
    for (size_t q = 0; q < ring; q++) {
        uint32_t t0 = top[q], t1 = top[(q + 1) % ring];
        uint32_t b0 = base0 + (uint32_t)q, b1 = base0 + (uint32_t)((q + 1) % ring);
        // The ring runs +X, +Z, -X, -Z: seen from outside, (t0, t1, b1) faces out.
        m->idx[k++] = t0, m->idx[k++] = t1, m->idx[k++] = b1;
        m->idx[k++] = t0, m->idx[k++] = b1, m->idx[k++] = b0;
        // Floor, facing down.
        m->idx[k++] = base0 + (uint32_t)ring, m->idx[k++] = b0, m->idx[k++] = b1;
    }
    free(top);
    m->vertices = nv;
    m->indices = ni;
    return 0;
}

// The solid's surface (overhangs, caves) as the writers' vertices: position, normal,
// and texture coordinates over the region from above.
static int from_solid(const volume_mesh *sm, double x0, double z0, double width, double depth,
                      double ox, double oz, mesh *m) {
    m->vertices = sm->vertex_count;
    m->indices = sm->index_count;
    m->v = malloc(sizeof(float) * VERTEX_FLOATS * (m->vertices ? m->vertices : 1));
    m->idx = malloc(sizeof(uint32_t) * (m->indices ? m->indices : 1));
    if (!m->v || !m->idx) return -1;
    for (size_t i = 0; i < m->vertices; i++) {
        float *v = m->v + i * VERTEX_FLOATS;
        const float *p = sm->pos + 3 * i;
        // The cells at the region's sides reach half a voxel past it: onto the side.
        double x = fmin(fmax(p[0], x0), x0 + width), z = fmin(fmax(p[2], z0), z0 + depth);
        v[0] = (float)(x - x0 + ox), v[1] = p[1], v[2] = (float)(z - z0 + oz);
        memcpy(v + 3, sm->normal + 3 * i, 3 * sizeof *v);
        v[6] = (float)((x - x0) / width), v[7] = (float)((z - z0) / depth);
    }
    memcpy(m->idx, sm->index, sizeof(uint32_t) * m->indices);
    return 0;
}

static void bounds(mesh *m) {
    for (int c = 0; c < 3; c++)
        m->lo[c] = INFINITY, m->hi[c] = -INFINITY;
    for (size_t i = 0; i < m->vertices; i++)
        for (int c = 0; c < 3; c++) {
            float x = m->v[i * VERTEX_FLOATS + c];
            m->lo[c] = fminf(m->lo[c], x);
            m->hi[c] = fmaxf(m->hi[c], x);
        }
}

// The cells at the region's sides reach half a voxel past it: onto the side, before
// simplifying, so the error is measured on the surface as written.
static void clamp_to_region(volume_mesh *sm, double x0, double z0, double x1, double z1) {
    for (size_t i = 0; i < sm->vertex_count; i++) {
        float *p = sm->pos + 3 * i;
        p[0] = (float)fmin(fmax(p[0], x0), x1), p[2] = (float)fmin(fmax(p[2], z0), z1);
    }
}

// Simplifies a heightfield within error_m metres: right triangles of a regular
// hierarchy (heightfield_simplify.h: no folds, no cracks, the border included), its true
// vertical deviation measured at every sample and the threshold lowered until it keeps
// to error_m; *achieved_m is that measured maximum.
static int simplify(mesh *m, const heightfield_grid *grid, double error_m, double *achieved_m) {
    uint32_t *out = NULL;
    size_t n = 0;
    heightfield_rtin r;
    if (heightfield_rtin_build(&r, grid->h, grid->w, grid->d) != 0) return -1;
    double threshold = error_m;
    for (int attempt = 0;; attempt++) {
        free(out);
        if (heightfield_rtin_mesh(&r, attempt < 8 ? threshold : 0, &out, &n) != 0) break;
        heightfield_error e;
        if (heightfield_error_measure(grid, m->v, VERTEX_FLOATS, out, n, &e) != 0) {
            free(out);
            out = NULL;
            break;
        }
        *achieved_m = e.max_deviation;
        if ((e.max_deviation <= error_m && e.folded == 0 && e.uncovered == 0) || attempt >= 8)
            break;
        // The split errors are along long edges; inside a triangle the ground may
        // stray further: aim lower by the overshoot.
        double shrink = 0.95 * error_m / e.max_deviation;
        threshold *= shrink < 0.8 ? shrink : 0.8;
    }
    heightfield_rtin_free(&r);
    if (!out) return -1;
    free(m->idx);
    m->idx = out;
    m->indices = n;
    float *v = malloc(sizeof(float) * VERTEX_FLOATS * m->vertices);
    if (!v) return -1;
    m->vertices = meshopt_optimizeVertexFetch(v, m->idx, m->indices, m->v, m->vertices,
                                              sizeof(float) * VERTEX_FLOATS);
    free(m->v);
    m->v = v;
    return 0;
}

// ---- writers ----------------------------------------------------------------------

static int write_obj(const char *path, const mesh *m, og_error *err) {
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f) return og_error_set(err, "%s: out of memory", path);
    fprintf(f, "# Orogen terrain: metres, +Y up\no terrain\n");
    for (size_t i = 0; i < m->vertices; i++) {
        const float *v = m->v + i * VERTEX_FLOATS;
        fprintf(f, "v %.9g %.9g %.9g\nvn %.6g %.6g %.6g\nvt %.7g %.7g\n", v[0], v[1], v[2], v[3],
                v[4], v[5], v[6], 1.0 - v[7]); // OBJ's v runs up from the bottom
    }
    for (size_t k = 0; k < m->indices; k += 3) {
        uint32_t a = m->idx[k] + 1, b = m->idx[k + 1] + 1, c = m->idx[k + 2] + 1;
        fprintf(f, "f %u/%u/%u %u/%u/%u %u/%u/%u\n", a, a, a, b, b, b, c, c, c);
    }
    fclose(f);
    int rc = param_file_write_atomic(path, text, len, err);
    free(text);
    return rc;
}

static int write_ply(const char *path, const mesh *m, og_error *err) {
    char *data = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&data, &len);
    if (!f) return og_error_set(err, "%s: out of memory", path);
    fprintf(f,
            "ply\nformat binary_little_endian 1.0\ncomment Orogen terrain: metres, +Y up\n"
            "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\nproperty float s\n"
            "property float t\nelement face %zu\nproperty list uchar uint vertex_indices\n"
            "end_header\n",
            m->vertices, m->indices / 3);
    fwrite(m->v, sizeof(float) * VERTEX_FLOATS, m->vertices, f); // x86-64 is little-endian
    for (size_t k = 0; k < m->indices; k += 3) {
        unsigned char three = 3;
        fwrite(&three, 1, 1, f);
        fwrite(m->idx + k, sizeof(uint32_t), 3, f);
    }
    fclose(f);
    int rc = param_file_write_atomic(path, data, len, err);
    free(data);
    return rc;
}

// Base colour from height and slope (sand, grass, rock, snow), about one texel per
// sample (a power of two up to 2048 per side), as PNG bytes.
static int base_colour_png(const float *h, int64_t w, int64_t d, double spacing, const char *path,
                           unsigned char **png, size_t *png_len, og_error *err) {
    int tw = 1, th = 1; // powers of two (what every GPU and glTF viewer likes), <= 2048
    while (tw * 2 <= w && tw < 2048)
        tw *= 2;
    while (th * 2 <= d && th < 2048)
        th *= 2;
    float lo = INFINITY, hi = -INFINITY;
    for (int64_t i = 0; i < w * d; i++)
        lo = fminf(lo, h[i]), hi = fmaxf(hi, h[i]);
    unsigned char *rgb = malloc((size_t)tw * (size_t)th * 3);
    if (!rgb) return og_error_set(err, "%s: out of memory", path);
    for (int y = 0; y < th; y++)
        for (int x = 0; x < tw; x++) {
            int64_t i = (int64_t)x * (w - 1) / (tw > 1 ? tw - 1 : 1);
            int64_t j = (int64_t)y * (d - 1) / (th > 1 ? th - 1 : 1);
            float c = h[j * w + i];
            float dx = h[j * w + (i < w - 1 ? i + 1 : i)] - h[j * w + (i > 0 ? i - 1 : i)];
            float dz = h[(j < d - 1 ? j + 1 : j) * w + i] - h[(j > 0 ? j - 1 : j) * w + i];
            double slope = sqrt((double)(dx * dx + dz * dz)) / (2 * spacing);
            double t = hi > lo ? (c - lo) / (hi - lo) : 0.5;
            double r = 0.32, g = 0.45, b = 0.22;           // grass
            if (t < 0.08) r = 0.76, g = 0.70, b = 0.50;    // sand
            if (slope > 0.7) r = 0.45, g = 0.42, b = 0.40; // rock
            if (t > 0.85 && slope < 1.0) r = g = b = 0.93; // snow
            unsigned char *p = rgb + ((size_t)y * tw + x) * 3;
            p[0] = (unsigned char)(r * 255), p[1] = (unsigned char)(g * 255),
            p[2] = (unsigned char)(b * 255);
        }
    char tmp[4300];
    snprintf(tmp, sizeof tmp, "%s.texture-%d.png", path, (int)getpid());
    int rc = image_write_rgb8(tmp, rgb, tw, th, err);
    free(rgb);
    if (rc != 0) return -1;
    FILE *f = fopen(tmp, "rb");
    rc = -1;
    if (f && fseek(f, 0, SEEK_END) == 0) {
        long n = ftell(f);
        rewind(f);
        *png = n > 0 ? malloc((size_t)n) : NULL;
        if (*png && fread(*png, 1, (size_t)n, f) == (size_t)n) {
            *png_len = (size_t)n;
            rc = 0;
        }
    }
    if (f) fclose(f);
    unlink(tmp);
    if (rc != 0) og_error_set(err, "%s: cannot read back the texture", path);
    return rc;
}

static size_t pad4(size_t n) {
    return (n + 3) & ~(size_t)3;
}

static int write_glb(const char *path, const mesh *m, const unsigned char *png, size_t png_len,
                     og_error *err) {
    const size_t nv = m->vertices;
    // Buffer: positions, normals, uvs (de-interleaved: one accessor per view), indices, image.
    const size_t pos_off = 0, nrm_off = nv * 12, uv_off = nv * 24, idx_off = nv * 32;
    const size_t img_off = pad4(idx_off + m->indices * 4);
    const size_t bin_len = pad4(img_off + png_len);
    unsigned char *bin = calloc(1, bin_len);
    if (!bin) return og_error_set(err, "%s: out of memory", path);
    for (size_t i = 0; i < nv; i++) {
        const float *v = m->v + i * VERTEX_FLOATS;
        memcpy(bin + pos_off + i * 12, v, 12);
        memcpy(bin + nrm_off + i * 12, v + 3, 12);
        memcpy(bin + uv_off + i * 8, v + 6, 8);
    }
    memcpy(bin + idx_off, m->idx, m->indices * 4);
    memcpy(bin + img_off, png, png_len);
    char *json = NULL;
    size_t json_len = 0;
    FILE *f = open_memstream(&json, &json_len);
    if (!f) {
        free(bin);
        return og_error_set(err, "%s: out of memory", path);
    }
    fprintf(
        f,
        "{\"asset\":{\"version\":\"2.0\",\"generator\":\"Orogen\"},\"scene\":0,"
        "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"name\":\"terrain\"}],"
        "\"meshes\":[{\"name\":\"terrain\",\"primitives\":[{\"attributes\":{\"POSITION\":0,"
        "\"NORMAL\":1,\"TEXCOORD_0\":2},\"indices\":3,\"material\":0}]}],"
        "\"materials\":[{\"name\":\"terrain\",\"pbrMetallicRoughness\":{\"baseColorTexture\":"
        "{\"index\":0},\"metallicFactor\":0,\"roughnessFactor\":1}}],"
        "\"textures\":[{\"sampler\":0,\"source\":0}],"
        "\"samplers\":[{\"magFilter\":9729,\"minFilter\":9987,\"wrapS\":33071,\"wrapT\":33071}],"
        "\"images\":[{\"bufferView\":4,\"mimeType\":\"image/png\"}],"
        "\"buffers\":[{\"byteLength\":%zu}],\"bufferViews\":["
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34962},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34962},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34962},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34963},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}],\"accessors\":["
        "{\"bufferView\":0,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\","
        "\"min\":[%.9g,%.9g,%.9g],\"max\":[%.9g,%.9g,%.9g]},"
        "{\"bufferView\":1,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},"
        "{\"bufferView\":2,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC2\"},"
        "{\"bufferView\":3,\"componentType\":5125,\"count\":%zu,\"type\":\"SCALAR\"}]}",
        bin_len, pos_off, nv * 12, nrm_off, nv * 12, uv_off, nv * 8, idx_off, m->indices * 4,
        img_off, png_len, nv, m->lo[0], m->lo[1], m->lo[2], m->hi[0], m->hi[1], m->hi[2], nv, nv,
        m->indices);
    fclose(f);
    const size_t jlen = pad4(json_len);
    const size_t total = 12 + 8 + jlen + 8 + bin_len;
    unsigned char *out = malloc(total);
    if (!out || total > UINT32_MAX) {
        free(bin), free(json), free(out);
        return og_error_set(err, "%s: the mesh is too large for one .glb (4 GiB): simplify it",
                            path);
    }
    uint32_t header[5] = {0x46546C67u, 2, (uint32_t)total, (uint32_t)jlen, 0x4E4F534Au};
    memcpy(out, header, 20);
    memcpy(out + 20, json, json_len);
    memset(out + 20 + json_len, ' ', jlen - json_len); // JSON pads with spaces
    uint32_t bin_header[2] = {(uint32_t)bin_len, 0x004E4942u};
    memcpy(out + 20 + jlen, bin_header, 8);
    memcpy(out + 28 + jlen, bin, bin_len);
    free(bin);
    free(json);
    int rc = param_file_write_atomic(path, (const char *)out, total, err);
    free(out);
    return rc;
}

int export_mesh_wanted(const char *path) {
    const char *dot = strrchr(path, '.');
    return dot &&
           (!strcasecmp(dot, ".obj") || !strcasecmp(dot, ".ply") || !strcasecmp(dot, ".glb"));
}

int export_mesh(world *w, const char *path, const export_mesh_options *o, export_mesh_report *rep,
                og_error *err) {
    const world_params *p = world_get_params(w);
    if (p->kind == WORLD_PLANET)
        return og_error_set(err, "%s: meshes are exported from flat worlds", path);
    layer_grid g;
    if (layer_grid_init(&g, p, TILE_LAYER_COARSE, 0, err) != 0) return -1;
    grid_rect r = o->rect;
    const int64_t W = r.x1 - r.x0, D = r.z1 - r.z0;
    if (W < 2 || D < 2) return og_error_set(err, "%s: a mesh needs at least 2 x 2 samples", path);
    if (W * D > EXPORT_MESH_MAX_SAMPLES)
        return og_error_set(err,
                            "%s: %lld x %lld samples is over the mesh limit of %lld: export "
                            "a smaller region",
                            path, (long long)W, (long long)D, (long long)EXPORT_MESH_MAX_SAMPLES);
    // Simplifying a closed solid could open it (a collapse that crowds an edge loses a face).
    if (o->solid && o->simplify > 0)
        return og_error_set(
            err, "%s: solid=1 and simplify= together are not supported yet: pick one", path);
    float *h = malloc(sizeof(float) * (size_t)(W * D));
    if (!h) return og_error_set(err, "%s: out of memory", path);
    mesh m = {0};
    unsigned char *png = NULL;
    size_t png_len = 0;
    int rc = -1;
    if (layer_grid_read(w, &g, r, h, err) != 0) goto done;
    double ox = (double)r.x0 * g.spacing, oz = (double)r.z0 * g.spacing;
    if (o->centred) ox = -(double)(W - 1) * g.spacing / 2, oz = -(double)(D - 1) * g.spacing / 2;
    rep->achieved_error = 0;
    rep->volume = 0;
    int volume = 0;
    if (export_solid_has_volume(w, r, &volume, err) != 0) goto done;
    if (volume) { // caves and overhangs: the solid's surface, the heightfield's included
        volume_mesh sm;
        if (export_solid_surface(w, r, o->solid, &sm, err) != 0) goto done;
        rep->input_triangles = sm.index_count / 3;
        rep->volume = 1;
        clamp_to_region(&sm, (double)r.x0 * g.spacing, (double)r.z0 * g.spacing,
                        (double)(r.x1 - 1) * g.spacing, (double)(r.z1 - 1) * g.spacing);
        volume_simplify_report vs;
        if (o->simplify > 0 && volume_simplify(&sm, o->simplify, &vs, err) != 0) {
            volume_mesh_free(&sm);
            goto done;
        }
        if (o->simplify > 0) rep->achieved_error = vs.max_error;
        int built = from_solid(&sm, (double)r.x0 * g.spacing, (double)r.z0 * g.spacing,
                               (double)(W - 1) * g.spacing, (double)(D - 1) * g.spacing,
                               o->centred ? ox : (double)r.x0 * g.spacing,
                               o->centred ? oz : (double)r.z0 * g.spacing, &m);
        volume_mesh_free(&sm);
        if (built != 0) {
            og_error_set(err, "%s: out of memory for the mesh", path);
            goto done;
        }
    } else if (build_grid(h, W, D, g.spacing, ox, oz, &m) != 0) {
        og_error_set(err, "%s: out of memory for the mesh", path);
        goto done;
    }
    if (!volume) rep->input_triangles = m.indices / 3;
    og_progress *progress = og_progress_current();
    if (og_progress_report(progress, 1, 4) != 0) {
        og_error_set(err, "%s: cancelled", path);
        goto done;
    }
    heightfield_grid grid = {h, W, D, g.spacing, ox, oz};
    if (o->simplify > 0 && !volume && simplify(&m, &grid, o->simplify, &rep->achieved_error) != 0) {
        og_error_set(err, "%s: out of memory simplifying", path);
        goto done;
    }
    if (o->solid && !volume) { // a volume surface came closed already
        float lo = INFINITY, hi = -INFINITY;
        for (int64_t i = 0; i < W * D; i++)
            lo = fminf(lo, h[i]), hi = fmaxf(hi, h[i]);
        float floor_y = lo - fmaxf(1.0f, 0.05f * (hi - lo));
        if (add_base(&m, W, D, floor_y) != 0) {
            og_error_set(err, "%s: out of memory for the base", path);
            goto done;
        }
    }
    if (og_progress_report(progress, 3, 4) != 0) {
        og_error_set(err, "%s: cancelled", path);
        goto done;
    }
    bounds(&m);
    const char *dot = strrchr(path, '.');
    if (!strcasecmp(dot, ".obj")) {
        rc = write_obj(path, &m, err);
    } else if (!strcasecmp(dot, ".ply")) {
        rc = write_ply(path, &m, err);
    } else {
        if (base_colour_png(h, W, D, g.spacing, path, &png, &png_len, err) != 0) goto done;
        rc = write_glb(path, &m, png, png_len, err);
    }
    if (rc == 0) {
        rep->vertices = m.vertices;
        rep->triangles = m.indices / 3;
        for (int c = 0; c < 3; c++)
            rep->lo[c] = m.lo[c], rep->hi[c] = m.hi[c];
    }
done:
    free(h);
    free(png);
    mesh_free(&m);
    return rc;
}
