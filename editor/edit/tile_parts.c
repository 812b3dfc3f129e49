#include "editor/edit/tile_parts.h"

#include "io/tile.h"

#include <stdlib.h>

static int part_order(const void *a, const void *b) {
    const tile_part *x = a, *y = b;
    if (x->face != y->face) return x->face < y->face ? -1 : 1;
    if (x->ty != y->ty) return x->ty < y->ty ? -1 : 1;
    if (x->tx != y->tx) return x->tx < y->tx ? -1 : 1;
    return 0;
}

void tile_parts_merge(tile_parts *l) {
    size_t n = l->count;
    if (!n) return;
    tile_part *parts = l->parts;
    qsort(parts, n, sizeof *parts, part_order);
    size_t out = 0;
    for (size_t i = 1; i < n; i++) {
        tile_part *m = &parts[out];
        if (!part_order(m, &parts[i])) {
            if (parts[i].x0 < m->x0) m->x0 = parts[i].x0;
            if (parts[i].z0 < m->z0) m->z0 = parts[i].z0;
            if (parts[i].x1 > m->x1) m->x1 = parts[i].x1;
            if (parts[i].z1 > m->z1) m->z1 = parts[i].z1;
        } else {
            parts[++out] = parts[i];
        }
    }
    l->count = out + 1;
}

int tile_parts_add_rect(tile_parts *l, int face, grid_rect r) {
    if (grid_rect_empty(r)) return 0;
    int64_t tx0 = world_grid_floor_div(r.x0, TILE_SIZE),
            tx1 = world_grid_floor_div(r.x1 - 1, TILE_SIZE);
    int64_t tz0 = world_grid_floor_div(r.z0, TILE_SIZE),
            tz1 = world_grid_floor_div(r.z1 - 1, TILE_SIZE);
    for (int64_t tz = tz0; tz <= tz1; tz++)
        for (int64_t tx = tx0; tx <= tx1; tx++) {
            if (l->count == l->cap) {
                size_t cap = l->cap ? l->cap * 2 : 64;
                tile_part *grown = realloc(l->parts, cap * sizeof *grown);
                if (!grown) return -1;
                l->parts = grown;
                l->cap = cap;
            }
            int64_t gx = tx * TILE_SIZE, gz = tz * TILE_SIZE;
            tile_part p = {face,
                           (int32_t)tx,
                           (int32_t)tz,
                           (int)((r.x0 > gx ? r.x0 : gx) - gx),
                           (int)((r.z0 > gz ? r.z0 : gz) - gz),
                           (int)((r.x1 < gx + TILE_SIZE ? r.x1 : gx + TILE_SIZE) - gx),
                           (int)((r.z1 < gz + TILE_SIZE ? r.z1 : gz + TILE_SIZE) - gz)};
            l->parts[l->count++] = p;
        }
    return 0;
}

void tile_parts_free(tile_parts *l) {
    free(l->parts);
    *l = (tile_parts){0};
}

void tile_part_publish(edit *e, tile_layer kind, int face, grid_rect r, grid_rect changed) {
    if (changed.x0 >= changed.x1) return;
    edit_dirty(
        e, kind, face,
        (grid_rect){r.x0 + changed.x0, r.z0 + changed.z0, r.x0 + changed.x1, r.z0 + changed.z1});
}
