#include "editor/world/volume_grid.h"

#include "editor/world/layer_grid.h"

#include <stdlib.h>
#include <string.h>

// Heights beyond this many metres are no terrain anyone edits (brush.h's limit too).
#define VOLUME_HEIGHT_LIMIT 1.0e6

int volume_grid_init(volume_grid *g, const world_params *p, og_error *err) {
    if (p->kind != WORLD_FLAT)
        return og_error_set(err, "volume edits (caves, overhangs) work on flat worlds; this world "
                                 "is a planet");
    g->spacing = p->spacing;
    g->ratio = p->volume_ratio > 0 ? p->volume_ratio : 1;
    g->voxel = p->spacing / g->ratio;
    g->extent = p->size;
    g->extent_z = world_params_size_z(p);
    return 0;
}

int volume_grid_check_position(const volume_grid *g, const double p[3], og_error *err) {
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
        return og_error_set(err, "position (%g, %g, %g) must be finite numbers", p[0], p[1], p[2]);
    double limit = ((double)INT32_MAX - 2) * VOLUME_BRICK_X * g->voxel;
    if (fabs(p[0]) > limit || fabs(p[2]) > limit)
        return og_error_set(err,
                            "position (%g, %g, %g) m lies beyond the addressable world (+-%g m)",
                            p[0], p[1], p[2], limit);
    if (fabs(p[1]) > VOLUME_HEIGHT_LIMIT)
        return og_error_set(err, "height %g m lies beyond +-%g m", p[1], VOLUME_HEIGHT_LIMIT);
    if (g->extent > 0) {
        double right = (double)(g->extent - 1) * g->spacing;
        double bottom = (double)(g->extent_z - 1) * g->spacing;
        if (p[0] < 0 || p[2] < 0 || p[0] > right || p[2] > bottom)
            return og_error_set(err,
                                "position (%g, %g, %g) m lies outside the world (x 0 to %g m, z 0 "
                                "to %g m)",
                                p[0], p[1], p[2], right, bottom);
    }
    return 0;
}

volume_box volume_grid_box_around(const volume_grid *g, const double lo[3], const double hi[3],
                                  double margin) {
    double v = g->voxel;
    volume_box b = {
        (int64_t)floor((lo[0] - margin) / v),    (int64_t)floor((lo[1] - margin) / v),
        (int64_t)floor((lo[2] - margin) / v),    (int64_t)ceil((hi[0] + margin) / v) + 1,
        (int64_t)ceil((hi[1] + margin) / v) + 1, (int64_t)ceil((hi[2] + margin) / v) + 1,
    };
    return b;
}

int64_t volume_box_voxels(volume_box b) {
    return volume_box_empty(b) ? 0 : (b.i1 - b.i0) * (b.j1 - b.j0) * (b.k1 - b.k0);
}

int64_t volume_box_bricks(volume_box b) {
    if (volume_box_empty(b)) return 0;
    int64_t nx =
        volume_floor_div(b.i1 - 1, VOLUME_BRICK_X) - volume_floor_div(b.i0, VOLUME_BRICK_X);
    int64_t ny =
        volume_floor_div(b.j1 - 1, VOLUME_BRICK_Y) - volume_floor_div(b.j0, VOLUME_BRICK_Y);
    int64_t nz =
        volume_floor_div(b.k1 - 1, VOLUME_BRICK_Z) - volume_floor_div(b.k0, VOLUME_BRICK_Z);
    return (nx + 1) * (ny + 1) * (nz + 1);
}

size_t volume_box_brick_keys(volume_box b, tile_key *out) {
    size_t n = 0;
    if (volume_box_empty(b)) return 0;
    for (int64_t by = volume_floor_div(b.j0, VOLUME_BRICK_Y);
         by <= volume_floor_div(b.j1 - 1, VOLUME_BRICK_Y); by++)
        for (int64_t bz = volume_floor_div(b.k0, VOLUME_BRICK_Z);
             bz <= volume_floor_div(b.k1 - 1, VOLUME_BRICK_Z); bz++)
            for (int64_t bx = volume_floor_div(b.i0, VOLUME_BRICK_X);
                 bx <= volume_floor_div(b.i1 - 1, VOLUME_BRICK_X); bx++)
                out[n++] = (tile_key){TILE_LAYER_VOLUME, 0, (int32_t)by, (int32_t)bx, (int32_t)bz};
    return n;
}

volume_box volume_brick_box(tile_key key) {
    volume_box b = {(int64_t)key.tx * VOLUME_BRICK_X,
                    (int64_t)key.level * VOLUME_BRICK_Y,
                    (int64_t)key.ty * VOLUME_BRICK_Z,
                    0,
                    0,
                    0};
    b.i1 = b.i0 + VOLUME_BRICK_X;
    b.j1 = b.j0 + VOLUME_BRICK_Y;
    b.k1 = b.k0 + VOLUME_BRICK_Z;
    return b;
}

static int64_t max64(int64_t a, int64_t b) {
    return a > b ? a : b;
}
static int64_t min64(int64_t a, int64_t b) {
    return a < b ? a : b;
}

volume_box volume_box_intersect(volume_box a, volume_box b) {
    volume_box r = {max64(a.i0, b.i0), max64(a.j0, b.j0), max64(a.k0, b.k0),
                    min64(a.i1, b.i1), min64(a.j1, b.j1), min64(a.k1, b.k1)};
    return r;
}

int volume_heights_read(world *w, const volume_grid *g, double step, int64_t i0, int64_t k0,
                        int64_t i1, int64_t k1, volume_heights *out, og_error *err) {
    *out = (volume_heights){.i0 = i0, .k0 = k0, .w = i1 - i0, .h = k1 - k0};
    layer_grid lg;
    if (layer_grid_init(&lg, world_get_params(w), TILE_LAYER_COARSE, 0, err) != 0) return -1;
    // Column i stands at i x step metres: q coarse samples per column step.
    double q = step / g->spacing;
    // The coarse samples around the columns, one more on each side for the slopes.
    grid_rect cr = {(int64_t)floor(i0 * q) - 1, (int64_t)floor(k0 * q) - 1,
                    (int64_t)floor((i1 - 1) * q) + 3, (int64_t)floor((k1 - 1) * q) + 3};
    int64_t cw = cr.x1 - cr.x0, ch = cr.z1 - cr.z0;
    float *coarse = malloc((size_t)(cw * ch) * sizeof *coarse);
    out->height = malloc((size_t)(out->w * out->h) * sizeof *out->height);
    out->slope_scale = malloc((size_t)(out->w * out->h) * sizeof *out->slope_scale);
    if (!coarse || !out->height || !out->slope_scale) {
        free(coarse);
        volume_heights_free(out);
        return og_error_set(err, "out of memory reading heights under %lld x %lld columns",
                            (long long)out->w, (long long)out->h);
    }
    if (layer_grid_read(w, &lg, cr, coarse, err) != 0) {
        free(coarse);
        volume_heights_free(out);
        return -1;
    }
    double spacing = g->spacing;
    for (int64_t k = k0; k < k1; k++) {
        double czf = k * q;
        int64_t cz = (int64_t)floor(czf);
        double fz = czf - cz;
        for (int64_t i = i0; i < i1; i++) {
            double cxf = i * q;
            int64_t cx = (int64_t)floor(cxf);
            double fx = cxf - cx;
            const float *s = coarse + (cz - cr.z0) * cw + (cx - cr.x0);
            double h00 = s[0], h10 = s[1], h01 = s[cw], h11 = s[cw + 1];
            double h = (h00 * (1 - fx) + h10 * fx) * (1 - fz) + (h01 * (1 - fx) + h11 * fx) * fz;
            // Central differences of the coarse samples, blended like the heights, so
            // the slope is continuous across cells.
            double gx00 = (s[1] - s[-1]) / 2, gx10 = (s[2] - s[0]) / 2;
            double gx01 = (s[cw + 1] - s[cw - 1]) / 2, gx11 = (s[cw + 2] - s[cw]) / 2;
            double gz00 = (s[cw] - s[-cw]) / 2, gz10 = (s[cw + 1] - s[1 - cw]) / 2;
            double gz01 = (s[2 * cw] - s[0]) / 2, gz11 = (s[2 * cw + 1] - s[1]) / 2;
            double gx =
                ((gx00 * (1 - fx) + gx10 * fx) * (1 - fz) + (gx01 * (1 - fx) + gx11 * fx) * fz) /
                spacing;
            double gz =
                ((gz00 * (1 - fx) + gz10 * fx) * (1 - fz) + (gz01 * (1 - fx) + gz11 * fx) * fz) /
                spacing;
            size_t c = (size_t)((k - k0) * out->w + (i - i0));
            out->height[c] = (float)h;
            out->slope_scale[c] = (float)(1.0 / sqrt(1.0 + gx * gx + gz * gz));
        }
    }
    free(coarse);
    return 0;
}

void volume_heights_free(volume_heights *vh) {
    free(vh->height);
    free(vh->slope_scale);
    vh->height = vh->slope_scale = NULL;
}

int volume_field_read(world *w, const volume_grid *g, const volume_heights *vh, volume_box box,
                      float *out, og_error *err) {
    int64_t n = volume_box_bricks(box);
    tile_key *keys = malloc((size_t)(n > 0 ? n : 1) * sizeof *keys);
    if (!keys) return og_error_set(err, "out of memory reading %lld bricks", (long long)n);
    size_t count = volume_box_brick_keys(box, keys);
    tile_cache *cache = world_cache(w);
    int64_t nx = box.i1 - box.i0, nz = box.k1 - box.k0;
    double v = g->voxel;
    int rc = 0;
    for (size_t b = 0; b < count && rc == 0; b++) {
        volume_box part = volume_box_intersect(volume_brick_box(keys[b]), box);
        tile_view view;
        if (tile_cache_acquire(cache, keys[b], &view, err) != 0) {
            rc = -1;
            break;
        }
        for (int64_t j = part.j0; j < part.j1; j++)
            for (int64_t k = part.k0; k < part.k1; k++) {
                const int16_t *pair =
                    (const int16_t *)view.data + 2 * volume_brick_offset(keys[b], part.i0, j, k);
                float *row = out + ((j - box.j0) * nz + (k - box.k0)) * nx + (part.i0 - box.i0);
                double y = (double)j * v;
                for (int64_t i = part.i0; i < part.i1; i++, pair += 2)
                    *row++ =
                        volume_combine(volume_heights_distance(vh, i, k, y),
                                       volume_to_metres(pair[0], v), volume_to_metres(pair[1], v));
            }
        tile_cache_release(cache, &view);
    }
    free(keys);
    return rc;
}

void volume_reader_init(volume_reader *r, world *w) {
    memset(r, 0, sizeof *r);
    r->cache = world_cache(w);
}

const int16_t *volume_reader_pair(volume_reader *r, int64_t i, int64_t j, int64_t k,
                                  og_error *err) {
    tile_key key = volume_brick_key(i, j, k);
    size_t slot = tile_key_hash(key) % VOLUME_READER_SLOTS;
    if (!r->used[slot] || !tile_key_equal(r->views[slot].key, key)) {
        if (r->used[slot]) tile_cache_release(r->cache, &r->views[slot]);
        r->used[slot] = 0;
        if (tile_cache_acquire(r->cache, key, &r->views[slot], err) != 0) return NULL;
        r->used[slot] = 1;
    }
    return (const int16_t *)r->views[slot].data + 2 * volume_brick_offset(key, i, j, k);
}

void volume_reader_close(volume_reader *r) {
    for (int s = 0; s < VOLUME_READER_SLOTS; s++)
        if (r->used[s]) tile_cache_release(r->cache, &r->views[s]);
    memset(r->used, 0, sizeof r->used);
}

typedef struct key_list {
    tile_key *keys;
    size_t count, cap;
    int out_of_memory;
} key_list;

static int collect_volume_key(void *user, tile_key key) {
    key_list *l = user;
    if (key.layer != TILE_LAYER_VOLUME) return 0;
    if (l->count == l->cap) {
        size_t cap = l->cap ? l->cap * 2 : 64;
        tile_key *grown = realloc(l->keys, cap * sizeof *grown);
        if (!grown) return l->out_of_memory = 1;
        l->keys = grown;
        l->cap = cap;
    }
    l->keys[l->count++] = key;
    return 0;
}

static int key_order(const void *pa, const void *pb) {
    const tile_key *a = pa, *b = pb;
    if (a->level != b->level) return a->level < b->level ? -1 : 1;
    if (a->ty != b->ty) return a->ty < b->ty ? -1 : 1;
    if (a->tx != b->tx) return a->tx < b->tx ? -1 : 1;
    return 0;
}

int volume_list_bricks(world *w, tile_key **keys, size_t *count, og_error *err) {
    key_list l = {0};
    *keys = NULL;
    *count = 0;
    // Written bricks live in the saved store, the unsaved-edit journal, or (not yet
    // written back) in the cache.
    tile_cache *cache = world_cache(w);
    size_t resident = tile_cache_edited_keys(cache, TILE_LAYER_VOLUME, NULL, 0);
    l.cap = resident + 64;
    l.keys = malloc(l.cap * sizeof *l.keys);
    if (!l.keys) return og_error_set(err, "out of memory listing volume bricks");
    l.count = tile_cache_edited_keys(cache, TILE_LAYER_VOLUME, l.keys, l.cap);
    if (l.count > l.cap) l.count = l.cap; // edits run on this thread: cannot grow meanwhile
    tile_store *stores[2] = {world_store(w), world_journal(w)};
    for (int s = 0; s < 2; s++) {
        if (!stores[s]) continue;
        if (tile_store_each(stores[s], collect_volume_key, &l, err) != 0 || l.out_of_memory) {
            free(l.keys);
            return l.out_of_memory ? og_error_set(err, "out of memory listing volume bricks") : -1;
        }
    }
    if (l.count) qsort(l.keys, l.count, sizeof *l.keys, key_order);
    size_t n = 0;
    for (size_t i = 0; i < l.count; i++)
        if (n == 0 || key_order(&l.keys[n - 1], &l.keys[i]) != 0) l.keys[n++] = l.keys[i];
    *keys = l.keys;
    *count = n;
    return 0;
}

int volume_has_edits(world *w, int *has, og_error *err) {
    *has = 0;
    tile_key *keys;
    size_t n;
    if (volume_list_bricks(w, &keys, &n, err) != 0) return -1;
    int rc = 0;
    for (size_t b = 0; b < n && !*has; b++) {
        tile_view v;
        if (tile_cache_acquire(world_cache(w), keys[b], &v, err) != 0) {
            rc = -1;
            break;
        }
        const int16_t *d = v.data;
        for (size_t i = 0; i < 2 * (size_t)TILE_SAMPLES && !*has; i++)
            *has = d[i] != VOLUME_FAR;
        tile_cache_release(world_cache(w), &v);
    }
    free(keys);
    return rc;
}

int volume_sample(world *w, const double p[3], double *distance, og_error *err) {
    volume_grid g;
    if (volume_grid_init(&g, world_get_params(w), err) != 0 ||
        volume_grid_check_position(&g, p, err) != 0)
        return -1;
    double fi = p[0] / g.voxel, fj = p[1] / g.voxel, fk = p[2] / g.voxel;
    int64_t i = (int64_t)floor(fi), j = (int64_t)floor(fj), k = (int64_t)floor(fk);
    volume_heights vh;
    if (volume_heights_read(w, &g, g.voxel, i, k, i + 2, k + 2, &vh, err) != 0) return -1;
    tile_cache *cache = world_cache(w);
    double corner[8];
    int rc = 0;
    for (int c = 0; c < 8 && rc == 0; c++) {
        int64_t ci = i + (c & 1), cj = j + (c >> 1 & 1), ck = k + (c >> 2 & 1);
        tile_key key = volume_brick_key(ci, cj, ck);
        tile_view view;
        if (tile_cache_acquire(cache, key, &view, err) != 0) {
            rc = -1;
            break;
        }
        const int16_t *v = (const int16_t *)view.data + 2 * volume_brick_offset(key, ci, cj, ck);
        corner[c] =
            volume_combine(volume_heights_distance(&vh, ci, ck, (double)cj * g.voxel),
                           volume_to_metres(v[0], g.voxel), volume_to_metres(v[1], g.voxel));
        tile_cache_release(cache, &view);
    }
    volume_heights_free(&vh);
    if (rc != 0) return -1;
    double ti = fi - i, tj = fj - j, tk = fk - k, d = 0;
    for (int c = 0; c < 8; c++)
        d += corner[c] * (c & 1 ? ti : 1 - ti) * (c >> 1 & 1 ? tj : 1 - tj) *
             (c >> 2 & 1 ? tk : 1 - tk);
    *distance = d;
    return 0;
}
