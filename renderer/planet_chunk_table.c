// The resident chunks by node key: open addressing with linear probing.
#include "renderer/planet_internal.h"
#include "renderer/planet_renderer.h"

static size_t slot_of(uint64_t key) {
    return (size_t)((key * 0x9E3779B97F4A7C15ull) >> 52) & (TABLE_SIZE - 1);
}

chunk *planet_find_chunk(planet_renderer *r, uint64_t key) {
    for (size_t s = slot_of(key);; s = (s + 1) & (TABLE_SIZE - 1)) {
        if (r->table[s] < 0) return NULL;
        if (r->chunks[r->table[s]].key == key) return &r->chunks[r->table[s]];
    }
}

void planet_table_insert(planet_renderer *r, int index) {
    size_t s = slot_of(r->chunks[index].key);
    while (r->table[s] >= 0)
        s = (s + 1) & (TABLE_SIZE - 1);
    r->table[s] = index;
}

// Linear probing's backward-shift deletion: no tombstones.
void planet_table_remove(planet_renderer *r, uint64_t key) {
    size_t s = slot_of(key);
    while (r->chunks[r->table[s]].key != key)
        s = (s + 1) & (TABLE_SIZE - 1);
    r->table[s] = -1;
    for (size_t j = (s + 1) & (TABLE_SIZE - 1); r->table[j] >= 0; j = (j + 1) & (TABLE_SIZE - 1)) {
        size_t home = slot_of(r->chunks[r->table[j]].key);
        // Move j back into the hole when its home is not in (s, j] cyclically.
        int between = s <= j ? (home > s && home <= j) : (home > s || home <= j);
        if (!between) {
            r->table[s] = r->table[j];
            r->table[j] = -1;
            s = j;
        }
    }
}

void planet_drop_all(planet_renderer *r) {
    for (int i = 0; i < MAX_CHUNKS; i++)
        r->chunks[i].key = 0;
    for (int i = 0; i < TABLE_SIZE; i++)
        r->table[i] = -1;
    r->resident = 0;
}

// A free chunk slot, evicting the least recently selected chunk not used this frame.
int planet_take_slot(planet_renderer *r) {
    int best = -1;
    for (int i = 0; i < MAX_CHUNKS; i++) {
        if (r->chunks[i].key == 0) return i;
        if (r->chunks[i].used < r->frame && (best < 0 || r->chunks[i].used < r->chunks[best].used))
            best = i;
    }
    if (best >= 0) {
        planet_table_remove(r, r->chunks[best].key);
        r->chunks[best].key = 0;
        r->resident--;
    }
    return best;
}
