#include "editor/edit/edit_mips.h"

#include "editor/edit/material_mips.h"
#include "editor/edit/mip_rows.h"
#include "editor/edit/parallel.h"
#include "editor/gen/gen.h"
#include "editor/params/world_grid.h"
#include "editor/world/thread_scratch.h"
#include "io/avx2_clone.h"

#include <stdlib.h>
#include <string.h>

static int64_t floor_div(int64_t a, int64_t b) {
    return world_grid_floor_div(a, b);
}

// The generator's tile for key (NULL when out of memory or outside the world); free it.
static float *generated_tile(world *w, tile_key key) {
    float *t = malloc(TILE_SAMPLES * sizeof *t);
    if (t && gen_tile(world_get_params(w), key, t) != 0) {
        free(t);
        return NULL;
    }
    return t;
}

// Samples along a bounded world's longer side or a planet face's; 0 when unbounded.
static int64_t largest_extent(const world_params *p) {
    int64_t extent = p->kind == WORLD_PLANET ? world_grid_face_samples(p) : p->size;
    if (extent > 0 && p->kind != WORLD_PLANET && world_params_size_z(p) > extent)
        extent = world_params_size_z(p);
    return extent > 0 ? extent : 0;
}

int edit_mips_tile_cover_level(const world_params *p) {
    int64_t extent = largest_extent(p);
    if (!extent) return EDIT_MIP_LEVELS_UNBOUNDED;
    int level = 1;
    while (level < TILE_MAX_LEVEL && ((extent - 1) >> level) >= TILE_SIZE)
        level++;
    return level;
}

// Every level a reader may ask for, not only down to the one where a tile covers the
// world: the flat viewport's clipmap reads levels up to EDIT_MIP_LEVELS_UNBOUNDED - 1
// whatever the world's size, and the planet viewport's root chunks a face in a few
// samples. Levels past a small world's last one are a sample or two each, so cheap.
int edit_mips_top_level(const world_params *p) {
    int64_t extent = largest_extent(p);
    if (!extent) return EDIT_MIP_LEVELS_UNBOUNDED;
    int top = p->kind == WORLD_PLANET ? 1 : EDIT_MIP_LEVELS_UNBOUNDED;
    while (top < TILE_MAX_LEVEL && ((extent - 1) >> top) >= 1) // down to one sample
        top++;
    return top;
}

// A child tile of a level: its bytes before the edit and the part of them kept
// (edit_snapshot), and when the level below wrote it in this update, its view, still
// pinned (read without a second acquire).
typedef struct child_tile {
    tile_view view; // data NULL: not pinned (acquired by the task that reads it)
    const float *before;
    grid_rect part;
} child_tile;

// Up to this many tiles of a level are held or looked up at once (a dab's levels
// write one to four; beyond, each task looks up its own).
enum { LEVEL_TILES_MAX = 16 };

// A level's tiles, tile (tx0 + i % tw, tz0 + i / tw) in tiles[i]: the parents it wrote
// (pinned until the next level has read them), or the children it reads.
typedef struct level_tiles {
    child_tile tiles[LEVEL_TILES_MAX];
    int64_t tx0, tz0, tw, th; // th 0: none
} level_tiles;

typedef struct level_job {
    edit *e;
    const level_tiles *children; // found before the tasks run; NULL: each task's own lookup
    level_tiles *wrote;          // the parents written, NULL: released at once
    int64_t child_extent;        // children along X at the child level (bounded); 0 = unbounded
    int64_t child_extent_z;      // and along Z
    int face, level, planet;     // level: the parent level being written
    int from_generator;          // before = the generated tiles, not the edit's snapshots
    grid_rect parents;           // parent samples to update
    int64_t ptx0, ptz0, ptw;     // parent tiles covering them
} level_job;

static const child_tile *tile_at(const level_tiles *t, int64_t tx, int64_t tz) {
    if (!t || !t->th || tx < t->tx0 || tz < t->tz0 || tx >= t->tx0 + t->tw || tz >= t->tz0 + t->th)
        return NULL;
    return &t->tiles[(tz - t->tz0) * t->tw + (tx - t->tx0)];
}

// The child tiles under j's parents into kids: those the level below wrote in this
// update from `below` (pinned), the others' snapshots under one lock, not one lock per
// tile. 0 when there are too many (each task looks its own up).
static int find_children(level_job *j, const level_tiles *below, level_tiles *kids) {
    int64_t lo = j->planet ? 0 : -1;
    kids->tx0 = floor_div(2 * j->parents.x0 + lo, TILE_SIZE);
    kids->tz0 = floor_div(2 * j->parents.z0 + lo, TILE_SIZE);
    kids->tw = floor_div(2 * j->parents.x1 - 1, TILE_SIZE) - kids->tx0 + 1;
    kids->th = floor_div(2 * j->parents.z1 - 1, TILE_SIZE) - kids->tz0 + 1;
    if (kids->tw * kids->th > LEVEL_TILES_MAX) return 0;
    tile_key keys[LEVEL_TILES_MAX];
    const void *before[LEVEL_TILES_MAX];
    grid_rect part[LEVEL_TILES_MAX];
    int at[LEVEL_TILES_MAX], n = 0;
    for (int i = 0; i < kids->tw * kids->th; i++) {
        int64_t tx = kids->tx0 + i % kids->tw, tz = kids->tz0 + i / kids->tw;
        const child_tile *held = tile_at(below, tx, tz);
        if (held && held->view.data) {
            kids->tiles[i] = *held;
            continue;
        }
        kids->tiles[i] = (child_tile){0};
        keys[n] = (tile_key){TILE_LAYER_COARSE, j->face, j->level - 1, (int32_t)tx, (int32_t)tz};
        at[n++] = i;
    }
    edit_snapshots(j->e, keys, (size_t)n, before, part);
    for (int k = 0; k < n; k++)
        kids->tiles[at[k]].before = before[k], kids->tiles[at[k]].part = part[k];
    return 1;
}

// row[x] = after[x] - before[x] for x < n, for `rows` rows (tile rows TILE_SIZE apart,
// the window's w apart); whether any is not zero. Its own function for AVX2 (a dab's
// level-1 window is 133^2 of them), a block a call (a stroke's moves: many short rows).
AVX2_CLONE static int change_rows(const float *restrict after, const float *restrict before,
                                  float *restrict row, int64_t w, int64_t rows, int64_t n) {
    int any = 0;
    for (int64_t z = 0; z < rows; z++, after += TILE_SIZE, before += TILE_SIZE, row += w)
        for (int64_t x = 0; x < n; x++) {
            row[x] = after[x] - before[x];
            any |= row[x] != 0.0f;
        }
    return any;
}

// Zeroes the samples of win (w x h) outside `keep` (window samples; may be empty).
static void zero_outside(float *win, int64_t w, int64_t h, grid_rect keep) {
    if (grid_rect_empty(keep)) {
        memset(win, 0, (size_t)(w * h) * sizeof *win);
        return;
    }
    memset(win, 0, (size_t)(keep.z0 * w) * sizeof *win);
    memset(win + keep.z1 * w, 0, (size_t)((h - keep.z1) * w) * sizeof *win);
    // The columns beside it, a column at a time: they are one to a few samples wide (the
    // filter's margin), and two memset calls a row cost more than the stores.
    for (int64_t x = 0; x < w; x++) {
        if (x == keep.x0) x = keep.x1;
        if (x >= w) break;
        for (int64_t z = keep.z0; z < keep.z1; z++)
            win[z * w + x] = 0.0f;
    }
}

// Fills win (w x h, origin cx0, cz0 in child samples) with after - before of every
// child tile the edit changed; zero elsewhere.
static int child_changes(level_job *j, int64_t cx0, int64_t cz0, int64_t w, int64_t h, float *win) {
    int64_t ty0 = floor_div(cz0, TILE_SIZE), ty1 = floor_div(cz0 + h - 1, TILE_SIZE);
    int64_t tx0 = floor_div(cx0, TILE_SIZE), tx1 = floor_div(cx0 + w - 1, TILE_SIZE);
    // Under one child tile (most levels of a move), only the samples its block of
    // changes leaves are zeroed, after it: not the whole window first.
    int one_tile = ty0 == ty1 && tx0 == tx1;
    grid_rect filled = {0, 0, 0, 0}; // window samples its block wrote
    if (!one_tile) memset(win, 0, (size_t)(w * h) * sizeof *win);
    tile_cache *cache = world_cache(edit_world(j->e));
    int any = 0;
    for (int64_t ty = ty0; ty <= ty1; ty++)
        for (int64_t tx = tx0; tx <= tx1; tx++) {
            tile_key key = {TILE_LAYER_COARSE, j->face, j->level - 1, (int32_t)tx, (int32_t)ty};
            grid_rect part = {0, 0, TILE_SIZE, TILE_SIZE}; // only there can the child differ
            float *generated = NULL;
            const float *before;
            const child_tile *kid = tile_at(j->children, tx, ty);
            if (kid) {
                before = kid->before;
                part = kid->part;
            } else if (j->from_generator) {
                generated = generated_tile(edit_world(j->e), key);
                before = generated;
            } else {
                before = edit_snapshot(j->e, key, &part);
            }
            if (!before || grid_rect_empty(part)) continue;
            tile_view v = kid ? kid->view : (tile_view){0};
            int pinned = v.data != NULL;
            og_error err;
            if (!pinned && tile_cache_acquire(cache, key, &v, &err) != 0) { // outside the world
                free(generated);
                continue;
            }
            const float *after = v.data;
            int64_t px0 = tx * TILE_SIZE + part.x0, px1 = tx * TILE_SIZE + part.x1;
            int64_t pz0 = ty * TILE_SIZE + part.z0, pz1 = ty * TILE_SIZE + part.z1;
            int64_t x0 = px0 > cx0 ? px0 : cx0, x1 = px1 < cx0 + w ? px1 : cx0 + w;
            int64_t z0 = pz0 > cz0 ? pz0 : cz0, z1 = pz1 < cz0 + h ? pz1 : cz0 + h;
            if (z0 < z1 && x0 < x1) {
                size_t t = (size_t)((z0 - ty * TILE_SIZE) * TILE_SIZE + (x0 - tx * TILE_SIZE));
                any |= change_rows(after + t, before + t, win + (z0 - cz0) * w + (x0 - cx0), w,
                                   z1 - z0, x1 - x0);
                filled = (grid_rect){x0 - cx0, z0 - cz0, x1 - cx0, z1 - cz0};
            }
            if (!pinned) tile_cache_release(cache, &v);
            free(generated);
        }
    if (one_tile) zero_outside(win, w, h, filled);
    // Beyond a bounded world's edge the terrain reads as its edge sample (as brushes
    // see it), so the change there is the edge's change.
    int64_t n = j->child_extent, nz = j->child_extent_z;
    if (any && n > 0 && (cx0 < 0 || cz0 < 0 || cx0 + w > n || cz0 + h > nz)) {
        for (int64_t z = 0; z < h; z++) {
            int64_t gz = cz0 + z, sz = gz < 0 ? 0 : gz >= nz ? nz - 1 : gz;
            for (int64_t x = 0; x < w; x++) {
                int64_t gx = cx0 + x, sx = gx < 0 ? 0 : gx >= n ? n - 1 : gx;
                if ((sx != gx || sz != gz) && sx - cx0 >= 0 && sx - cx0 < w && sz - cz0 >= 0 &&
                    sz - cz0 < h)
                    win[z * w + x] = win[(sz - cz0) * w + (sx - cx0)];
            }
        }
    }
    return any;
}

static int parent_tile_task(void *user, int task, og_error *err) {
    level_job *j = user;
    int64_t tx = j->ptx0 + task % j->ptw, tz = j->ptz0 + task / j->ptw;
    grid_rect sub =
        grid_rect_intersect(j->parents, (grid_rect){tx * TILE_SIZE, tz * TILE_SIZE,
                                                    (tx + 1) * TILE_SIZE, (tz + 1) * TILE_SIZE});
    if (grid_rect_empty(sub)) return 0;
    int64_t pw = sub.x1 - sub.x0, ph = sub.z1 - sub.z0;
    // Flat: parent p averages children 2p-1..2p+1; planet: children 2p, 2p+1.
    int64_t lo = j->planet ? 0 : -1;
    int64_t cw = 2 * pw + (j->planet ? 0 : 1), ch = 2 * ph + (j->planet ? 0 : 1);
    int64_t cx0 = 2 * sub.x0 + lo, cz0 = 2 * sub.z0 + lo;
    float *win = thread_scratch(SCRATCH_MIP_WINDOW, (size_t)(cw * ch) * sizeof *win);
    if (!win) return og_error_set(err, "out of memory updating mip levels");
    int rc = 0;
    if (child_changes(j, cx0, cz0, cw, ch, win)) {
        tile_key key = {TILE_LAYER_COARSE, j->face, j->level, (int32_t)tx, (int32_t)tz};
        tile_view v;
        grid_rect local = {sub.x0 - tx * TILE_SIZE, sub.z0 - tz * TILE_SIZE,
                           sub.x1 - tx * TILE_SIZE, sub.z1 - tz * TILE_SIZE};
        const void *snap;
        grid_rect kept;
        if (edit_tile_acquire_snapshot(j->e, key, local, &v, &snap, &kept, err) != 0) {
            rc = -1;
        } else {
            // The parent as it was before the edit plus the whole change so far, so the
            // update can run again while a stroke goes on (the viewport shows it live).
            float *t = v.data;
            float *generated = j->from_generator ? generated_tile(edit_world(j->e), key) : NULL;
            const float *was = j->from_generator ? generated : snap;
            size_t at = (size_t)((sub.z0 - tz * TILE_SIZE) * TILE_SIZE + (sub.x0 - tx * TILE_SIZE));
            if (!j->planet) // flat: the whole block in one call (mip_rows.h)
                mip_rows_block(win, (int)cw, (int)pw, (int)ph, was ? was + at : NULL, t + at,
                               TILE_SIZE);
            for (int64_t z = 0; z < ph && j->planet; z++) {
                size_t row =
                    (size_t)((sub.z0 + z - tz * TILE_SIZE) * TILE_SIZE + (sub.x0 - tx * TILE_SIZE));
                float *dst = t + row;
                const float *before = was ? was + row : dst;
                for (int64_t x = 0; x < pw; x++) {
                    const float *c = win + (2 * z) * cw + 2 * x;
                    dst[x] = before[x] + 0.25f * (c[0] + c[1] + c[cw] + c[cw + 1]);
                }
            }
            free(generated);
            if (j->wrote) // the next level reads it
                j->wrote->tiles[task] = (child_tile){v, snap, kept};
            else
                edit_tile_release(j->e, &v);
        }
    }
    return rc;
}

static void release_held(edit *e, level_tiles *h) {
    for (int64_t i = 0; i < h->tw * h->th; i++)
        if (h->tiles[i].view.data) edit_tile_release(e, &h->tiles[i].view);
    h->th = 0;
}

int edit_mips_update(edit *e, og_error *err) {
    const dirty_rect *d;
    size_t n = edit_dirty_rects(e, &d), done = edit_mips_current(e);
    if (done == n) return 0;
    // Only the areas changed since the last call: edit_dirty starts a new area after the
    // ones done, so the parent tiles they reach are the only ones written.
    if (edit_mips_update_from(e, done, err) != 0 || material_mips_update_from(e, done, err) != 0)
        return -1;
    edit_publish_from(e, done);
    edit_set_mips_current(e, n);
    return 0;
}

// Brings levels first..top of face up to date over r (samples of level first - 1 that
// changed); from_generator: against the generated tiles rather than the edit's snapshots.
static int update_levels(edit *e, int face, grid_rect r, int first, int from_generator,
                         og_error *err) {
    const world_params *p = world_get_params(edit_world(e));
    int planet = p->kind == WORLD_PLANET;
    int64_t extent = planet ? world_grid_face_samples(p) : p->size;
    int64_t extent_z = planet ? extent : world_params_size_z(p);
    int top = edit_mips_top_level(p);
    // Each level's written tiles stay pinned while the next level reads them; the
    // generator's path compares with generated tiles, not snapshots, so holds none.
    level_tiles held[2], kids;
    held[0].th = held[1].th = 0;
    int rc = 0;
    for (int level = first; level <= top && rc == 0; level++) {
        grid_rect pr = planet ? (grid_rect){floor_div(r.x0, 2), floor_div(r.z0, 2),
                                            floor_div(r.x1 - 1, 2) + 1, floor_div(r.z1 - 1, 2) + 1}
                              : (grid_rect){-floor_div(-(r.x0 - 1), 2), -floor_div(-(r.z0 - 1), 2),
                                            floor_div(r.x1, 2) + 1, floor_div(r.z1, 2) + 1};
        if (extent > 0) {
            int64_t ext = planet ? extent >> level : ((extent - 1) >> level) + 1;
            int64_t ext_z = planet ? ext : ((extent_z - 1) >> level) + 1;
            if (ext < 1) break;
            pr = grid_rect_intersect(pr, (grid_rect){0, 0, ext, ext_z});
        }
        if (grid_rect_empty(pr)) break;
        level_job job = {.e = e,
                         .face = face,
                         .level = level,
                         .planet = planet,
                         .from_generator = from_generator,
                         .parents = pr};
        if (extent > 0) {
            job.child_extent = planet ? extent >> (level - 1) : ((extent - 1) >> (level - 1)) + 1;
            job.child_extent_z = planet ? job.child_extent : ((extent_z - 1) >> (level - 1)) + 1;
        }
        job.ptx0 = floor_div(pr.x0, TILE_SIZE);
        job.ptz0 = floor_div(pr.z0, TILE_SIZE);
        job.ptw = floor_div(pr.x1 - 1, TILE_SIZE) - job.ptx0 + 1;
        int64_t pth = floor_div(pr.z1 - 1, TILE_SIZE) - job.ptz0 + 1;
        level_tiles *prev = &held[level & 1], *cur = &held[(level + 1) & 1];
        if (!from_generator && find_children(&job, prev, &kids)) job.children = &kids;
        if (!from_generator && job.ptw * pth <= LEVEL_TILES_MAX) {
            cur->tx0 = job.ptx0, cur->tz0 = job.ptz0, cur->tw = job.ptw, cur->th = pth;
            memset(cur->tiles, 0, (size_t)(job.ptw * pth) * sizeof *cur->tiles);
            job.wrote = cur;
        }
        rc = parallel_run((int)(job.ptw * pth), parent_tile_task, &job, err);
        release_held(e, prev);
        r = pr;
    }
    release_held(e, &held[0]);
    release_held(e, &held[1]);
    return rc;
}

int edit_mips_update_from(edit *e, size_t first, og_error *err) {
    const world_params *p = world_get_params(edit_world(e));
    int faces = p->kind == WORLD_PLANET ? 6 : 1;
    const dirty_rect *d;
    size_t n = edit_dirty_rects(e, &d);
    if (first > n) first = n;
    d += first, n -= first;
    for (int face = 0; face < faces; face++) {
        grid_rect r = {0, 0, 0, 0};
        int have = 0;
        for (size_t i = 0; i < n; i++) {
            if (d[i].layer != TILE_LAYER_COARSE || d[i].face != face) continue;
            r = have ? grid_rect_union(r, d[i].rect) : d[i].rect;
            have = 1;
        }
        if (have && update_levels(e, face, r, 1, 0, err) != 0) return -1;
    }
    return 0;
}

int edit_mips_refilter_bounded(edit *e, int first, og_error *err) {
    const world_params *p = world_get_params(edit_world(e));
    if (p->kind == WORLD_PLANET || p->size <= 0 || first < 1) return 0;
    grid_rect whole = {0, 0, ((p->size - 1) >> (first - 1)) + 1,
                       ((world_params_size_z(p) - 1) >> (first - 1)) + 1};
    return update_levels(e, 0, whole, first, 1, err);
}
